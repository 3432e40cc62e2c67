#!/usr/bin/python3
"""README.md, pasted: runs the README's commands the way a user types them, in the order the
README gives them, against the master of this rostest, and fails when one stops working.

Every line of a ```bash block is run through bash, from a scratch directory (the directory
"you launched from"). A `roslaunch` line stands for the first terminal: it keeps running, as
long as the following lines need it, until the next `roslaunch` line stops it with Ctrl-C
(SIGINT to its process group). Each other line is checked by what it is:

- `rosrun PKG EXE --help`: exit 0, prints a usage;
- `rostopic echo -n 1 TOPIC`: exit 0, prints a message (a missing Python message module makes
  rostopic fail with "Cannot load message class"); a `MESH_RESOURCE` names a file that exists;
- `rostopic echo TOPIC` and `tf_echo ... RATE`: run a few seconds then Ctrl-C; they print
  messages; tf_echo's poses differ from line to line (the motion shows);
- `rosservice call /stone/...`: exit 0, `success: True`, and one second later the latest
  segment on /stone/events is still the one this call started (the scene does not undo it; for
  `place`, or the `rest` of the stone it named, which a set-down stone makes at once; for
  `place`, `remove` and `clear` among the segments of placed stones, not the node's own); a
  `set_state` or `set_angular_velocity` naming a placed stone has started a segment of that
  stone (the physics goes on from it: a lifted stone falls);
  the simulation controls instead by what they do to the stone's /tf stamps: after `pause` none
  comes, after `step "ticks: N"` (`success: True`) exactly one more, N * dt later, and after
  `unpause` they go on, from a `time_jump` event with detail `unpaused`;
- `rosrun virtual_go stone_node ...` (not --help) stands for the first terminal as a
  `roslaunch` line does (the one before is stopped), until it publishes its start event;
- `rosrun virtual_go bag_report ...`: exit 0 (with --strict 0 or 1, as the README says); its
  --csv and --plot files exist;
- `rosbag info BAG`, `rosbag check BAG`: exit 0; check finds no type that needs a migration;
- `rosbag record -O BAG ...` stands for another terminal: it keeps running (recording what the
  following lines do) until a line reads a bag, starts a node or the README ends, which stops it
  with Ctrl-C; BAG must then exist;
- `rosrun virtual_go sgf_replay GAME ...` (not --help): exit 0 within GAME_TIMEOUT_S, and it says
  it replayed the game;
- `rostopic pub ... /clicked_point ...` (rviz's Publish Point, typed): exit 0, and within a
  second a `place` segment of a new placed stone;
- `source FILE`: the file exists (the test itself runs in that environment).

`roslaunch` lines of other blocks (lists of variants, some with rviz) are loaded with
`roslaunch --nodes`: the package, the launch file, its arguments and files must resolve.
A bash line of another kind fails the test: every command the README gives is checked.

The README must keep showing: both --help lines, a recorded game replayed with sgf_replay, a
click on /clicked_point, `rostopic echo -n 1` on every topic the live
node publishes and a `rosservice call` of every service it offers (both taken from the master
while the node runs), a tf_echo live and during a replay, a record and a replay launch. Last, a
live launch after the replay must publish (a `use_sim_time` left behind would silence it).
"""
import os
import re
import shlex
import subprocess
import sys
import tempfile
import time
import unittest

import rosgraph
import rospkg
import rospy
import rostest
import yaml
from tf2_msgs.msg import TFMessage
from virtual_go.msg import StoneEvent, StoneInfo

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))
from process_group import interrupt_group  # noqa: E402  (test/support, beside this folder)

PKG = "virtual_go"
NODE = "/stone"
TIMEOUT_S = 30.0  # for a command that should finish by itself
STREAM_S = 4.0  # how long a streaming command runs before Ctrl-C
LAUNCH_MIN_S = 8.0  # a launch runs at least this long (a recording then holds several seconds)
GAME_TIMEOUT_S = 180.0  # sgf_replay of a whole game, at the README's interval
# Services every node has; not the README's business.
ROS_SERVICES = ("get_loggers", "set_logger_level")
# The simulation controls: checked by their effect on /tf, not by an event of their name.
CONTROLS = ("pause", "unpause", "step")
SETTLE_S = 0.5  # a timer tick under way when a control lands, and the ticks a step takes


