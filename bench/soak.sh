#!/usr/bin/env bash
# Soak run (not part of CI): the demo pipeline on the synthetic D415 at 30 Hz,
# one brick, for SOAK_MINUTES (default 10), with get_brick_pose called all
# along (brick_pose_latency, SOAK_SERVICE_HZ calls a second). Samples the
# nodelet manager's resident memory every SOAK_SAMPLE_S (10) seconds and
# reports RSS after warm-up vs at the end, service calls made/answered and
# the detection rate against the camera's. Results: bench/results/soak.txt
# (and soak_rss.csv, soak_launch.log).
#
#   bench/soak.sh                      10 minutes
#   SOAK_MINUTES=3 bench/soak.sh
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
export PATH=/usr/bin:/bin:$PATH
set +u
# shellcheck disable=SC1091
source "$root/ws/devel/setup.bash"
set -u
bin=$root/ws/devel/lib/brick_pose
results=$root/bench/results
mkdir -p "$results"
minutes=${SOAK_MINUTES:-10}
sample_s=${SOAK_SAMPLE_S:-10}
warmup_s=${SOAK_WARMUP_S:-60}   # caches, pools and allocator arenas settle
service_hz=${SOAK_SERVICE_HZ:-20}
total_s=$(( minutes * 60 ))
(( total_s > warmup_s + 2 * sample_s )) || { echo "soak: SOAK_MINUTES too short for a ${warmup_s} s warm-up" >&2; exit 2; }
[[ -x "$bin/brick_pose_latency" ]] || { echo "soak: build first (make build)" >&2; exit 2; }

# Its own master, so that it neither disturbs nor is disturbed by a test run.
export ROS_MASTER_URI=http://127.0.0.1:${SOAK_PORT:-11421}
export ROS_HOSTNAME=127.0.0.1
roslaunch --port "${ROS_MASTER_URI##*:}" "$root/launch/demo.launch" scene:=single rate_hz:=30 \
  >"$results/soak_launch.log" 2>&1 &
launch_pid=$!
cleanup() { kill -INT "$launch_pid" 2>/dev/null; wait "$launch_pid" 2>/dev/null; }
trap cleanup EXIT

# The manager is a direct child of this roslaunch (other runs may have their own).
manager_pid=""
for _ in $(seq 60); do
  manager_pid=$(pgrep -P "$launch_pid" -f "__name:=brick_pose_manager" | head -1)
  [[ -n "$manager_pid" ]] && break
  sleep 1
done
[[ -n "$manager_pid" ]] || { echo "soak: no brick_pose_manager under roslaunch $launch_pid" >&2; exit 1; }
start_epoch=$(date +%s)
echo "soak: ${minutes} min at 30 Hz, manager pid $manager_pid, warm-up ${warmup_s} s, load: $(cut -d' ' -f1-3 /proc/loadavg)"

# Service calls and rates over everything after the warm-up.
"$bin/brick_pose_latency" --duration-s $(( total_s - warmup_s )) --warmup-s "$warmup_s" --service-hz "$service_hz" \
  >"$results/soak_latency.txt" 2>&1 &
latency_pid=$!

echo "elapsed_s,rss_mb" >"$results/soak_rss.csv"
manager_died=0
while :; do
  elapsed=$(( $(date +%s) - start_epoch ))
  rss_kb=$(ps -o rss= -p "$manager_pid" 2>/dev/null | tr -d ' ')
  if [[ -z "$rss_kb" ]]; then manager_died=1; echo "soak: manager died after ${elapsed} s"; break; fi
  echo "$elapsed,$(awk -v kb="$rss_kb" 'BEGIN { printf "%.1f", kb / 1024 }')" >>"$results/soak_rss.csv"
  (( elapsed >= total_s )) && break
  sleep "$sample_s"
done
wait "$latency_pid"
latency_status=$?

# RSS after warm-up vs at the end. Single samples swing by +-15 MB with the
# frames in flight, so the growth is judged on the mean of the first and of
# the last minute after warm-up; the single samples and the peak are kept too.
read -r rss_warm rss_end rss_peak rss_first_min rss_last_min < <(awk -F, -v w="$warmup_s" -v end_s="$total_s" '
  NR > 1 && $1 >= w {
    if (first == "") first = $2; last = $2; if ($2 > peak) peak = $2
    if ($1 < w + 60) { head_sum += $2; head_n++ }
    if ($1 > end_s - 60) { tail_sum += $2; tail_n++ }
  }
  END { printf "%s %s %s %.1f %.1f\n", first, last, peak, head_n ? head_sum / head_n : 0, tail_n ? tail_sum / tail_n : 0 }' \
  "$results/soak_rss.csv")
json=$(grep -E '^\{' "$results/soak_latency.txt" | tail -1)
field() { echo "$json" | grep -oE "\"$1\": [0-9.]+" | grep -oE '[0-9.]+$'; }
{
  echo "soak: $(date -u +%FT%TZ), ${minutes} min, demo.launch scene:=single rate_hz:=30, $(nproc) cores"
  echo "load average at the end: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "manager RSS: ${rss_warm:-?} MB after ${warmup_s} s warm-up, ${rss_end:-?} MB at the end, peak ${rss_peak:-?} MB"
  echo "manager RSS, mean of a minute: ${rss_first_min} MB just after warm-up, ${rss_last_min} MB at the end;" \
       "growth $(awk -v a="$rss_first_min" -v b="$rss_last_min" 'BEGIN { printf "%+.1f", b - a }') MB"
  echo "service: $(field service_calls) calls, $(field service_answered) answered with a pose, p95 $(field service_p95_ms) ms"
  echo "rates: detections $(field rate_hz) Hz of a $(field camera_rate_hz) Hz camera"
  echo "latency: p50 $(field latency_p50_ms) ms, p95 $(field latency_p95_ms) ms"
  [[ $manager_died -eq 0 ]] || echo "MANAGER DIED (see soak_launch.log)"
  echo "rss samples: soak_rss.csv; brick_pose_latency output:"
  sed 's/^/  /' "$results/soak_latency.txt"
} | tee "$results/soak.txt"
[[ $manager_died -eq 0 && $latency_status -eq 0 ]]
