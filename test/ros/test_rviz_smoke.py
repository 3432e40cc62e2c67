#!/usr/bin/python3
"""rviz smoke test: rviz with config/stone.rviz, on a private Xvfb display with Mesa's
software renderer, shows the stone node's marker. A screenshot (import -window root) must
contain stone-coloured (near-black) pixels in a stone-sized blob near the middle of the 3D
view, where the camera of stone.rviz looks at the stone (test/ros/config/rviz.yaml keeps it
there)."""
import os
import subprocess
import sys
import time
import unittest

import rospkg
import rostest

PKG = "virtual_go"
WIDTH, HEIGHT = 1080, 720
# The 3D view of stone.rviz in a 1080 x 720 window: right of the Displays dock, below the
# tool bar.
VIEW = (365, 62, 1065, 690)  # x0, y0, x1, y1
DARK = 30  # the black stone renders near (12, 12, 14); grid crossings reach (47, 36, 23)


def read_ppm(data):
    """(width, height, rgb bytes) of a binary PPM (P6) as written by imagemagick."""
    fields, pos = [], 0
    while len(fields) < 4:
        while data[pos:pos + 1].isspace():
            pos += 1
        if data[pos:pos + 1] == b"#":
            pos = data.index(b"\n", pos)
            continue
        end = pos
        while not data[end:end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    if fields[0] != b"P6" or int(fields[3]) != 255:
        raise ValueError("not an 8-bit P6 image")
    width, height = int(fields[1]), int(fields[2])
    return width, height, data[pos + 1:pos + 1 + 3 * width * height]


def dark_pixels(width, rgb, box):
    x0, y0, x1, y1 = box
    found = []
    for y in range(y0, y1):
        row = rgb[3 * (y * width + x0):3 * (y * width + x1)]
        for i in range(0, len(row), 3):
            if row[i] < DARK and row[i + 1] < DARK and row[i + 2] < DARK:
                found.append((x0 + i // 3, y))
    return found


def free_display():
    n = 90
    while os.path.exists("/tmp/.X11-unix/X%d" % n) or os.path.exists("/tmp/.X%d-lock" % n):
        n += 1
    return n


class RvizSmokeTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        env = dict(os.environ)
        env["DISPLAY"] = ":%d" % free_display()
        env["LIBGL_ALWAYS_SOFTWARE"] = "1"
        self.env = env
        self.start(["Xvfb", env["DISPLAY"], "-screen", "0", "%dx%dx24" % (WIDTH, HEIGHT),
                    "-nolisten", "tcp"])
        time.sleep(1.0)
        config = os.path.join(rospkg.RosPack().get_path(PKG), "config", "stone.rviz")
        self.start(["rviz", "-d", config, "__name:=rviz_smoke"])
        self.shot = os.path.join(os.environ.get("ROS_HOME", "/tmp"), "rviz_smoke.png")

    def start(self, command):
        log = open(os.devnull, "w")
        self.processes.append(subprocess.Popen(command, env=self.env, stdout=log, stderr=log))

    def tearDown(self):
        for process in reversed(self.processes):  # only what this test started, by pid
            process.terminate()
            try:
                process.wait(timeout=10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()

    def screenshot(self):
        data = subprocess.run(["import", "-window", "root", "-depth", "8", "ppm:-"], env=self.env,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              timeout=30).stdout
        if data:
            with open(self.shot, "wb") as f:
                f.write(data)
        return read_ppm(data) if data else None

    def test_stone_is_drawn_in_view(self):
        deadline = time.time() + 90.0
        found = []
        while time.time() < deadline:
            time.sleep(2.0)
            for process in self.processes:
                self.assertIsNone(process.poll(), "%s exited" % process.args[0])
            image = self.screenshot()
            if image is None:
                continue
            width, height, rgb = image
            self.assertEqual((width, height), (WIDTH, HEIGHT))
            found = dark_pixels(width, rgb, VIEW)
            if len(found) >= 300:
                break
        self.assertGreaterEqual(len(found), 300,
                                "no stone-coloured blob in the 3D view; see %s" % self.shot)
        xs = [p[0] for p in found]
        ys = [p[1] for p in found]
        cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
        view_cx, view_cy = (VIEW[0] + VIEW[2]) / 2, (VIEW[1] + VIEW[3]) / 2
        # Where the camera looks: the middle of the view, the stone slightly below centre.
        self.assertLess(abs(cx - view_cx), 100, "stone not where expected: x %.0f" % cx)
        self.assertLess(abs(cy - view_cy), 150, "stone not where expected: y %.0f" % cy)
        # Stone-sized (the 22 mm lens at 0.2 m is about 80 px across), not grid or panel.
        self.assertLess(max(xs) - min(xs), 250)
        self.assertLess(max(ys) - min(ys), 250)


if __name__ == "__main__":
    rostest.rosrun(PKG, "rviz_smoke", RvizSmokeTest, sys.argv)
