#!/usr/bin/python3
"""catkin_lint finds nothing in the package at its strictest (-W2 --strict: every notice and
warning an error), so a new problem fails here. The few checks the package deliberately does
not follow are switched off in CMakeLists.txt by catkin_lint pragmas, each with its reason
(README.md, "Maintainers' notes"). One more is switched off here, as it concerns the checkout,
not the package: package_path_name (the folder's name is the user's: a clone into another name,
a git worktree; catkin finds the package by its package.xml).

Run by catkin's run_tests (test/package_tests.cmake); alone:
  python3 test/package/test_catkin_lint.py --text
"""
import os
import shutil
import subprocess
import tempfile
import unittest

import rosunit

PKG = "virtual_go"
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


class CatkinLintTest(unittest.TestCase):
    def test_no_problem_at_the_strictest_level(self):
        lint = shutil.which("catkin_lint", path="/usr/bin:/bin")
        self.assertIsNotNone(lint, "catkin_lint not found: apt-get install catkin-lint "
                             "(scripts/setup.sh does)")
        with tempfile.TemporaryDirectory(prefix="vg_catkin_lint_") as home:
            # Only the package's own pragmas count: no user configuration (~/.catkin_lint,
            # $XDG_CONFIG_HOME, .catkin_lint along ROS_PACKAGE_PATH) and no rosdep cache.
            env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": home,
                   "XDG_CONFIG_HOME": home}
            result = subprocess.run(
                [lint, "-W2", "--strict", "--offline", "--explain", "--ignore", "package_path_name",
                 SOURCE], env=env, text=True,
                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL,
                timeout=300)
        self.assertEqual(result.returncode, 0, "catkin_lint -W2 --strict:\n" + result.stdout)


if __name__ == "__main__":
    rosunit.unitrun(PKG, "catkin_lint", CatkinLintTest)
