# Wraps a catkin workspace around this package. `make demo` and `make test` do every set-up step
# (Debian packages, workspace, build) on a fresh Debian 12 machine.
SHELL := /bin/bash
.SHELLFLAGS := -e -o pipefail -c
REPO := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
# The workspace sits beside the repository (a workspace inside it would contain a link to itself,
# which rosrun cannot search).
WS ?= $(abspath $(REPO)/../tow_sim_ws)
# catkin and rostest need Debian's python3, not another one earlier on PATH.
export PATH := /usr/bin:/bin:$(PATH)
CATKIN_ARGS := -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3
JOBS ?= 2

.PHONY: deps workspace build test demo offline-demo screenshot bench clean
# rviz opens when there is a display; without one the demo runs headless and prints a status line each second.
RVIZ ?= $(if $(DISPLAY),true,false)
MANOEUVRE ?= turn

deps:
	@$(REPO)/scripts/install_deps.sh

workspace:
	@mkdir -p $(WS)/src
	@ln -sfn $(REPO) $(WS)/src/tow_sim

build: deps workspace
	cd $(WS) && catkin_make $(CATKIN_ARGS) -j$(JOBS)

test: build
	cd $(WS) && rm -rf build/test_results && catkin_make $(CATKIN_ARGS) -j$(JOBS) tests
	cd $(WS) && source devel/setup.bash && catkin_make $(CATKIN_ARGS) -j1 run_tests > $(WS)/run_tests.log 2>&1 \
	  || { tail -n 60 $(WS)/run_tests.log; echo "catkin_make run_tests failed (log: $(WS)/run_tests.log)"; }
	@grep -E '^(\[  (PASSED|FAILED) |\[==========\] [0-9]+ tests? from .* ran)|critical angle|energy drift|mode [0-9]:|length error|trim at|after 60 s|yawed|pitched|incidence|CB [0-9]' $(WS)/run_tests.log || true
	@cd $(WS) && /usr/bin/python3 $(REPO)/scripts/test_summary.py build/test_results

demo: build
	source $(WS)/devel/setup.bash && roslaunch tow_sim tow_sim.launch rviz:=$(RVIZ) manoeuvre:=$(MANOEUVRE)

offline-demo: build
	$(WS)/devel/lib/tow_sim/tow_sim_demo

screenshot: build
	$(REPO)/scripts/rviz_screenshot.sh $(REPO)/docs/rviz_demo.png 40 $(MANOEUVRE)

bench: build
	@for b in $(WS)/devel/lib/tow_sim/bench_*; do echo "== $$b"; $$b; done

clean:
	rm -rf $(WS)
