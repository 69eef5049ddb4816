#!/usr/bin/env bash
# Starts brick_pose on a live D415: checks that the realsense2_camera driver
# is installed (roslaunch alone would only say "resource not found"), then
# runs launch/d415.launch with the given arguments.
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
# shellcheck source=scripts/ros_env.sh
source "$root/scripts/ros_env.sh"
if ! rospack find realsense2_camera >/dev/null 2>&1; then
  cat >&2 <<'MSG'
brick_pose: the realsense2_camera ROS driver is not installed.
  Debian 12 packages neither librealsense2 nor realsense2_camera. Install
  librealsense2 (Intel's packages or a source build), build realsense2_camera
  (ROS 1 branch, "ros1-legacy") in a catkin workspace, source its setup.bash,
  then run this again. To try the pipeline without a camera: make demo, or
  roslaunch brick_pose bag.launch bag:=FILE.bag
MSG
  exit 1
fi
exec roslaunch "$root/launch/d415.launch" "$@"
