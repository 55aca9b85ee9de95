#!/usr/bin/env bash
# The peer benchmark of docs/measurements/peers.md in one command: installs Boost and
# SUNDIALS if missing (scripts/deps.sh bench), builds benchmarks/peers in Release and runs it,
# writing peers.csv, peers.json and peers.md to the output folder.
#
#   scripts/peers.sh [--out DIR] [--build DIR] [--repeats R] [--threads N]
#
# Defaults: --out build/peers-out  --build build/release-bench  --repeats 5  --threads $(nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
out=build/peers-out
build=build/release-bench
repeats=5
threads=$(nproc 2>/dev/null || echo 2)
while [[ $# -gt 0 ]]; do
  case "$1" in
    --out) out=$2; shift ;;
    --build) build=$2; shift ;;
    --repeats) repeats=$2; shift ;;
    --threads) threads=$2; shift ;;
    -h|--help) sed -n 2,8p "$0"; exit 0 ;;
    *) echo "peers.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
scripts/deps.sh bench
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_BUILD_BENCHMARKS=ON \
      -DSTICKSLIP_BUILD_PEER_BENCHMARKS=ON
cmake --build "$build" --target peer_benchmark -j "$threads"
mkdir -p "$out"
"$build/benchmarks/peers/peer_benchmark" --out "$out" --repeats "$repeats"
echo "peers.sh: results in $out"
