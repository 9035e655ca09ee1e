# Sourced by scripts/demo and scripts/test: installs what a fresh Debian 12 machine lacks, makes
# the catkin workspace .ws/ inside the checkout (git-ignored) and builds the package in it.
# Afterwards WS, DEVEL_LIB and ROS_HOME are set and the workspace's setup.bash is sourced.

set -euo pipefail

REPO="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="$REPO/.ws"
# A pyenv or venv python3 without the ROS modules breaks catkin's CMake: Debian's comes first.
export PATH="/usr/bin:/bin:$PATH"
export ROS_HOME="$WS/ros_home"
export ROS_LOG_DIR="$ROS_HOME/log"
JOBS="${HEX_SLAM_JOBS:-2}"

# Debian 12 packages ROS 1 itself; these are what the package builds, tests and runs with.
HEX_SLAM_DEBS=(
  build-essential cmake libgtest-dev
  ros-core-dev ros-message-generation ros-message-runtime python3-genpy
  python3-rostest python3-roslaunch python3-rosmaster rosbash
  libroslib-dev libtf2-ros-dev libtf2-geometry-msgs-dev librosbag-dev
  libsensor-msgs-dev libnav-msgs-dev libgeometry-msgs-dev libstd-msgs-dev libstd-srvs-dev
  libvisualization-msgs-dev libdiagnostic-msgs-dev
  libeigen3-dev libyaml-cpp-dev libpng-dev libceres-dev libbenchmark-dev libcli11-dev
  python3-sensor-msgs python3-nav-msgs python3-geometry-msgs python3-std-srvs
  python3-visualization-msgs python3-diagnostic-msgs python3-tf2-ros python3-rosbag
  python3-numpy python3-yaml python3-matplotlib
  rviz
)

hex_slam_install_deps() {
  local missing=()
  local pkg
  for pkg in "${HEX_SLAM_DEBS[@]}"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$pkg")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "== installing ${#missing[@]} Debian packages: ${missing[*]}"
  local sudo=""
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo="sudo"
    else
      echo "error: these packages are missing and we are not root (no sudo): ${missing[*]}" >&2
      exit 1
    fi
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends \
    "${missing[@]}" >/dev/null
}

hex_slam_build() {
  mkdir -p "$WS/src" "$ROS_LOG_DIR"
  # The workspace's only package is this checkout.
  ln -sfn "$REPO" "$WS/src/hex_slam"
  echo "== building in $WS (catkin_make -j$JOBS)"
  (cd "$WS" && catkin_make -j"$JOBS" >"$WS/build.log" 2>&1) || {
    tail -n 60 "$WS/build.log" >&2
    echo "error: build failed; full log in $WS/build.log" >&2
    exit 1
  }
  # catkin caches the devel space's environment when it first configures, before message
  # generation has made devel/lib/python3/dist-packages: tests run by `catkin_make run_tests` then
  # cannot import hex_slam.srv. Configure once more when the cache misses it (a no-op build).
  if [ -d "$WS/devel/lib/python3/dist-packages" ] &&
     ! grep -q "dist-packages" "$WS/build/catkin_generated/setup_cached.sh"; then
    (cd "$WS" && catkin_make --force-cmake -j"$JOBS" >>"$WS/build.log" 2>&1) || {
      tail -n 60 "$WS/build.log" >&2
      echo "error: reconfiguring failed; full log in $WS/build.log" >&2
      exit 1
    }
  fi
  # setup.bash reads unset variables.
  set +u
  # shellcheck disable=SC1091
  source "$WS/devel/setup.bash"
  set -u
  DEVEL_LIB="$WS/devel/lib/hex_slam"
}

hex_slam_install_deps
# Scripts that build elsewhere (the sanitizer build) set HEX_SLAM_SETUP_ONLY=1.
if [ "${HEX_SLAM_SETUP_ONLY:-0}" != 1 ]; then
  hex_slam_build
fi
