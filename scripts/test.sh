#!/usr/bin/env bash
# README command 2: install, build, and run every test (gtest and rostest), then the demo in RViz under Xvfb
# (scripts/rviz_screenshot.sh: RViz subscribes to the contact's topics and draws them without errors), then every
# command of the README as written (scripts/check_readme.py).
# Prints ctest's summary and exits non-zero on any failure.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

install_deps
build all tests
cd "$WS/build"
rm -rf "test_results/$PKG"  # stale XML would be counted again
log "running the tests"
rc=0
# The gtest binaries (nothing in them is timed) side by side, one per core; then the rostests one at a time: they
# measure rates and latencies, which a second test running beside them skews
ctest --output-on-failure --no-tests=error -j"$(nproc)" -E _rostest_ || rc=$?
ctest --output-on-failure --no-tests=error -R _rostest_ || rc=$?
catkin_test_results "test_results/$PKG" >/dev/null || { [ "$rc" -ne 0 ] || rc=1; }
# One line over every test case (ctest counts binaries; catkin_test_results counts gtest cases twice).
/usr/bin/python3 - "test_results/$PKG" <<'PY' || true
import glob, sys, xml.etree.ElementTree as ET
passed = failed = skipped = 0
# gtest binaries write gtest-*.xml; the test nodes of rostests (gtest, hztest, publishtest) rosunit-*.xml
for path in glob.glob(sys.argv[1] + "/gtest-*.xml") + glob.glob(sys.argv[1] + "/rosunit-*.xml"):
    for case in ET.parse(path).getroot().iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            failed += 1
        elif case.find("skipped") is not None or case.get("status") == "notrun":
            skipped += 1
        else:
            passed += 1
print("test cases: %d passed, %d failed, %d skipped" % (passed, failed, skipped))
PY
log "the demo in RViz (scripts/rviz_screenshot.sh)"
"$REPO/scripts/rviz_screenshot.sh" "$WS/output/rviz_demo.png" || rc=1
log "the README's commands, as written (scripts/check_readme.py)"
/usr/bin/python3 "$REPO/scripts/check_readme.py" || rc=1
if [ "$rc" -ne 0 ]; then
  catkin_test_results --verbose "test_results/$PKG" | grep -E 'Summary|Failure|failure' | head -50 || true
  log "tests FAILED"
else
  log "all tests passed"
fi
exit "$rc"
