#!/usr/bin/python3
"""sgf_replay onto the real stone node (board enabled). `rosrun virtual_go sgf_replay` plays the
whole game record (Debian kigo's Honinbo-51-5.sgf, named in test_data_paths.txt) through the
node's ~clear, ~place and ~remove, each stone set down at its point; then the node's ~stones,
read as {point: colour} (~clear took the node's own stone off too), must equal GNU Go's
`list_stones black|white` after `loadsgf` of the same record, stone for stone: 228 stones after
268 moves and 40 captures. The same for GNU Go's self-play games (fixed seeds, made by the
build), whose captures sgf_replay removed must be those GNU Go counts (`captures black|white`)."""
import os
import re
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


REPLAYED = re.compile(r"replayed (\d+) moves: (\d+) stones placed, (\d+) removed")


class SgfReplayNodeTest(unittest.TestCase):
    def replay_onto_node(self, game):
        """Replays `game` onto the node; returns (moves, placed, removed, wall seconds) once the
        node's ~stones equal GNU Go's position for the same record, stone for stone."""
        rospy.wait_for_service("/stone/place", timeout=30)
        started = time.monotonic()
        run = subprocess.run(["rosrun", PKG, "sgf_replay", game, "--node", "/stone",
                              "--interval", "0", "--drop-height", "0"],
                             capture_output=True, text=True, timeout=200)
        replay_s = time.monotonic() - started
        self.assertEqual(run.returncode, 0, run.stderr)
        counts = REPLAYED.search(run.stdout)
        self.assertIsNotNone(counts, run.stdout)
        moves, placed, removed = (int(x) for x in counts.groups())
        expected = fake_test.gnugo_board(game)
        self.assertEqual(len(expected), placed - removed)
        # The requests apply at the node's next steps; ~stones goes out at each change. ~clear
        # took the node's own stone off too: every stone listed is the game's.
        last = {}

        def board():
            msg = last.get("msg")
            if msg is None:
                return None
            return {p: c for p, c in zip(msg.point, msg.color)}

        sub = rospy.Subscriber("/stone/stones", StoneStates, lambda m: last.update(msg=m))
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline and board() != expected:
            time.sleep(0.05)
        sub.unregister()
        got = board()
        self.assertIsNotNone(got, "no ~stones")
        self.assertNotIn("stone", last["msg"].name)  # ~clear took it off
        self.assertEqual(len(last["msg"].name), len(expected))  # one per point, none off the grid
        differ = sorted(p for p in set(got) | set(expected) if got.get(p) != expected.get(p))
        self.assertEqual(differ, [], "node vs GNU Go at those points: %s" %
                         ["%s %s/%s" % (p, got.get(p), expected.get(p)) for p in differ])
        return moves, placed, removed, replay_s

    def test_whole_game_on_the_node_is_gnugos_board(self):
        moves, placed, removed, replay_s = self.replay_onto_node(fake_test.GAME)
        self.assertEqual((moves, placed, removed), (268, 268, 40))
        print("replayed 268 moves onto the node in %.1f s (wall)" % replay_s)

    def test_gnugo_self_play_games_on_the_node_are_gnugos_boards(self):
        # GNU Go's own games (test/go_tests.cmake makes them with fixed seeds): the stones each
        # side captured, as GNU Go counts them, are the stones sgf_replay removed.
        self.assertTrue(SELF_PLAY, "no self-play games named in test_data_paths.txt")
        for game in SELF_PLAY:
            with self.subTest(game=os.path.basename(game)):
                self.assertTrue(os.path.isfile(game), "%s missing (make gnugo_selfplay_games)"
                                % game)
                moves, placed, removed, replay_s = self.replay_onto_node(game)
                _, by_black, by_white = fake_test.gnugo(["loadsgf %s" % game, "captures black",
                                                         "captures white"])
                self.assertEqual(removed, int(by_black) + int(by_white))
                self.assertGreater(removed, 0, "%s has no capture" % game)
                print("%s: %d moves, %d stones placed, %d captured, onto the node in %.1f s "
                      "(wall)" % (os.path.basename(game), moves, placed, removed, replay_s))


SELF_PLAY = []


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
    SELF_PLAY.extend(paths["selfplay"].split())
    if not os.path.isfile(fake_test.GAME):
        sys.exit("test_sgf_replay_node: the game record %s is missing (scripts/setup.sh "
                 "fetches it from Debian's kigo package)" % fake_test.GAME)
    rostest.rosrun(PKG, "sgf_replay_node", SgfReplayNodeTest, sys.argv)
