#!/usr/bin/env bash
# `make bench`: every benchmark driver one after the other, each timed (wall and CPU seconds into
# docs/bench/bench_wall_time.csv), then the charts and the tables of docs/BENCHMARKS.md, whose
# "Wall time" section is written from that file last, so the page gives the time of the run
# that made it. Usage: [BENCH_ONLY=<step>] scripts/run_bench.sh [BUILD_DIR] (BENCH_ONLY runs one step
# alone and leaves the wall-time table as it was)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build}"
bin="$build/devel/lib/virtual_origami"
out="$root/docs/bench"
doc="$root/docs/BENCHMARKS.md"
export PATH=/usr/bin:$PATH
cd "$root"
mkdir -p "$out"

times_csv="$out/bench_wall_time.csv"
pending="$(mktemp)"
trap 'rm -f "$pending" "$cpu_file"' EXIT
echo "step,wall_seconds,cpu_seconds" >"$pending"

# CPU seconds of every finished child of this shell (user + system) into $cpu_now, from `times`,
# which must run in this shell itself: in a command substitution it counts a subshell's children.
cpu_file="$(mktemp)"
children_cpu() {
  times >"$cpu_file"
  cpu_now="$(tail -n 1 "$cpu_file" | tr -d 's' | awk '{ split($1, u, "m"); split($2, s, "m"); printf "%.3f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }')"
}

minus() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.3f", a - b }'; }

run_start="$(date +%s.%N)"
children_cpu
run_cpu="$cpu_now"
# BENCH_ONLY=<step> runs that step alone (the wall-time table is then left as it was).
step() {
  local name="$1"
  shift
  if [ -n "${BENCH_ONLY:-}" ] && [ "$name" != "$BENCH_ONLY" ]; then
    return 0
  fi
  echo "bench: $name"
  local start cpu
  start="$(date +%s.%N)"
  children_cpu
  cpu="$cpu_now"
  "$@"
  children_cpu
  echo "$name,$(minus "$(date +%s.%N)" "$start"),$(minus "$cpu_now" "$cpu")" >>"$pending"
}

step solver_bench "$bin/solver_bench" "$out"
step sweep_bench "$bin/sweep_bench" "$out"
step curved_bench "$bin/curved_bench" "$out/curved_solvers.csv"
# One core: CHOLMOD's OpenMP loops capped to one thread.
step curved_speed_bench env OMP_THREAD_LIMIT=1 "$bin/curved_speed_bench" "$out"
# One core, as curved_speed_bench (CHOLMOD's OpenMP loops capped to one thread).
step fold_bench env OMP_THREAD_LIMIT=1 "$bin/fold_bench" "$out"
# One core: a corner-face turn drag at 1,681, 5,000 and 10,000 vertices (docs/SOLVERS.md).
step turn_bench sh -c "OMP_THREAD_LIMIT=1 \"$bin/turn_bench\" 1681 5000 10000 > \"$out/turns.csv\""
# One core, as fold_bench: the crane's gestures, each pointer event to its serialized markers.
step gesture_bench env OMP_THREAD_LIMIT=1 "$bin/gesture_bench" "$out/gesture_latency.csv" test/data/crane_reference.json
# One core: Origami Simulator's example patterns folded by assignment in steps and in one call,
# each call stopped after 20 s of its CPU (docs/BENCHMARKS.md, "Real crease patterns").
step pattern_bench env OMP_THREAD_LIMIT=1 "$bin/pattern_bench" bench/patterns/origami-simulator "$out/patterns.csv" 20
step replay_bench "$bin/replay_bench" "$out/replay.csv" sequences/crane.json sequences/penguin.json sequences/miura_ori.json
step mesh_bench "$bin/mesh_bench" "$out"
# Journal and memory: their temporary files in the build folder, on disk (not a tmpfs /tmp).
step journal_bench "$bin/journal_bench" "$out" "$build"
step memory_bench "$bin/memory_bench" "$out" "$build"

