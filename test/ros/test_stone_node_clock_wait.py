#!/usr/bin/python3
"""use_sim_time without /clock must not be silent. With /use_sim_time true (set by the .test
file) and no /clock, the stone node publishes nothing; it must warn, once, that it is waiting
for /clock, about 3 s after it starts waiting. When the test then publishes /clock the stone
starts (a `start` event on /stone/events) and the node says that /clock moves again; when the
test stops /clock the node warns once more, naming the ROS time it stands at. The node's log
is read from /rosout; waits are in wall time (ROS time is what is under test)."""
import signal
import subprocess
import sys
import threading
import time
import unittest

import roslib.packages
import rospy
import rostest
from rosgraph_msgs.msg import Clock, Log
from virtual_go.msg import StoneEvent

PKG = "virtual_go"
PATIENCE_S = 3.0  # the node's: ROS time still this long counts as a stall


class ClockWaitTest(unittest.TestCase):
    def setUp(self):
        self.logs = []
        self.events = []
        self.lock = threading.Lock()
        rospy.Subscriber("/rosout", Log, self.on_log, queue_size=100)
        rospy.Subscriber("/stone/events", StoneEvent, self.events.append, queue_size=100)
        self.clock = rospy.Publisher("/clock", Clock, queue_size=10)
        # Started after the subscriptions above: /rosout is not latched.
        node = roslib.packages.find_node(PKG, "stone_node")[0]
        self.node_started = time.time()
        self.node = subprocess.Popen([node, "__name:=stone"])

    def tearDown(self):
        self.node.send_signal(signal.SIGINT)
        self.node.wait(timeout=10)

    def on_log(self, msg):
        if msg.name == "/stone":
            with self.lock:
                self.logs.append((time.time(), msg))

    def waits(self, since):
        """(wall time, message) of the node's 'waiting for /clock' warnings after `since`."""
        with self.lock:
            return [(t, m) for t, m in self.logs
                    if t >= since and m.level == Log.WARN and "waiting for /clock" in m.msg]

    def wait_for(self, predicate, timeout_s):
        deadline = time.time() + timeout_s
        while time.time() < deadline and not predicate():
            time.sleep(0.05)
        return predicate()

    def publish_clock(self, start_s, duration_s):
        """/clock at 100 Hz of wall time, moving with it, from start_s; returns the last."""
        begin = time.time()
        now_s = start_s
        while time.time() - begin < duration_s:
            now_s = start_s + (time.time() - begin)
            self.clock.publish(Clock(clock=rospy.Time.from_sec(now_s)))
            time.sleep(0.01)
        return now_s

    def test_waiting_for_clock_is_reported_once_per_stall(self):
        # No /clock yet: one warning, within patience plus the node's start and check period.
        self.assertTrue(self.wait_for(lambda: self.waits(0), PATIENCE_S + 10.0),
                        "no 'waiting for /clock' warning without /clock")
        t, first = self.waits(0)[0]
        self.assertGreaterEqual(t - self.node_started, PATIENCE_S, "warned before the patience")
        self.assertIn("use_sim_time", first.msg)
        self.assertIn("no /clock", first.msg)
        self.assertFalse(self.events, "the stone started without /clock")
        # Once: nothing more over twice the patience.
        time.sleep(2 * PATIENCE_S)
        self.assertEqual(len(self.waits(0)), 1, [m.msg for _, m in self.waits(0)])

        # /clock runs: the stone starts, the node says /clock moves, and no warning comes
        # while it runs (longer than the patience).
        running_since = time.time()
        last_s = self.publish_clock(100.0, 2 * PATIENCE_S)
        self.assertTrue(any(e.reason == "start" for e in self.events), "no start on /clock")
        with self.lock:
            moves = [m for t, m in self.logs if t >= running_since and "moves again" in m.msg]
        self.assertEqual(len(moves), 1)
        self.assertEqual(self.waits(running_since), [])

        # /clock stops: one more warning, naming the time it stands at.
        stopped = time.time()
        self.assertTrue(self.wait_for(lambda: self.waits(stopped), PATIENCE_S + 5.0),
                        "no warning when /clock stopped")
        t, again = self.waits(stopped)[0]
        self.assertGreaterEqual(t - stopped, PATIENCE_S - 0.5, "warned before the patience")
        self.assertIn("stood at ", again.msg)
        stood_s = float(again.msg.split("stood at ")[1].split(" ")[0])
        self.assertAlmostEqual(stood_s, last_s, delta=0.05)
        time.sleep(2 * PATIENCE_S)
        self.assertEqual(len(self.waits(stopped)), 1)


if __name__ == "__main__":
    rospy.init_node("clock_wait_test", disable_signals=True)
    rostest.rosrun(PKG, "stone_node_clock_wait", ClockWaitTest, sys.argv)
