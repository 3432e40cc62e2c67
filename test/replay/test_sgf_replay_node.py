#!/usr/bin/python3
"""sgf_replay onto the real stone node (board enabled). `rosrun virtual_go sgf_replay` plays the
whole game record (Debian kigo's Honinbo-51-5.sgf, named in test_data_paths.txt) through the
node's ~clear, ~place and ~remove, each stone set down at its point; then the node's ~stones,
read as {point: colour} over the placed stones (the initial stone `stone` of the single-stone
interface is not part of the game), must equal GNU Go's `list_stones black|white` after
`loadsgf` of the same record, stone for stone: 228 stones after 268 moves and 40 captures."""
import os
import subprocess
import sys
import time
import unittest

import rospy
import rostest
from virtual_go.msg import StoneStates

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import test_sgf_replay as fake_test  # noqa: E402  (GNU Go's board: gnugo_board)

PKG = "virtual_go"


class SgfReplayNodeTest(unittest.TestCase):
    def test_whole_game_on_the_node_is_gnugos_board(self):
        rospy.wait_for_service("/stone/place", timeout=30)
        started = time.monotonic()
        run = subprocess.run(["rosrun", PKG, "sgf_replay", fake_test.GAME, "--node", "/stone",
                              "--interval", "0", "--drop-height", "0"],
                             capture_output=True, text=True, timeout=200)
        replay_s = time.monotonic() - started
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertIn("replayed 268 moves: 268 stones placed, 40 removed", run.stdout)
        expected = fake_test.gnugo_board(fake_test.GAME)
        self.assertEqual(len(expected), 268 - 40)
        # The requests apply at the node's next steps; ~stones goes out at each change.
        last = {}

        def board():
            msg = last.get("msg")
            if msg is None:
                return None
            return {p: c for n, p, c in zip(msg.name, msg.point, msg.color) if n != "stone"}

        sub = rospy.Subscriber("/stone/stones", StoneStates, lambda m: last.update(msg=m))
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and board() != expected:
            time.sleep(0.05)
        sub.unregister()
        got = board()
        self.assertIsNotNone(got, "no ~stones")
        placed = [n for n in last["msg"].name if n != "stone"]
        self.assertEqual(len(placed), len(expected))  # one stone per point, none off the grid
        differ = sorted(p for p in set(got) | set(expected) if got.get(p) != expected.get(p))
        self.assertEqual(differ, [], "node vs GNU Go at those points: %s" %
                         ["%s %s/%s" % (p, got.get(p), expected.get(p)) for p in differ])
        print("replayed 268 moves onto the node in %.1f s (wall)" % replay_s)


if __name__ == "__main__":
    rospy.init_node("test_sgf_replay_node")
    from catkin.find_in_workspaces import find_in_workspaces
    found = find_in_workspaces(search_dirs=["share"], project=PKG, path="test_data_paths.txt",
                               first_match_only=True)
    if not found:
        sys.exit("test_sgf_replay_node: test_data_paths.txt not found in the devel space")
    with open(found[0]) as f:
        paths = dict(line.split(" ", 1) for line in f.read().splitlines() if line)
    fake_test.GAME, fake_test.GNUGO = paths["game"], paths["gnugo"]
    if not os.path.isfile(fake_test.GAME):
        sys.exit("test_sgf_replay_node: the game record %s is missing (scripts/setup.sh "
                 "fetches it from Debian's kigo package)" % fake_test.GAME)
    rostest.rosrun(PKG, "sgf_replay_node", SgfReplayNodeTest, sys.argv)
