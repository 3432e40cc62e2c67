#!/usr/bin/env bash
# Takes a screenshot of rviz showing the stone node, headless: a private Xvfb display, Mesa's
# software renderer and a private ROS master. Used for docs/rviz.png and (--game) docs/game.png.
set -euo pipefail
usage() {
  cat <<'USAGE'
usage: scripts/rviz_screenshot.sh OUT.png [CONFIG.yaml] [SECONDS]
       scripts/rviz_screenshot.sh --game OUT.png [SECONDS] [ARG:=VALUE ...]
  Launches `roslaunch virtual_go stone.launch rviz:=true` (node parameters from CONFIG.yaml,
  default config/stone.yaml) on a private Xvfb display and master, waits SECONDS (default 12)
  and writes a screenshot of the whole display to OUT.png. With --game it launches
  `roslaunch virtual_go game.launch rviz:=true ARG:=VALUE ...` instead (a game played onto the
  board; the game setup fetched into the build folder unless game:= is given) and waits SECONDS
  (default 60), e.g. `--game docs/game.png 60 to_move:=150 interval:=0.05 drop_height:=0`.
  Needs the package built (scripts/setup.sh) and xvfb, imagemagick and rviz installed.
USAGE
}
game=false
if [ "${1:-}" = --game ]; then
  game=true
  shift
fi
case "${1:-}" in
  -h | --help) usage; exit 0 ;;
  "") usage >&2; exit 2 ;;
esac
VG_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VG_BUILD="${VG_BUILD:-$VG_ROOT/build_catkin}"
out="$(realpath -m "$1")"
if $game; then
  seconds="${2:-60}"
  launch_args=(game.launch rviz:=true)
  if [ $# -gt 2 ]; then launch_args+=("${@:3}"); fi
  case " ${launch_args[*]} " in
    *" game:="*) ;;
    *) launch_args+=(game:="$VG_BUILD/test_data/kigo/usr/share/kigo/games/Honinbo-51-5.sgf") ;;
  esac
else
  config="$(realpath "${2:-$VG_ROOT/config/stone.yaml}")"
  seconds="${3:-12}"
  launch_args=(stone.launch rviz:=true config:="$config")
fi

export PATH="/usr/bin:$PATH"
set +u
source "$VG_BUILD/devel/setup.bash"
set -u
export ROS_HOME="${ROS_HOME:-$VG_BUILD/ros_home}"
export LIBGL_ALWAYS_SOFTWARE=1

# A display and a master port nobody else uses.
display=99
while [ -e "/tmp/.X11-unix/X$display" ] || [ -e "/tmp/.X$display-lock" ]; do display=$((display + 1)); done
port=$((20000 + RANDOM % 20000))
export ROS_MASTER_URI="http://localhost:$port"

Xvfb ":$display" -screen 0 1080x720x24 -nolisten tcp >/dev/null 2>&1 &
xvfb_pid=$!
launch_pid=""
cleanup() {
  [ -n "$launch_pid" ] && kill -INT "$launch_pid" 2>/dev/null && wait "$launch_pid" 2>/dev/null
  kill "$xvfb_pid" 2>/dev/null || true
}
trap cleanup EXIT
sleep 1
export DISPLAY=":$display"
roslaunch -p "$port" virtual_go "${launch_args[@]}" >"$ROS_HOME/rviz_screenshot.log" 2>&1 &
launch_pid=$!
sleep "$seconds"
mkdir -p "$(dirname "$out")"
import -window root "$out"
echo "wrote $out"
