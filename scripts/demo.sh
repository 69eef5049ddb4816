#!/usr/bin/env bash
# The demo: the synthetic D415 (and the pipeline) in one nodelet manager,
# headless; prints what is published, then stops. Extra arguments go to
# roslaunch (e.g. scene:=organised_pile lighting:=sunlight seed:=7).
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
# shellcheck source=scripts/ros_env.sh
source "$root/scripts/ros_env.sh"
export ROS_MASTER_URI=http://127.0.0.1:${BRICK_POSE_DEMO_PORT:-11411}
export ROS_HOSTNAME=127.0.0.1
log=$root/ws/demo.log
roslaunch --port "${ROS_MASTER_URI##*:}" brick_pose demo.launch "$@" >"$log" 2>&1 &
launch_pid=$!
cleanup() { kill -INT "$launch_pid" 2>/dev/null; wait "$launch_pid" 2>/dev/null; }
trap cleanup EXIT

echo "brick_pose demo: starting the synthetic D415 (log in ws/demo.log)"
for _ in $(seq 1 60); do
  rostopic list 2>/dev/null | grep -q /camera/color/image_raw && break
  sleep 0.5
done
if ! rostopic list >/dev/null 2>&1; then
  echo "brick_pose demo: roslaunch did not come up" >&2; tail -20 "$log"; exit 1
fi
"$root/ws/devel/lib/brick_pose/brick_pose_demo"  # the arguments were for roslaunch
