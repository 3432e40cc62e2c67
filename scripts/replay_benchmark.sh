#!/usr/bin/env bash
# The issue's two goals for a Go board in ROS, measured (benchmarks, not timed tests):
#   (a) a whole game replayed onto a node that owns the clock (~publish_clock, ~real_time_factor
#       0, ~rate 60): simulated seconds per wall second while sgf_replay plays it;
#   (b) the node's CPU with one stone in flight, one stone resting, and 361 stones resting, A/B
#       against another build of the node (--baseline) as scripts/node_overhead.sh does.
# Starts its own ROS master on a private port.
set -euo pipefail

usage() {
  cat <<'EOF'
usage: scripts/replay_benchmark.sh [--game FILE.sgf] [--interval S] [--window SECONDS]
                                   [--baseline STONE_NODE] [--stone-contact true|false]
                                   [--replay-only] [--out FILE]

(a) Replay: starts build_catkin/devel/lib/virtual_go/stone_node (or $VG_BUILD/...) with the
    board, ~publish_clock true, ~real_time_factor 0 (as fast as it can) and ~rate 60 (states at
    60 Hz of simulated time), and runs `sgf_replay GAME --interval S` onto it twice: stones set
    down (--drop-height 0) and dropped from 1 cm (--drop-height 0.01, each stone falls, bounces
    and comes to rest). Reports the wall seconds of the replay, the simulated seconds /clock
    advanced meanwhile and their ratio (the issue's goal: at least 100). --interval is wall time
    between moves (default 0: as fast as the service calls go). GAME defaults to the Honinbo game
    (268 moves) that vg_fetch_game_records puts into the build folder.
(b) CPU: the node at ~rate 60 following ROS time, a rospy subscriber on /tf, CPU of the node
    process from /proc/<pid>/stat over a window (default 10 s) once the scene is set:
      flight       no board: the stone falls freely for the whole window;
      1 resting    the board, the stone set down flat at tengen, at rest;
      361 resting  the same, plus 360 stones set down (~place, drop_height 0) on every other
                   point, all at rest (the issue's goal: <= 1.5 x "1 resting").
    With --baseline another stone_node binary (e.g. the main checkout's) is measured the same
    way, interleaved (A, B, A, B), so the load of the machine hits both alike.
--stone-contact sets the node's ~contact/stone/enabled (default: the node's default, true) in
both parts; --replay-only skips (b).
Writes a Markdown report (default docs/benchmarks/replay.md).
EOF
}

VG_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VG_BUILD="${VG_BUILD:-$VG_ROOT/build_catkin}"
game="$VG_BUILD/test_data/kigo/usr/share/kigo/games/Honinbo-51-5.sgf"
interval=0
window=10
baseline=""
stone_contact=""
replay_only=0
out="$VG_ROOT/docs/benchmarks/replay.md"
while [ $# -gt 0 ]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --game) game="$2"; shift ;;
    --interval) interval="$2"; shift ;;
    --window) window="$2"; shift ;;
    --baseline) baseline="$2"; shift ;;
    --stone-contact)
      case "$2" in
        true | false) stone_contact="$2" ;;
        *) echo "replay_benchmark.sh: --stone-contact takes true or false, got '$2'" >&2; exit 2 ;;
      esac
      shift ;;
    --replay-only) replay_only=1 ;;
    --out) out="$2"; shift ;;
    *) echo "replay_benchmark.sh: unknown option $1 (see --help)" >&2; exit 2 ;;
  esac
  shift
done

node_bin="$VG_BUILD/devel/lib/virtual_go/stone_node"
replay_bin="$VG_BUILD/devel/lib/virtual_go/sgf_replay"
for f in "$node_bin" "$replay_bin"; do
  if [ ! -x "$f" ]; then
    echo "replay_benchmark.sh: $f not found; build stone_node and sgf_replay first" >&2
    exit 1
  fi
done
if [ ! -f "$game" ]; then
  echo "replay_benchmark.sh: no game record $game (source scripts/setup.sh; vg_fetch_game_records)" >&2
  exit 1
fi
if [ -n "$baseline" ] && [ ! -x "$baseline" ]; then
  echo "replay_benchmark.sh: --baseline $baseline is not an executable" >&2
  exit 2
