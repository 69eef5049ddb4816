#!/usr/bin/env bash
# Builds brick_pose in Release in a catkin workspace kept inside the repository
# (ws/, git-ignored): ws/src/brick_pose is a link back to the repository root.
set -euo pipefail
root=$(cd -P "$(dirname "$0")/.." && pwd)
# Debian's catkin needs the system python3 (a pyenv python3 lacks catkin_pkg).
export PATH=/usr/bin:/bin:$PATH
# The package in the workspace is a folder of links to the repository's
# top-level entries, not one link to the repository itself: roslaunch walks
# package folders following links, and would loop through ws/ forever.
package="$root/ws/src/brick_pose"
[[ -L "$package" ]] && rm "$package"
mkdir -p "$package"
find "$package" -maxdepth 1 -type l -delete
for entry in "$root"/* "$root"/.ci; do
  name=$(basename "$entry")
  case "$name" in ws | build* | .git) continue ;; esac
  ln -sfn "$entry" "$package/$name"
done
cd "$root/ws"
jobs=${JOBS:-$(nproc)}
log="$root/ws/build.log"
echo "brick_pose: building (Release, -j$jobs; log in ws/build.log)"
start=$(date +%s)
if ! catkin_make -j"$jobs" -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3 \
  -DCATKIN_ENABLE_TESTING=ON -DBRICK_POSE_BUILD_BENCHMARKS=ON "$@" >"$log" 2>&1; then
  grep -n -i -E "error|exception" "$log" | head -40
  tail -20 "$log"
  echo "brick_pose: build FAILED (full log: ws/build.log)" >&2
  exit 1
fi
echo "brick_pose: built in $(( $(date +%s) - start )) s"
