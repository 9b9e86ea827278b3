#!/usr/bin/env bash
# Runs one rostest suite for ctest. `rostest --text` shows the test's output but then exits 0
# even when a test fails, so the suite's XML results decide the exit code.
# Usage: run_rostest.sh DEVEL_DIR SUITE.test
set -uo pipefail
devel="$1"
suite="$2"
results="$(mktemp -d)"
trap 'rm -rf "$results"' EXIT
export ROS_HOME="$results"
"$devel/env.sh" rostest --text "$suite"
status=$?
if [ "$status" -ne 0 ]; then
  exit "$status"
fi
"$devel/env.sh" catkin_test_results --verbose "$results/test_results"
