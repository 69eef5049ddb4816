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
# The same on unorganised piles of up to 12 bricks (issue 14), at two modes.
for resolution in 1280x720 848x480; do
  echo "== bench_pose --max-pile-bricks 12 --resolution $resolution"
  "$bin/bench_pose" --frames "$frames" --max-pile-bricks 12 --resolution "$resolution" --out "$results/piles12_$resolution" 2>&1 |
    tee "$results/bench_pose_piles12_$resolution.txt"
  [[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
done
run_bench bench_tracking --frames 60 --scenes 6

# End-to-end latency of the running pipeline (frame arrival to tf) at 30 Hz,
# service calls meanwhile: one brick, then the piles users run (issue 14),
# each in a fresh launch. LATENCY_S sets each run's length.
export ROS_MASTER_URI=http://127.0.0.1:${BENCH_PORT:-11412}
export ROS_HOSTNAME=127.0.0.1
latency_s=${LATENCY_S:-30}
run_latency() {  # run_latency LABEL roslaunch-args...
  local label=$1; shift
  echo "== pipeline latency ($label): synthetic D415 at 30 Hz, $*"
  roslaunch --port "${ROS_MASTER_URI##*:}" "$root/launch/demo.launch" rate_hz:=30 "$@" \
    >"$results/pipeline_latency_$label.log" 2>&1 &
  local launch_pid=$!
  sleep 8
  "$bin/brick_pose_latency" --duration-s "$latency_s" --warmup-s 5 --label "${label}_" 2>&1 |
    tee "$results/pipeline_latency_$label.txt"
  [[ ${PIPESTATUS[0]} -eq 0 ]] || status=1
  kill -INT "$launch_pid" 2>/dev/null
  wait "$launch_pid" 2>/dev/null
}
run_latency single scene:=single seed:=1
# Piles of at least 8 bricks with at least 2 long ones (issue 14): seed 8 has
# 10 bricks (5 blue or orange), seed 3 has 12 (8). A static pile reuses its
# front end while nothing changes; pile_every_frame measures every frame
# afresh (reuse off): what each frame costs while something in view moves.
pile=(scene:=unorganised_pile max_pile_bricks:=12)
no_reuse=$(mktemp --suffix=.yaml)
echo "reuse_unchanged_frames: false" >"$no_reuse"
run_latency pile "${pile[@]}" seed:=8
run_latency pile_848 "${pile[@]}" seed:=8 resolution:=848x480
run_latency pile_12 "${pile[@]}" seed:=3
run_latency pile_every_frame "${pile[@]}" seed:=8 params:="$no_reuse"
# Touching rows: 12 red bricks end to end and side by side, no gaps.
run_latency touching scene:=touching_rows types:=red seed:=14
rm -f "$no_reuse"
exit $status
