#!/usr/bin/env bash
# Installs the Debian packages virtual_go needs (with sudo when not root), then configures and
# builds the package into build_catkin/ (devel space build_catkin/devel). Not build/: rosrun
# skips executables below <package>/build/, and the repository root is the package. Safe to
# run again: it installs only what is missing and rebuilds incrementally. Sourced by run.sh and test.sh (the functions leave
# the caller's shell options alone and return non-zero on failure); runnable alone.

VG_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VG_BUILD="${VG_BUILD:-$VG_ROOT/build_catkin}"

# Debian 12's system ROS 1 (no /opt/ros) plus the tools the tests use.
VG_PACKAGES=(
  build-essential cmake python3 python3-catkin-pkg catkin
  ros-core-dev libroscpp-dev libtf2-ros-dev libtf2-eigen-dev librosbag-dev librostest-dev
  python3-rostest python3-rosbag ros-message-generation ros-std-srvs ros-geometry-msgs
  ros-nav-msgs ros-visualization-msgs libdiagnostic-updater-dev ros-diagnostic-msgs
  libros-rosgraph-msgs-dev
  libeigen3-dev libboost-dev libgtest-dev
  rviz tf2-tools tf-tools xvfb xauth imagemagick gnuplot-nox procps catkin-lint
  gnugo
)
# What the README's user commands need, which --no-install-recommends leaves out: rosrun
# (rosbash, only a Recommends of ros-core), and the Python modules of every message type a
# user inspects with rostopic, rosservice or rosbag (they cannot load a type without them).
# genpy generates this package's own (virtual_go/StoneInfo, ...) into the devel space.
VG_PACKAGES+=(
  rosbash python3-genpy python3-std-msgs python3-geometry-msgs python3-nav-msgs
  python3-visualization-msgs python3-std-srvs python3-tf2-msgs python3-rosgraph-msgs
  python3-diagnostic-msgs
)

vg_sudo() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

vg_install_packages() {
  local missing=()
  local p
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -gt 0 ]; then
    echo "virtual_go: installing ${missing[*]}" >&2
    vg_sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq || return 1
    vg_sudo env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
      "${missing[@]}" >&2 || return 1
  fi
}

# catkin needs the system python (another python3 may come first on PATH without catkin_pkg).
vg_environment() {
  export PATH="/usr/bin:$PATH"
  export ROS_HOME="${ROS_HOME:-$VG_BUILD/ros_home}"
  mkdir -p "$ROS_HOME"
}

# Configures $VG_BUILD (the log in $VG_BUILD/configure.log, shown when cmake fails). Alone,
# it is what test/package/test_configure_long_path.py runs from a deep checkout.
vg_configure() {
  vg_environment
  # catkin bakes the environment the run_tests target gives every test (setup_cached.sh) at
  # configure time, with only the devel paths that exist then: without this folder a first
  # configure leaves PYTHONPATH empty and Python tests cannot import virtual_go.msg.
  mkdir -p "$VG_BUILD/devel/lib/python3/dist-packages"
  cmake -S "$VG_ROOT" -B "$VG_BUILD" -DPYTHON_EXECUTABLE=/usr/bin/python3 \
    -DCATKIN_ENABLE_TESTING=ON "$@" >"$VG_BUILD/configure.log" 2>&1 || {
    cat "$VG_BUILD/configure.log" >&2
    echo "virtual_go: cmake configure failed" >&2
    return 1
  }
}

vg_configure_and_build() {
  vg_configure "$@" || return 1
  cmake --build "$VG_BUILD" -- -j"$(nproc)"
}

# Real game records for the replay tests: the professional games Debian's kigo package ships
# (Honinbo-51-5.sgf, Mehin-21-2.sgf), unpacked into the build folder without installing kigo
# (and KDE). They are GPL-2+ like kigo, so they are fetched, not kept in this repository.
# Idempotent; a failure warns (the tests that need them then say what is missing).
VG_KIGO_DIR="$VG_BUILD/test_data/kigo"
vg_fetch_game_records() {
  local games="$VG_KIGO_DIR/usr/share/kigo/games"
  [ -f "$games/Honinbo-51-5.sgf" ] && [ -f "$games/Mehin-21-2.sgf" ] && return 0
  local download="$VG_BUILD/test_data/download"
  rm -rf "$download" && mkdir -p "$download" "$VG_KIGO_DIR" || return 1
  # apt-get download needs the package lists; fetch them once if they are missing.
  (cd "$download" && apt-get download kigo >/dev/null 2>&1) ||
    { vg_sudo env DEBIAN_FRONTEND=noninteractive apt-get update -qq &&
      (cd "$download" && apt-get download kigo >/dev/null); } || {
    echo "virtual_go: could not download Debian's kigo package (game records for the tests)" >&2
    return 1
  }
  dpkg-deb -x "$download"/kigo_*.deb "$download/x" &&
    mkdir -p "$games" &&
    cp "$download"/x/usr/share/kigo/games/*.sgf "$games/" &&
    cp "$download"/x/usr/share/doc/kigo/copyright "$VG_KIGO_DIR/copyright" &&
    rm -rf "$download" || {
    echo "virtual_go: could not unpack the kigo game records" >&2
    return 1
  }
}

vg_setup() {
  vg_install_packages "${VG_PACKAGES[@]}" || return 1
  mkdir -p "$VG_BUILD"
  vg_fetch_game_records || echo "virtual_go: continuing without the kigo game records" >&2
  vg_configure_and_build "$@"
}

# The devel space's setup.bash reads unset variables: source it with nounset off.
vg_source_devel() {
  local nounset=0
  case $- in *u*) nounset=1 ;; esac
  set +u
  # shellcheck disable=SC1091
  source "$VG_BUILD/devel/setup.bash"
  local status=$?
  if [ $nounset -eq 1 ]; then set -u; fi
  return $status
}

# A private ROS master for a benchmark script, so that a running roscore (or a colleague's test)
# is neither used nor disturbed: the environment and devel space as above, ROS_MASTER_URI on a
# port drawn from [$2, $2 + $3), roscore logging to $ROS_HOME/$1_roscore.log. Every process the
# caller appends to the array `pids` (roscore is the first) is ended on exit (vg_stop_pids).
vg_private_master() {
  local name="$1" first_port="$2" ports="$3"
  vg_environment
  vg_source_devel || return 1
  export VG_ROOT  # scripts/node_cpu.py is found through it
  local port=$((first_port + RANDOM % ports))
  export ROS_MASTER_URI="http://localhost:$port"
  pids=()
  trap vg_stop_pids EXIT
  roscore -p "$port" >"$ROS_HOME/${name}_roscore.log" 2>&1 &
  pids+=($!)
  local _
  for _ in $(seq 50); do rosparam list >/dev/null 2>&1 && break; sleep 0.2; done
}
vg_stop_pids() {
  local p
  for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
  for p in "${pids[@]}"; do wait "$p" 2>/dev/null || true; done
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  set -euo pipefail
  case "${1:-}" in
    -h | --help)
      echo "usage: scripts/setup.sh   install Debian packages (sudo if not root), configure, build"
      exit 0
      ;;
  esac
  vg_setup
fi
