#!/usr/bin/env bash
# The sanitizer job: builds sst with ASan and UBSan (clang) in build-fuzz/, runs the unit tests
# there, then the libFuzzer harnesses of tests/fuzz, each for SECONDS (default 60) on a scratch
# corpus seeded from tests/fuzz/corpus/<name>/ (the committed seeds are only read). A sanitizer
# report fails the unit tests; a crash, sanitizer report, input over 10 s or heap over 2 GB stops
# that harness, leaves the input in build-fuzz/findings/ and fails the script.
# Unit tests: those labelled `unit` (tests/CMakeLists.txt, docs/testing.md), so that the renders,
# which ASan slows several times, stay in the Release run; they run in one process, as starting
# the sanitized test binary once per test would cost more than the tests.
# Usage: scripts/fuzz.sh [SECONDS] [HARNESS ...]   (harnesses: gltf texture config image)
#        scripts/fuzz.sh --ci   (CI: the unit tests, then a fixed number of inputs per harness
#                               from a fixed seed, so that a run is repeatable; about half a
#                               minute each on 2 cores)
#        scripts/fuzz.sh --no-unit-tests ...   (only the harnesses)
set -euo pipefail
cd "$(dirname "$0")/.."
declare -A ci_runs=([gltf]=60000 [texture]=60000 [config]=60000 [image]=3000)
ci=0
unit_tests=1
if [ "${1:-}" = "--no-unit-tests" ]; then unit_tests=0; shift; fi
if [ "${1:-}" = "--ci" ]; then ci=1; shift; set -- 0 "$@"; fi
seconds=${1:-60}
shift || true
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=(gltf texture config image)
launcher=()
if command -v ccache > /dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache -DCMAKE_C_COMPILER_LAUNCHER=ccache); fi
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "${launcher[@]}" -DSST_FUZZ=ON -DSST_ENABLE_VULKAN=OFF -DSST_BUILD_TESTS=ON -DSST_BUILD_BENCHMARKS=OFF > /dev/null
targets=("${harnesses[@]/#/fuzz_}")
[ $unit_tests = 0 ] || targets+=(sst_tests)
cmake --build build-fuzz -j2 --target "${targets[@]}"
mkdir -p build-fuzz/findings
export LSAN_OPTIONS="suppressions=$PWD/tests/fuzz/lsan.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}"
status=0
if [ $unit_tests = 1 ]; then
  # ctest names a parameterized test by its value (Prefix/Suite.Test/"radix"), gtest by its index.
  filter=$(ctest --test-dir build-fuzz -N -L '^unit$' | sed -n 's/^ *Test *#[0-9]*: //p' |
           awk '{ n = $1; if (gsub("/", "/", n) >= 2) sub("/[^/]*$", "/*", n); print n }' | sort -u | paste -sd: -)
  [ -n "$filter" ] || { echo "no test labelled unit in build-fuzz"; exit 1; }
  count=$(build-fuzz/tests/sst_tests --gtest_list_tests --gtest_filter="$filter" | grep -c '^  ' || true)
  echo "unit tests under ASan and UBSan: $count tests"
  start=$(date +%s)
  if ! build-fuzz/tests/sst_tests --gtest_filter="$filter" --gtest_brief=1 > build-fuzz/unit_tests.log 2>&1; then
    echo "unit tests under sanitizers: FAILED (build-fuzz/unit_tests.log)"
    tail -n 60 build-fuzz/unit_tests.log
    status=1
  fi
  echo "unit tests under sanitizers: $(($(date +%s) - start)) s"
fi
# Every limit derived from the machine's memory is derived from 4 GiB instead, so that a run refuses
# the same inputs on every machine (and repeats with --ci) and stays below libFuzzer's 2 GB heap limit.
# The image harness gets 256 MiB: ASan's allocator writes every large allocation whole, and OpenEXR
# allocates buffers from the header's width that a Release build never touches (a 588-byte file
# declaring one line of 16M pixels read in 0.6 s in Release, 25 s under ASan: a timeout in CI), so
# the images it may read must be smaller under ASan than the machine would allow.
declare -A memory_mb=([image]=256)
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
  if ! SST_MEMORY_LIMIT_MB=${memory_mb[$h]:-4096} "build-fuzz/tests/fuzz/fuzz_$h" "build-fuzz/corpus/$h" "tests/fuzz/corpus/$h" "${limit[@]}" \
      -timeout=10 -rss_limit_mb=2048 -artifact_prefix="build-fuzz/findings/$h-" -print_final_stats=1 \
      > "build-fuzz/fuzz_$h.log" 2>&1; then
    echo "fuzz_$h: FINDING (build-fuzz/fuzz_$h.log, build-fuzz/findings/)"
    tail -n 40 "build-fuzz/fuzz_$h.log"
    status=1
  fi
  grep -E "^stat::(number_of_executed_units|average_exec_per_sec|peak_rss_mb)|^Done [0-9]+ runs" "build-fuzz/fuzz_$h.log" | sort -u || true
done
exit $status
