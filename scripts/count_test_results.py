#!/usr/bin/python3
"""Counts test cases in a catkin test_results folder: prints "PASSED FAILED SKIPPED".

catkin_test_results sums the totals of both <testsuites> and <testsuite> elements, which counts
every gtest case twice; this counts <testcase> elements instead. A file that cannot be parsed
(a test binary that crashed mid-write) counts as one failure.
"""
import os
import sys
import xml.etree.ElementTree as ET


def count(folder):
    passed = failed = skipped = 0
    for root, _, files in os.walk(folder):
        for name in files:
            if not name.endswith(".xml"):
                continue
            try:
                tree = ET.parse(os.path.join(root, name))
            except ET.ParseError:
                failed += 1
                continue
            for case in tree.iter("testcase"):
                if case.find("failure") is not None or case.find("error") is not None:
                    failed += 1
                elif case.find("skipped") is not None or case.get("status") == "notrun":
                    skipped += 1
                else:
                    passed += 1
    return passed, failed, skipped


if __name__ == "__main__":
    print(*count(sys.argv[1]))
