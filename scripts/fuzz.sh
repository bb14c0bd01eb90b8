#!/usr/bin/env bash
# libFuzzer targets (clang, libclang-rt-14-dev from apt) for the kinematics, the brush and cylinder models
# and the odometry -> estimate path, with AddressSanitizer and UndefinedBehaviorSanitizer, each from its
# committed seed corpus in fuzz/corpus/<target>. By default a fixed seed and a fixed number of runs per target
# (bounded, and reproducible: CI explores the same inputs every time; FUZZ_RUNS_PERCENT scales them, FUZZ_TARGETS
# picks targets);
# FUZZ_SECONDS=N fuzzes each target for N s with a random seed instead (the README says how long 10^7 executions
# take). .ci/run runs the default. A failure leaves its input in $WS/fuzz/ and fails the run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

APT_PACKAGES+=(clang libclang-rt-14-dev)
install_deps
# the brush and estimator targets bound their cost per input (fuzz/*.cpp), but under eq. (4b) (half their inputs)
# an input costs ~10x the rigid law's under ASan (the Coulomb steady solver is ~10-30x slower): 2.5*10^4 of each
# keeps CI within its time (10^5 of fuzz_brush took 15 min on the development machine); longer campaigns with
# FUZZ_SECONDS or FUZZ_RUNS_PERCENT
declare -A RUNS=([fuzz_kinematics]=2000000 [fuzz_brush]=25000 [fuzz_cylinder]=300000 [fuzz_estimator]=25000)
OUTDIR="$WS/fuzz"
B="${WS}_fuzz"
mkdir -p "$OUTDIR"
# the targets come from the package's own CMakeLists.txt (option SCE_FUZZ): the same core library definition
SAN="-fsanitize=address,undefined -fno-sanitize-recover=undefined"
log "configuring the fuzz targets with clang in $B"
cmake -S "$REPO" -B "$B" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCE_FUZZ=ON \
  -DCATKIN_ENABLE_TESTING=OFF -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_CXX_FLAGS="$SAN -fsanitize=fuzzer-no-link" -DCMAKE_EXE_LINKER_FLAGS="$SAN" \
  -DCMAKE_SHARED_LINKER_FLAGS="$SAN" > "$B.configure.log" 2>&1 || { cat "$B.configure.log"; exit 1; }
read -r -a TARGETS <<< "${FUZZ_TARGETS:-fuzz_kinematics fuzz_brush fuzz_cylinder fuzz_estimator}"
log "building ${TARGETS[*]}"
if ! make -C "$B" -j"$(nproc)" "${TARGETS[@]}" > "$B.build.log" 2>&1; then
  grep -E "error|Error" "$B.build.log" | head -40
  log "the fuzz build FAILED ($B.build.log)"
  exit 1
fi
rc=0
for target in "${TARGETS[@]}"; do
  bin="$B/devel/lib/$PKG/$target"
  [ -x "$bin" ] || bin="$(find "$B" -type f -name "$target" -perm -u+x | head -1)"
  runs=$(( ${RUNS[$target]} * ${FUZZ_RUNS_PERCENT:-100} / 100 ))
  work="$OUTDIR/${target}_corpus"
  [ -n "${FUZZ_SECONDS:-}" ] || rm -rf "$work"  # the reproducible run starts from the seeds alone
  mkdir -p "$work"
  if [ -n "${FUZZ_SECONDS:-}" ]; then
    budget=(-max_total_time="$FUZZ_SECONDS")
    log "fuzzing $target for $FUZZ_SECONDS s"
  else
    budget=(-runs="$runs" -seed=1)
    log "fuzzing $target: $runs runs, seed 1"
  fi
  status=0
  (cd "$OUTDIR" && UBSAN_OPTIONS=halt_on_error=1 "$bin" "${budget[@]}" -max_len=512 -print_final_stats=1 \
    "$work" "$REPO/fuzz/corpus/$target" > "$OUTDIR/$target.log" 2>&1) || status=$?
  grep -E "^#[0-9]+ *DONE|stat::number_of_executed_units|ERROR|runtime error|Assertion|deadly signal|SUMMARY" \
    "$OUTDIR/$target.log" || true
  if [ "$status" -ne 0 ]; then
    log "$target FAILED (exit $status; $OUTDIR/$target.log, the input in $OUTDIR/crash-* or the like)"
    rc=1
  fi
done
[ "$rc" -eq 0 ] && log "fuzzing found nothing" || log "fuzzing FAILED"
exit "$rc"
