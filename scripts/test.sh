#!/usr/bin/env bash
# Runs every stickslip test: installs missing Debian packages, then configures, builds and runs
# CTest in two build trees, both compiled by Clang 14 when it is installed (scripts/deps.sh test
# installs it; Clang compiles the project's units at -O1 in 1/2 to 2/3 of GCC 12's CPU time,
# docs/measurements/test_build.md), the default C++ compiler otherwise:
# - an AddressSanitizer + UBSan build (-O1 -DNDEBUG), which runs every unit test;
# - a normal build (-O1 -DNDEBUG, warnings as errors), which runs what the sanitizer build cannot:
#   the header-hygiene, packaging, Python, MPI and example tests, the blade regression pins, the
#   allocation counts and the full-size versions of the cases the sanitizer build scales down
#   (STICKSLIP_TEST_SPLIT, cmake/StickslipWarnings.cmake). Its header-hygiene units and packaging
#   consumers are compiled by the default compiler (GCC on Debian; STICKSLIP_PACKAGING_CXX), so
#   that every public header is checked, warnings as errors, by both compilers.
# Each unit test thus runs once, in the build that checks the most; compilation is what the run's
# time is made of. A plain `ctest` in one's own build tree (STICKSLIP_TEST_SPLIT off) runs all.
# The two suites run at the same time, each with one job per core: the cores idle in one suite
# (its longest units at the end of its build, its serial tests) work for the other, and the
# command takes about the two suites' CPU time over the number of cores. The normal suite prints
# to the terminal, the sanitizer suite to build/sanitize.log (printed when it ends).
# STICKSLIP_TEST_SEQUENTIAL=1 runs them one after the other (about half the peak memory).
# Exits non-zero on any failure. Build trees: build/test and build/sanitize.
# The benchmarks are built by scripts/work_precision.sh (and by any build with
# -DSTICKSLIP_BUILD_BENCHMARKS=ON); set STICKSLIP_TEST_BENCHMARKS=1 to build them here too.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

run_suite() {  # name, extra cmake args...
  local name=$1; shift
  echo "=== stickslip: ${name} build ==="
  # Ninja schedules the whole build graph at once (both cores busy to the last unit, no per-target
  # make recursion); a build tree configured earlier keeps its generator.
  # A tree configured with another compiler is started afresh (CMake cannot switch it in place).
  local want="" have="" arg
  for arg in "$@"; do case "${arg}" in -DCMAKE_CXX_COMPILER=*) want=${arg#-DCMAKE_CXX_COMPILER=} ;; esac; done
  if [ -n "${want}" ] && [ -f "build/${name}/CMakeCache.txt" ]; then
    have=$(sed -n 's/^CMAKE_CXX_COMPILER:[A-Z]*=//p' "build/${name}/CMakeCache.txt")
    if [ "$(command -v "${want}" || echo "${want}")" != "${have}" ]; then
      echo "stickslip: build/${name} was configured with ${have}; configuring it afresh with ${want}"
      rm -rf "build/${name}"
    fi
  fi
  local generator=()
  if [ ! -f "build/${name}/CMakeCache.txt" ] && command -v ninja >/dev/null 2>&1; then generator=(-G Ninja); fi
  local t0 t1 t2 t3
  t0=$(date +%s)
  # Each step returns on failure itself (set -e does not act in a function called under ||).
  cmake -S . -B "build/${name}" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release -DSTICKSLIP_WARNINGS_AS_ERRORS=ON "$@" || return
  t1=$(date +%s)
  cmake --build "build/${name}" -j "${jobs}" || return
  t2=$(date +%s)
  (cd "build/${name}" && ctest --output-on-failure -j "${jobs}") || return
  t3=$(date +%s)
  echo "stickslip: ${name} suite: configure $((t1 - t0)) s, build $((t2 - t1)) s, tests $((t3 - t2)) s"
}

start=$(date +%s)
scripts/deps.sh test
echo "stickslip: packages checked in $(( $(date +%s) - start )) s"
benchmarks=OFF
if [ "${STICKSLIP_TEST_BENCHMARKS:-0}" = "1" ]; then benchmarks=ON; fi
sanitize_cxx=()
normal_cxx=()
if command -v clang++-14 >/dev/null 2>&1; then
  sanitize_cxx=(-DCMAKE_CXX_COMPILER=clang++-14)
  normal_cxx=(-DCMAKE_CXX_COMPILER=clang++-14)
  default_cxx=$(command -v g++ || command -v c++ || true)
  if [ -n "${default_cxx}" ]; then normal_cxx+=("-DSTICKSLIP_PACKAGING_CXX=${default_cxx}"); fi
fi
sanitize_args=("-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" "${sanitize_cxx[@]}" -DSTICKSLIP_SANITIZE=ON
               -DSTICKSLIP_BUILD_BENCHMARKS=OFF -DSTICKSLIP_BUILD_EXAMPLES=OFF -DSTICKSLIP_HEADER_HYGIENE=OFF
               -DSTICKSLIP_TEST_SPLIT=ON)
normal_args=("-DCMAKE_CXX_FLAGS_RELEASE=-O1 -DNDEBUG" "${normal_cxx[@]}" -DSTICKSLIP_BUILD_BENCHMARKS=${benchmarks}
             -DSTICKSLIP_BUILD_EXAMPLES=ON -DSTICKSLIP_TEST_SPLIT=ON)

if [ "${STICKSLIP_TEST_SEQUENTIAL:-0}" = "1" ]; then
  run_suite test "${normal_args[@]}"
  run_suite sanitize "${sanitize_args[@]}"
  echo "stickslip: all test suites passed in $(( $(date +%s) - start )) s"
  exit 0
fi

mkdir -p build
sanitize_log=build/sanitize.log
# Its own session (setsid), so that an interrupt or a failure here stops its whole tree of jobs.
export -f run_suite
export jobs
setsid bash -c 'set -euo pipefail; run_suite sanitize "$@"' run_suite "${sanitize_args[@]}" > "${sanitize_log}" 2>&1 &
sanitize_pid=$!
trap 'kill -- -"${sanitize_pid}" 2>/dev/null || true' INT TERM
echo "stickslip: the sanitizer suite runs alongside, output in ${sanitize_log}"
normal_status=0
run_suite test "${normal_args[@]}" || normal_status=$?
sanitize_status=0
wait "${sanitize_pid}" || sanitize_status=$?
trap - INT TERM
echo "=== stickslip: sanitizer suite (${sanitize_log}) ==="
cat "${sanitize_log}"
if [ "${normal_status}" != 0 ] || [ "${sanitize_status}" != 0 ]; then
  echo "stickslip: FAILED (normal suite exit ${normal_status}, sanitizer suite exit ${sanitize_status})" >&2
  exit 1
fi
echo "stickslip: all test suites passed in $(( $(date +%s) - start )) s"
