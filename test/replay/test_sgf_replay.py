#!/usr/bin/python3
"""sgf_replay, the executable, against a stand-in for the stone node (labelled as such: the
node's ~place and ~remove are not written yet). This test is the stand-in: it serves
/fake_board/clear (std_srvs/Trigger), /fake_board/place (virtual_go/PlaceStone) and
/fake_board/remove (virtual_go/RemoveStone), records every call, and keeps the board the calls
leave (point -> colour). It runs `rosrun virtual_go sgf_replay` as a user would and checks:
the calls come in order (clear first, one place per move, in the order of GNU Go's move_history,
removes naming stones the place calls created and not yet removed); the board left equals GNU
Go's `list_stones` for the same record (the whole game, and --to-move); a malformed record calls
nothing and names the line; missing services are named; a refused call stops the replay.

The game record (Debian kigo's Honinbo-51-5.sgf) and the gnugo executable are named in
test_data_paths.txt, which test/replay_tests.cmake writes into the devel space."""
import os
import subprocess
import sys
import tempfile
import threading
import unittest

import rospy
import rostest
from std_srvs.srv import Trigger, TriggerResponse
from virtual_go.srv import PlaceStone, PlaceStoneResponse, RemoveStone, RemoveStoneResponse

PKG = "virtual_go"
GAME = None
GNUGO = None


def gnugo(commands):
    """GNU Go's answers (without '= ') to GTP commands, in order."""
    run = subprocess.run([GNUGO, "--mode", "gtp"], input="\n".join(commands) + "\nquit\n",
                         capture_output=True, text=True, timeout=60, check=True)
    answers = [a.strip() for a in run.stdout.split("\n\n") if a.strip()]
    for a in answers:
        if not a.startswith("="):
            raise RuntimeError("GNU Go: " + a)
    return [a[1:].strip() for a in answers][:len(commands)]


def gnugo_board(path, before_move=None):
    """{point: colour} of GNU Go's position for `loadsgf path [before_move]`."""
    load = "loadsgf %s" % path + ("" if before_move is None else " %d" % before_move)
    _, black, white = gnugo([load, "list_stones black", "list_stones white"])
    board = {p: "black" for p in black.split()}
    board.update({p: "white" for p in white.split()})
    return board


class FakeBoard:
    """The stand-in node's services and what they leave on the board."""

    def __init__(self):
        self.lock = threading.Lock()
        self.reset()
        rospy.Service("/fake_board/clear", Trigger, self.clear)
        rospy.Service("/fake_board/place", PlaceStone, self.place)
        rospy.Service("/fake_board/remove", RemoveStone, self.remove)

    def reset(self, refuse_place=0):
        with getattr(self, "lock", threading.Lock()):
            self.calls = []
            self.stones = {}  # name -> (point, colour)
            self.made = 0
            self.places = 0
            self.refuse_place = refuse_place  # refuse the n-th place (1-based); 0: never

    def clear(self, _):
        with self.lock:
            self.calls.append(("clear",))
            self.stones.clear()
        return TriggerResponse(success=True, message="cleared")

    def place(self, req):
        with self.lock:
            self.calls.append(("place", req.point, req.color, req.drop_height))
            self.places += 1
            if self.places == self.refuse_place:
                return PlaceStoneResponse(success=False, message="refused by the stand-in")
            self.made += 1
            name = "stone_%d" % self.made
            self.stones[name] = (req.point, req.color)
        return PlaceStoneResponse(success=True, message="placed", name=name)

    def remove(self, req):
        with self.lock:
            self.calls.append(("remove", req.name))
            if req.name not in self.stones:
                return RemoveStoneResponse(success=False, message="no stone " + req.name)
            del self.stones[req.name]
        return RemoveStoneResponse(success=True, message="removed")

    def board(self):
        with self.lock:
            return {point: colour for point, colour in self.stones.values()}


def sgf_replay(*args, timeout=180):
    return subprocess.run(["rosrun", PKG, "sgf_replay"] + list(args), capture_output=True,
                          text=True, timeout=timeout)


