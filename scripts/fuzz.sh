#!/usr/bin/env bash
# Runs every libFuzzer harness of tests/fuzz/ for the given number of seconds each (default 60):
#   scripts/fuzz.sh [seconds] [harness...]
# Configures a Clang build in build/fuzz with -DSTICKSLIP_FUZZ=ON (libFuzzer + ASan + UBSan), builds
# the <harness>_fuzzer binaries and runs each on a scratch copy of its regression corpus
# (tests/fuzz/corpus/<harness>/), so new interesting inputs land in build/fuzz/corpus/<harness>/
# and never in the checked-in corpus. libFuzzer runs in fork mode and goes on after a finding: each
# crash, violation (abort), timeout (-timeout, a hang) or allocation beyond -malloc_limit_mb /
# -rss_limit_mb leaves its input in build/fuzz/findings/<harness>/. Exits non-zero if any harness
# found something. Logs: build/fuzz/logs/<harness>.log.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
harnesses=("$@")
if [ ${#harnesses[@]} -eq 0 ]; then harnesses=(contact stepper frame_modes member_shapes model steady_state separation); fi
cxx=${STICKSLIP_FUZZ_CXX:-$(command -v clang++ || true)}
if [ -z "${cxx}" ]; then
  echo "scripts/fuzz.sh: clang++ not found (Debian: apt-get install clang libclang-rt-dev)" >&2
  exit 2
fi
jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build/fuzz -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER="${cxx}" \
      "-DCMAKE_CXX_FLAGS_RELEASE=-O1 -g -DNDEBUG" -DSTICKSLIP_FUZZ=ON -DSTICKSLIP_HEADER_HYGIENE=OFF \
      -DSTICKSLIP_BUILD_EXAMPLES=OFF -DSTICKSLIP_BUILD_BENCHMARKS=OFF -DSTICKSLIP_INSTALL=OFF > /dev/null
targets=()
for h in "${harnesses[@]}"; do targets+=("${h}_fuzzer"); done
cmake --build build/fuzz -j "${jobs}" --target "${targets[@]}"

status=0
for h in "${harnesses[@]}"; do
  corpus=build/fuzz/corpus/${h}
  findings=build/fuzz/findings/${h}
  mkdir -p "${corpus}" "${findings}" build/fuzz/logs
  cp -n tests/fuzz/corpus/"${h}"/* "${corpus}"/ 2>/dev/null || true
  echo "=== ${h}: ${seconds} s ==="
  # -timeout: work per input is bounded (tests/fuzz/*_fuzz.cpp); the slowest bounded case, the
  # stepper harness's 2e5-sample cap, takes ~1.5 s (~10 s under ASan), so 30 s is a hang.
  # -rss_limit_mb / -malloc_limit_mb catch the absurd allocations that a fuzz run found.
  UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "build/fuzz/tests/fuzz/${h}_fuzzer" "${corpus}" -max_total_time="${seconds}" -timeout=30 \
    -rss_limit_mb=2048 -malloc_limit_mb=1024 -max_len=512 -fork=1 -ignore_crashes=1 \
    -ignore_timeouts=1 -ignore_ooms=1 -artifact_prefix="${findings}/" \
    > "build/fuzz/logs/${h}.log" 2>&1 || true
  grep -E "^#[0-9]+: cov:" "build/fuzz/logs/${h}.log" | tail -1 || true
  found=$(find "${findings}" -type f | wc -l)
  if [ "${found}" -gt 0 ]; then
    status=1
    echo "${h}: ${found} finding(s) in ${findings}/ (log: build/fuzz/logs/${h}.log); causes (replayed):"
    for f in "${findings}"/*; do
      timeout 60 "build/fuzz/tests/fuzz/${h}_fuzzer" "${f}" 2>&1 |
        grep -m1 -E "VIOLATION|exception not derived|ERROR: (AddressSanitizer|libFuzzer)|runtime error" |
        cut -c1-160 || echo "(timeout or no message)"
    done | sort | uniq -c | sort -rn | head -20
  fi
done
cat <<'MSG'
To keep a finding as a regression input: reproduce it with the replay tool
  build/<dir>/tests/fuzz/stickslip_fuzz_replay <harness> build/fuzz/findings/<harness>/<file>
copy it to tests/fuzz/corpus/<harness>/<name after what it reproduces>, list it in
tests/fuzz/corpus/KNOWN_FAILING.txt until its fix is merged, and record it in docs/stability.md
("Fuzzing"). Inputs in build/fuzz/corpus/ are coverage only: merge them by hand if wanted
(<harness>_fuzzer -merge=1 tests/fuzz/corpus/<harness> build/fuzz/corpus/<harness>).
MSG
exit ${status}
