#!/usr/bin/env bash
# `make bench`: the accuracy and speed benchmarks against ground truth. Each
# tool prints a table and one JSON line; everything is also kept under
# bench/results/. Run on an otherwise idle machine: the figures are timings.
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
# shellcheck source=scripts/ros_env.sh
source "$root/scripts/ros_env.sh"
bin=$root/ws/devel/lib/brick_pose
results=$root/bench/results
mkdir -p "$results"
frames=${BENCH_FRAMES:-200}
status=0

run_bench() {
  local name=$1; shift
  if [[ ! -x "$bin/$name" ]]; then
    echo "== $name: not built"; status=1; return
  fi
  echo "== $name $*"
  "$bin/$name" "$@" 2>&1 | tee "$results/$name.txt"
  [[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
}

cd "$root"
run_bench bench_frontend --frames "$frames"
run_bench bench_registration --frames "$frames"
run_bench bench_pose --frames "$frames" --out "$results"

# End-to-end latency of the running pipeline (frame arrival to tf) with one
# brick at 30 Hz, and service calls meanwhile.
echo "== pipeline latency: synthetic D415 at 30 Hz, one brick"
export ROS_MASTER_URI=http://127.0.0.1:${BENCH_PORT:-11412}
export ROS_HOSTNAME=127.0.0.1
roslaunch --port "${ROS_MASTER_URI##*:}" "$root/launch/demo.launch" scene:=single rate_hz:=30 \
  >"$results/pipeline_latency.log" 2>&1 &
launch_pid=$!
sleep 8
"$bin/brick_pose_latency" --duration-s 30 --warmup-s 5 2>&1 | tee "$results/pipeline_latency.txt"
[[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
kill -INT "$launch_pid" 2>/dev/null
wait "$launch_pid" 2>/dev/null
exit $status
