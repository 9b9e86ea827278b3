#!/usr/bin/env bash
# Installs the Debian 12 (bookworm) packages that virtual_origami needs to build,
# test and run. ROS 1 comes from Debian's own packages (no /opt/ros).
# Idempotent: apt is only touched when a package is missing.
set -euo pipefail

PACKAGES=(
  # toolchain
  build-essential cmake g++ pkg-config
  # core library
  libeigen3-dev nlohmann-json3-dev libcgal-dev
  # curved Newton solver: CHOLMOD's supernodal Cholesky, on a single-threaded optimised BLAS
  libsuitesparse-dev libopenblas0-serial
  # unit tests
  libgtest-dev libgmock-dev googletest
  # catkin and message generation (genmsg + the C++/Python generators)
  catkin python3-catkin-pkg ros-core-dev
  ros-message-generation python3-genmsg python3-gencpp python3-genpy ros-message-runtime
  # message packages: the -dev packages carry headers and cmake configs,
  # the ros-* packages carry the .msg/.srv files generate_messages() reads
  libstd-msgs-dev ros-std-msgs python3-std-msgs
  libstd-srvs-dev ros-std-srvs
  libgeometry-msgs-dev ros-geometry-msgs python3-geometry-msgs
  libvisualization-msgs-dev ros-visualization-msgs
  # ROS layer (nodes, tf, bags, interactive markers, rviz)
  libroscpp-dev libtf2-ros-dev libtf2-geometry-msgs-dev librosbag-dev python3-rosbag
  libinteractive-markers-dev librviz-dev rviz
  # the font of rviz's frame names (rviz pulls it in; named here so it is there for sure)
  fonts-liberation
  # live-tunable solver parameters
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  # ROS and end-to-end tests (rostest suites are Python: rospy and the Python messages)
  python3-rostest python3-roslaunch python3-rospy python3-rosnode
  # rosrun, as the README runs single nodes
  rosbash
  python3-std-srvs python3-tf2-ros python3-visualization-msgs
  xvfb xdotool imagemagick
  # fold_sequence's PNG frames (rsvg-convert)
  librsvg2-bin
  # fuzzing (make fuzz): clang with libFuzzer and the sanitizer runtimes
  clang-14 libclang-rt-14-dev
  # benchmark charts (make bench)
  python3-matplotlib
)

missing=()
for pkg in "${PACKAGES[@]}"; do
  status="$(dpkg-query -W -f='${db:Status-Status}' "$pkg" 2>/dev/null || true)"
  if [ "$status" != "installed" ]; then
    missing+=("$pkg")
  fi
done

if [ "${#missing[@]}" -eq 0 ]; then
  echo "install_deps: all ${#PACKAGES[@]} packages already installed"
  exit 0
fi

SUDO=()
if [ "$(id -u)" -ne 0 ]; then
  if ! command -v sudo >/dev/null 2>&1; then
    echo "install_deps: not root and sudo not found; missing: ${missing[*]}" >&2
    exit 1
  fi
  SUDO=(sudo)
fi

echo "install_deps: installing ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update
"${SUDO[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${missing[@]}"
