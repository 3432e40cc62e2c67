#!/usr/bin/python3
"""The package configures from a checkout path of 200 characters or more (issue 18).

catkin names a rostest's targets and their folders after the test's arguments; an absolute path
among them made a folder name grow with the checkout path until it passed the file system's
255-byte limit on a name, and cmake's generate step failed for any user with a deeper workspace
than CI's. This test copies the package's sources (no build folders) into a folder whose path is
at least MIN_PATH_CHARS long, configures it as scripts/setup.sh does (its vg_configure, in a
plain environment without any devel space sourced), and requires that the configure succeeds
and that no target, file or folder name it creates holds a folder name of the checkout path:
names independent of the path, not merely short enough for this one. Configure only (about
30 s); the copy is deleted afterwards.

Run by catkin's run_tests (test/package_tests.cmake); alone:
  python3 test/package/test_configure_long_path.py --text
"""
import os
import shutil
import subprocess
import tempfile
import unittest

import rosunit

PKG = "virtual_go"
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
MIN_PATH_CHARS = 200  # the issue's: a deep but ordinary workspace
# Every folder of the padding holds this word; a generated name holding it came from the path.
MARKER = "deep_checkout"
CONFIGURE_TIMEOUT_S = 900  # a generous bound on a loaded 2-core machine; normally ~30 s


def copy_ignore(folder, names):
    """What a fresh clone would not hold: git's data, build folders (any with a CMakeCache.txt,
    and build* at the root as .gitignore has it), caches and bags."""
    ignored = set()
    for name in names:
        path = os.path.join(folder, name)
        if name in (".git", "__pycache__") or name.endswith((".bag", ".bag.active")):
            ignored.add(name)
        elif os.path.isdir(path) and (
                os.path.exists(os.path.join(path, "CMakeCache.txt"))
                or (folder == SOURCE and name.startswith("build"))):
            ignored.add(name)
    return ignored


class ConfigureLongPathTest(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="vg_long_path_")
        path = os.path.join(self.root, "home", "alice")
        index = 0
        while len(os.path.join(path, "catkin_ws", "src", PKG)) < MIN_PATH_CHARS:
            path = os.path.join(path, f"{MARKER}_{index}_projects_robotics_go_simulation")
            index += 1
        self.checkout = os.path.join(path, "catkin_ws", "src", PKG)
        shutil.copytree(SOURCE, self.checkout, ignore=copy_ignore, symlinks=True)

    def tearDown(self):
        shutil.rmtree(self.root, ignore_errors=True)

    def run_in_checkout(self, command, timeout_s):
        # A user's fresh shell: no devel space, no ROS_PACKAGE_PATH from the run_tests wrapper.
        env = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8", "HOME": os.environ.get("HOME", "/")}
        return subprocess.run(["bash", "-c", command], cwd=self.checkout, env=env, text=True,
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                              stdin=subprocess.DEVNULL, timeout=timeout_s)

    def test_configures_with_names_independent_of_the_path(self):
        self.assertGreaterEqual(len(self.checkout), MIN_PATH_CHARS)
        build = os.path.join(self.checkout, "build_catkin")
        configure = self.run_in_checkout("source scripts/setup.sh && vg_configure",
                                         CONFIGURE_TIMEOUT_S)
        # vg_configure prints the whole log on failure; the end names the failing step.
        tail = "\n".join(configure.stdout.splitlines()[-40:])
        self.assertEqual(configure.returncode, 0,
                         f"configure failed from a {len(self.checkout)}-character checkout path "
                         f"{self.checkout}:\n{tail}")

        grown = []
        for folder, dirs, files in os.walk(build):
            grown += [os.path.join(folder, n) for n in dirs + files if MARKER in n]
        self.assertEqual(grown, [], f"{len(grown)} generated names hold the checkout path, e.g. "
                         f"{grown[:3]}")

        targets = self.run_in_checkout("cmake --build build_catkin --target help", 120)
        self.assertEqual(targets.returncode, 0, targets.stdout[-2000:])
        listed = [t for t in targets.stdout.splitlines() if t.startswith("... ")]
        self.assertGreater(len(listed), 50, "the target list is not what cmake's help prints:\n"
                           + targets.stdout[-2000:])
        grown = [t[4:] for t in listed if MARKER in t]
        self.assertEqual(grown, [], f"{len(grown)} targets hold the checkout path, e.g. "
                         f"{grown[:3]}")


if __name__ == "__main__":
    rosunit.unitrun(PKG, "configure_long_path", ConfigureLongPathTest)
