#!/usr/bin/env bash
# Installs the package into a folder of the build tree and runs the default launch from there, in an
# environment that knows only the install space (not the source tree, not the devel space): every
# node, launch and rviz file, the rviz plugin and its description must have been installed.
# Usage: install_space_test.sh BUILD_DIR SOURCE_DIR
set -euo pipefail
build="$1"
source_dir="$2"
prefix="$(mktemp -d "$build/install_space_test.XXXXXX")"
trap 'rm -rf "$prefix"' EXIT

cmake --install "$build" --prefix "$prefix" >"$prefix/install.log"

mkdir -p "$prefix/home" "$prefix/data"
# The environment an install space's setup gives (a package built on its own installs none):
# only the install prefix and Debian's ROS under /usr.
run_installed() {
  env -i HOME="$prefix/home" PATH="$prefix/bin:/usr/bin:/bin" ROS_HOME="$prefix/home" \
    VO_INSTALL_TEST_DATA="$prefix/data" ROS_PACKAGE_PATH="$prefix/share" CMAKE_PREFIX_PATH="$prefix:/usr" \
    LD_LIBRARY_PATH="$prefix/lib" PYTHONPATH="$prefix/lib/python3/dist-packages" \
    PKG_CONFIG_PATH="$prefix/lib/pkgconfig" ROS_ETC_DIR=/etc/ros ROS_PYTHON_VERSION=3 ROS_VERSION=1 \
    ROS_DISTRO=Debian ROS_MASTER_URI=http://localhost:11311 bash -c "$1"
}

share="$(run_installed 'rospack find virtual_origami')"
if [ "$share" != "$prefix/share/virtual_origami" ]; then
  echo "roslaunch would find virtual_origami at '$share', not in the install space" >&2
  exit 1
fi

missing=()
for node in paper_model spring_solver curved_mesh_solver interaction recorder replay state_markers gripper_example crane_puff \
            fold_sequence fold_demo; do
  [ -x "$prefix/lib/virtual_origami/$node" ] || missing+=("node $node")
done
for file in launch/origami.launch launch/replay.launch launch/gripper_example.launch launch/crane_puff.launch \
            rviz/origami.rviz rviz/crane_puff.rviz \
            src/rviz_plugin/plugin_description.xml package.xml; do
  [ -f "$share/$file" ] || missing+=("$file")
done
[ -f "$prefix/lib/libvirtual_origami_rviz.so" ] || missing+=("the rviz plugin library")
[ -f "$prefix/lib/python3/dist-packages/virtual_origami/msg/__init__.py" ] || missing+=("the Python messages")
plugins="$(run_installed 'rospack plugins --attrib=plugin rviz' | grep '^virtual_origami ' || true)"
[ "$plugins" = "virtual_origami $share/src/rviz_plugin/plugin_description.xml" ] || missing+=("rviz's entry for the plugin (got: $plugins)")
if [ "${#missing[@]}" -gt 0 ]; then
  printf 'not installed: %s\n' "${missing[@]}" >&2
  exit 1
fi

# rostest starts its own master on a free port; the suite's XML results decide pass or fail.
export ROS_HOME="$prefix/home"
run_installed "rostest --text '$source_dir/test/install/install_space.test'"
run_installed "catkin_test_results --verbose '$prefix/home/test_results'"