# paper_model + spring_solver + 4 clients (bench/contention_bench.launch): a master on a free
# port of its own, a ROS_HOME and a data folder (the journal, on disk) of its own, removed
# after; the CSVs are moved into docs/bench only when the run wrote them.
run_contention() {
  local name="$1" ros_home data port status=0
  shift
  ros_home="$(mktemp -d)"
  data="$(mktemp -d -p "$build" contention_bench.XXXXXX)"
  port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
  ROS_HOME="$ros_home" timeout 600 "$build/devel/env.sh" roslaunch -p "$port" virtual_origami contention_bench.launch \
    data_dir:="$data" csv_prefix:="$data/$name" "$@" || status=$?
  if [ "$status" -eq 0 ] && [ -s "$data/$name.csv" ] && [ -s "$data/${name}_refusals.csv" ]; then
    mv "$data/$name.csv" "$data/${name}_refusals.csv" "$out/"
  else
    echo "contention_bench: no CSV written (roslaunch status $status)" >&2
    status=1
  fi
  rm -rf "$ros_home" "$data"
  return "$status"
}
# A slow solver (the seed's scheme, the launch's default), then the default solver.
step contention_bench run_contention contention
step contention_bench_newton run_contention contention_newton solver:=newton tolerance:=1e-10 max_iterations:=1000 \
  rotations:=100 rotations_alone:=50
# The user's path (bench/user_path.launch): origami.launch's nodes (rviz aside) driven through
# their services and the interaction node's feedback topic, as contention_bench on a master port,
# ROS_HOME and data folder of its own; journal_sync on (the default) on every pattern, then off on
# the Miura-ori of 1,000 vertices. USER_PATH_SIZES, USER_PATH_OTHER_SIZES and USER_PATH_NOSYNC_SIZES
# override the vertex counts.
run_user_path() {
  local ros_home data port status=0 prefix
  ros_home="$(mktemp -d)"
  # Absolute: the nodes run in ROS_HOME, where a relative build folder means nothing.
  data="$(cd "$(mktemp -d -p "$build" user_path_bench.XXXXXX)" && pwd)"
  prefix="$data/user_path"
  for configuration in journal_sync no_journal_sync; do
    port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')"
    if [ "$configuration" = journal_sync ]; then
      set -- sizes:="${USER_PATH_SIZES:-1000,2500,5000,10000}" other_sizes:="${USER_PATH_OTHER_SIZES:-1000}"
    else
      set -- journal_sync:=false patterns:=miura sizes:="${USER_PATH_NOSYNC_SIZES:-1000}"
    fi
    ROS_HOME="$ros_home" timeout 1800 "$build/devel/env.sh" roslaunch -p "$port" virtual_origami user_path.launch \
      data_dir:="$data" csv_prefix:="$prefix" configuration:="$configuration" "$@" || status=$?
  done
  # What a run that stopped early wrote is kept too (each row is written as it is measured).
  if [ -s "$prefix.csv" ] && [ -s "${prefix}_breakdown.csv" ]; then
    mv "$prefix.csv" "${prefix}_breakdown.csv" "$out/"
  else
    echo "user_path_bench: no CSV written (roslaunch status $status)" >&2
    status=1
  fi
  rm -rf "$ros_home" "$data"
  return "$status"
}
step user_path_bench run_user_path
step plot_charts /usr/bin/python3 bench/plot_charts.py "$out" docs/images/bench "$doc"
if [ -n "${BENCH_ONLY:-}" ]; then
  exit 0
fi
children_cpu
echo "total,$(minus "$(date +%s.%N)" "$run_start"),$(minus "$cpu_now" "$run_cpu")" >>"$pending"
mv "$pending" "$times_csv"
/usr/bin/python3 bench/plot_charts.py "$out" docs/images/bench "$doc" --only wall_time
