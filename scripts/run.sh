#!/usr/bin/env bash
# `make run`: the whole system (paper_model, spring_solver, rviz) folds a short demo through
# its services, then an rviz screenshot and the FOLD file of the result go to the output
# folder. Headless (no DISPLAY) it runs rviz under Xvfb and stops when done; with a display
# it leaves rviz open until Ctrl-C.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="$(mkdir -p "${1:-$root/output}" && cd "${1:-$root/output}" && pwd)"
export PATH="/usr/bin:$PATH"
set +u
source "$root/build/devel/setup.bash"
set -u
export ROS_MASTER_URI="http://localhost:11411"  # a master of its own, apart from any other
export ROS_HOME="$out/ros"

pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  sleep 2
  for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT

headless=0
if [ -z "${DISPLAY:-}" ]; then
  headless=1
  export DISPLAY=:97
  Xvfb "$DISPLAY" -screen 0 1024x768x24 -nolisten tcp >"$out/xvfb.log" 2>&1 &
  pids+=($!)
  sleep 1
fi

roslaunch virtual_origami origami.launch data_dir:="$out" journal:=session.jsonl resume:=false >"$out/roslaunch.log" 2>&1 &
pids+=($!)
for _ in $(seq 120); do rostopic list >/dev/null 2>&1 && break; sleep 0.5; done  # the master is up
python3 "$root/scripts/fold_demo_client.py" "$out"
sleep 4  # let rviz draw the last state
import -window root "$out/rviz.png"
echo "wrote $out/rviz.png (rviz), $out/result.fold and $out/result.obj (the folded paper), $out/session.jsonl (its history)"
if [ "$headless" = 0 ]; then
  echo "rviz stays open: fold on through the services (see README); Ctrl-C to stop"
  wait "${pids[-1]}"
fi
