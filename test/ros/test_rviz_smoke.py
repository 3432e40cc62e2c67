#!/usr/bin/python3
"""rviz smoke test: rviz with config/stone.rviz, on a private Xvfb display with Mesa's software
renderer, draws the stone node's stones (~stone_markers) and the board (~board/enabled is set by
the .test file) whatever the start order:

- rviz first, then the node;
- the node first, rviz 12 s later (longer than tf's 10 s cache, so nothing from the node's
  start is still fresh);
- a recorded bag played with --clock under use_sim_time, rviz started before the replay.

Each order passes when, in three screenshots in a row over several seconds,
- the pixels show it: stone-coloured (near-black) pixels in a stone-sized blob near the middle
  of the 3D view, where the camera of stone.rviz looks (test/ros/config/rviz.yaml keeps it there);
- the board is drawn: board-coloured (lit wood) pixels fill a large part of the 3D view (the
  background and the table are grey, the lines dark brown, the stone black);
- rviz's own status of every display is Ok: rviz colours a display's name blue when it is
  enabled and Ok and in the status colour otherwise (rviz::Display::getViewData), so the
  Displays panel must show three blue names (Board, TF, Stone) and no name in the warning or
  error colour. A marker that failed tf2's message filter turns the Stone name red ("Unknown
  reason for transform failure (frame=[stone])"), a board marker that failed it the Board name;
- rviz's log has no mesh loading error.
"""
import os
import signal
import subprocess
import sys
import tempfile
import time
import unittest

import rosgraph
import roslib.packages
import rospkg
import rostest

PKG = "virtual_go"
WIDTH, HEIGHT = 1080, 720
# The 3D view of stone.rviz in a 1080 x 720 window: right of the Displays dock, below the
# tool bar.
VIEW = (365, 62, 1065, 690)  # x0, y0, x1, y1
DARK = 30  # the black stone renders near (12, 12, 14); grid crossings reach (47, 36, 23)
# Names in the Displays tree (right of the icons, left of the check boxes), below the header.
DISPLAY_NAMES = (44, 85, 170, 400)  # x0, y0, x1, y1
NODE_TOPICS = ["/tf", "/tf_static", "/stone/pose", "/stone/odom", "/stone/marker",
               "/stone/stone_markers", "/stone/stones", "/stone/info", "/stone/events",
               "/stone/board_markers"]
# Of the 3D view, at least this share must be lit wood: the camera looks down at the board's
# centre from 35 cm, so the board fills most of the view.
BOARD_SHARE = 0.3


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


