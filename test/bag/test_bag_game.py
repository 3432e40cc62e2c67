#!/usr/bin/python3
"""A bag of a replayed game passes `bag_report --strict` (issue 16). rosbag records the node's
topics, /tf and /tf_static while `sgf_replay` drops the first 40 moves of Debian kigo's
Honinbo-51-5.sgf onto the board (--drop-height 0.02: each stone flies, lands, bounces and rests);
bag_report --strict on the bag must exit 0. A copy with one resting stone's position moved by
1 um in one ~stones message (written with rosbag's Python API) must fail, naming that stone.

Points are 22.0 mm apart across and the stones 22.2 mm (black) and 21.9 mm (white) wide; each
dropped stone is aimed at the free spot beside its neighbours (world/stone_placement.h), so no two
overlap and, with stone-stone contact on (the node's default), none is knocked: no island forms in
these moves."""
import os
import subprocess
import sys
import time
import unittest

import rosbag
import rosgraph
import rospy
import rostest
from virtual_go.msg import StoneStates

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from process_group import interrupt_group  # noqa: E402  (test/support, beside this folder)

PKG = "virtual_go"
NODE = "/stone"
MOVES = 40
# Late timer ticks on a loaded machine show as gaps in ~odom, ~pose and the initial stone's /tf
# (as in bag_record.test): about a tenth of the ~10 s recorded at 60 Hz.
MAX_GAPS = "75"
TOPICS = ["/tf", "/tf_static"] + [NODE + "/" + t for t in (
    "pose", "odom", "marker", "stone_markers", "stones", "info", "events", "board_markers")]
GAME = None  # set in main from test_data_paths.txt


def ros_home():
    return os.environ.get("ROS_HOME", os.path.join(os.path.expanduser("~"), ".ros"))


def recorder_subscribed():
    """True once a rosbag recorder subscribes to every topic the node already publishes."""
    _, subscribers, _ = rosgraph.Master("/test_bag_game").getSystemState()
    subs = {topic: nodes for topic, nodes in subscribers}
    return all(any(n.startswith("/record") for n in subs.get(t, []))
               for t in (NODE + "/stones", NODE + "/events", "/tf"))


def bag_report(path):
    started = time.monotonic()
    run = subprocess.run(["rosrun", PKG, "bag_report", path, "--strict", "--max-gaps", MAX_GAPS],
                         capture_output=True, text=True, timeout=300)
    return run, time.monotonic() - started


def nudged_copy(source, target):
    """Copies the bag, moving one resting placed stone by 1e-6 m along x in one ~stones message
    (one in the middle of its rest). Returns the stone's name."""
    with rosbag.Bag(source) as bag:
        # (message index, stone) of every resting placed stone, in ~stones order.
        resting = []
        for k, (_, msg, _) in enumerate(bag.read_messages(topics=[NODE + "/stones"])):
            resting += [(k, n) for n, r in zip(msg.name, msg.resting) if r and n != "stone"]
    assert resting, "no resting placed stone in any ~stones message"
    first_stone = resting[0][1]
    mine = [k for k, n in resting if n == first_stone]
    target_k = mine[len(mine) // 2]
    with rosbag.Bag(source) as bag, rosbag.Bag(target, "w") as out:
        k = -1
        for topic, raw, t, header in bag.read_messages(raw=True, return_connection_header=True):
            if topic == NODE + "/stones":
                k += 1
                if k == target_k:
                    msg = StoneStates()
                    msg.deserialize(raw[1])
                    msg.pose[list(msg.name).index(first_stone)].position.x += 1e-6
                    out.write(topic, msg, t, connection_header=header)
                    continue
            out.write(topic, raw, t, raw=True, connection_header=header)
    return first_stone


class BagOfAGameTest(unittest.TestCase):
    def test_game_bag_passes_strict_and_a_nudged_stone_fails(self):
        rospy.wait_for_service(NODE + "/place", timeout=60)
        bag = os.path.join(ros_home(), "bag_game.bag")
        for stale in (bag, bag + ".active"):
            if os.path.exists(stale):
                os.remove(stale)
        recorder = subprocess.Popen(["rosbag", "record", "-O", bag] + TOPICS,
                                    start_new_session=True, stdout=subprocess.DEVNULL)
        try:
            deadline = time.monotonic() + 30
            while not recorder_subscribed():
                self.assertLess(time.monotonic(), deadline, "rosbag record did not subscribe")
                time.sleep(0.1)
            replay = subprocess.run(
                ["rosrun", PKG, "sgf_replay", GAME, "--node", NODE, "--to-move", str(MOVES),
                 "--interval", "0.1", "--drop-height", "0.02"],
                capture_output=True, text=True, timeout=120)
            self.assertEqual(replay.returncode, 0, replay.stderr)
            # Until every stone rests, then 1.5 s more: the resting stones' /tf, sent once per
            # simulated second, gets into the bag too.
            time.sleep(0.5)  # the last requests apply at the node's next steps
            last = {}
            sub = rospy.Subscriber(NODE + "/stones", StoneStates, lambda m: last.update(msg=m))
            deadline = time.monotonic() + 60
            while True:
                msg = last.get("msg")
                if msg is not None and len(msg.name) > 1 and all(msg.resting):
                    break
                self.assertLess(time.monotonic(), deadline, "the stones did not come to rest")
                time.sleep(0.1)
            sub.unregister()
            time.sleep(1.5)
        finally:
            # Until `record` itself has closed the bag, not only the `rosbag` wrapper.
            self.assertTrue(interrupt_group(recorder), "rosbag record ignored SIGINT for 30 s")
        self.assertTrue(os.path.isfile(bag), "rosbag did not close " + bag)

        run, seconds = bag_report(bag)
        print("bag_report --strict on %s (%.1f MB): exit %d in %.1f s (wall)"
              % (bag, os.path.getsize(bag) / 1e6, run.returncode, seconds))
        self.assertEqual(run.returncode, 0, run.stdout[-6000:] + run.stderr)
        self.assertIn("stones (", run.stdout)

        nudged = os.path.join(ros_home(), "bag_game_nudged.bag")
        stone = nudged_copy(bag, nudged)
        run, _ = bag_report(nudged)
        self.assertEqual(run.returncode, 1, run.stdout[-6000:] + run.stderr)
        failed = [line for line in run.stdout.splitlines() if line.strip().startswith("FAIL")]
        self.assertTrue(any("rest motion" in line and "stone %s " % stone in line
                            for line in failed), "\n".join(failed) or run.stdout[-3000:])


if __name__ == "__main__":
    rospy.init_node("test_bag_game")
    from catkin.find_in_workspaces import find_in_workspaces
    found = find_in_workspaces(search_dirs=["share"], project=PKG, path="test_data_paths.txt",
                               first_match_only=True)
    if not found:
        sys.exit("test_bag_game: test_data_paths.txt not found in the devel space")
    with open(found[0]) as f:
        GAME = dict(line.split(" ", 1) for line in f.read().splitlines() if line)["game"]
    if not os.path.isfile(GAME):
        sys.exit("test_bag_game: the game record %s is missing (scripts/setup.sh fetches it "
                 "from Debian's kigo package)" % GAME)
    rostest.rosrun(PKG, "bag_game", BagOfAGameTest, sys.argv)
