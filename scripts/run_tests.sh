#!/usr/bin/env bash
# Runs every unit test and rostest of brick_pose and exits non-zero if any
# fails. `catkin_make run_tests` exits 0 on failures, so the verdict comes
# from catkin_test_results over the result files.
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
# shellcheck source=scripts/ros_env.sh
source "$root/scripts/ros_env.sh"
cd "$root/ws"
results=build/test_results
rm -rf "$results"
start=$(date +%s)
echo "brick_pose: running tests (log in ws/test.log)"
# Build the test executables in parallel, then run them one at a time (the
# rostests start nodelet managers and would compete for the two cores).
catkin_make tests -j"$(nproc)" >"$root/ws/test.log" 2>&1 &&
  catkin_make run_tests -j1 >>"$root/ws/test.log" 2>&1
build_status=$?
# Last: `catkin_make install`, then a rostest and the demo from the install space.
"$root/scripts/install_check.sh"
# Per-test lines for the reader, then the verdict.
grep -E "^\[ *(OK|FAILED) *\]|^\[  PASSED  \]|^\[  FAILED  \]|^-- run_tests.py|^\[ROSTEST\]|FAILURE" "$root/ws/test.log" | grep -v "^-- run_tests.py: verify result" || true
summary=$(catkin_test_results "$results" 2>&1)
verdict=$?
echo "$summary" | tail -15
if [[ $build_status -ne 0 ]]; then
  echo "brick_pose: building or running the tests failed (see ws/test.log)" >&2
  tail -30 "$root/ws/test.log"
  verdict=1
fi
# Count the test cases over all result files.
read -r total failed < <(python3 - "$results" <<'PY'
import sys, pathlib, xml.etree.ElementTree as ET
total = failed = 0
for path in pathlib.Path(sys.argv[1]).rglob("*.xml"):
    try:
        root = ET.parse(path).getroot()
    except ET.ParseError:
        failed += 1
        continue
    for case in root.iter("testcase"):
        total += 1
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
print(total, failed)
PY
)
if [[ ${total:-0} -eq 0 ]]; then
  echo "brick_pose: no test results found" >&2
  verdict=1
fi
echo "brick_pose: tests finished in $(( $(date +%s) - start )) s"
echo "$(( total - failed )) passed, ${failed} failed"
exit $verdict
