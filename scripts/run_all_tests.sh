#!/usr/bin/env bash
# usage: WS=DIR REPO=DIR JOBS=N CATKIN_ARGS=ARGS FUZZ_SECONDS=N scripts/run_all_tests.sh
#
# `make test`: every stage runs even when an earlier one failed (the size, layer, package and format checks,
# the test build, run_tests, the install space, the sanitizers, fuzzing), its exit status is recorded in
# WS/test_stages.txt, and scripts/test_summary.py gives the verdict over all of them (the expected results
# of every suite included, so a test that never ran is a failure). Takes no arguments; the Makefile (make
# test) calls it with these in the environment, all required:
#
#   WS            the catkin workspace
#   REPO          the repository
#   JOBS          parallel build jobs (make test: 2)
#   CATKIN_ARGS   catkin_make's arguments (make test: -DCMAKE_BUILD_TYPE=Release -DPYTHON_EXECUTABLE=...)
#   FUZZ_SECONDS  seconds of fuzzing per target; 0 skips the fuzz stage (make test: 30)
#   -h, --help    prints this help and exits
#
# Exit status: 2 for wrong arguments (nothing runs), not 0 when a variable is missing; else test_summary.py's
# (0 when everything passed).
set -o pipefail
source "$(dirname "${BASH_SOURCE[0]}")/cli.sh"
cli_help "$@"
cli_refuse_options "$@"
: "${WS:?}" "${REPO:?}" "${JOBS:?}" "${CATKIN_ARGS:?}" "${FUZZ_SECONDS:?}"
stages="$WS/test_stages.txt"
: > "$stages"

# Runs a stage ("name" then the command); records its exit status; never stops the script.
stage() {
  local name="$1"
  shift
  "$@"
  local status=$?
  echo "$name $status" >> "$stages"
  [[ $status == 0 ]] || echo "== stage '$name' failed with status $status"
  return 0
}

run_tests() {
  cd "$WS" && source devel/setup.bash && catkin_make $CATKIN_ARGS -j1 run_tests > "$WS/run_tests.log" 2>&1
  local status=$?
  if [[ $status != 0 ]]; then
    tail -n 60 "$WS/run_tests.log"
    echo "catkin_make run_tests failed (log: $WS/run_tests.log)"
  fi
  return $status
}

# The style guide's limits, package.xml against the code and the committed format, on the sources (not the build).
stage "size limits (scripts/check_sizes.py)" /usr/bin/python3 "$REPO/scripts/check_sizes.py" "$REPO"
stage "layers (scripts/check_layers.py)" /usr/bin/python3 "$REPO/scripts/check_layers.py" "$REPO"
stage "package dependencies (scripts/check_package.py)" /usr/bin/python3 "$REPO/scripts/check_package.py" "$REPO"
stage "clang-format (.clang-format)" bash -c "cd '$REPO' && clang-format --dry-run -Werror \$(find src include tools test bench fuzz \( -name '*.cpp' -o -name '*.h' \))"

cd "$WS" && rm -rf build/test_results
stage "build the tests" bash -c "cd '$WS' && catkin_make $CATKIN_ARGS -j$JOBS tests"
stage "catkin_make run_tests" run_tests
# The figures the tests print, for the log.
grep -E '^(\[  (PASSED|FAILED) |\[==========\] [0-9]+ tests? from .* ran)|critical angle|energy drift|mode [0-9]:|length error|trim at|after 60 s|yawed|pitched|incidence|CB [0-9]|equilibrium|rviz screenshot|drift from|reversing|odometry at|soak|cable/state|late step|unstable node|slope' \
  "$WS/run_tests.log" || true
# The install space alone: catkin_make install, then the tools and the demo from install/setup.bash only.
stage "install space (scripts/check_install.sh)" bash -c "cd '$WS' && catkin_make $CATKIN_ARGS -j$JOBS install > '$WS/install.log' 2>&1 && '$REPO/scripts/check_install.sh' '$WS/install'"
stage "make sanitize" make --no-print-directory -C "$REPO" sanitize
suites=(--suite "gtest/rostest" "$WS/build/test_results" "$WS/build/tow_sim/tow_sim_expected_results.txt"
        --suite "core tests under ASan+UBSan" "$WS/sanitize/test_results" "$WS/sanitize/tow_sim_expected_results.txt")
if [[ "$FUZZ_SECONDS" != 0 ]]; then
  stage "make fuzz" make --no-print-directory -C "$REPO" fuzz
  suites+=(--suite "fuzz targets, $FUZZ_SECONDS s each" "$WS/fuzz/test_results" "$WS/fuzz/tow_sim_expected_fuzz_results.txt")
fi
/usr/bin/python3 "$REPO/scripts/test_summary.py" "${suites[@]}" --stages "$stages"
