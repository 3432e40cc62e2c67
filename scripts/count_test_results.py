#!/usr/bin/env python3
"""Counts JUnit results under a folder (catkin's test_results) and prints 'N passed, M failed'.

Exit status 1 when any test failed, when a test produced no result (catkin writes a MISSING-*
file with a failure then), or when no test ran at all.
"""
import sys
import xml.etree.ElementTree as ET
from pathlib import Path


def count(folder):
    passed, failed, skipped, failures = 0, 0, 0, []
    files = sorted(Path(folder).rglob("*.xml")) if Path(folder).is_dir() else []
    for path in files:
        try:
            root = ET.parse(path).getroot()
        except ET.ParseError as err:
            failed += 1
            failures.append(f"{path.name}: unreadable result ({err})")
            continue
        cases = list(root.iter("testcase"))
        if not cases:
            # A suite-level error with no test cases still counts as a failure.
            errors = int(root.get("errors", 0) or 0) + int(root.get("failures", 0) or 0)
            if errors:
                failed += 1
                failures.append(f"{path.name}: suite error without test cases")
            continue
        for case in cases:
            name = f"{path.stem}: {case.get('classname', '')}.{case.get('name', '')}"
            if case.find("failure") is not None or case.find("error") is not None:
                failed += 1
                failures.append(name)
            elif case.find("skipped") is not None or case.get("status") == "notrun":
                skipped += 1
            else:
                passed += 1
    return passed, failed, skipped, failures


def main():
    if len(sys.argv) != 2 or sys.argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        print("usage: count_test_results.py TEST_RESULTS_DIR")
        return 0 if len(sys.argv) == 2 else 2
    passed, failed, skipped, failures = count(sys.argv[1])
    for name in failures:
        print(f"FAILED: {name}")
    if passed + failed == 0:
        print("no test ran")
        failed = 1
    line = f"{passed} passed, {failed} failed"
    if skipped:
        line += f", {skipped} skipped"
    print(line)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
