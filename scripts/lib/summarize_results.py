#!/usr/bin/env python3
"""Counts test cases in catkin's JUnit result files; prints the failures and one summary line.

Usage: summarize_results.py RESULTS_DIR [EXPECTED_FILE ...]
Exit status 1 when any test failed or errored, or an expected result file is missing (a test
binary that crashed before writing results counts as a failure).
"""
import os
import sys
import xml.etree.ElementTree as ET


def main():
    root_dir = sys.argv[1]
    expected = sys.argv[2:]
    passed = failed = 0
    failures = []
    seen = set()
    for dirpath, _, files in os.walk(root_dir):
        for name in sorted(files):
            if not name.endswith(".xml"):
                continue
            seen.add(name)
            path = os.path.join(dirpath, name)
            try:
                tree = ET.parse(path)
            except ET.ParseError as e:
                failed += 1
                failures.append("%s: unreadable result file (%s)" % (name, e))
                continue
            for case in tree.iter("testcase"):
                problems = [c for c in case if c.tag in ("failure", "error")]
                label = "%s.%s" % (case.get("classname", "?"), case.get("name", "?"))
                if problems:
                    failed += 1
                    text = (problems[0].get("message") or problems[0].text or "").strip().splitlines()
                    failures.append("%s: %s" % (label, text[0] if text else problems[0].tag))
                elif case.get("status", "run") != "notrun":
                    passed += 1
    for name in expected:
        if name not in seen:
            failed += 1
            failures.append("%s: no results (the test did not run or crashed)" % name)
    for line in failures:
        print("FAILED " + line)
    print("%d passed, %d failed" % (passed, failed))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
