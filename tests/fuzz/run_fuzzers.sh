#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (tests/fuzz/CMakeLists.txt) and runs
# each for a bounded time from a copy of its committed seed corpus
# (tests/fuzz/corpus/<target>/; the copy is what grows).  Any crash,
# sanitizer report, leak, timeout or out-of-memory fails the script and
# prints the end of the log and the input that triggered it.
#   RRC_FUZZ_SECONDS  seconds per target (default 60)
#   RRC_FUZZ_BUILD    build directory (default build/fuzz)
set -euo pipefail
cd "$(dirname "$0")/../.."
seconds=${RRC_FUZZ_SECONDS:-60}
build=${RRC_FUZZ_BUILD:-build/fuzz}

mkdir -p "$build"
cmake -S tests/fuzz -B "$build" -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo > "$build/configure.log" 2>&1 ||
  { cat "$build/configure.log"; exit 1; }
cmake --build "$build" -j"$(nproc)"

targets=(descriptors exr)
# Each target is one single-threaded process: with a core for each they run
# side by side, each still fuzzing its full time on a core of its own;
# with fewer cores, one after the other.
parallel=0
if (( $(nproc) >= ${#targets[@]} )); then parallel=1; fi

declare -A pids
start() {  # start <target>: fuzz from a fresh copy of its seed corpus, log in $build/work/<target>/log
  local target=$1 work="$build/work/$1"
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp tests/fuzz/corpus/"$target"/* "$work/corpus/"
  # -timeout: one input may take at most 10 s; -rss_limit_mb: a malformed
  # input must not make the reader take more than 2 GB.
  "$build/rrc_fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$work/artifacts/" "$work/corpus" > "$work/log" 2>&1 &
  pids[$target]=$!
}
finish() {  # finish <target>: wait for it; on failure print its log's end and the input, and exit
  local target=$1 work="$build/work/$1"
  if ! wait "${pids[$target]}"; then
    echo "fuzz: rrc_fuzz_$target FAILED (log: $work/log)"
    tail -n 80 "$work/log"
    ls -l "$work/artifacts"
    kill "${pids[@]}" 2> /dev/null || true  # the other target, if still running
    exit 1
  fi
  local runs
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo "?")
  echo "fuzz: rrc_fuzz_$target: $runs inputs in ${seconds} s, no crash"
}

if ((parallel)); then
  for target in "${targets[@]}"; do start "$target"; done
  for target in "${targets[@]}"; do finish "$target"; done
else
  for target in "${targets[@]}"; do start "$target"; finish "$target"; done
fi
