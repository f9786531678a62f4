#!/usr/bin/env bash
# Every test carries a subsystem label (tests/CMakeLists.txt, sortlast_label), so `ctest -L volume`
# and the others find all of a subsystem's tests. Lists the tests without one; exit 1 if any.
# Usage: check_labels.sh BUILD_DIR
set -euo pipefail
build=$1
subsystems='volume|particles|surfaces|glow|compositing|service|insitu|io|python|scene|robustness|gl|layout'
# ctest --show-only=json-v1 lists each test with its properties (LABELS among them).
missing=$(ctest --test-dir "$build" --show-only=json-v1 | python3 -c '
import json, re, sys
tests = json.load(sys.stdin)["tests"]
subsystems = set(sys.argv[1].split("|"))
for t in tests:
    labels = next((p["value"] for p in t.get("properties", []) if p["name"] == "LABELS"), [])
    if not subsystems & set(labels):
        print(t["name"])
' "$subsystems")
if [ -n "$missing" ]; then
  echo "tests without a subsystem label (add them to a sortlast_label list in tests/CMakeLists.txt):"
  echo "$missing"
  exit 1
fi
echo "labels: every test has a subsystem label"
