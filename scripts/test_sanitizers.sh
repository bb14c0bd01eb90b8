#!/usr/bin/env bash
# The core's and the CLI's tests built with AddressSanitizer and UndefinedBehaviorSanitizer (gcc), in a
# separate build directory: any leak, out-of-bounds access or undefined behaviour fails the run.
# .ci/run runs it after scripts/test.sh.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

install_deps
B="${WS}_asan"
FLAGS="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined"
log "building the tests with ASan + UBSan in $B"
# (-g1: the line tables the reports' stack traces need, without the rest of -g's debug information, which made the
# build a third longer: 73 against 48 s for the calibration's Ceres file)
cmake -S "$REPO" -B "$B" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g1 -DNDEBUG" -DCMAKE_CXX_FLAGS="$FLAGS" \
  -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
  -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" > "$B.configure.log" 2>&1 || { cat "$B.configure.log"; exit 1; }
TESTS=(test_cylinder test_brush test_uncertainty test_contact_estimator test_contact_eval test_contact_fit)
# a failed build fails the job (the last good binaries must never be the ones tested)
if ! make -C "$B" -j"$(nproc)" "${TESTS[@]}" > "$B.build.log" 2>&1; then
  grep -E "error|Error" "$B.build.log" | head -40
  log "the sanitizer build FAILED ($B.build.log)"
  exit 1
fi
grep -E "warning: .*sanitiz" "$B.build.log" || true  # only shows the warnings; the build's status is above
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=1" UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# The accuracy sweeps (hundreds of random operating points and histories against converged references) run the same
# code as the tests kept here, at 15x the release build's cost under the sanitizers (the Coulomb law's references made
# them longer still).
# scripts/test.sh runs them in the release build; the code they run is run here by the other tests, and under ASan by
# the fuzz targets (scripts/fuzz.sh).
SWEEPS="BrushAuto.AlongTheDemoManoeuvre:BrushAuto.EstimateCoversRandomHistories"
SWEEPS+=":BrushTransient.ErrorEstimateCoversNoisyHistoriesAtRandomPoints:ForceCovariance.SteadyModelAgainstMonteCarlo"
SWEEPS+=":BrushSteady.ErrorEstimateBoundsTheErrorOnRandomPoints:BrushAuto.WithinItsTargetAtRandomPoints"
SWEEPS+=":BrushTransient.ConvergesMonotonicallyOnTheFigure4Set:ContactFit.FrictionIsOnlyABoundWhereTheRunNeverSlides"
SWEEPS+=":BrushTransient.EstimateCoversTheDefaultRobotsNoisyHistories"
# the same for the checks of the transient model's estimate along random histories and of the sliding steps over the
# envelope (10-13 s each in the release build: 2-3 minutes each here, a third of this stage on a 2.1 GHz host), and the
# calibration's coverage over a synthetic run
SWEEPS+=":BrushTransient.SubstepsCutShortKeepTheirErrorInTheEstimateUntilTheirBristlesLeave"
SWEEPS+=":BrushTransient.EstimateCoversNoisyRollsOfTensOfSpacingsAMessage"
SWEEPS+=":BrushTransient.EstimateCoversNoisySkidsThatRollAboutASpacingAMessage"
SWEEPS+=":BristleAdvance.SlidingStepErrorBoundsTheErrorOverTheWholeEnvelope"
SWEEPS+=":ContactFit.RecoversTheParametersOfASyntheticRunWithinItsIntervals"
# and the parked walk against Monte Carlo (300 realisations of 300 messages per case, 50 s in the release build): under
# the sanitizers one shard ran it for 11 of CI's 49 minutes (2026-12-02); the walk's code runs here in
# EstimateCovariance.StandstillWalkGrowsIsHeldByFrictionAndIsLostWithItsNoise and in test_contact_estimator's
# MotionHold tests
SWEEPS+=":EstimateCovariance.StandstillRandomWalkAgainstMonteCarlo"
# Each binary's tests split into gtest shards (three per core, so that one long test leaves the others to the other
# cores), run one per core at a time: nothing here is timed, and this stage took 9 of CI's 49 minutes one test at a
# time (test_brush 7.4, BrushExtremes' random envelope 2.6 of it)
CORES="$(nproc)"
SHARDS=$((3 * CORES))
shard() {  # binary, shard index: its log and its exit status in files
  local status=0
  GTEST_TOTAL_SHARDS="$SHARDS" GTEST_SHARD_INDEX="$2" "$B/devel/lib/$PKG/$1" --gtest_brief=1 --gtest_filter="-$SWEEPS" \
    > "$B/$1.shard$2.log" 2>&1 || status=$?
  echo "$status" > "$B/$1.shard$2.rc"
}
rc=0
for t in "${TESTS[@]}"; do
  log "$t (ASan + UBSan, $SHARDS shards on $CORES cores)"
  for ((s = 0; s < SHARDS; ++s)); do
    while [ "$(jobs -rp | wc -l)" -ge "$CORES" ]; do wait -n || true; done
    rm -f "$B/$t.shard$s.rc"
    shard "$t" "$s" &
  done
  wait
  for ((s = 0; s < SHARDS; ++s)); do
    cat "$B/$t.shard$s.log"
    [ "$(cat "$B/$t.shard$s.rc" 2>/dev/null)" = 0 ] || { rc=1; log "$t shard $s of $SHARDS FAILED"; }
  done
done
[ "$rc" -eq 0 ] && log "sanitizer runs clean" || log "sanitizer runs FAILED"
exit "$rc"
