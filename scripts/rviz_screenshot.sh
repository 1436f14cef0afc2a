#!/usr/bin/env bash
# Takes a screenshot of rviz showing the running demo, under a virtual X display (Xvfb).
# Usage: scripts/rviz_screenshot.sh OUT.png [SECONDS_TO_RUN (default 40)] [manoeuvre (default turn)] [config.yaml]
# SECONDS_TO_RUN `markers`: as soon as the cable is laid out and rviz listens to cable/markers (at most
# 120 s), plus 3 s to draw them.
# Needs a built workspace (make build); uses Xvfb and ImageMagick's import.
set -euo pipefail
out="$(realpath -m "${1:?usage: rviz_screenshot.sh OUT.png [seconds] [manoeuvre]}")"
seconds="${2:-40}"
manoeuvre="${3:-turn}"
config="${4:-}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${WS:-$(realpath -m "$repo/../tow_sim_ws")}"
export PATH=/usr/bin:/bin:$PATH
set +u
source "$ws/devel/setup.bash"
set -u
display=":$((90 + RANDOM % 9))"
Xvfb "$display" -screen 0 1280x860x24 >/dev/null 2>&1 &
xvfb_pid=$!
export DISPLAY="$display" LIBGL_ALWAYS_SOFTWARE=1
port=$((11400 + RANDOM % 500))
export ROS_MASTER_URI="http://localhost:$port"
roslaunch -p "$port" tow_sim tow_sim.launch rviz:=true manoeuvre:="$manoeuvre" print_status:=false \
  ${config:+config:="$(realpath "$config")"} >/tmp/tow_sim_screenshot_launch.log 2>&1 &
launch_pid=$!
cleanup() { kill "$launch_pid" 2>/dev/null || true; sleep 2; kill "$xvfb_pid" 2>/dev/null || true; }
trap cleanup EXIT
if [[ "$seconds" == markers ]]; then
  # The node publishes cable/markers once the cable is laid out (at the first ship odometry) and while
  # someone listens: wait until rviz subscribes and the markers flow (`rostopic bw` needs no message
  # class), then give rviz a moment to draw them.
  for _ in $(seq 60); do
    subscribers="$(rostopic info /cable/markers 2>/dev/null || true)"
    flow="$(PYTHONUNBUFFERED=1 timeout 3 rostopic bw /cable/markers 2>/dev/null || true)"
    if [[ "$subscribers" == *"/rviz "* && "$flow" == *average* ]]; then
      break
    fi
    sleep 1
  done
  sleep 3
else
  sleep "$seconds"
fi
import -window root "$out"
echo "wrote $out"
