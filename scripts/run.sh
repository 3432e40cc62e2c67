#!/usr/bin/env bash
# The main job: set up (packages, build) and run the stone demo.
set -euo pipefail
case "${1:-}" in
  -h | --help)
    echo "usage: scripts/run.sh   set up (packages, build) and run the virtual_go demo"
    exit 0
    ;;
esac
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
vg_setup >&2
exec "$VG_BUILD/devel/lib/virtual_go/stone_demo" "$@"
