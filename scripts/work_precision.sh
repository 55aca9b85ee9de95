#!/usr/bin/env bash
# The performance study of docs/performance.md in one command: builds the benchmarks in Release,
# runs the work-precision program (CSV/JSON/markdown tables) and its plots (PNG), and with
# --with-micro also the model micro-benchmarks (Google Benchmark JSON + a markdown table).
#
#   scripts/work_precision.sh [--with-micro] [--out DIR] [--build DIR] [--threads N]
#
# Defaults: --out out/work_precision (untracked; pass --out docs/performance to refresh the
# committed data of docs/performance.md)  --build build/release-bench  --threads $(nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/work_precision
build=build/release-bench
threads=$(nproc 2>/dev/null || echo 2)
micro=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --with-micro) micro=1 ;;
    --out) out=$2; shift ;;
    --build) build=$2; shift ;;
    --threads) threads=$2; shift ;;
    -h|--help) sed -n 2,8p "$0"; exit 0 ;;
    *) echo "work_precision.sh: unknown argument $1" >&2; exit 2 ;;
  esac
  shift
done
scripts/deps.sh all   # Eigen, Spectra, Google Benchmark, and python3-matplotlib for the plots
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_BUILD_BENCHMARKS=ON
targets=(work_precision)
[[ $micro == 1 ]] && targets+=(model_benchmark)
cmake --build "$build" --target "${targets[@]}" -j "$threads"
mkdir -p "$out"
"$build/benchmarks/work_precision/work_precision" --out "$out" --threads "$threads"
/usr/bin/python3 benchmarks/work_precision/plot_work_precision.py "$out"
if [[ $micro == 1 ]]; then
  # Medians of 5 repetitions: a shared 2-core VM varies by up to 2x between single runs.
  "$build/benchmarks/model/model_benchmark" --benchmark_out="$out/model_benchmark.json" \
      --benchmark_out_format=json --benchmark_repetitions=5
  /usr/bin/python3 benchmarks/model/micro_table.py "$out/model_benchmark.json" > "$out/model_benchmark.md"
fi
echo "work_precision.sh: results in $out"