fi
# shellcheck source=scripts/setup.sh
source "$VG_ROOT/scripts/setup.sh"
vg_private_master replay_benchmark 11900 400
mkdir -p "$(dirname "$out")"
: >"$ROS_HOME/replay_benchmark_node.log"  # every node's output, appended

# Starts node binary $1 named /stone with the parameters in "$2" (YAML); sets node_pid.
start_node() {
  rosparam delete /stone >/dev/null 2>&1 || true
  rosparam set use_sim_time false
  printf '%s\n' "$2" >"$ROS_HOME/replay_benchmark_params.yaml"
  rosparam load "$ROS_HOME/replay_benchmark_params.yaml" /stone
  "$1" __name:=stone >>"$ROS_HOME/replay_benchmark_node.log" 2>&1 &
  node_pid=$!
  pids+=("$node_pid")
  for _ in $(seq 100); do rosservice list 2>/dev/null | grep -q '^/stone/reset$' && break; sleep 0.1; done
}
stop_node() {
  kill -INT "$node_pid" 2>/dev/null || true
  wait "$node_pid" 2>/dev/null || true
}

# The stone lying flat on the board at tengen (z = half its 9.2 mm height), still.
flat_at_tengen='
rate: 60.0
board: {enabled: true}
initial: {position: [0.0, 0.0, 0.0046], orientation: [0.0, 0.0, 0.0, 1.0], velocity: [0.0, 0.0, 0.0], angular_velocity: [0.0, 0.0, 0.0]}
auto_reset_period: 0.0
auto_reset_after_rest: 0.0
publish_clock: false
real_time_factor: 1.0
'
[ -n "$stone_contact" ] && flat_at_tengen+="contact: {stone: {enabled: $stone_contact}}
"

# ---- (a) the replay against the clock the node publishes.
replay_row() {  # $1: drop height
  local params="${flat_at_tengen/publish_clock: false/publish_clock: true}"
  start_node "$node_bin" "${params/real_time_factor: 1.0/real_time_factor: 0.0}"
  /usr/bin/python3 - "$replay_bin" "$game" "$interval" "$1" <<'EOF'
import re, subprocess, sys, time
import rospy
from rosgraph_msgs.msg import Clock
replay, game, interval, drop = sys.argv[1:5]
rospy.init_node("replay_benchmark_probe", anonymous=True, disable_signals=True)
latest = {}
rospy.Subscriber("/clock", Clock, lambda m: latest.update(t=m.clock.to_sec()), queue_size=1)
deadline = time.monotonic() + 10
while "t" not in latest and time.monotonic() < deadline:
    time.sleep(0.01)
sim0, wall0 = latest["t"], time.monotonic()
run = subprocess.run([replay, game, "--node", "/stone", "--interval", interval,
                      "--drop-height", drop], capture_output=True, text=True)
wall1 = time.monotonic()
time.sleep(0.2)
sim1 = latest["t"]
if run.returncode != 0:
    sys.exit("sgf_replay failed: " + run.stderr)
done = re.search(r"replayed (\d+) moves: (\d+) stones placed, (\d+) removed", run.stdout)
moves = done.group(1) if done else "?"
wall, sim = wall1 - wall0, sim1 - sim0
print(f"| {drop} | {moves} | {wall:.2f} | {sim:.2f} | {sim / wall:.0f} |")
rospy.signal_shutdown("done")
EOF
  stop_node
}

# ---- (b) CPU of a node over the window, once its scene is set.
cpu_row() {  # $1: label of the build, $2: binary, $3: case
  local params="$flat_at_tengen" places=0
  case "$3" in
    flight) params='
rate: 60.0
board: {enabled: false}
initial: {position: [0.0, 0.0, 0.0], velocity: [0.0, 0.0, 0.0]}
auto_reset_period: 0.0
publish_clock: false
real_time_factor: 1.0' ;;
    "1 resting") ;;
    "361 resting") places=1 ;;
  esac
  start_node "$2" "$params"
  /usr/bin/python3 - "$node_pid" "$window" "$places" "$1" "$3" <<'EOF'
