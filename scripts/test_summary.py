#!/usr/bin/env python3
"""The verdict of `make test`: counts the test cases in the JUnit XML files of each suite and checks them
against the suite's manifest of expected results.

    test_summary.py --suite LABEL RESULTS_DIR MANIFEST [--suite ...] [--stages FILE] [--allow-skip NAME ...]

A manifest (written by CMake, or by the Makefile for fuzzing) has one line per expected result: a file
path relative to RESULTS_DIR, or FILE::NAME for a test case NAME that must be inside FILE (CTest's one
JUnit file). A missing manifest, a missing result file or test case (the binary never ran, crashed before
writing its XML, or was killed at its time limit), an unreadable file, a failure or an error, and a
skipped or not-run test case (unless named with --allow-skip CLASS.NAME) each count as one failure.
--stages names a file of `STAGE EXIT_STATUS` lines (the build, run_tests, sanitizer and fuzzing stages of
`make test`); a non-zero status is a failure too.

Prints the failures, one line per suite saying what was counted, and last a line `N passed, N failed`.
Exits 1 when anything failed or nothing was counted.
"""
import argparse
import pathlib
import sys
import xml.etree.ElementTree as ET


class Tally:
    def __init__(self):
        self.passed = 0
        self.failed = 0
        self.problems = []

    def fail(self, message):
        self.failed += 1
        self.problems.append(message)


def read_manifest(path):
    return [line.strip() for line in pathlib.Path(path).read_text().splitlines() if line.strip()]


def count_file(path, tally, allowed_skips):
    """Counts the test cases of one JUnit file; returns the set of their names, or None if unreadable."""
    try:
        root = ET.parse(path).getroot()
    except (ET.ParseError, OSError) as error:
        tally.fail(f"UNREADABLE {path} ({error})")
        return None
    names = set()
    for case in root.iter("testcase"):
        name = case.get("name", "")
        full = f"{case.get('classname', '')}.{name}"
        names.add(name)
        if case.find("failure") is not None or case.find("error") is not None:
            tally.fail(f"FAILED {full} ({path.name})")
        elif case.find("skipped") is not None or case.get("status") == "notrun":
            if full in allowed_skips:
                tally.passed += 1
            else:
                tally.fail(f"NOT RUN {full} ({path.name}): skipped tests count as failures")
        else:
            tally.passed += 1
    return names


def count_suite(label, results_dir, manifest, allowed_skips):
    tally = Tally()
    results = pathlib.Path(results_dir)
    try:
        expected = read_manifest(manifest)
    except OSError as error:
        tally.fail(f"{label}: no manifest of expected results ({error})")
        return tally
    if not expected:
        tally.fail(f"{label}: the manifest {manifest} lists no tests")
    files = sorted(results.rglob("*.xml")) if results.is_dir() else []
    cases = {}
    for path in files:
        names = count_file(path, tally, allowed_skips)
        if names is not None:
            cases[path.relative_to(results).as_posix()] = names
    for line in expected:
        file_name, _, case_name = line.partition("::")
        if file_name not in cases:
            tally.fail(f"MISSING {label}: {file_name} under {results_dir} (the test did not run, crashed before "
                       f"writing its results, or was killed at its time limit)")
        elif case_name and case_name not in cases[file_name]:
            tally.fail(f"MISSING {label}: test {case_name} in {file_name}")
    return tally


def count_stages(path):
    tally = Tally()
    try:
        lines = pathlib.Path(path).read_text().splitlines()
    except OSError as error:
        tally.fail(f"stages: no record of the test stages ({error})")
        return tally
    for line in lines:
        if not line.strip():
            continue
        stage, _, status = line.rpartition(" ")
        if status.strip() == "0":
            tally.passed += 1
        else:
            tally.fail(f"FAILED stage '{stage}' exited with status {status}")
    return tally


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--suite", nargs=3, action="append", default=[], metavar=("LABEL", "RESULTS_DIR", "MANIFEST"))
    parser.add_argument("--stages", help="file of 'STAGE EXIT_STATUS' lines")
    parser.add_argument("--allow-skip", action="append", default=[], metavar="CLASS.NAME")
    args = parser.parse_args(argv)
    if not args.suite:
        parser.error("give at least one --suite")

    total = Tally()
    lines = []
    for label, results_dir, manifest in args.suite:
        tally = count_suite(label, results_dir, manifest, set(args.allow_skip))
        lines.append(f"  {label}: {tally.passed} passed, {tally.failed} failed")
        total.passed += tally.passed
        total.failed += tally.failed
        total.problems += tally.problems
    if args.stages:
        tally = count_stages(args.stages)
        lines.append(f"  stages (size limits, layers, package, format, build, run_tests, install space, sanitizers, fuzzing: exit status): "
                     f"{tally.passed} passed, {tally.failed} failed")
        total.passed += tally.passed
        total.failed += tally.failed
        total.problems += tally.problems
    for problem in total.problems:
        print(problem)
    print("counted:")
    for line in lines:
        print(line)
    if total.passed + total.failed == 0:
        total.failed += 1
        print("nothing was counted")
    print(f"{total.passed} passed, {total.failed} failed")
    return 1 if total.failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
