#!/usr/bin/env bash
# The main job: set up (packages, build), then launch the stone node; with rviz when a display
# is available, headless otherwise.
set -euo pipefail
case "${1:-}" in
  -h | --help)
    cat <<'USAGE'
usage: scripts/run.sh [ARG:=VALUE ...]
  Set up (packages, build), then `roslaunch virtual_go stone.launch`, with rviz:=true when
  $DISPLAY is set. Arguments go to roslaunch, for example:
    scripts/run.sh config:=$PWD/config/tumble.yaml      the wobbling stone, no gravity
    scripts/run.sh record:=true                          also record ./virtual_go.bag (bag:=FILE for another)
    scripts/run.sh rviz:=false                           headless even with a display
  Stop with Ctrl-C. Topics, services and parameters: README.md, "The ROS node".
USAGE
    exit 0
    ;;
esac
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
vg_setup >&2 || exit 1
vg_source_devel
rviz=false
if [ -n "${DISPLAY:-}" ]; then rviz=true; fi
exec roslaunch virtual_go stone.launch rviz:="$rviz" "$@"
