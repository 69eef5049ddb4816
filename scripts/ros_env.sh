# Sourced by the scripts that run ROS: the built workspace's environment,
# with Debian's python3 first on PATH (a pyenv python3 lacks catkin_pkg).
# Expects $root, the repository root.
export PATH=/usr/bin:/bin:$PATH
if [[ ! -f "$root/ws/devel/setup.bash" ]]; then
  echo "brick_pose: not built yet (run make build)" >&2
  exit 1
fi
set +u  # setup.bash reads unset variables
# shellcheck disable=SC1091
source "$root/ws/devel/setup.bash"
set -u
