#!/usr/bin/env bash
# Installs the Debian 12 packages brick_pose needs to build, test and run.
# Idempotent and quiet when everything is already there. ROS 1 comes from
# Debian's own packages (no /opt/ros, no rosdep).
set -euo pipefail

packages=(
  build-essential cmake ccache pkg-config
  catkin python3-catkin-pkg
  ros-core-dev libnodeletlib-dev libnodelet-dev libnodeletlib-tools pluginlib-dev
  libcv-bridge-dev libimage-transport-dev libmessage-filters-dev
  libtf2-ros-dev libtf2-eigen-dev libtf2-msgs-dev
  libpcl-conversions-dev libpcl-dev libopencv-dev libeigen3-dev
  python3-rostest python3-roslaunch librostest-dev rosbash
  librosbag-dev python3-rosbag ros-sensor-msgs ros-geometry-msgs
  libvisualization-msgs-dev libstd-srvs-dev libdiagnostic-updater-dev
  libdynamic-reconfigure-config-init-mutex-dev python3-dynamic-reconfigure
  libgtest-dev
  clang-16 libclang-rt-16-dev  # scripts/fuzz.sh: libFuzzer (clang 14 rejects lambdas capturing structured bindings)
)

missing=()
for package in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$package" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$package")
done
[[ ${#missing[@]} -eq 0 ]] && exit 0

echo "brick_pose: installing ${#missing[@]} missing Debian packages: ${missing[*]}"
sudo_cmd=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "brick_pose: need root or sudo to install packages" >&2; exit 1; }
  sudo_cmd=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
echo "brick_pose: packages installed"
