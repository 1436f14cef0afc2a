#!/usr/bin/env bash
# usage: scripts/record_demo.sh OUT_DIR [SECONDS] [MANOEUVRE]
#
# Runs the demo headless (tow_sim.launch rviz:=false record:=true) for SECONDS of wall time, stops it
# (rosbag closes the bag), and prints `rosbag info` of the bag written.
#
#   OUT_DIR     where the bag (OUT_DIR/tow_sim_DATE-TIME.bag) and launch.log go; made if missing, and
#               tow_sim_*.bag files already in it are removed first
#   SECONDS     wall time to run, a number > 0 (default 20)
#   MANOEUVRE   the scripted ship's manoeuvre: straight, turn, zigzag, speed_change or waypoints
#               (default straight)
#   -h, --help  prints this help and exits
#
# Needs a built workspace (make build): WS (default ../tow_sim_ws beside the repository)/devel/setup.bash.
# Exit status: 2 for wrong arguments (nothing runs); 0 when a bag was written, 1 when none was.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "${@:1:1}" "${@:3}"  # SECONDS ($2) is checked as a number below
[[ -n "${1:-}" ]] || cli_fail "OUT_DIR missing"
seconds="${2:-20}"
cli_is_positive "$seconds" || cli_fail "SECONDS must be a number of seconds > 0, not '$seconds'"
out="$(realpath -m "$1")"
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
