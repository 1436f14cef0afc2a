#!/usr/bin/env python3
"""Counts the test cases in the JUnit XML files under test_results folders (catkin's and CTest's).

Prints the per-file failures, then one last line `N passed, N failed[, N skipped]`. Exits 1 when a
test failed or errored, when a result file is unreadable, or when no test ran at all.
"""
import pathlib
import sys
import xml.etree.ElementTree as ET


def main(folders) -> int:
    passed = failed = skipped = 0
    problems = []
    files = sorted(f for folder in folders for f in pathlib.Path(folder).rglob("*.xml"))
    folder = ", ".join(folders)
    for path in files:
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as error:
            problems.append(f"{path}: unreadable result file ({error})")
            failed += 1
            continue
        for case in root.iter("testcase"):
            name = f"{case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                problems.append(f"FAILED {name} ({path.name})")
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    for line in problems:
        print(line)
    summary = f"{passed} passed, {failed} failed"
    if skipped:
        summary += f", {skipped} skipped"
    if not files or passed + failed == 0:
        print(f"no test results found under {folder}")
        print(summary)
        return 1
    print(summary)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:] or ["build/test_results"]))
