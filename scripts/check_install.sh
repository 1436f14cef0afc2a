#!/usr/bin/env bash
# usage: scripts/check_install.sh INSTALL_DIR
#
# The install space alone: with only INSTALL_DIR/setup.bash sourced in an empty environment (no devel space,
# no source tree on the package path), the batch runner, tow_sim_fatigue, tow_sim_plot, tow_sim_chart
# (drawing its charts with the installed tow_sim_plot), tow_sim_sweep, the Python module and the demo
# (headless, on a master of its own, on a free port) run, in a temporary folder removed at the end.
#
#   INSTALL_DIR  the install space of `catkin_make install` (make test: WS/install)
#   -h, --help   prints this help and exits
#
# Exit status: 2 for wrong arguments (nothing runs); 0 when every check passed, else not 0.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "$@"
[[ -n "${1:-}" ]] || cli_fail "INSTALL_DIR missing"
install="$(realpath "$1")"
[[ -f "$install/setup.bash" ]] || { echo "no $install/setup.bash: run catkin_make install" >&2; exit 1; }
work="$(mktemp -d /tmp/tow_sim_install_check.XXXXXX)"
trap 'rm -rf "$work"' EXIT
port="$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("localhost", 0)); print(s.getsockname()[1])')"
env -i HOME="$work" PATH=/usr/bin:/bin LANG=C.UTF-8 ROS_MASTER_URI="http://localhost:$port" \
  bash -c '
set -eo pipefail
source "$1/setup.bash"
set -u
share="$(rospack find tow_sim)"
case "$share" in
  "$1"/*) echo "tow_sim from $share" ;;
  *) echo "rospack finds tow_sim at $share, not in the install space $1"; exit 1 ;;
esac
cd "$HOME"
echo "== tow_sim_batch"
rosrun tow_sim tow_sim_batch --scenario "$share/scenarios/heave_snap.yaml" --out run | tail -n 2
echo "== tow_sim_fatigue"
rosrun tow_sim tow_sim_fatigue run --breaking-load 1e5
echo "== tow_sim_plot"
rosrun tow_sim tow_sim_plot run | tail -n 2
ls run/*.png
echo "== tow_sim_chart"
rosrun tow_sim tow_sim_chart --config "$share/config/tow_sim.yaml" --speeds 1:2:1 --cable-out 200:300:100 \
  --out chart | tail -n 2
ls chart/*.png
echo "== tow_sim_sweep"
printf "base: %s\ngrid:\n  cable.segments: [20, 30]\n" "$share/scenarios/heave_snap.yaml" > sweep.yaml
rosrun tow_sim tow_sim_sweep sweep.yaml --out sweep --jobs 2 2>/dev/null
echo "== the Python module"
python3 -c "
import tow_sim, tow_sim.msg
assert tow_sim.__file__.startswith(\"$1/\"), tow_sim.__file__
eq = tow_sim.steady_tow(tow_sim.load_config(\"$share/config/tow_sim.yaml\"), speed=2.0, cable_out=300.0)
print(\"tow_sim from\", tow_sim.__file__, \"- steady tow at 2 m/s on 300 m: depth %.1f m\" % eq.depth)
"
echo "== the demo, headless"
roslaunch tow_sim tow_sim.launch rviz:=false print_status:=false > demo.log 2>&1 &
demo=$!
for _ in $(seq 60); do rostopic list > /dev/null 2>&1 && break; sleep 1; done  # the master it starts
status=0
timeout 120 rostopic echo -n 1 cable/state/tension_ship || status=$?
kill -INT "$demo" 2> /dev/null || true  # as Ctrl-C; a roslaunch that has not set up its handler yet ignores it
for _ in $(seq 30); do kill -0 "$demo" 2> /dev/null || break; sleep 1; done
kill -TERM "$demo" 2> /dev/null || true
wait "$demo" || true
[[ $status == 0 ]] || { tail -n 30 demo.log; exit 1; }
echo "install space: every check passed"
' check_install "$install"
