#!/usr/bin/env python3
"""Checks that every CTest test of a Catch2 executable runs exactly one test case.

catch_discover_tests() registers one CTest test per Catch2 test case, named
after it. A name that CMake splits (a ';' makes a list) or that Catch2's
filter reads otherwise gives CTest tests that match no test case: Catch2
then runs nothing and exits 0, and CTest counts a pass. This lists each
CTest test's command with `--list-test-names-only` and fails, naming the
tests, where a Catch2 command selects other than one test case.

Usage: check_test_registration.py BUILD_DIR
"""
import json
import os
import subprocess
import sys


def main(argv):
    if len(argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    build = argv[1]
    listing = subprocess.run(["ctest", "--test-dir", build, "--show-only=json-v1"],
                             capture_output=True, text=True, check=True)
    tests = json.loads(listing.stdout)["tests"]
    catch_tests, bad = 0, []
    for test in tests:
        command = test.get("command", [])
        # Catch2 tests: one of our test executables given the test case's name.
        if len(command) != 2 or not os.path.basename(command[0]).startswith("test_"):
            continue
        catch_tests += 1
        directory = next((p["value"] for p in test.get("properties", []) if p["name"] == "WORKING_DIRECTORY"), build)
        run = subprocess.run(command + ["--list-test-names-only"], capture_output=True, text=True, cwd=directory)
        names = [line for line in run.stdout.splitlines() if line.strip()]
        if len(names) != 1:
            bad.append((test["name"], len(names)))
    for name, count in bad:
        print(f"check_test_registration: CTest test '{name}' selects {count} Catch2 test cases, not 1 "
              "(a ';' in a test case's name splits it)", file=sys.stderr)
    print(f"[test] {catch_tests} Catch2 tests registered, {len(bad)} selecting other than one test case", file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
