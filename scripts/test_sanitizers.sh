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
cmake -S "$REPO" -B "$B" -DPYTHON_EXECUTABLE=/usr/bin/python3 -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS="$FLAGS" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
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
rc=0
for t in "${TESTS[@]}"; do
  log "$t (ASan + UBSan)"
  "$B/devel/lib/$PKG/$t" --gtest_brief=1 --gtest_filter="-$SWEEPS" || rc=1
done
[ "$rc" -eq 0 ] && log "sanitizer runs clean" || log "sanitizer runs FAILED"
exit "$rc"
