#!/usr/bin/python3
"""Seeded service fuzz of the real stone_node on the board scene (issue 19's "done when").

Starts a roscore on a private port, loads config/stone.yaml into /stone, starts
`rosrun virtual_go stone_node __name:=stone`, fires seeded random calls at /stone/set_state,
/stone/set_angular_velocity and /stone/reset (paced calls and bursts of back-to-back calls;
states on the board, the table, its edges and sides, in flight; tiny and denormal components,
spins up to ~max_angular_velocity, absurd-but-finite and invalid values) and measures:

  stalls        the largest gap between consecutive /stone/pose messages (wall time of
                arrival) and the longest service response; gaps over --stall-s are counted
  false applied an accepted call whose own ~events message (same reason, in call order,
                arriving after the call was sent) never arrives, or that a `held` event follows
  held          `held` events
  SIGINT        wall time from SIGINT to the node's exit: once mid-burst on the 500 rad/s spin
                scene (~initial/angular_velocity [0, 0, 500]) and once at the end of the fuzz

Exit status 0 when every "done when" figure holds (0 stalls, 0 false applied, 0 held, every
SIGINT exit under 1 s), 1 otherwise. Needs the devel space sourced
(`source build_catkin/devel/setup.bash`) and python3 from /usr/bin (rospy). Run from the
repository root:  scripts/service_fuzz.py --calls 2400 --seed 1
"""

import argparse
import math
import os
import random
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

# Stone size 33 of config/stone.yaml: 9.2 mm thick, 22 mm wide.
HALF_HEIGHT_M = 0.0046
RADIUS_M = 0.011
DENORMALS = [5e-324, -5e-324, 2.2e-308, -1e-310, 1e-300, -1e-300, 1e-200, -1e-200, 1e-160]
# The issue's reproductions 1 and 2 (position, orientation xyzw, velocity, angular velocity).
ISSUE_STATES = [
    ((0.0, 0.0, 0.0046), (0, 0, 0, 1), (0.0, 0.0, -1.0e-300), (0, 0, 0)),
    ((0.12893891187898582, 0.5796630466403868, -0.1469),
     (0, 0, -0.761761390444585, 0.6478576880981907),
     (0.6701816734748083, -0.7221209988260908, -0.5072551328940269),
     (-128.07336588560432, -97.25579954563787, 64.34073791755785)),
    ((0.06329200445817529, 0.18126251172692187, 0.2046), (0, 0, 0.031737043719820196,
                                                          0.9994962531475174),
     (0, 0, 0), (-72.31305689267572, -25.286227209648988, -10.85487149189666)),
]


def free_port():
    with socket.socket() as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


class Node:
    """The stone_node process, its log in a file."""

    def __init__(self, env, log_path):
        self.log = open(log_path, "w")
        self.proc = subprocess.Popen(["rosrun", "virtual_go", "stone_node", "__name:=stone"],
                                     env=env, stdout=self.log, stderr=subprocess.STDOUT)

    def sigint_exit_s(self, limit_s=10.0):
        """Sends SIGINT; returns the wall time until the process exits (None: not in limit_s,
        then it is killed)."""
        t0 = time.monotonic()
        self.proc.send_signal(signal.SIGINT)
        try:
            self.proc.wait(timeout=limit_s)
            return time.monotonic() - t0
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
            return None


