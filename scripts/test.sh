#!/usr/bin/env bash
# README command 2: install, build, and run every test (gtest, and rostest once the node exists).
# Prints ctest's summary and exits non-zero on any failure.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

install_deps
build all tests
cd "$WS/build"
rm -rf "test_results/$PKG"  # stale XML would be counted again
log "running the tests"
rc=0
ctest --output-on-failure --no-tests=error -j"$(nproc)" || rc=$?
catkin_test_results "test_results/$PKG" >/dev/null || { [ "$rc" -ne 0 ] || rc=1; }
if [ "$rc" -ne 0 ]; then
  catkin_test_results --verbose "test_results/$PKG" | grep -E 'Summary|Failure|failure' | head -50 || true
  log "tests FAILED"
else
  log "all tests passed"
fi
exit "$rc"