def readme_blocks(path):
    """[(language, first line number, [lines])] of the fenced blocks of a Markdown file."""
    blocks, current = [], None
    with open(path) as f:
        for number, line in enumerate(f, 1):
            line = line.rstrip("\n")
            if line.startswith("```"):
                if current is None:
                    current = (line[3:].strip(), number + 1, [])
                else:
                    blocks.append(current)
                    current = None
            elif current is not None:
                current[2].append(line)
    return blocks


def words(line):
    return shlex.split(line, comments=True)


class Process:
    """A command run through bash in its own process group, like a terminal's foreground job."""

    def __init__(self, line, cwd, env, log):
        self.line = line
        self.log = log
        self.out = open(log, "w+")
        self.process = subprocess.Popen(["bash", "-c", line], cwd=cwd, env=env, stdout=self.out,
                                        stderr=subprocess.STDOUT, start_new_session=True)

    def ctrl_c(self, timeout_s=20.0):
        # The whole job ends, not only bash: `rosbag record`'s wrapper exits before `record` has
        # closed the bag.
        interrupt_group(self.process, timeout_s)
        return self.output()

    def wait(self, timeout_s):
        try:
            self.process.wait(timeout=timeout_s)
        except subprocess.TimeoutExpired:
            self.ctrl_c()
            raise
        return self.output()

    def output(self):
        self.out.flush()
        with open(self.log, errors="replace") as f:
            return f.read()


