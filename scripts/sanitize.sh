#!/usr/bin/env bash
# AddressSanitizer + UndefinedBehaviorSanitizer build of the ROS-free core and
# its unit tests (ws/sanitize, RelWithDebInfo so reports carry file:line), then
# ctest. Exits non-zero if the build fails, a test fails, or any sanitizer
# reports (ASan aborts the test; UBSan is built with -fno-sanitize-recover, and
# the log is also scanned in case a report slipped out of a forked process).
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
export PATH=/usr/bin:/bin:$PATH
build_dir=$root/ws/sanitize
log=$build_dir/ctest.log
jobs=${SANITIZE_JOBS:-2}

# Leak checking stays on: a leak in the core is a bug. halt_on_error makes the
# first report fail its test; print_stacktrace gives UBSan reports a backtrace.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:halt_on_error=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-halt_on_error=1:print_stacktrace=1}

# Eigen switches to its own aligned malloc (offset stored before each block)
# under AddressSanitizer, while the prebuilt PCL frees and allocates with
# plain malloc: clouds crossing the boundary then look like heap overflows in
# handmade_aligned_free. Keep the ABI of the system libraries.
eigen_flags="-DEIGEN_MALLOC_ALREADY_ALIGNED=1"
start_s=$(date +%s)
cmake -S "$root" -B "$build_dir" -DBRICK_POSE_CORE_ONLY=ON -DBRICK_POSE_SANITIZE=ON \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$eigen_flags" >/dev/null || { echo "sanitize: configure failed" >&2; exit 1; }
cmake --build "$build_dir" -j"$jobs" || { echo "sanitize: build failed" >&2; exit 1; }
build_s=$(( $(date +%s) - start_s ))

(cd "$build_dir" && ctest --output-on-failure -j"$jobs" ${CTEST_ARGS:-}) 2>&1 | tee "$log"
ctest_status=${PIPESTATUS[0]}
total_s=$(( $(date +%s) - start_s ))

status=0
[[ $ctest_status -eq 0 ]] || { echo "sanitize: ctest failed"; status=1; }
if grep -qE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" "$log"; then
  echo "sanitize: sanitizer reports (see $log):"
  grep -nE "ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:" "$log" | head -20
  status=1
fi
echo "sanitize: build ${build_s} s, total ${total_s} s, $([[ $status -eq 0 ]] && echo clean || echo FAILED)"
exit $status