class Generator:
    """Seeded random requests: (service, request, expected_valid, label)."""

    def __init__(self, rng, board_size, max_w):
        self.rng = rng
        self.bx, self.by, self.bz = board_size[0] / 2, board_size[1] / 2, board_size[2]
        self.max_w = max_w

    def tiny(self):
        r = self.rng
        return r.choice(DENORMALS) if r.random() < 0.7 else r.choice([-1, 1]) * 10 ** r.uniform(
            -320, -3)

    def vec(self, scale, tiny_p=0.15):
        r = self.rng
        v = []
        for _ in range(3):
            if r.random() < tiny_p:
                v.append(self.tiny())
            elif r.random() < 0.1:
                v.append(0.0)
            else:
                v.append(r.gauss(0, scale))
        return v

    def spin(self):
        r = self.rng
        kind = r.random()
        if kind < 0.2:
            return self.vec(1e-3, tiny_p=0.8)
        if kind < 0.45:  # at or just under the bound, any direction
            d = self.unit()
            mag = self.max_w * r.choice([1.0, 0.999999, r.uniform(0.8, 1.0)])
            return [mag * c for c in d]
        if kind < 0.6:  # about the symmetry axis only
            return [0.0, 0.0, r.uniform(-self.max_w, self.max_w)]
        d = self.unit()
        mag = 10 ** r.uniform(-2, math.log10(self.max_w))
        return [mag * c for c in d]

    def unit(self):
        while True:
            v = [self.rng.gauss(0, 1) for _ in range(3)]
            n = math.sqrt(sum(c * c for c in v))
            if n > 1e-6:
                return [c / n for c in v]

    def quat(self):
        r = self.rng
        kind = r.random()
        if kind < 0.3:
            return [0.0, 0.0, 0.0, 1.0]
        if kind < 0.5:  # flat, turned about z
            a = r.uniform(-math.pi, math.pi) / 2
            return [0.0, 0.0, math.sin(a), math.cos(a)]
        if kind < 0.6:  # absurd but finite norm (normalised by the node)
            s = r.choice([1e-300, 1e-150, 1e150, 1e300])
            return [s * c for c in self.quat_uniform()]
        return self.quat_uniform()

    def quat_uniform(self):
        q = [self.rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(c * c for c in q))
        return [c / n for c in q]

    def position(self):
        r, bx, by, bz = self.rng, self.bx, self.by, self.bz
        kind = r.choice(["board", "board", "above", "table", "edge", "side", "corner", "far"])
        if kind == "board":  # resting, touching or just above the top face
            z = HALF_HEIGHT_M + r.choice([0.0, 0.0, self.tiny(), r.uniform(-1e-4, 1e-3)])
            return kind, [r.uniform(-bx, bx), r.uniform(-by, by), z]
        if kind == "above":
            return kind, [r.uniform(-bx, bx), r.uniform(-by, by), r.uniform(0.005, 0.5)]
        if kind == "table":
            x = r.choice([-1, 1]) * r.uniform(bx + RADIUS_M, bx + 0.5)
            return kind, [x, r.uniform(-1, 1), -bz + HALF_HEIGHT_M + r.uniform(-1e-4, 0.05)]
        if kind == "edge":  # over the board's top edge, half on, half off
            if r.random() < 0.5:
                p = [r.choice([-1, 1]) * (bx + r.uniform(-RADIUS_M, RADIUS_M)),
                     r.uniform(-by, by)]
            else:
                p = [r.uniform(-bx, bx), r.choice([-1, 1]) * (by + r.uniform(-RADIUS_M, RADIUS_M))]
            return kind, p + [r.uniform(-HALF_HEIGHT_M, 0.02)]
        if kind == "side":  # beside the board's side, below its top face
            if r.random() < 0.5:
                p = [r.choice([-1, 1]) * (bx + r.uniform(0, 2 * RADIUS_M)), r.uniform(-by, by)]
            else:
                p = [r.uniform(-bx, bx), r.choice([-1, 1]) * (by + r.uniform(0, 2 * RADIUS_M))]
            return kind, p + [r.uniform(-bz, 0.0)]
        if kind == "corner":
            return kind, [r.choice([-1, 1]) * (bx + r.uniform(-RADIUS_M, RADIUS_M)),
                          r.choice([-1, 1]) * (by + r.uniform(-RADIUS_M, RADIUS_M)),
                          r.uniform(-bz, 0.03)]
        return kind, [r.uniform(-999, 999) / math.sqrt(3) for _ in range(3)]

    def invalid(self, req):
        """Spoils one field of a set_state request; returns what was spoiled."""
        r = self.rng
        what = r.choice(["nan", "inf", "speed", "spin", "distance", "zero_quat", "ninf"])
        if what == "nan":
            req.twist.linear.y = float("nan")
        elif what == "inf":
            req.pose.position.x = float("inf")
        elif what == "ninf":
            req.twist.angular.z = float("-inf")
        elif what == "speed":
            req.twist.linear.x = r.choice([1000.001, 1e308, 1.7976931348623157e308])
        elif what == "spin":
            req.twist.angular.x = self.max_w * r.choice([1.000001, 2.0, 1e300])
        elif what == "distance":
            req.pose.position.z = r.choice([1000.001, 1e300])
        elif what == "zero_quat":
            req.pose.orientation.x = req.pose.orientation.y = 0.0
            req.pose.orientation.z = req.pose.orientation.w = 0.0
        return what

    def request(self, srv):
        from std_srvs.srv import TriggerRequest
        from virtual_go.srv import SetAngularVelocityRequest, SetStateRequest
        r = self.rng
        kind = r.random()
        if kind < 0.1:
            return "reset", TriggerRequest(), True, "reset"
        if kind < 0.35:
            req = SetAngularVelocityRequest()
            w = self.spin()
            req.angular_velocity.x, req.angular_velocity.y, req.angular_velocity.z = w
            req.frame = r.choice(["", "world", "stone"])
            valid = True
            if r.random() < 0.15:
                valid = False
                what = r.choice(["nan", "big", "frame"])
                if what == "nan":
                    req.angular_velocity.y = float("nan")
                elif what == "big":
                    req.angular_velocity.z = self.max_w * 1.01
                else:
                    req.frame = r.choice(["body", "x" * 300, "World"])
            return "set_angular_velocity", req, valid, "w"
        req = SetStateRequest()
        if r.random() < 0.03:
            p, q, v, w = r.choice(ISSUE_STATES)
            label = "issue"
        else:
            label, p = self.position()
            q = self.quat()
            speed = r.choice([1e-3, 0.1, 1.0, 3.0, 10.0]) if r.random() < 0.9 else 999.0
            v = self.vec(speed / math.sqrt(3))
            if r.random() < 0.2:
                v = [self.tiny() for _ in range(3)]
            w = self.spin()
        (req.pose.position.x, req.pose.position.y, req.pose.position.z) = p
        (req.pose.orientation.x, req.pose.orientation.y, req.pose.orientation.z,
         req.pose.orientation.w) = q
        req.twist.linear.x, req.twist.linear.y, req.twist.linear.z = v
        req.twist.angular.x, req.twist.angular.y, req.twist.angular.z = w
        # Keep generated values inside the bounds unless spoiled on purpose.
        if math.sqrt(sum(c * c for c in v)) > 1000 or math.sqrt(sum(c * c for c in w)) > self.max_w:
            return self.request(srv)
        valid = True
        if r.random() < 0.12:
            valid = False
            label = "invalid_" + self.invalid(req)
        return "set_state", req, valid, label


