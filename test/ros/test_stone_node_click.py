#!/usr/bin/python3
"""rviz's Publish Point tool onto the stone node: PointStamped clicks on /clicked_point, read back
from ~stones. Clicks near D4 and (in the `camera` frame of the .test file) near Q16 and J4 set
down black_1, white_1, black_2 on those points; a click off the board and one onto D4 again place
nothing, each with a WARN on /rosout naming the point and the reason, and do not flip the colour.
The points' world positions are the board's numbers written here (22 mm across, 23.7 mm along,
tengen at the origin), and the camera's transform is the .test file's, inverted by hand."""
import math
import sys
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import PointStamped
from rosgraph_msgs.msg import Log
from virtual_go.msg import StoneStates

PKG = "virtual_go"
SPACING_X, SPACING_Y = 0.022, 0.0237  # m
COLUMNS = "ABCDEFGHJKLMNOPQRST"
# The .test file's static transform world -> camera: translation, then yaw about z.
CAMERA_T = (0.1, 0.05, 0.3)
CAMERA_YAW = math.pi / 2
TIMEOUT_S = 10.0


def world_of(point, dx=0.0, dy=0.0):
    """The world position of a GTP point, offset by dx, dy spacings."""
    column, row = COLUMNS.index(point[0]), int(point[1:]) - 1
    return ((column - 9 + dx) * SPACING_X, (row - 9 + dy) * SPACING_Y, 0.0)


def in_camera(p):
    """A world position in the camera frame: R^T (p - t), R the yaw."""
    x, y, z = (p[k] - CAMERA_T[k] for k in range(3))
    c, s = math.cos(CAMERA_YAW), math.sin(CAMERA_YAW)
    return (c * x + s * y, -s * x + c * y, z)


class StoneNodeClickTest(unittest.TestCase):
    def setUp(self):
        self.stones = None
        self.warnings = []
        rospy.Subscriber("/stone/stones", StoneStates, self.on_stones)
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        self.clicks = rospy.Publisher("/clicked_point", PointStamped, queue_size=10)
        deadline = time.monotonic() + TIMEOUT_S
        while time.monotonic() < deadline and (self.clicks.get_num_connections() == 0 or
                                               self.stones is None):
            time.sleep(0.05)
        self.assertGreater(self.clicks.get_num_connections(), 0, "the node does not listen")

    def on_stones(self, message):
        self.stones = message

    def on_log(self, message):
        if message.name == "/stone" and message.level == Log.WARN and "clicked_point" in message.msg:
            self.warnings.append(message.msg)

    def click(self, frame, p):
        message = PointStamped()
        message.header.frame_id = frame
        message.header.stamp = rospy.Time.now()
        message.point.x, message.point.y, message.point.z = p
        self.clicks.publish(message)

    def placed(self):
        """{name: (colour, point, resting)} of the placed stones on ~stones."""
        m = self.stones
        return {n: (c, p, r) for n, c, p, r in zip(m.name, m.color, m.point, m.resting)
                if n != "stone"}

    def wait_for(self, condition, what):
        deadline = time.monotonic() + TIMEOUT_S
        while time.monotonic() < deadline and not condition():
            time.sleep(0.05)
        self.assertTrue(condition(), "%s; ~stones: %s, warnings: %s"
                        % (what, self.placed(), self.warnings))

    def test_clicks_place_alternating_stones_and_refusals_warn(self):
        self.click("world", world_of("D4", 0.4, -0.3))
        self.wait_for(lambda: len(self.placed()) == 1, "the first click placed no stone")
        # Onto D4 again, then off the board (10 spacings right of tengen): nothing, two warnings.
        self.click("world", world_of("D4", -0.2, 0.2))
        self.wait_for(lambda: len(self.warnings) == 1, "no warning for a click onto D4")
        self.assertIn("D4", self.warnings[0])
        self.assertIn("black_1 already lies there", self.warnings[0])
        self.click("world", (10 * SPACING_X, 0.0, 0.0))
        self.wait_for(lambda: len(self.warnings) == 2, "no warning for a click off the board")
        self.assertIn("off the board", self.warnings[1])
        # In the camera frame (rviz with another fixed frame): white at Q16, then black at J4,
        # clicked on a stone's height above the board.
        self.click("camera", in_camera(world_of("Q16", -0.4, 0.4)))
        self.wait_for(lambda: len(self.placed()) == 2, "the click in the camera frame placed none")
        q = world_of("J4", 0.3, 0.1)
        self.click("camera", in_camera((q[0], q[1], 0.009)))
        self.wait_for(lambda: len(self.placed()) == 3 and all(r for _, _, r in
                                                              self.placed().values()),
                      "the third stone did not come to rest")
        self.assertEqual(self.placed(), {"black_1": ("black", "D4", True),
                                         "white_1": ("white", "Q16", True),
                                         "black_2": ("black", "J4", True)})
        # Set down where ~place sets them: on the intersections.
        m = self.stones
        for name, point in (("black_1", "D4"), ("white_1", "Q16"), ("black_2", "J4")):
            pose = m.pose[m.name.index(name)]
            x, y, _ = world_of(point)
            self.assertAlmostEqual(pose.position.x, x, places=9)
            self.assertAlmostEqual(pose.position.y, y, places=9)
        self.assertEqual(len(self.warnings), 2, self.warnings)


if __name__ == "__main__":
    rospy.init_node("test_stone_node_click")
    rostest.rosrun(PKG, "stone_node_click", StoneNodeClickTest, sys.argv)
