#!/usr/bin/env bash
# The main job: installs missing Debian packages, builds in Release and runs the default
# blade-damper scene (the paper's three preloads and a preload sweep), writing CSV/JSON/PNG
# results under ./out/ and printing a summary. Extra arguments go to the example program.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh demo
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release \
      -DSTICKSLIP_BUILD_TESTS=OFF -DSTICKSLIP_BUILD_BENCHMARKS=OFF -DSTICKSLIP_BUILD_EXAMPLES=ON
cmake --build build/release --target blade_damper -j "${jobs}"
mkdir -p out
build/release/examples/blade_damper/blade_damper --demo --out out "$@"
if command -v /usr/bin/python3 >/dev/null 2>&1; then
  /usr/bin/python3 examples/blade_damper/plot.py out
fi