class SgfReplayTest(unittest.TestCase):
    fake = None

    @classmethod
    def setUpClass(cls):
        cls.fake = FakeBoard()

    def setUp(self):
        self.fake.reset()

    def test_whole_game_leaves_gnugos_board(self):
        run = sgf_replay(GAME, "--node", "/fake_board", "--interval", "0",
                         "--drop-height", "0.02")
        self.assertEqual(run.returncode, 0, run.stderr)
        calls = self.fake.calls
        self.assertEqual(calls[0], ("clear",))
        self.assertEqual(calls.count(("clear",)), 1)
        places = [c for c in calls if c[0] == "place"]
        removes = [c for c in calls if c[0] == "remove"]
        # The main line's 268 moves, each dropped from 2 cm; the 40 captured stones taken off.
        self.assertEqual(len(places), 268)
        self.assertEqual(len(removes), 40)
        self.assertTrue(all(c[3] == 0.02 for c in places))
        # In the order of the main line as GNU Go reads it (move_history lists the last first).
        history = gnugo(["loadsgf " + GAME, "move_history"])[1].splitlines()
        moves = [tuple(line.split()) for line in reversed(history)]
        self.assertEqual([(c[2], c[1]) for c in places], moves)
        # Every remove named a stone that was on the board (the stand-in refuses others).
        self.assertNotIn("failed", run.stderr)
        self.assertEqual(self.fake.board(), gnugo_board(GAME))
        self.assertIn("replayed 268 moves: 268 stones placed, 40 removed", run.stdout)

    def test_to_move_stops_there(self):
        run = sgf_replay(GAME, "--node", "/fake_board", "--interval", "0", "--to-move", "150")
        self.assertEqual(run.returncode, 0, run.stderr)
        self.assertEqual(len([c for c in self.fake.calls if c[0] == "place"]), 150)
        self.assertEqual(self.fake.board(), gnugo_board(GAME, 151))  # GNU Go: before move 151
        run = sgf_replay(GAME, "--node", "/fake_board", "--to-move", "269")
        self.assertEqual(run.returncode, 3)
        self.assertIn("--to-move 269: %s has 268 moves" % GAME, run.stderr)

    def test_malformed_record_calls_nothing(self):
        with tempfile.NamedTemporaryFile("w", suffix=".sgf", delete=False) as f:
            f.write("(;FF[4]GM[1]SZ[19]\n;B[pd];W[dd]\n;B[pq];W[zz])\n")
        try:
            run = sgf_replay(f.name, "--node", "/fake_board", "--interval", "0")
        finally:
            os.remove(f.name)
        self.assertEqual(run.returncode, 3)
        self.assertIn(f.name + ":3:9: W[zz]: 'zz' is not a point", run.stderr)
        self.assertIn("nothing was placed", run.stderr)
        self.assertEqual(self.fake.calls, [])

    def test_missing_services_are_named(self):
        run = sgf_replay(GAME, "--node", "/nobody", "--timeout", "1")
        self.assertEqual(run.returncode, 4)
        for service in ("/nobody/clear", "/nobody/place", "/nobody/remove"):
            self.assertIn(service, run.stderr)
        self.assertEqual(self.fake.calls, [])

    def test_refused_place_stops_the_replay(self):
        self.fake.reset(refuse_place=10)
        run = sgf_replay(GAME, "--node", "/fake_board", "--interval", "0")
        self.assertEqual(run.returncode, 1)
        self.assertIn("move 10 (line 4): white", run.stderr)
        self.assertIn("failed: refused by the stand-in", run.stderr)
        self.assertEqual(self.fake.calls[-1][0], "place")  # nothing after the refused call
        self.assertEqual(len([c for c in self.fake.calls if c[0] == "place"]), 10)

    def test_help_and_bad_options(self):
        run = sgf_replay("--help")
        self.assertEqual(run.returncode, 0)
        self.assertIn("usage: rosrun virtual_go sgf_replay GAME.sgf", run.stdout)
        run = sgf_replay(GAME, "--interval", "-1")
        self.assertEqual(run.returncode, 2)
        self.assertIn("--interval '-1': must be between 0 and 3600", run.stderr)


if __name__ == "__main__":
    rospy.init_node("test_sgf_replay")
    from catkin.find_in_workspaces import find_in_workspaces
    found = find_in_workspaces(search_dirs=["share"], project=PKG, path="test_data_paths.txt",
                               first_match_only=True)
    if not found:
        sys.exit("test_sgf_replay: test_data_paths.txt not found in the devel space "
                 "(configure with tests enabled)")
    with open(found[0]) as f:
        paths = dict(line.split(" ", 1) for line in f.read().splitlines() if line)
    GAME, GNUGO = paths["game"], paths["gnugo"]
    if not os.path.isfile(GAME):
        sys.exit("test_sgf_replay: the game record %s is missing (scripts/setup.sh fetches it "
                 "from Debian's kigo package)" % GAME)
    rostest.rosrun(PKG, "sgf_replay", SgfReplayTest, sys.argv)