def pixels(width, rgb, box, predicate):
    x0, y0, x1, y1 = box
    found = []
    for y in range(y0, y1):
        row = rgb[3 * (y * width + x0):3 * (y * width + x1)]
        for i in range(0, len(row), 3):
            if predicate(row[i], row[i + 1], row[i + 2]):
                found.append((x0 + i // 3, y))
    return found


def is_dark(r, g, b):
    return r < DARK and g < DARK and b < DARK


def is_wood(r, g, b):
    """The board's colour (0.86, 0.70, 0.36) under rviz's light: yellow-brown, clearly brighter
    than the ink of the lines (0.35, 0.26, 0.14), unlike the grey table and background."""
    return r > 100 and r > g > b and r - b > 50 and g - b > 25


# rviz's text colours: Ok display names (40, 120, 197), Warn (192, 128, 0), Error (192, 32, 32);
# anti-aliasing blends them with the white background, so the tests keep margins.
def is_ok_blue(r, g, b):
    return b > 150 and r < 110 and b - r > 60


def is_warn_orange(r, g, b):
    return r > 150 and 90 < g < 170 and b < 60


def is_error_red(r, g, b):
    return r > 150 and g < 80 and b < 80


def bands(ys):
    """Runs of consecutive rows: one per line of text."""
    runs = []
    for y in sorted(set(ys)):
        if runs and y <= runs[-1][1] + 2:
            runs[-1][1] = y
        else:
            runs.append([y, y])
    return runs


def check_image(width, rgb):
    """None when the stone is drawn and every display is Ok, else what is wrong."""
    names = DISPLAY_NAMES
    warned = pixels(width, rgb, names, is_warn_orange)
    failed = pixels(width, rgb, names, is_error_red)
    if failed:
        return "a display reports an error (red name at y %d)" % failed[0][1]
    if warned:
        return "a display reports a warning (orange name at y %d)" % warned[0][1]
    ok_names = bands(y for _, y in pixels(width, rgb, names, is_ok_blue))
    if len(ok_names) != 3:
        return "%d display names in the Ok colour, expected 3 (Board, TF, Stone)" % len(ok_names)
    wood = len(pixels(width, rgb, VIEW, is_wood))
    view_area = (VIEW[2] - VIEW[0]) * (VIEW[3] - VIEW[1])
    if wood < BOARD_SHARE * view_area:
        return "no board: %.0f %% of the 3D view is board-coloured, expected at least %.0f %%" % (
            100.0 * wood / view_area, 100.0 * BOARD_SHARE)
    dark = pixels(width, rgb, VIEW, is_dark)
    if len(dark) < 300:
        return "no stone-coloured blob in the 3D view (%d dark pixels)" % len(dark)
    xs = [p[0] for p in dark]
    ys = [p[1] for p in dark]
    cx, cy = sum(xs) / len(xs), sum(ys) / len(ys)
    view_cx, view_cy = (VIEW[0] + VIEW[2]) / 2, (VIEW[1] + VIEW[3]) / 2
    # Where the camera looks: the middle of the view, the stone slightly below centre.
    if abs(cx - view_cx) >= 100 or abs(cy - view_cy) >= 150:
        return "dark blob not where the stone should be: centre (%.0f, %.0f)" % (cx, cy)
    # Stone-sized (the 22 mm lens at 0.2 m is about 80 px across), not grid or panel.
    if max(xs) - min(xs) >= 250 or max(ys) - min(ys) >= 250:
        return "dark blob too large for the stone: %d x %d px" % (max(xs) - min(xs),
                                                                  max(ys) - min(ys))
    return None


class RvizSmokeTest(unittest.TestCase):
    def setUp(self):
        self.processes = []
        self.master = rosgraph.Master("/rviz_smoke_test")
        self.folder = tempfile.mkdtemp(prefix="rviz_smoke_", dir=os.environ.get("ROS_HOME"))
        self.env = dict(os.environ, LIBGL_ALWAYS_SOFTWARE="1")
        # Xvfb picks a free display itself and writes its number once it accepts clients.
        read_end, write_end = os.pipe()
        self.start("xvfb", ["Xvfb", "-displayfd", str(write_end), "-screen", "0",
                            "%dx%dx24" % (WIDTH, HEIGHT), "-nolisten", "tcp"],
                   pass_fds=(write_end,))
        os.close(write_end)
        with os.fdopen(read_end) as f:
            self.env["DISPLAY"] = ":" + f.readline().strip()
        self.shot = os.path.join(self.folder, "rviz_smoke.png")
        self.rviz_log = os.path.join(self.folder, "rviz.log")

    def tearDown(self):
        for _, process in reversed(self.processes):  # only what this test started, by pid
            if process.poll() is None:
                process.send_signal(signal.SIGINT)
                try:
                    process.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    process.kill()
                    process.wait()
        try:
            self.master.deleteParam("/use_sim_time")
        except rosgraph.MasterError:
            pass  # not set

    def start(self, name, command, **kwargs):
        log = open(os.path.join(self.folder, name + ".log") if name != "xvfb" else os.devnull,
                   "w")
        process = subprocess.Popen(command, env=self.env, stdout=log, stderr=subprocess.STDOUT,
                                   **kwargs)
        self.processes.append((name, process))
        return process

    def start_rviz(self):
        config = os.path.join(rospkg.RosPack().get_path(PKG), "config", "stone.rviz")
        self.start("rviz", ["rviz", "-d", config, "__name:=rviz_smoke"])
        # Up when its Stone and Board displays have subscribed to their markers.
        for topic in ("/stone/stone_markers", "/stone/board_markers"):
            self.wait_for(lambda: "/rviz_smoke" in self.subscribers(topic), 60,
                          "rviz did not subscribe to %s" % topic)

    def start_node(self):
        node = roslib.packages.find_node(PKG, "stone_node")[0]
        # Parameters: test/ros/config/rviz.yaml, loaded under /stone by the .test file.
        self.start("stone_node", [node, "__name:=stone"])
        self.wait_for(lambda: "/stone" in self.publishers("/tf"), 30, "the node publishes no /tf")

    def system_state(self):
        return self.master.getSystemState()

    def subscribers(self, topic):
        return next((nodes for t, nodes in self.system_state()[1] if t == topic), [])

    def publishers(self, topic):
        return next((nodes for t, nodes in self.system_state()[0] if t == topic), [])

    def wait_for(self, predicate, timeout_s, message):
        deadline = time.time() + timeout_s
        while time.time() < deadline:
            self.assert_running()
            if predicate():
                return
            time.sleep(0.2)
        self.fail(message)

    def assert_running(self):
        for name, process in self.processes:
            if name not in ("record", "play"):
                self.assertIsNone(process.poll(), "%s exited" % name)

    def screenshot(self):
        data = subprocess.run(["import", "-window", "root", "-depth", "8", "ppm:-"], env=self.env,
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                              timeout=30).stdout
        if data:
            with open(self.shot, "wb") as f:
                f.write(data)
        return read_ppm(data) if data else None

    def assert_stone_drawn(self, timeout_s=60.0, confirmations=3):
        """Waits until the stone and the board are drawn and every display is Ok, then wants the
        same in the next screenshots: a transient state does not pass."""
        deadline = time.time() + timeout_s
        problem, good = "no screenshot", 0
        while time.time() < deadline and good < confirmations:
            time.sleep(1.5)
            self.assert_running()
            image = self.screenshot()
            if image is None:
                continue
            width, height, rgb = image
            self.assertEqual((width, height), (WIDTH, HEIGHT))
            problem = check_image(width, rgb)
            if problem is None:
                good += 1
            elif good > 0:
                self.fail("after %d good screenshots: %s; see %s" % (good, problem, self.shot))
        self.assertEqual(good, confirmations, "%s; see %s" % (problem, self.shot))
        with open(self.rviz_log, errors="replace") as f:
            errors = [line for line in f if "Could not load" in line or "mesh" in line.lower()]
        self.assertEqual(errors, [], "rviz log: %s" % "".join(errors))

    def test_rviz_before_node(self):
        self.start_rviz()
        self.start_node()
        self.assert_stone_drawn()

    def test_node_long_before_rviz(self):
        self.start_node()
        time.sleep(12.0)
        self.start_rviz()
        self.assert_stone_drawn()

    def test_replay_of_a_bag(self):
        bag = os.path.join(self.folder, "replay.bag")
        record = self.start("record", ["rosbag", "record", "--duration=8", "-O", bag] +
                            NODE_TOPICS)
        self.wait_for(lambda: any("/record" in n for n in self.subscribers("/stone/marker")), 30,
                      "rosbag record did not subscribe")
        self.start_node()
        self.assertEqual(record.wait(timeout=60), 0, "rosbag record failed")
        self.assertTrue(os.path.exists(bag), "no bag written")
        node = next(p for name, p in self.processes if name == "stone_node")
        node.send_signal(signal.SIGINT)
        node.wait(timeout=10)
        self.processes = [(n, p) for n, p in self.processes if p is not node]

        self.master.setParam("/use_sim_time", True)
        self.start_rviz()
        self.start("play", ["rosbag", "play", "--clock", bag])
        self.assert_stone_drawn()


if __name__ == "__main__":
    rostest.rosrun(PKG, "rviz_smoke", RvizSmokeTest, sys.argv)
