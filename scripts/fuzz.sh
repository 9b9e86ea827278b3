#!/usr/bin/env bash
# `make fuzz`: builds the libFuzzer targets of test/fuzz/ with clang-14, AddressSanitizer and
# UndefinedBehaviorSanitizer into build-fuzz/, then fuzzes each for FUZZ_SECONDS, one after
# the other (the machine has two cores). New inputs go to build-fuzz/corpus/<target>/, seeded
# from the committed test/fuzz/corpus/<target>/; a crash, sanitizer report or invariant
# violation is written to test/fuzz/crashes/<target>/, where ctest replays it from then on.
# Usage: FUZZ_SECONDS=600 FUZZ_TARGETS="fold_reader session_ops" scripts/fuzz.sh
set -uo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${FUZZ_SECONDS:-60}"
targets="${FUZZ_TARGETS:-fold_reader session_ops}"
build="${FUZZ_BUILD_DIR:-$root/build-fuzz}"
export PATH=/usr/bin:$PATH

CC=clang-14 CXX=clang++-14 cmake -S "$root/test/fuzz" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null || exit 1
cmake --build "$build" -j "${JOBS:-2}" || exit 1

status=0
summary="$build/fuzz-summary.txt"
: >"$summary"
for target in $targets; do
  case "$target" in
    fold_reader) max_len=8192 ;;
    *) max_len=1024 ;;
  esac
  work="$build/corpus/$target"
  crashes="$root/test/fuzz/crashes/$target"
  mkdir -p "$work" "$crashes"
  log="$build/$target.log"
  echo "fuzz: $target for $seconds s (log $log)"
  # -timeout is for hangs: the sanitizer build runs the solvers ~70 times slower than Release,
  # and an input of 60 ms in Release (30 refused squashes) took 24 s on a loaded machine.
  (cd "$build" && "./${target}_fuzz" -max_total_time="$seconds" -max_len="$max_len" -timeout=120 -rss_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$crashes/" "$work" "$root/test/fuzz/corpus/$target") >"$log" 2>&1
  code=$?
  runs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')"
  cov="$(grep -E '^#[0-9]+' "$log" | tail -n 1 | grep -o 'cov: [0-9]*' | grep -o '[0-9]*')"
  corpus="$(find "$work" -type f | wc -l)"
  line="$target: exit $code, ${runs:-?} executions in $seconds s, coverage ${cov:-?} edges, corpus $corpus inputs"
  echo "fuzz: $line"
  echo "$line" >>"$summary"
  if [ "$code" -ne 0 ]; then
    status=1
    grep -E 'ERROR|invariant violated|Test unit written' "$log" | head -n 5
  fi
done
exit "$status"
