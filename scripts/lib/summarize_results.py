#!/usr/bin/env python3
"""Counts test cases in catkin's JUnit result files; prints the failures, the skips with their
reasons, and one summary line "N passed, N failed, N skipped".

Usage: summarize_results.py RESULTS_DIR [EXPECTED_FILE ...]
Exit status 1 when any test failed or errored, or an expected result file is missing (a test
binary that crashed before writing results counts as a failure).

A skipped test is never counted as passed. gtest (1.12, Debian 12) writes a GTEST_SKIP() as
<testcase ... result="skipped"> with a <skipped message="file:line\nreason"> child, and a
DISABLED_ test as <testcase ... status="notrun">; both count as skipped.

rostest leaves two files per .test file: the gtest XML of the test node (rosunit-<test>.xml,
which knows about skips) and its own summary (rostest-<file>.xml) with one wrapper test case
(rostest.runner.RosTest.test<name>) that fails when the node failed, crashed or timed out. The
node's test cases are counted from its own file; the wrapper counts only when it failed (a passing
wrapper would count the whole .test file once more as a pass, even when all its tests skipped).
"""
import os
import sys
import xml.etree.ElementTree as ET


def text_lines(text):
    lines = [l.strip() for l in (text or "").strip().splitlines() if l.strip()]
    return lines


DETAIL_LINES = 120
DETAIL_LINE_CHARS = 400


def detail_lines(problem):
    """The failure's message and text (the message attribute alone is often cut), at most
    DETAIL_LINES lines of at most DETAIL_LINE_CHARS characters, duplicates of the message dropped."""
    message = (problem.get("message") or "").strip()
    body = (problem.text or "").strip()
    text = message if not body or body == message else (message + "\n" + body if message not in body else body)
    lines = [l.rstrip() for l in text.splitlines() if l.strip()]
    cut = len(lines) - DETAIL_LINES
    lines = [l if len(l) <= DETAIL_LINE_CHARS else l[:DETAIL_LINE_CHARS] + " [...]" for l in lines[:DETAIL_LINES]]
    if cut > 0:
        lines.append("[... %d more lines in the result file]" % cut)
    return lines


def skip_reason(case):
    """Reason of a skipped test case, or None when it ran."""
    for child in case:
        if child.tag == "skipped":
            lines = text_lines(child.get("message") or child.text)
            # gtest puts "file:line" first, the GTEST_SKIP() message after it.
            if len(lines) > 1 and ":" in lines[0] and " " not in lines[0]:
                return " ".join(lines[1:]) + " (" + lines[0] + ")"
            return " ".join(lines) if lines else "skipped (no reason given)"
    if case.get("result") == "skipped":
        return "skipped (no reason given)"
    if case.get("status") == "notrun":
        return "disabled (DISABLED_ prefix: a known, reported bug)"
    return None


def rosunit_cases(root_dir):
    """(classname, name) of every test case found in rosunit-*.xml files."""
    cases = set()
    for dirpath, _, files in os.walk(root_dir):
        for name in files:
            if name.startswith("rosunit-") and name.endswith(".xml"):
                try:
                    tree = ET.parse(os.path.join(dirpath, name))
                except ET.ParseError:
                    continue
                for case in tree.iter("testcase"):
                    cases.add((case.get("classname", "?"), case.get("name", "?")))
    return cases


def main():
    root_dir = sys.argv[1]
    expected = sys.argv[2:]
    passed = failed = skipped = 0
    failures = []
    details = []
    skips = []
    seen = set()
    node_cases = rosunit_cases(root_dir)
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
            summary_file = name.startswith("rostest-")
            for case in tree.iter("testcase"):
                key = (case.get("classname", "?"), case.get("name", "?"))
                label = "%s.%s" % key
                problems = [c for c in case if c.tag in ("failure", "error")]
                if problems:
                    # A failure is never lost, even if the node's own file has the case too.
                    if summary_file and key in node_cases:
                        continue
                    failed += 1
                    text = text_lines(problems[0].get("message") or problems[0].text)
                    failures.append("%s: %s" % (label, " | ".join(text[:3])[:300] if text else problems[0].tag))
                    details.append((label, detail_lines(problems[0])))
                    continue
                if summary_file and (key in node_cases or key[0] == "rostest.runner.RosTest"):
                    continue  # counted from rosunit-*.xml, which knows whether it was skipped
                reason = skip_reason(case)
                if reason is not None:
                    skipped += 1
                    skips.append("%s: %s" % (label, reason))
                else:
                    passed += 1
    for name in expected:
        if name not in seen:
            failed += 1
            failures.append("%s: no results (the test did not run or crashed)" % name)
    for line in failures:
        print("FAILED " + line)
    # The whole message of each failure after the one-line list: a CI log is often all there is
    # of an intermittent failure (the tests' messages carry what the process saw, e.g. the
    # replay's event list and projector_host's log tail).
    for label, lines in details:
        if lines:
            print("FAILED> ---- %s ----" % label)
            for line in lines:
                print("FAILED>   " + line)
    for line in skips:
        print("SKIPPED " + line)
    print("%d passed, %d failed, %d skipped" % (passed, failed, skipped))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
