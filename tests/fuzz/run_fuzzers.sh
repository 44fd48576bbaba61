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

for target in descriptors exr; do
  work="$build/work/$target"
  rm -rf "$work"
  mkdir -p "$work/corpus" "$work/artifacts"
  cp tests/fuzz/corpus/"$target"/* "$work/corpus/"
  # -timeout: one input may take at most 10 s; -rss_limit_mb: a malformed
  # input must not make the reader take more than 2 GB.
  if ! "$build/rrc_fuzz_$target" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
      -artifact_prefix="$work/artifacts/" "$work/corpus" > "$work/log" 2>&1; then
    echo "fuzz: rrc_fuzz_$target FAILED (log: $work/log)"
    tail -n 80 "$work/log"
    ls -l "$work/artifacts"
    exit 1
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$work/log" | grep -o '[0-9]*$' || echo "?")
  echo "fuzz: rrc_fuzz_$target: $runs inputs in ${seconds} s, no crash"
done
