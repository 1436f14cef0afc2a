# Wraps a catkin workspace around this package. `make demo` and `make test` do every set-up step
# (Debian packages, workspace, build) on a fresh Debian 12 machine.
SHELL := /bin/bash
.SHELLFLAGS := -e -o pipefail -c
REPO := $(abspath $(dir $(lastword $(MAKEFILE_LIST))))
# The workspace sits beside the repository (a workspace inside it would contain a link to itself,
# which rosrun cannot search). In an existing catkin workspace (the repository cloned as WS/src/tow_sim)
# it is that workspace: a second one would link the same package into it, and catkin would see two.
ENCLOSING_WS := $(shell { [ -f "$(REPO)/../../.catkin_workspace" ] || readlink "$(REPO)/../CMakeLists.txt" 2>/dev/null | grep -q toplevel.cmake; } && cd "$(REPO)/../.." && pwd)
WS ?= $(or $(ENCLOSING_WS),$(abspath $(REPO)/../tow_sim_ws))
# catkin and rostest need Debian's python3, not another one earlier on PATH.
export PATH := /usr/bin:/bin:$(PATH)
CATKIN_ARGS := -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=/usr/bin/python3
JOBS ?= 2

.PHONY: deps workspace build test sanitize fuzz soak accuracy demo offline-demo screenshot bench bench-docs survey-bench docs clean
SAN_DIR := $(WS)/sanitize
SAN_FLAGS := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
FUZZ_DIR := $(WS)/fuzz
FUZZ_SECONDS ?= 30
FUZZ_TARGETS := $(basename $(notdir $(wildcard $(REPO)/fuzz/*.cpp)))
export ASAN_OPTIONS := detect_leaks=1:halt_on_error=1:abort_on_error=1
export UBSAN_OPTIONS := halt_on_error=1:print_stacktrace=1
# rviz opens when there is a display; without one the demo runs headless and prints a status line each second.
RVIZ ?= $(if $(DISPLAY),true,false)
MANOEUVRE ?= turn
# Wall-time length of the odometry soak rostest in make test (make soak runs it for the full 10 minutes).
SOAK_SECONDS ?= 120
export TOW_SIM_SOAK_SECONDS := $(SOAK_SECONDS)

deps:
	@$(REPO)/scripts/install_deps.sh

workspace:
	@mkdir -p $(WS)/src
	@[ "$$(realpath -m $(WS)/src/tow_sim)" = "$(REPO)" ] || ln -sfn $(REPO) $(WS)/src/tow_sim

build: deps workspace
	cd $(WS) && catkin_make $(CATKIN_ARGS) -j$(JOBS)

# Every stage runs and is counted; the last line is the verdict over all of them (scripts/run_all_tests.sh).
test: build
	@WS=$(WS) REPO=$(REPO) JOBS=$(JOBS) CATKIN_ARGS="$(CATKIN_ARGS)" FUZZ_SECONDS=$(FUZZ_SECONDS) \
	  $(REPO)/scripts/run_all_tests.sh

# The core tests again, built with AddressSanitizer and UndefinedBehaviorSanitizer (plain CMake, no
# catkin); any report fails its test. Sanitized code runs ~30x slower, so the long physics runs (the
# 100 s energy and 1000 s length-drift runs, the batch scenarios, the tow point frame's dopri5 references)
# and the suites' reruns with dopri5 are
# left to the normal build; every other test runs. Built at -O1 with line tables only (-g1: reports name
# functions and lines; build type Sanitize adds no flags of its own), which compiles 2.5x faster than
# -O2 -g. Results:
# $(SAN_DIR)/test_results/ctest_sanitizers.xml.
SAN_OPT := -O1 -g1 -DNDEBUG
SAN_SKIP := -TowPointFrame.*:TowNav.AStraightTowWithNoCurrentAgreesWithTheSteadyTow:TowNav.BeatsTheLaybackRulesInATurnInACrossCurrentItDoesNotKnow:TowNav.ItsErrorIsWithinTheChiSquareBoundsOfTheCovarianceItReports:MotionResponse.HeaveAndSurgeResponsesAgreeWithSmallAmplitudeRunsInTheTimeDomain:SeaState.*:Vacuum.ReleasedChainKeepsItsEnergy:BendingStiffness.ATautSpansFirstFrequencyIsTheBeamStrings:BendingStiffness.WithoutTensionAPinnedFreeChainBendsAtTheBeamsFrequency:BendingStiffness.ReleasedInVacuumTheChainKeepsItsEnergyWithTheBendingEnergy:ImplicitStepping.ABendingStiffCableAgreesWithTightDopri5:Vacuum.ImplicitStepperConvergesToTheConservedEnergy:Water.SegmentLengthsHoldThroughAThousandSecondsOfTurns:HardRegimes.TwoHourSoakWithRandomManoeuvresAndCommands:Seabed.CableLaidOnTheBottomAtRestHasNoTensionGradientWhereItLies:Winch.PayingOutDeepensTowardTheLongerCablesEquilibrium:ImplicitStepping.ShippedScenariosAgreeWithTightDopri5:ImplicitStepping.Ros2FixedStepsConvergeAtSecondOrder:ImplicitStepping.Ros34pw2FixedStepsConvergeAtThirdOrder:ImplicitStepping.AFineCableWithHalfSecondStepsStaysBoundedAndKeepsItsLengths:Waves.AnIrregularSeaTowStaysBounded:ElasticCable.ConservesEnergyInVacuum:ElasticCable.ConservesEnergyOnAFrictionlessSeabed:ElasticCable.ConvergesToTheRigidChainAsEAGrows:ElasticCable.AnIrregularSeaTowStaysBounded:VehicleRoll.ASteadyTurnHeelsItByTheRollDampingOfItsSpin
sanitize: deps
	@echo "== core tests under AddressSanitizer + UndefinedBehaviorSanitizer"
	@rm -rf $(SAN_DIR)/test_results && mkdir -p $(SAN_DIR)/test_results
	cmake -S $(REPO) -B $(SAN_DIR) -DTOW_SIM_CORE_ONLY=ON -DTOW_SIM_PYTHON=OFF -DCMAKE_BUILD_TYPE=Sanitize '-DTOW_SIM_CTEST_EXCLUDE=test_batch;test_sweep' \
	  -DTOW_SIM_CTEST_STEPPER_RUNS=OFF "-DCMAKE_CXX_FLAGS=$(SAN_FLAGS) $(SAN_OPT)" "-DCMAKE_EXE_LINKER_FLAGS=$(SAN_FLAGS)" \
	  > $(SAN_DIR).configure.log
	cmake --build $(SAN_DIR) -j$(JOBS) > $(SAN_DIR).build.log 2>&1 || { tail -n 40 $(SAN_DIR).build.log; exit 1; }
	cd $(SAN_DIR) && GTEST_FILTER=$(SAN_SKIP) ctest -j$(JOBS) --output-on-failure --output-junit $(SAN_DIR)/test_results/ctest_sanitizers.xml \
	  > $(SAN_DIR).ctest.log 2>&1 || { tail -n 80 $(SAN_DIR).ctest.log; exit 1; }
	@tail -n 3 $(SAN_DIR).ctest.log

# The node for 10 minutes of wall time beside a misbehaving odometry publisher (make test runs 2), the
# node and ship_motion_node for 10 minutes in an irregular sea on the rigid and on an elastic cable (make
# test: 25 s in regular waves, rigid), and an hour's tow in an irregular sea in the batch, rigid and
# elastic (make test runs 10 minutes of each).
soak: build
	cd $(WS) && catkin_make $(CATKIN_ARGS) -j$(JOBS) tests
	cd $(WS) && source devel/setup.bash && rostest tow_sim odom_soak.test duration:=600
	cd $(WS) && source devel/setup.bash && rostest tow_sim ship_in_waves.test duration:=600 \
	  config:=$(REPO)/test/ros/waves_irregular_config.yaml
	TOW_SIM_SEAWAY_SECONDS=3600 $(WS)/devel/lib/tow_sim/test_waves --gtest_filter=Waves.AnIrregularSeaTowStaysBounded
	TOW_SIM_SEAWAY_SECONDS=3600 $(WS)/devel/lib/tow_sim/test_elastic_tow \
	  --gtest_filter=ElasticCable.AnIrregularSeaTowStaysBounded
	cd $(WS) && source devel/setup.bash && rostest tow_sim ship_in_waves.test duration:=600 \
	  config:=$(REPO)/test/ros/waves_elastic_config.yaml

# The implicit stepper against tight dopri5 on the four manoeuvre scenarios at nu = 100 and 1000 (make test
# runs nu = 100): about half an hour, most of it the dopri5 references at nu = 1000.
accuracy: build
	cd $(WS) && catkin_make $(CATKIN_ARGS) -j$(JOBS) tests
	TOW_SIM_ACCURACY_SEGMENTS=100,1000 $(WS)/devel/lib/tow_sim/test_implicit_stepping \
	  --gtest_filter=ImplicitStepping.ShippedScenariosAgreeWithTightDopri5

# libFuzzer (clang) on the configuration/scenario loader and on odometry and fin-command handling,
# FUZZ_SECONDS each, from the seed corpus in fuzz/corpus; fails on any crash or sanitizer report. Built
# at the sanitizer stage's -O1 -g1 (it compiled in 5 min at -O2 -g in the last CI).
fuzz: deps
	@mkdir -p $(FUZZ_DIR) && rm -rf $(FUZZ_DIR)/test_results && mkdir -p $(FUZZ_DIR)/test_results
	cmake -S $(REPO) -B $(FUZZ_DIR) -DTOW_SIM_CORE_ONLY=ON -DTOW_SIM_PYTHON=OFF -DCMAKE_BUILD_TYPE=Sanitize \
	  -DCMAKE_CXX_COMPILER=clang++ "-DCMAKE_CXX_FLAGS=$(SAN_FLAGS) $(SAN_OPT)" > $(FUZZ_DIR).configure.log
	cmake --build $(FUZZ_DIR) -j$(JOBS) --target $(FUZZ_TARGETS:%=fuzz_%) > $(FUZZ_DIR).build.log 2>&1 \
	  || { tail -n 40 $(FUZZ_DIR).build.log; exit 1; }
	@found=0; for f in $(FUZZ_TARGETS); do \
	  mkdir -p $(FUZZ_DIR)/corpus_$$f && \
	  echo "== fuzzing $$f for $(FUZZ_SECONDS) s" && \
	  if $(FUZZ_DIR)/fuzz_$$f -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 -artifact_prefix=$(FUZZ_DIR)/ \
	       $(FUZZ_DIR)/corpus_$$f $(REPO)/fuzz/corpus/$$f > $(FUZZ_DIR)/$$f.log 2>&1; then \
	    runs=$$(grep -oE "stat::number_of_executed_units: *[0-9]+" $(FUZZ_DIR)/$$f.log | grep -oE "[0-9]+$$"); \
	    echo "fuzz_$$f: $$runs runs, no crash"; \
	    echo "<testsuite name=\"fuzz\"><testcase classname=\"fuzz\" name=\"$$f\"/></testsuite>" > $(FUZZ_DIR)/test_results/fuzz-$$f.xml; \
	  else \
	    found=1; tail -n 40 $(FUZZ_DIR)/$$f.log; echo "fuzz_$$f found a crash: see $(FUZZ_DIR)"; \
	    echo "<testsuite name=\"fuzz\"><testcase classname=\"fuzz\" name=\"$$f\"><failure message=\"crash or sanitizer report: $(FUZZ_DIR)/$$f.log\"/></testcase></testsuite>" > $(FUZZ_DIR)/test_results/fuzz-$$f.xml; \
	  fi; \
	done; exit $$found

demo: build
	source $(WS)/devel/setup.bash && roslaunch tow_sim tow_sim.launch rviz:=$(RVIZ) manoeuvre:=$(MANOEUVRE)

offline-demo: build
	$(WS)/devel/lib/tow_sim/tow_sim_demo

screenshot: build
	$(REPO)/scripts/rviz_screenshot.sh $(REPO)/docs/rviz_demo.png 40 $(MANOEUVRE)

# docs/parameters.md's parameter tables and config/tow_sim.yaml, generated from the parameter tables.
docs: build
	$(WS)/devel/lib/tow_sim/tow_sim_param_docs $(REPO)/docs/parameters.md $(REPO)/config/tow_sim.yaml

bench: build
	@for b in $(WS)/devel/lib/tow_sim/bench_*; do echo "== $$b"; $$b; done
	@echo "== bench/bench_python.py"
	@source $(WS)/devel/setup.bash && TOW_SIM_BIN=$(WS)/devel/lib/tow_sim /usr/bin/python3 $(REPO)/bench/bench_python.py

# Runs bench_chain, bench_steppers, bench_chart and bench_python.py and writes their figures into
# docs/benchmarks.md with the commit and date (a few minutes).
bench-docs: build
	source $(WS)/devel/setup.bash && /usr/bin/python3 $(REPO)/scripts/bench_docs.py $(WS)/devel/lib/tow_sim \
	  --doc $(REPO)/docs/benchmarks.md

# The towfish estimator against the layback rules on a lawn-mower survey (docs/survey.md): about 2 minutes.
survey-bench: build
	/usr/bin/python3 $(REPO)/scripts/survey_benchmark.py $(WS)/devel/lib/tow_sim $(WS)/survey_bench \
	  --plot $(REPO)/docs/plots/survey_benchmark.png --doc $(REPO)/docs/survey.md --doc $(REPO)/README.md

clean:
	rm -rf $(WS)
