#!/usr/bin/env bash
# Measures stone_node's overhead: CPU share of the node process (from /proc/<pid>/stat over a
# fixed window) and the publish-period jitter seen by a subscriber, at 60 Hz and 1000 Hz, with
# and without subscribers on ~pose and ~odom. Starts its own ROS master on a private port.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/node_overhead.sh [--window SECONDS] [--rates "60 1000"] [--out FILE]

Runs build_catkin/devel/lib/virtual_go/stone_node (or $VG_BUILD/devel/...; build it first with
scripts/setup.sh) named `stone` with config/stone.yaml and ~rate overridden, once per rate and
subscriber mode, for a fixed window (default 10 s), and writes a Markdown table (default
docs/benchmarks/node_overhead.md):
  - CPU: (utime + stime) of the node from /proc/<pid>/stat over the window, in % of one core;
  - period: the spacing of /tf messages for the stone as received by a rospy subscriber
    (wall clock at arrival, so transport jitter is included), p50 / p99 / max, and the
    deviation from the nominal period;
  - "tf only": nobody subscribes to ~pose / ~odom (the node should skip building them);
    "tf + pose + odom": the subscriber also takes ~pose and ~odom.
EOF
}

VG_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VG_BUILD="${VG_BUILD:-$VG_ROOT/build_catkin}"
window=10
rates="60 1000"
out="$VG_ROOT/docs/benchmarks/node_overhead.md"
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --window) window="$2"; shift ;;
    --rates) rates="$2"; shift ;;
    --out) out="$2"; shift ;;
    *) echo "node_overhead.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

node_bin="$VG_BUILD/devel/lib/virtual_go/stone_node"
if [ ! -x "$node_bin" ]; then
  echo "node_overhead.sh: $node_bin not found; build the package first (scripts/setup.sh)" >&2
  exit 1
fi
# shellcheck source=scripts/setup.sh
source "$VG_ROOT/scripts/setup.sh"
vg_private_master node_overhead 11400 500
mkdir -p "$(dirname "$out")"

# The measuring client: subscribes, waits for the node's first message, then samples the node's
# CPU time and the /tf arrival times over the window. Prints one Markdown table row.
measure() {
  /usr/bin/python3 - "$@" <<'EOF'
import os, sys, time
import rospy
from tf2_msgs.msg import TFMessage
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Odometry
sys.path.insert(0, os.path.join(os.environ["VG_ROOT"], "scripts"))
from node_cpu import cpu_seconds

pid, rate, window, mode = int(sys.argv[1]), float(sys.argv[2]), float(sys.argv[3]), sys.argv[4]
rospy.init_node("node_overhead_probe", anonymous=True, disable_signals=True)
arrivals, counts = [], {"pose": 0, "odom": 0}
recording = [False]

def on_tf(msg):
    if recording[0] and any(t.child_frame_id == "stone" for t in msg.transforms):
        arrivals.append(time.monotonic())

def counter(key):
    def on_msg(_):
        if recording[0]:
            counts[key] += 1
    return on_msg

rospy.Subscriber("/tf", TFMessage, on_tf, queue_size=1000, tcp_nodelay=True)
if mode == "full":
    rospy.Subscriber("/stone/pose", PoseStamped, counter("pose"), queue_size=1000, tcp_nodelay=True)
    rospy.Subscriber("/stone/odom", Odometry, counter("odom"), queue_size=1000, tcp_nodelay=True)
time.sleep(2.0)  # connections up, node warmed

recording[0] = True
c0, t0 = cpu_seconds(pid), time.monotonic()
time.sleep(window)
c1, t1 = cpu_seconds(pid), time.monotonic()
recording[0] = False
cpu = 100.0 * (c1 - c0) / (t1 - t0)
periods = sorted(1e3 * (b - a) for a, b in zip(arrivals, arrivals[1:]))
def pct(p):
    return periods[min(len(periods) - 1, int(round(p / 100.0 * (len(periods) - 1))))] if periods else float("nan")
nominal = 1e3 / rate
label = "tf + pose + odom" if mode == "full" else "tf only"
extra = f"{counts['pose']} / {counts['odom']}" if mode == "full" else "-"
print(f"| {rate:g} | {label} | {cpu:.1f} | {len(arrivals)} | {extra} | {nominal:.3f} | "
      f"{pct(50):.3f} | {pct(99):.3f} | {max(periods) if periods else float('nan'):.3f} | "
      f"{max(pct(99) - nominal, nominal - periods[0]) if periods else float('nan'):.3f} |")
rospy.signal_shutdown("done")
EOF
}

rows=()
for rate in $rates; do
  for mode in tf full; do
    rosparam delete /stone >/dev/null 2>&1 || true
    rosparam load "$VG_ROOT/config/stone.yaml" /stone
    rosparam set /stone/rate "$rate"
    "$node_bin" __name:=stone >"$ROS_HOME/node_overhead_node.log" 2>&1 &
    node_pid=$!
    pids+=("$node_pid")
    echo "node_overhead.sh: rate $rate Hz, $mode: measuring for $window s" >&2
    if row="$(measure "$node_pid" "$rate" "$window" "$mode")"; then
      rows+=("$row")
    else
      rows+=("| $rate | $mode | measurement failed (see $ROS_HOME/node_overhead_node.log) | | | | | | | |")
    fi
    kill "$node_pid" 2>/dev/null || true
    wait "$node_pid" 2>/dev/null || true
  done
done

{
  echo "# stone_node overhead"
  echo
  echo "Measured by \`scripts/node_overhead.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC'),"
  echo "$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), $(nproc) cores, load average"
  echo "$(cut -d' ' -f1-3 /proc/loadavg) at the end. Node: config/stone.yaml with ~rate overridden,"
  echo "window $window s per row. CPU = node process (utime + stime) / wall time, % of one core."
  echo "Periods: spacing of the stone's /tf messages at a rospy subscriber (wall clock on arrival,"
  echo "so they include ROS transport and the subscriber's own scheduling); jitter = the larger of"
  echo "p99 - nominal and nominal - min."
  echo
  echo "| rate (Hz) | subscribers | CPU (%) | /tf msgs | pose / odom msgs | nominal period (ms) | p50 (ms) | p99 (ms) | max (ms) | jitter (ms) |"
  echo "|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
} >"$out"
echo "node_overhead.sh: wrote $out" >&2