import os, sys, time
import rospy
from tf2_msgs.msg import TFMessage
from virtual_go.srv import PlaceStone
sys.path.insert(0, os.path.join(os.environ["VG_ROOT"], "scripts"))
from node_cpu import cpu_seconds
pid, window, places, build, case = int(sys.argv[1]), float(sys.argv[2]), sys.argv[3] == "1", sys.argv[4], sys.argv[5]
rospy.init_node("replay_benchmark_cpu", anonymous=True, disable_signals=True)
tf = [0]
rospy.Subscriber("/tf", TFMessage, lambda m: tf.__setitem__(0, tf[0] + 1), queue_size=1000,
                 tcp_nodelay=True)
if places:
    place = rospy.ServiceProxy("/stone/place", PlaceStone)
    columns = "ABCDEFGHJKLMNOPQRST"
    for c in columns:
        for r in range(1, 20):
            if c + str(r) == "K10":
                continue  # the node's own stone lies there
            answer = place(point=c + str(r), color="black" if (ord(c) + r) % 2 else "white")
            if not answer.success:
                sys.exit("~place %s%d: %s" % (c, r, answer.message))
time.sleep(3.0)  # the scene settled (the set-down stones rest at once), connections up

n0, c0, t0 = tf[0], cpu_seconds(pid), time.monotonic()
time.sleep(window)
n1, c1, t1 = tf[0], cpu_seconds(pid), time.monotonic()
print(f"| {build} | {case} | {100.0 * (c1 - c0) / (t1 - t0):.2f} | {n1 - n0} |")
rospy.signal_shutdown("done")
EOF
  stop_node
}

replay_rows=()
for drop in 0 0.01; do
  echo "replay_benchmark.sh: replaying $(basename "$game"), drop height $drop m" >&2
  replay_rows+=("$(replay_row "$drop")")
done

builds=("this" "$node_bin")
[ -n "$baseline" ] && builds+=("baseline" "$baseline")
cpu_rows=()
for round in 1 2; do
  [ "$replay_only" = 1 ] && break
  for scene in "flight" "1 resting" "361 resting"; do
    for ((k = 0; k < ${#builds[@]}; k += 2)); do
      echo "replay_benchmark.sh: CPU, ${builds[k]}, $scene, round $round ($window s)" >&2
      cpu_rows+=("$(cpu_row "${builds[k]}" "${builds[k + 1]}" "$scene")")
    done
  done
done

{
  echo "# A Go game on the node: replay speed and the cost of resting stones"
  echo
  echo "Measured by \`scripts/replay_benchmark.sh\` on $(date -u '+%Y-%m-%d %H:%M UTC'),"
  echo "$(grep -m1 'model name' /proc/cpuinfo | sed 's/.*: //'), $(nproc) cores shared with other"
  echo "jobs (load average $(cut -d' ' -f1-3 /proc/loadavg) at the end). Stone-stone contact"
  echo "(\`~contact/stone/enabled\`): ${stone_contact:-default (true)}."
  echo
  echo "## Replay with ~real_time_factor 0 at 60 Hz"
  echo
  echo "\`sgf_replay $(basename "$game") --interval $interval\` onto a node with the board,"
  echo "\`~publish_clock\` true, \`~real_time_factor\` 0, \`~rate\` 60. Simulated seconds: how far"
  echo "/clock moved while sgf_replay ran (wall seconds)."
  echo
  echo "| drop height (m) | moves | wall (s) | simulated (s) | simulated / wall |"
  echo "|---|---|---|---|---|"
  printf '%s\n' "${replay_rows[@]}"
  if [ "$replay_only" = 0 ]; then
    echo
    echo "## Node CPU at 60 Hz"
    echo
    echo "CPU = node process (utime + stime) / wall time over $window s, % of one core; a rospy"
    echo "subscriber on /tf; two rounds. \"this\": $node_bin."
    [ -n "$baseline" ] && echo "\"baseline\": $baseline."
    echo
    echo "| build | scene | CPU (%) | /tf msgs |"
    echo "|---|---|---|---|"
    printf '%s\n' "${cpu_rows[@]}"
  fi
} >"$out"
echo "replay_benchmark.sh: wrote $out" >&2
