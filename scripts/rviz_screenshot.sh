#!/usr/bin/env bash
# usage: scripts/rviz_screenshot.sh OUT.png [SECONDS] [MANOEUVRE] [CONFIG.yaml]
#
# Takes a screenshot of rviz showing the running demo (tow_sim.launch rviz:=true), under a virtual X
# display (Xvfb), and prints the file(s) written.
#
#   OUT.png      the screenshot to write
#   SECONDS      wall time the demo runs before the screenshot, a number > 0 (default 40), or `markers`:
#                as soon as the cable is laid out and rviz listens to cable/markers (at most 150 s),
#                plus 3 s to draw them
#   MANOEUVRE    the scripted ship's manoeuvre: straight, turn, zigzag, speed_change or waypoints
#                (default turn)
#   CONFIG.yaml  the configuration tow_sim.launch loads (default: its own, config/tow_sim.yaml)
#   -h, --help   prints this help and exits
#
# SHOTS=N (default 1): N screenshots 2 s apart, OUT-1.png .. OUT-N.png, the last also as OUT.png (software
# GL on a loaded machine can take a while to draw the first frame with the cable in it).
# Needs a built workspace (make build): WS (default ../tow_sim_ws beside the repository)/devel/setup.bash;
# uses Xvfb and ImageMagick's import. The launch's log: /tmp/tow_sim_screenshot_launch.log.
# Exit status: 2 for wrong arguments (nothing runs); 0 when the screenshot was written.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "${@:1:1}" "${@:3}"  # SECONDS ($2) is checked below
[[ -n "${1:-}" ]] || cli_fail "OUT.png missing"
seconds="${2:-40}"
[[ "$seconds" == markers ]] || cli_is_positive "$seconds" ||
  cli_fail "SECONDS must be a number of seconds > 0 or 'markers', not '$seconds'"
out="$(realpath -m "$1")"
manoeuvre="${3:-turn}"
config="${4:-}"
repo="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
ws="${WS:-$(realpath -m "$repo/../tow_sim_ws")}"
export PATH=/usr/bin:/bin:$PATH
set +u
source "$ws/devel/setup.bash"
set -u
shots="${SHOTS:-1}"
# Xvfb picks a free display itself and writes its number to the pipe (no clash with another X server).
display_file="$(mktemp)"
Xvfb -displayfd 3 -screen 0 1280x860x24 3>"$display_file" >/dev/null 2>&1 &
xvfb_pid=$!
launch_pid=""
cleanup() {
  [[ -n "$launch_pid" ]] && kill "$launch_pid" 2>/dev/null && sleep 2
  kill "$xvfb_pid" 2>/dev/null || true
}
trap cleanup EXIT
for _ in $(seq 50); do
  [[ -s "$display_file" ]] && break
  sleep 0.2
done
[[ -s "$display_file" ]] || { echo "rviz_screenshot.sh: Xvfb did not start" >&2; exit 1; }
display=":$(head -n 1 "$display_file")"
rm -f "$display_file"
export DISPLAY="$display" LIBGL_ALWAYS_SOFTWARE=1
port=$((11400 + RANDOM % 500))
export ROS_MASTER_URI="http://localhost:$port"
roslaunch -p "$port" tow_sim tow_sim.launch rviz:=true manoeuvre:="$manoeuvre" print_status:=false \
  ${config:+config:="$(realpath "$config")"} >/tmp/tow_sim_screenshot_launch.log 2>&1 &
launch_pid=$!
if [[ "$seconds" == markers ]]; then
  # The node publishes cable/markers once the cable is laid out (at the first ship odometry) and while
  # someone listens: wait until rviz subscribes and the markers flow (`rostopic bw` needs no message
  # class), then give rviz a moment to draw them.
  # At most 150 s of wall time (each round may take seconds on a loaded machine), inside the test's limit.
  for _ in $(seq 60); do
    ((SECONDS < 150)) || break
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
if ((shots <= 1)); then
  import -window root "$out"
  echo "wrote $out"
  exit 0
fi
for k in $(seq "$shots"); do
  import -window root "${out%.png}-$k.png"
  ((k < shots)) && sleep 2
done
cp "${out%.png}-$shots.png" "$out"
echo "wrote ${out%.png}-1.png .. ${out%.png}-$shots.png and $out"
