#!/usr/bin/env bash
# Builds the libFuzzer harnesses of tests/fuzz in build-fuzz/ (clang; ASan and UBSan over all of
# sst) and runs each for SECONDS (default 60) on a scratch corpus seeded from tests/fuzz/corpus/<name>/
# (the committed seeds are only read). A crash, sanitizer report, input over 10 s or heap over
# 2 GB stops that harness, leaves the input in build-fuzz/findings/ and fails the script.
# Usage: scripts/fuzz.sh [SECONDS] [HARNESS ...]   (harnesses: gltf texture config image)
#        scripts/fuzz.sh --ci   (CI: a fixed number of inputs per harness from a fixed seed, so
#                               that a run is repeatable; about half a minute each on 2 cores)
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A ci_runs=([gltf]=60000 [texture]=60000 [config]=60000 [image]=3000)
ci=0
if [ "${1:-}" = "--ci" ]; then ci=1; shift; set -- 0 "$@"; fi
seconds=${1:-60}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(gltf texture config image)
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "${launcher[@]}" -DSST_FUZZ=ON -DSST_ENABLE_VULKAN=OFF -DSST_BUILD_TESTS=OFF -DSST_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build build-fuzz -j2 --target "${harnesses[@]/#/fuzz_}"
mkdir -p build-fuzz/findings
# Every limit derived from the machine's memory is derived from 4 GiB instead, so that a run refuses
# the same inputs on every machine (and repeats with --ci) and stays below libFuzzer's 2 GB heap limit.
export SST_MEMORY_LIMIT_MB=4096
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
status=0
for h in "${harnesses[@]}"; do
  mkdir -p "build-fuzz/corpus/$h"
  if [ $ci = 1 ]; then
    limit=(-runs="${ci_runs[$h]}" -seed=1)
    rm -rf "build-fuzz/corpus/$h"
    mkdir -p "build-fuzz/corpus/$h"
    echo "fuzz_$h: ${ci_runs[$h]} inputs, seed 1"
  else
    limit=(-max_total_time="$seconds")
    echo "fuzz_$h: ${seconds} s"
  fi
  if ! "build-fuzz/tests/fuzz/fuzz_$h" "build-fuzz/corpus/$h" "tests/fuzz/corpus/$h" "${limit[@]}" \
      -timeout=10 -rss_limit_mb=2048 -artifact_prefix="build-fuzz/findings/$h-" -print_final_stats=1 \
      > "build-fuzz/fuzz_$h.log" 2>&1; then
    echo "fuzz_$h: FINDING (build-fuzz/fuzz_$h.log, build-fuzz/findings/)"
    tail -n 40 "build-fuzz/fuzz_$h.log"
    status=1
  fi
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^Done [0-9]+ runs" "build-fuzz/fuzz_$h.log" | sort -u || true
done
exit $status
