#!/usr/bin/env bash
# make test, last step: `catkin_make install`, then, in a shell that sees only
# the install space, the installed package's exports, a rostest and the demo.
# Writes a JUnit file into the test results so catkin_test_results counts it.
set -uo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
export PATH=/usr/bin:/bin:$PATH
ws=$root/ws
install=$ws/install
results=$ws/build/test_results/brick_pose
log=$ws/install_check.log
mkdir -p "$results"
: >"$log"
failures=()
cases=()

check() {  # check NAME COMMAND...: runs COMMAND, records a test case
  local name=$1; shift
  echo "== $name" >>"$log"
  if "$@" >>"$log" 2>&1; then cases+=("$name"); else cases+=("$name"); failures+=("$name"); fi
}

in_install_space() {  # a clean environment with only the install space sourced
  env -i HOME="$HOME" PATH=/usr/bin:/bin LANG=C.UTF-8 ROS_MASTER_URI=http://127.0.0.1:11472 ROS_HOSTNAME=127.0.0.1 \
    bash -c "source '$install/setup.bash' || exit 1; $1"
}

check "catkin_make install" bash -c "cd '$ws' && catkin_make install -DCMAKE_INSTALL_PREFIX='$install' -j2"
check "installed package.xml exports no test plugin" \
  bash -c "! grep -q 'test_nodelet_plugins' '$install/share/brick_pose/package.xml'"
check "installed plugin libraries exist" in_install_space \
  "for lib in \$(rospack plugins --attrib=plugin nodelet | awk '/^brick_pose /{print \$2}'); do
     grep -o 'lib/lib[a-z_]*' \"\$lib\" | while read -r path; do test -f '$install/'\$path.so || { echo missing \$path; exit 1; }; done; done"
check "rostest brick_pose install_check.test from the install space" in_install_space \
  "rostest --text brick_pose install_check.test"
check "demo from the install space" in_install_space \
  "roslaunch --port 11472 brick_pose demo.launch >'$ws/install_demo.log' 2>&1 & launch=\$!
   trap 'kill -INT \$launch; wait \$launch' EXIT
   sleep 2; rosrun brick_pose brick_pose_demo"

# JUnit for catkin_test_results.
{
  echo "<?xml version=\"1.0\" encoding=\"UTF-8\"?>"
  echo "<testsuite name=\"install_check\" tests=\"${#cases[@]}\" failures=\"${#failures[@]}\" errors=\"0\">"
  for name in "${cases[@]}"; do
    echo "  <testcase classname=\"install_check\" name=\"$name\">"
    for failed in "${failures[@]}"; do
      [[ "$failed" == "$name" ]] && echo "    <failure message=\"failed: see ws/install_check.log\"/>"
    done
    echo "  </testcase>"
  done
  echo "</testsuite>"
} >"$results/install_check.xml"
echo "brick_pose: install space check: $(( ${#cases[@]} - ${#failures[@]} )) of ${#cases[@]} passed (log in ws/install_check.log)"
[[ ${#failures[@]} -eq 0 ]]
