#!/usr/bin/env bash
# The reconfigure-under-load rostest (test/rostest/load.test) against a ThreadSanitizer build (gcc) of the
# nodelet, in a four-thread manager: there odometry, reconfigure and diagnostics callbacks run concurrently
# (the nodelet takes the multi-threaded node handles). The manager binary is Debian's, so the TSan runtime is
# preloaded into it. A data race or lock-order inversion in this package's code fails the run; those TSan
# finds inside the uninstrumented roscpp and boost are counted, not judged (scripts/tsan_reports.py says
# how the two are told apart). .ci/run runs it after the ASan job.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"
APT_PACKAGES+=(llvm-14)  # llvm-symbolizer for the frames of the dlopen'ed nodelet

install_deps
B="${WS}_tsan"
FLAGS="-fsanitize=thread -fno-omit-frame-pointer -g1 -O1"  # -g1: the reports' line tables, a shorter build
log "building the nodelet and the load test with ThreadSanitizer in $B"
cmake -S "$REPO" -B "$B" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=None -DCATKIN_ENABLE_TESTING=ON \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=thread" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=thread" > "$B.configure.log" 2>&1 || { cat "$B.configure.log"; exit 1; }
# a failed build fails the job (the last good binaries must never be the ones tested)
if ! make -C "$B" -j"$(nproc)" "${PKG}_nodelet" test_load > "$B.build.log" 2>&1; then
  grep -E "error|Error" "$B.build.log" | head -40
  log "the ThreadSanitizer build FAILED ($B.build.log)"
  exit 1
fi

set +u
# shellcheck disable=SC1091
source "$B/devel/setup.bash"
set -u
REPORTS="$B/tsan_reports"
rm -rf "$REPORTS" && mkdir -p "$REPORTS"
# every instrumented process writes its reports to a file of its own (rostest's output is not where they go)
export TSAN_OPTIONS="log_path=$REPORTS/tsan:history_size=4:external_symbolizer_path=/usr/bin/llvm-symbolizer-14"
rc=0
log "load.test nodelet:=true under ThreadSanitizer"
# TSan slows everything several times: a lower rate, and no delivery, latency or memory bounds (load.test
# checks those uninstrumented); what counts here is concurrency under reconfigure.
rostest --text "$PKG" load.test nodelet:=true rate:=2000.0 duration:=25.0 min_delivered:=0.0 max_latency:=1000.0 \
  max_rss_growth_mb:=100000.0 time_limit:=300 launch_prefix:="env LD_PRELOAD=$(gcc -print-file-name=libtsan.so)" \
  > "$B/load.log" 2>&1 || { rc=1; tail -40 "$B/load.log"; }
grep -E "^load:" "$B/load.log" || true
/usr/bin/python3 "$REPO/scripts/tsan_reports.py" "$REPORTS" "$REPO" "$B/devel/lib" || rc=1
[ "$rc" -eq 0 ] && log "ThreadSanitizer run clean" || log "ThreadSanitizer run FAILED"
exit "$rc"