class ReadmeCommandsTest(unittest.TestCase):
    def setUp(self):
        self.root = rospkg.RosPack().get_path(PKG)
        self.readme = os.path.join(self.root, "README.md")
        self.folder = tempfile.mkdtemp(prefix="readme_", dir=os.environ.get("ROS_HOME"))
        # The user's shell: this environment (the devel space sourced), in the scratch folder.
        self.env = dict(os.environ, PWD=self.folder)
        self.master = rosgraph.Master("/readme_commands_test")
        self.terminal = None  # the running roslaunch line
        self.recorder = None  # a running `rosbag record` line, and the bag it writes
        self.recorded_bag = None
        self.terminal_started = 0.0
        self.launch_lines = []  # bash-block roslaunch lines, in order
        self.count = 0
        self.line_number = 0
        self.since = 0.0
        self.ran = []  # (kind, line) of every checked line
        self.node_topics, self.node_services = set(), set()
        self.events = []
        rospy.Subscriber(NODE + "/events", StoneEvent, self.events.append, queue_size=100)
        self.tf_stamp = 0  # ns, of the latest /tf of the stone
        self.paused_stamp = None
        rospy.Subscriber("/tf", TFMessage, self.on_tf, queue_size=100)

    def on_tf(self, message):
        for t in message.transforms:
            if t.child_frame_id == "stone":
                self.tf_stamp = t.header.stamp.to_nsec()

    def tearDown(self):
        if self.recorder:
            self.recorder.ctrl_c()
        if self.terminal:
            self.terminal.ctrl_c()

    def where(self, line):
        return "README.md line %d: %s" % (self.line_number, line)

    def run_line(self, line):
        self.count += 1
        return Process(line, self.folder, self.env,
                       os.path.join(self.folder, "command_%02d.log" % self.count))

    def finish(self, line, allowed=(0,)):
        process = self.run_line(line)
        try:
            output = process.wait(TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self.fail("%s: did not finish in %.0f s" % (self.where(line), TIMEOUT_S))
        self.assertIn(process.process.returncode, allowed,
                      "%s: exit %d:\n%s" % (self.where(line), process.process.returncode, output))
        return output

    def stream(self, line):
        process = self.run_line(line)
        time.sleep(STREAM_S)
        self.assertIsNone(process.process.poll(), "%s: ended early:\n%s" %
                          (self.where(line), process.output()))
        return process.ctrl_c()

    # ---- the kinds of line ----

    def check_source(self, argv, line):
        path = argv[1] if os.path.isabs(argv[1]) else os.path.join(self.root, argv[1])
        self.assertTrue(os.path.exists(path), "%s: no such file" % self.where(line))

    def check_help(self, argv, line):
        output = self.finish(line)
        self.assertTrue(output.lstrip().startswith("usage"), "%s:\n%s" % (self.where(line), output))

    def check_echo_once(self, argv, line):
        output = self.finish(line)
        self.assertIn("---", output, "%s: no message:\n%s" % (self.where(line), output))
        self.assertNotIn("ERROR", output, self.where(line))
        for uri in re.findall(r'mesh_resource: "file://([^"]+)"', output):
            self.assertTrue(os.path.exists(uri), "%s: mesh %s missing" % (self.where(line), uri))

    def check_echo_stream(self, argv, line):
        output = self.stream(line)
        self.assertIn("---", output, "%s: no message:\n%s" % (self.where(line), output))
        self.assertNotIn("ERROR", output, self.where(line))

    def check_tf_echo(self, argv, line):
        output = self.stream(line)
        number = r"-?[0-9.]+(?:e[-+]?[0-9]+)?"
        vector = r"\[%s\]" % ", ".join([number] * 3)
        quaternion = r"\[%s\]" % ", ".join([number] * 4)
        poses = re.findall(r"Translation: (%s)\s*- Rotation: in Quaternion (%s)" %
                           (vector, quaternion), output)
        self.assertGreaterEqual(len(poses), 3, "%s: fewer than 3 poses:\n%s" %
                                (self.where(line), output))
        distinct = len(set(poses))
        self.assertGreaterEqual(distinct, 3, "%s: the stone does not seem to move (%d distinct "
                                "poses of %d):\n%s" % (self.where(line), distinct, len(poses),
                                                       output))

    def check_service(self, argv, line):
        service = argv[2]
        self.assertTrue(service.startswith(NODE + "/"), self.where(line))
        reason = service[len(NODE) + 1:]
        seen = len(self.events)
        output = self.finish(line)
        self.assertIn("success: True", output, "%s:\n%s" % (self.where(line), output))
        # The change starts a segment named after it, and nothing undoes it a second later.
        time.sleep(1.0)
        self.assertTrue(self.events, "%s: no /stone/events" % self.where(line))
        latest = self.events[-1]
        request = yaml.safe_load(argv[3]) if len(argv) > 3 else None
        named = request.get("name") if isinstance(request, dict) else None
        if reason in ("set_state", "set_angular_velocity") and named:
            # A named stone on the board: the change starts a segment of that stone, which the
            # physics then goes on from (a lifted stone falls, a spinning one slows).
            mine = [e.reason for e in self.events[seen:] if e.stone == named]
            self.assertIn(reason, mine, "%s: no `%s` segment of %s: %s"
                          % (self.where(line), reason, named, mine))
            return
        if reason in ("place", "remove", "clear"):
            # Placed stones: the node's own stone (named after its frame, `stone`) may still be
            # settling from its toss; its segments are not the call's.
            placed = [e for e in self.events if e.stone and e.stone != "stone"]
            self.assertTrue(placed, "%s: no segment of a placed stone" % self.where(line))
            latest = placed[-1]
        if reason == "place":
            # A stone set down rests at the instant it is placed: the latest segment is then its
            # own `rest`, which keeps the placement.
            named = [l.split(":", 1)[1].strip().strip('"') for l in output.splitlines()
                     if l.startswith("name:")]
            self.assertTrue(named and named[0], "%s: ~place named no stone:\n%s"
                            % (self.where(line), output))
            if latest.reason == "rest":
                self.assertEqual(latest.stone, named[0], "%s: the latest segment is a `rest` of "
                                 "%s, not of the placed %s" % (self.where(line), latest.stone,
                                                                named[0]))
                return
        self.assertEqual(latest.reason, reason, "%s: one second later the current segment is "
                         "`%s`, not `%s`: the scene undid the call"
                         % (self.where(line), latest.reason, reason))

    def check_control(self, argv, line):
        name = argv[2].rsplit("/", 1)[1]
        output = self.finish(line)
        where = "%s:\n%s" % (self.where(line), output)
        time.sleep(SETTLE_S)
        if name == "pause":
            self.paused_stamp = self.tf_stamp
            time.sleep(1.0)
            self.assertEqual(self.tf_stamp, self.paused_stamp, "%s: /tf goes on" % where)
        elif name == "step":
            self.assertIn("success: True", output, where)
            self.assertIsNotNone(self.paused_stamp, "%s: step before pause" % where)
            ticks = yaml.safe_load(argv[3])["ticks"]
            dt_ns = rospy.wait_for_message(NODE + "/info", StoneInfo, timeout=5.0).dt_ns
            self.assertEqual(self.tf_stamp - self.paused_stamp, ticks * dt_ns,
                             "%s: /tf is not %d ticks after the pause" % (where, ticks))
            self.paused_stamp = self.tf_stamp
            time.sleep(1.0)
            self.assertEqual(self.tf_stamp, self.paused_stamp, "%s: /tf goes on" % where)
        else:
            before = self.tf_stamp
            time.sleep(1.0)
            self.assertGreater(self.tf_stamp, before, "%s: /tf does not go on" % where)
            latest = self.events[-1] if self.events else None
            self.assertTrue(latest and latest.reason == "time_jump" and
                            latest.detail == "unpaused", "%s: no time_jump unpaused" % where)

    def run_node(self, argv, line):
        self.stop_terminal()
        seen = len(self.events)
        self.terminal = self.run_line(line)
        self.terminal_started = time.time()
        deadline = time.time() + TIMEOUT_S
        while time.time() < deadline and not any(e.reason == "start"
                                                 for e in self.events[seen:]):
            self.assertIsNone(self.terminal.process.poll(), "%s: ended:\n%s" %
                              (self.where(line), self.terminal.output()))
            time.sleep(0.1)
        self.assertTrue(any(e.reason == "start" for e in self.events[seen:]),
                        "%s: the node published no start event in %.0f s" %
                        (self.where(line), TIMEOUT_S))
        publishers, _, services = self.master.getSystemState()
        self.node_topics |= set(t for t, n in publishers if NODE in n and t != "/rosout")
        self.node_services |= set(s for s, n in services if NODE in n and
                                  s.rsplit("/", 1)[1] not in ROS_SERVICES)

    def check_bag_report(self, argv, line):
        output = self.finish(line, (0, 1) if "--strict" in argv else (0,))
        self.assertTrue(output.strip(), "%s: no output" % self.where(line))
        for option in ("--csv", "--plot"):
            if option in argv:
                path = os.path.join(self.folder, argv[argv.index(option) + 1])
                self.assertTrue(os.path.getsize(path) > 0, "%s: no %s" % (self.where(line), path))

    def check_rosbag(self, argv, line):
        output = self.finish(line)
        if argv[1] == "check":  # a type without its Python module needs a "migration"
            self.assertIn("does not need any migrations", output, self.where(line))
        else:
            self.assertIn("/stone/marker", output, self.where(line))

    def check_record(self, argv, line):
        self.stop_recorder()
        self.assertIn("-O", argv, "%s: name the bag with -O" % self.where(line))
        bag = argv[argv.index("-O") + 1]
        self.recorded_bag = os.path.join(self.folder, bag if bag.endswith(".bag") else bag + ".bag")
        self.recorder = self.run_line(line)
        self.recorder_line = (self.line_number, line)
        time.sleep(2.0)  # subscribed before the next line acts
        self.assertIsNone(self.recorder.process.poll(), "%s: ended early:\n%s"
                          % (self.where(line), self.recorder.output()))

    def stop_recorder(self):
        if not self.recorder:
            return
        output = self.recorder.ctrl_c()
        self.recorder = None
        number, line = self.recorder_line
        self.assertTrue(os.path.exists(self.recorded_bag), "README.md line %d: %s: no %s after "
                        "Ctrl-C:\n%s" % (number, line, self.recorded_bag, output))

    def check_game(self, argv, line):
        process = self.run_line(line)
        try:
            output = process.wait(GAME_TIMEOUT_S)
        except subprocess.TimeoutExpired:
            self.fail("%s: did not finish in %.0f s" % (self.where(line), GAME_TIMEOUT_S))
        self.assertEqual(process.process.returncode, 0, "%s: exit %d:\n%s"
                         % (self.where(line), process.process.returncode, output))
        self.assertIn("replayed", output, "%s:\n%s" % (self.where(line), output))

    def check_click(self, argv, line):
        placed_before = set(e.stone for e in self.events if e.reason == "place")
        output = self.finish(line)
        deadline = time.time() + 2.0
        while time.time() < deadline:
            new = set(e.stone for e in self.events if e.reason == "place") - placed_before
            if new:
                return
            time.sleep(0.1)
        self.fail("%s: no stone placed within 2 s:\n%s" % (self.where(line), output))

    def check_launch_loads(self, argv, line):
        nodes = self.finish(line.replace("roslaunch", "roslaunch --nodes", 1))
        self.assertTrue(nodes.strip(), "%s: starts no node" % self.where(line))

    def launch(self, argv, line):
        self.stop_terminal()
        nodes = self.finish(line.replace("roslaunch", "roslaunch --nodes", 1)).split()
        self.terminal = self.run_line(line)
        self.terminal_started = time.time()
        self.launch_lines.append(line)
        deadline = time.time() + TIMEOUT_S
        while time.time() < deadline:
            running = set(n for _, names in self.registrations() for n in names)
            if all(n in running for n in nodes):
                break
            self.assertIsNone(self.terminal.process.poll(), "%s: ended:\n%s" %
                              (self.where(line), self.terminal.output()))
            time.sleep(0.2)
        else:
            self.fail("%s: nodes %s did not all start" % (self.where(line), nodes))
        if NODE in nodes:
            self.wait_for_node(line)
            publishers, _, services = self.master.getSystemState()
            self.node_topics |= set(t for t, n in publishers if NODE in n and t != "/rosout")
            self.node_services |= set(s for s, n in services if NODE in n and
                                      s.rsplit("/", 1)[1] not in ROS_SERVICES)

    def wait_for_node(self, line):
        # Started: the node announced a segment since the launch (it needs a running clock for
        # that). Not necessarily `start`: ~events is latched with its last message, and a scene
        # that settles within the first ticks (game.launch: the node's stone set down on the
        # table) has published start, impacts and rest before this subscriber is connected.
        deadline = time.time() + TIMEOUT_S
        while time.time() < deadline and not any(e.header.stamp.to_sec() > self.since
                                                  for e in self.events):
            time.sleep(0.1)
        self.assertTrue(any(e.header.stamp.to_sec() > self.since for e in self.events),
                        "%s: the node published no event in %.0f s" %
                        (self.where(line), TIMEOUT_S))

    def registrations(self):
        """(topic or service, [node]) for every publication, subscription and service."""
        for kind in self.master.getSystemState():
            yield from kind

    def stop_terminal(self):
        self.stop_recorder()
        if self.terminal:
            remaining = LAUNCH_MIN_S - (time.time() - self.terminal_started)
            if remaining > 0:
                time.sleep(remaining)
            self.terminal.ctrl_c()
            self.terminal = None

    # ---- the walk ----

    def classify(self, argv):
        if argv[0] == "source":
            return "source"
        if argv[0] == "roslaunch":
            return "launch"
        if argv[-1] in ("--help", "-h") and argv[0] == "rosrun":
            return "help"
        if argv[:2] == ["rostopic", "echo"]:
            return "echo_once" if "-n" in argv else "echo_stream"
        if argv[:2] == ["rosservice", "call"]:
            return "control" if argv[2].rsplit("/", 1)[-1] in CONTROLS else "service"
        if argv[:3] == ["rosrun", PKG, "stone_node"]:
            return "node"
        if argv[0].endswith("tf_echo") or argv[:3] == ["rosrun", "tf", "tf_echo"]:
            return "tf_echo"
        if argv[:3] == ["rosrun", PKG, "bag_report"]:
            return "bag_report"
        if argv[:2] in (["rosbag", "info"], ["rosbag", "check"]):
            return "rosbag"
        if argv[:2] == ["rosbag", "record"]:
            return "record"
        if argv[:3] == ["rosrun", PKG, "sgf_replay"]:
            return "game"
        if argv[:2] == ["rostopic", "pub"] and "/clicked_point" in argv:
            return "click"
        return None

    def test_readme_commands_work_as_written(self):
        blocks = readme_blocks(self.readme)
        self.assertTrue(blocks, "no code blocks in README.md")
        replaying = False
        for language, first, lines in blocks:
            for offset, line in enumerate(lines):
                self.line_number = first + offset
                if language != "bash":  # lists, layouts, output: only roslaunch lines load
                    if line.split()[:1] == ["roslaunch"]:
                        self.check_launch_loads(words(line), line)
                        self.ran.append(("launch_loads", line))
                    continue
                argv = words(line)
                if not argv:
                    continue
                kind = self.classify(argv)
                self.assertIsNotNone(kind, "%s: a command this test does not know how to check"
                                     % self.where(line))
                if kind == "launch":
                    self.since = time.time() - 1.0
                    self.launch(argv, line)
                    replaying = "replay.launch" in line
                    kind = "replay" if replaying else "launch"
                elif kind == "node":
                    self.run_node(argv, line)
                    replaying = False
                else:
                    if kind in ("bag_report", "rosbag"):
                        self.stop_recorder()  # the bag is read: the recording ends first
                    getattr(self, "check_" + kind)(argv, line)
                    if kind == "tf_echo" and replaying:
                        kind = "tf_echo_replay"
                self.ran.append((kind, line))
        self.stop_terminal()

        kinds = [k for k, _ in self.ran]
        for kind in ("help", "service", "control", "node", "echo_once", "tf_echo",
                     "tf_echo_replay", "replay", "bag_report", "rosbag", "record", "game",
                     "click"):
            self.assertIn(kind, kinds, "README.md has no runnable %s line" % kind)
        helped = " ".join(line for k, line in self.ran if k == "help")
        for exe in ("stone_node", "bag_report"):
            self.assertIn("virtual_go %s --help" % exe, helped)
        self.assertIn("record:=true", " ".join(line for k, line in self.ran if k == "launch"))
        echoed = set(words(line)[-1] for k, line in self.ran if k == "echo_once")
        self.assertTrue(self.node_topics, "no live node seen")
        self.assertEqual(sorted(self.node_topics - echoed), [],
                         "topics of the node without a `rostopic echo -n 1` line in README.md")
        called = set(words(line)[2] for k, line in self.ran if k in ("service", "control"))
        self.assertEqual(sorted(self.node_services - called), [],
                         "services of the node without a `rosservice call` line in README.md")

        # After the replay: the first live launch line again must publish, whatever the
        # replay left on the master.
        live = next(line for line in self.launch_lines if "replay.launch" not in line)
        self.line_number = 0
        self.since = time.time() - 1.0
        self.launch(words(live), live)
        output = self.finish("rostopic echo -n 1 /tf")
        self.assertIn("child_frame_id: \"stone\"", output, "no /tf after the replay")
        self.stop_terminal()


if __name__ == "__main__":
    rospy.init_node("readme_commands_test", disable_signals=True)
    rostest.rosrun(PKG, "readme_commands", ReadmeCommandsTest, sys.argv)