class Monitor:
    """Subscribes to /stone/pose and /stone/events; records wall arrival times."""

    def __init__(self):
        import rospy
        from geometry_msgs.msg import PoseStamped
        from virtual_go.msg import StoneEvent
        self.lock = threading.Lock()
        self.pose_times = []
        self.events = []  # (arrival monotonic, msg)
        self.subs = [
            rospy.Subscriber("/stone/pose", PoseStamped, self.on_pose, queue_size=1000,
                             tcp_nodelay=True),
            rospy.Subscriber("/stone/events", StoneEvent, self.on_event, queue_size=100000,
                             tcp_nodelay=True),
        ]

    def on_pose(self, msg):
        with self.lock:
            self.pose_times.append(time.monotonic())

    def on_event(self, msg):
        with self.lock:
            self.events.append((time.monotonic(), msg))

    def reset(self):
        with self.lock:
            self.pose_times = []
            self.events = []

    def snapshot(self):
        with self.lock:
            return list(self.pose_times), list(self.events)

    def close(self):
        for s in self.subs:
            s.unregister()


def max_gap(times, t_from=None, t_to=None):
    ts = [t for t in times if (t_from is None or t >= t_from) and (t_to is None or t <= t_to)]
    if t_from is not None and ts:
        ts = [t_from] + ts
    if t_to is not None:
        ts = ts + [t_to]
    gaps = [b - a for a, b in zip(ts, ts[1:])]
    return gaps


def match_events(calls, arrivals):
    """calls: accepted calls in order, each dict(reason, t_sent: monotonic). arrivals: (arrival
    monotonic, message) in arrival order. An accepted call's own event is the next event of its
    reason that arrives after the call was sent (events of requests come in call order). The
    event stamps are not used to match: under load the physics step a request lands on may be
    stamped before the call's wall time. Returns (calls without their event, calls followed by
    held, events numbered by the node but not received, matched stamps out of order)."""
    request_reasons = {"set_state", "set_angular_velocity", "reset"}
    events = [m for _, m in arrivals]
    missing, followed_by_held = [], []
    i = 0
    matched = []  # (call index, event index)
    for k, (t_arrival, ev) in enumerate(arrivals):
        if ev.reason not in request_reasons:
            continue
        j = i
        while j < len(calls) and not (calls[j]["reason"] == ev.reason and
                                      t_arrival >= calls[j]["t_sent"]):
            j += 1
        if j == len(calls):
            continue  # an event no accepted call explains
        missing.extend(calls[i:j])
        matched.append((j, k))
        i = j + 1
    missing.extend(calls[i:])
    stamps = [events[k].header.stamp.to_sec() + events[k].time_offset for _, k in matched]
    out_of_order = sum(1 for a, b in zip(stamps, stamps[1:]) if b < a)
    for n, (j, k) in enumerate(matched):
        end = matched[n + 1][1] if n + 1 < len(matched) else len(events)
        if any(events[m].reason == "held" for m in range(k + 1, end)):
            followed_by_held.append(calls[j])
    segs = [ev.segment for ev in events]
    # Events the node numbered but this subscriber never got (lost between publisher and us).
    seg_lost = sum(b - a - 1 for a, b in zip(segs, segs[1:]) if b > a + 1)
    return missing, followed_by_held, seg_lost, out_of_order


