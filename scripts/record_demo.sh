#!/usr/bin/env bash
# Runs the demo headless with record:=true for SECONDS of wall time, stops it (rosbag closes the bag),
# and prints `rosbag info` of the bag written.
# Usage: scripts/record_demo.sh OUT_DIR [SECONDS (default 20)] [manoeuvre (default straight)]
# Needs a built workspace (make build).
set -euo pipefail
out="$(realpath -m "${1:?usage: record_demo.sh OUT_DIR [seconds] [manoeuvre]}")"
seconds="${2:-20}"
manoeuvre="${3:-straight}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${WS:-$(realpath -m "$repo/../tow_sim_ws")}"
export PATH=/usr/bin:/bin:$PATH
set +u
source "$ws/devel/setup.bash"
set -u
mkdir -p "$out"
rm -f "$out"/tow_sim_*.bag "$out"/tow_sim_*.bag.active
port=$((11900 + RANDOM % 90))
export ROS_MASTER_URI="http://localhost:$port"
roslaunch -p "$port" tow_sim tow_sim.launch rviz:=false print_status:=false manoeuvre:="$manoeuvre" record:=true \
  bag:="$out/tow_sim" >"$out/launch.log" 2>&1 &
launch_pid=$!
sleep "$seconds"
kill -INT "$launch_pid"
wait "$launch_pid" || true
bag="$(ls "$out"/tow_sim_*.bag 2>/dev/null | head -n 1)"
[[ -n "$bag" ]] || { echo "no bag written in $out" >&2; tail -n 20 "$out/launch.log" >&2; exit 1; }
rosbag info "$bag"
