# SPDX-License-Identifier: MIT
"""Reads back from CTest the properties the test registrations promise, so that a property list
mangled on its way through gtest_discover_tests fails here instead of leaving tests that run
something else than their names say:
  - the World tests repeated on the paper's pipeline (names ending .paper and .paper_rule) carry
    the label paper_pipeline and SMB_TEST_PIPELINE=paper or paper-rule, and there are some;
  - the tests of the four-lane path (label four_lanes) carry SMB_NO_AVX2;
  - every GoogleTest case has a timeout.

Usage: check_test_properties.py CTEST BUILD_DIR
"""

import json
import subprocess
import sys


def properties_of(test):
    return {entry["name"]: entry["value"] for entry in test.get("properties", [])}


def as_list(value):
    return value if isinstance(value, list) else [value]


def main():
    if len(sys.argv) != 3:
        sys.exit("usage: check_test_properties.py CTEST BUILD_DIR")
    ctest, build_dir = sys.argv[1], sys.argv[2]
    listing = subprocess.run([ctest, "--test-dir", build_dir, "--show-only=json-v1"],
                             check=True, capture_output=True, text=True).stdout
    tests = json.loads(listing)["tests"]
    problems = []
    repeats = 0
    for test in tests:
        name = test["name"]
        props = properties_of(test)
        labels = as_list(props.get("LABELS", []))
        environment = as_list(props.get("ENVIRONMENT", []))
        for suffix, pipeline in ((".paper", "paper"), (".paper_rule", "paper-rule")):
            if name.endswith(suffix):
                repeats += 1
                if "paper_pipeline" not in labels:
                    problems.append(f"{name}: no label paper_pipeline (labels {labels})")
                if f"SMB_TEST_PIPELINE={pipeline}" not in environment:
                    problems.append(f"{name}: SMB_TEST_PIPELINE={pipeline} not set (environment {environment})")
        if "paper_pipeline" in labels and not name.endswith((".paper", ".paper_rule")):
            problems.append(f"{name}: labelled paper_pipeline but not a repeat on the paper's pipeline")
        if "four_lanes" in labels and "SMB_NO_AVX2=1" not in environment:
            problems.append(f"{name}: labelled four_lanes without SMB_NO_AVX2=1 (environment {environment})")
        # gtest_discover_tests gives each case it registers this property.
        if "SKIP_REGULAR_EXPRESSION" in props and "TIMEOUT" not in props:
            problems.append(f"{name}: a GoogleTest case without a timeout")
    if repeats == 0:
        problems.append("no test repeats the World tests on the paper's pipeline")
    for problem in problems[:20]:
        print(problem)
    if len(problems) > 20:
        print(f"... and {len(problems) - 20} more")
    print(f"{len(tests)} tests read, {repeats} on the paper's pipeline, {len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
