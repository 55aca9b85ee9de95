#!/usr/bin/env bash
# Runs every stickslip test: installs missing Debian packages, then configures, builds and runs
# CTest twice - a normal build with warnings as errors, and an AddressSanitizer + UBSan build.
# Exits non-zero on any failure. Build trees: build/test and build/sanitize.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh test
jobs=$(nproc 2>/dev/null || echo 2)

run_suite() {  # name, extra cmake args...
  local name=$1; shift
  echo "=== stickslip: ${name} build ==="
  cmake -S . -B "build/${name}" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DSTICKSLIP_WARNINGS_AS_ERRORS=ON -DSTICKSLIP_BUILD_BENCHMARKS=ON "$@"
  cmake --build "build/${name}" -j "${jobs}"
  (cd "build/${name}" && ctest --output-on-failure -j "${jobs}")
}

run_suite test
run_suite sanitize -DSTICKSLIP_SANITIZE=ON -DSTICKSLIP_BUILD_BENCHMARKS=OFF
echo "stickslip: all test suites passed"
