#!/usr/bin/env bash
# The main job: set up (packages, build, game records), then launch a real game played onto the
# board (launch/game.launch), or the single stone (scene:=stone); with rviz when a display is
# available, headless otherwise.
set -euo pipefail
case "${1:-}" in
  -h | --help)
    cat <<'USAGE'
usage: scripts/run.sh [scene:=game|stone] [ARG:=VALUE ...]
  Set up (packages, build, the kigo game records), then launch, with rviz:=true when $DISPLAY
  is set:
    scene:=game (default)  `roslaunch virtual_go game.launch`: sgf_replay plays a professional
                           game (Honinbo-51-5, 268 moves, from Debian's kigo) onto the board, a
                           move a second; when it ends the final position stays (Ctrl-C stops)
    scene:=stone           `roslaunch virtual_go stone.launch`: one stone tossed onto the board,
                           resting, tossed again
  The other arguments go to roslaunch, for example:
    scripts/run.sh game:=$PWD/my.sgf interval:=0.2       another game, five moves a second
    scripts/run.sh drop_height:=0                        stones set down at rest, not dropped
    scripts/run.sh record:=true                          also record ./game.bag (bag:=FILE for another)
    scripts/run.sh scene:=stone config:=$PWD/config/tumble.yaml   the wobbling stone, no gravity
    scripts/run.sh scene:=stone record:=true             the stone, recorded to ./virtual_go.bag
    scripts/run.sh rviz:=false                           headless even with a display
  In rviz, the Publish Point tool puts a stone on the clicked Go point (black, white, ...).
  Stop with Ctrl-C. Topics, services and parameters: README.md, "The ROS node".
USAGE
    exit 0
    ;;
esac
scene=game
args=()
for arg in "$@"; do
  case "$arg" in
    scene:=*) scene="${arg#scene:=}" ;;
    *) args+=("$arg") ;;
  esac
done
case "$scene" in
  game | stone) ;;
  *)
    echo "scripts/run.sh: scene:=$scene: unknown scene (game or stone; --help)" >&2
    exit 2
    ;;
esac
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
vg_setup >&2 || exit 1
vg_source_devel
rviz=false
if [ -n "${DISPLAY:-}" ]; then rviz=true; fi
if [ "$scene" = stone ]; then
  exec roslaunch virtual_go stone.launch rviz:="$rviz" "${args[@]}"
fi
# The record setup fetched (its folder follows $VG_BUILD), unless the arguments name a game.
game="$VG_KIGO_DIR/usr/share/kigo/games/Honinbo-51-5.sgf"
for arg in "${args[@]}"; do
  case "$arg" in game:=*) game="" ;; esac
done
if [ -n "$game" ] && [ ! -f "$game" ]; then
  echo "scripts/run.sh: no game record at $game (setup could not fetch Debian's kigo package);" \
    "give one with game:=FILE.sgf, or run the single stone: scripts/run.sh scene:=stone" >&2
  exit 1
fi
exec roslaunch virtual_go game.launch rviz:="$rviz" ${game:+game:="$game"} "${args[@]}"