def call(proxies, srv, req, stats):
    t0 = time.monotonic()
    tw = time.time()
    stats["pending_since"] = t0
    try:
        resp = proxies[srv](req)
        ok, msg = resp.success, resp.message
    except Exception as e:  # a broken connection: the node died or was killed
        ok, msg = None, "exception: %s" % e
    dt = time.monotonic() - t0
    stats["pending_since"] = None
    return ok, msg, dt, tw


def wait_for(pred, timeout_s):
    t_end = time.monotonic() + timeout_s
    while time.monotonic() < t_end:
        if pred():
            return True
        time.sleep(0.05)
    return False


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--calls", type=int, default=2400, help="total fuzz calls (default 2400)")
    ap.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    ap.add_argument("--burst-size", type=int, default=100, help="calls per burst (default 100)")
    ap.add_argument("--burst-share", type=float, default=0.5,
                    help="share of the calls sent in bursts (default 0.5)")
    ap.add_argument("--stall-s", type=float, default=0.5, help="a gap counted as a stall (0.5)")
    ap.add_argument("--config", default=os.path.join(ROOT, "config", "stone.yaml"))
    ap.add_argument("--port", type=int, default=0, help="roscore port (default: a free one)")
    ap.add_argument("--out", default=None, help="folder for the logs (default: a temp folder)")
    ap.add_argument("--verbose", action="store_true", help="list every finding (default: the first 10 of each kind)")
    args = ap.parse_args()

    out = args.out or tempfile.mkdtemp(prefix="service_fuzz_")
    os.makedirs(out, exist_ok=True)
    port = args.port or free_port()
    env = dict(os.environ)
    env["ROS_MASTER_URI"] = "http://localhost:%d" % port
    env["ROS_HOME"] = os.path.join(out, "ros_home")
    env.pop("ROS_NAMESPACE", None)
    os.environ.update({"ROS_MASTER_URI": env["ROS_MASTER_URI"], "ROS_HOME": env["ROS_HOME"]})
    os.makedirs(env["ROS_HOME"], exist_ok=True)
    print("service_fuzz: seed %d, master port %d, logs in %s" % (args.seed, port, out))

    core_log = open(os.path.join(out, "roscore.log"), "w")
    core = subprocess.Popen(["roscore", "-p", str(port)], env=env, stdout=core_log,
                            stderr=subprocess.STDOUT, start_new_session=True)
    node = None
    try:
        import rosgraph
        master = rosgraph.Master("/service_fuzz", master_uri=env["ROS_MASTER_URI"])

        def master_up():
            try:
                master.getPid()
                return True
            except Exception:
                return False

        if not wait_for(master_up, 30):
            sys.exit("service_fuzz: roscore did not come up on port %d" % port)

        import rospy
        from std_srvs.srv import Trigger
        from virtual_go.srv import SetAngularVelocity, SetState
        subprocess.call(["rosparam", "load", args.config, "/stone"], env=env)
        rospy.init_node("service_fuzz", anonymous=True, disable_signals=True)
        board_size = rospy.get_param("/stone/board/size")
        max_w = float(rospy.get_param("/stone/max_angular_velocity", 500.0))
        rng = random.Random(args.seed)
        gen = Generator(rng, board_size, max_w)

        def start_node(tag):
            n = Node(env, os.path.join(out, "stone_node_%s.log" % tag))
            for s in ["/stone/set_state", "/stone/set_angular_velocity", "/stone/reset"]:
                rospy.wait_for_service(s, timeout=30)
            proxies = {
                "set_state": rospy.ServiceProxy("/stone/set_state", SetState, persistent=True),
                "set_angular_velocity": rospy.ServiceProxy("/stone/set_angular_velocity",
                                                           SetAngularVelocity, persistent=True),
                "reset": rospy.ServiceProxy("/stone/reset", Trigger, persistent=True),
            }
            return n, proxies

        # ---- Phase 1: the fuzz on the default board scene. ----
        monitor = Monitor()
        node, proxies = start_node("fuzz")
        if not wait_for(lambda: len(monitor.snapshot()[0]) > 5, 20):
            print("service_fuzz: no /stone/pose within 20 s of the services")
        stats = {"pending_since": None}
        stop_watch = threading.Event()
        watch = {"longest_pending": 0.0}

        def watchdog():
            while not stop_watch.is_set():
                p = stats["pending_since"]
                if p is not None:
                    watch["longest_pending"] = max(watch["longest_pending"], time.monotonic() - p)
                time.sleep(0.01)

        threading.Thread(target=watchdog, daemon=True).start()

        t_start = time.monotonic()
        accepted, results = [], []
        bursts = []  # durations
        n_burst_calls = int(args.calls * args.burst_share) // args.burst_size * args.burst_size
        n_bursts = n_burst_calls // args.burst_size
        plan = ["burst"] * n_bursts + ["paced"] * (args.calls - n_burst_calls)
        rng.shuffle(plan)
        sent = 0
        for item in plan:
            if item == "burst":
                tb = time.monotonic()
                batch = [gen.request(None) for _ in range(args.burst_size)]
                for srv, req, valid, label in batch:
                    ok, msg, dt, tw = call(proxies, srv, req, stats)
                    results.append((srv, valid, label, ok, msg, dt))
                    if ok:
                        accepted.append({"reason": srv, "t_sent": time.monotonic() - dt, "label": label,
                                         "req": req, "burst": True})
                bursts.append(time.monotonic() - tb)
                sent += len(batch)
                time.sleep(rng.uniform(0.0, 0.5))
            else:
                srv, req, valid, label = gen.request(None)
                ok, msg, dt, tw = call(proxies, srv, req, stats)
                results.append((srv, valid, label, ok, msg, dt))
                if ok:
                    accepted.append({"reason": srv, "t_sent": time.monotonic() - dt, "label": label, "req": req,
                                     "burst": False})
                sent += 1
                # Mostly short pauses; sometimes long enough for landings, rolling and rest.
                time.sleep(rng.choice([0.0, 0.002, 0.01, 0.03, 0.1]) if rng.random() < 0.97
                           else rng.uniform(0.5, 2.0))
        time.sleep(2.0)  # the last requests' steps and events
        t_end = time.monotonic()
        stop_watch.set()
        pose_times, events = monitor.snapshot()
        sigint_end = node.sigint_exit_s()
        node = None
        monitor.close()

        gaps = max_gap(pose_times, t_start, t_end)
        stalls = [g for g in gaps if g > args.stall_s]
        resp_times = [r[5] for r in results]
        ev_msgs = [e[1] for e in events]
        missing, followed, seg_gaps, out_of_order = match_events(accepted, events)
        held = [e for e in ev_msgs if e.reason == "held"]
        invalid_accepted = [r for r in results if not r[1] and r[3]]
        valid_refused = [r for r in results if r[1] and not r[3]]
        no_answer = [r for r in results if r[3] is None]
        reasons = {}
        for e in ev_msgs:
            reasons[e.reason] = reasons.get(e.reason, 0) + 1
        jumps = [e for e in ev_msgs if e.reason == "time_jump"]

        # ---- Phase 2: SIGINT mid-burst on the 500 rad/s spin scene. ----
        subprocess.check_call(["rosparam", "set", "/stone/initial/angular_velocity",
                               "[0.0, 0.0, 500.0]"], env=env)
        monitor2 = Monitor()
        node, proxies = start_node("spin500")
        wait_for(lambda: len(monitor2.snapshot()[0]) > 5, 20)
        t_spin0 = monitor2.snapshot()[0][0] if monitor2.snapshot()[0] else time.monotonic()
        time.sleep(6.0)  # the issue's lock-up came 3.4 s after start
        spin_gaps = max_gap(monitor2.snapshot()[0], t_spin0, time.monotonic())
        holder = {}
        half_burst = threading.Event()

        def interrupt_mid_burst():
            half_burst.wait(timeout=30)
            holder["t"] = node.sigint_exit_s()

        th = threading.Thread(target=interrupt_mid_burst)
        th.start()
        mid_calls = 0
        for n in range(args.burst_size):
            if n == args.burst_size // 2:
                half_burst.set()
            srv, req, valid, label = gen.request(None)
            ok, msg, dt, tw = call(proxies, srv, req, stats)
            if ok is None:
                break
            mid_calls += 1
        half_burst.set()
        th.join()
        sigint_mid = holder.get("t")
        node = None
        monitor2.close()

        # ---- Report. ----
        n_acc = len(accepted)
        print("calls: %d (%d accepted, %d refused, %d unanswered); bursts: %d of %d calls, "
              "each in %.3f .. %.3f s" % (len(results), n_acc,
                                          sum(1 for r in results if r[3] is False),
                                          len(no_answer), len(bursts), args.burst_size,
                                          min(bursts) if bursts else 0,
                                          max(bursts) if bursts else 0))
        print("fuzz wall time: %.1f s; /stone/pose messages: %d" % (t_end - t_start,
                                                                    len(pose_times)))
        print("stalls: largest /stone/pose gap %.3f s, gaps > %.2f s: %d; longest service "
              "response %.4f s (median %.4f s)" % (max(gaps) if gaps else float("nan"),
                                                  args.stall_s, len(stalls), max(resp_times),
                                                  sorted(resp_times)[len(resp_times) // 2]))
        print("events: %d (%s); events numbered by the node but never received (segment gaps): %d; "
              "time_jump events: %d"
              % (len(ev_msgs), ", ".join("%s %d" % kv for kv in sorted(reasons.items())),
                 seg_gaps, len(jumps)))
        print("false applied: %d (accepted without their own event: %d; followed by held: %d)"
              % (len(missing) + len(followed), len(missing), len(followed)))
        print("  of those without their event: %d sent in bursts, %d paced; request events "
              "stamped before the one before: %d"
              % (sum(1 for c in missing if c["burst"]), sum(1 for c in missing if not c["burst"]),
                 out_of_order))
        print("held events: %d" % len(held))
        print("invalid requests accepted: %d; valid-looking requests refused: %d"
              % (len(invalid_accepted), len(valid_refused)))
        print("500 rad/s scene: largest /stone/pose gap over its first 6 s: %.3f s"
              % (max(spin_gaps) if spin_gaps else float("nan")))
        fmt = lambda t: "did not exit in 10 s (killed)" if t is None else "%.3f s" % t
        print("SIGINT: at the end of the fuzz %s; mid-burst on the 500 rad/s scene (after %d "
              "calls) %s" % (fmt(sigint_end), mid_calls, fmt(sigint_mid)))
        lim = None if args.verbose else 10  # findings listed
        causes = {}
        for r in valid_refused:
            key = re.sub(r"[-+]?[0-9][0-9.e+-]*", "N", r[4])[:90]  # the cause, not the values
            causes[key] = causes.get(key, 0) + 1
        for key, n in sorted(causes.items(), key=lambda kv: -kv[1]):
            print("  %5d refused as: %s" % (n, key))
        if True:
            for r in valid_refused[:lim]:
                print("  refused: %s %s: %s" % (r[0], r[2], r[4]))
            for c in missing[:lim]:
                print("  no event for accepted %s (%s%s): %s" % (c["reason"], c["label"],
                                                                ", burst" if c["burst"] else "",
                                                              str(c["req"]).replace("\n", " ")))
            for c in followed[:lim]:
                print("  held after accepted %s (%s): %s" % (c["reason"], c["label"],
                                                            str(c["req"]).replace("\n", " ")))
            for e in held[:lim]:
                print("  held: %s" % e.detail)
            for r in invalid_accepted[:lim]:
                print("  invalid accepted: %s %s" % (r[0], r[2]))
        good = (not stalls and max(resp_times) <= args.stall_s and not missing and not followed
                and not held and sigint_end is not None and sigint_end < 1.0
                and sigint_mid is not None and sigint_mid < 1.0)
        print("service_fuzz: %s" % ("PASS" if good else "FAIL"))
        return 0 if good else 1
    finally:
        if node is not None and node.proc.poll() is None:
            node.proc.kill()
            node.proc.wait()
        try:
            import rospy
            rospy.signal_shutdown("done")
        except Exception:
            pass
        os.killpg(core.pid, signal.SIGINT)
        try:
            core.wait(timeout=10)
        except subprocess.TimeoutExpired:
            os.killpg(core.pid, signal.SIGKILL)


if __name__ == "__main__":
    sys.exit(main())
