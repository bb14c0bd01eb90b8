#!/usr/bin/env bash
# libFuzzer targets (clang, libclang-rt-14-dev from apt) for the kinematics, the brush and cylinder models
# and the odometry -> estimate path, with AddressSanitizer and UndefinedBehaviorSanitizer, each from its
# committed seed corpus in fuzz/corpus/<target>. By default a fixed seed and a fixed number of runs per target
# (bounded, about 15 s each, and reproducible: CI explores the same inputs every time); FUZZ_SECONDS=N fuzzes
# each target for N s with a random seed instead. .ci/run runs the default. A crash leaves its input in
# $WS/fuzz/ and fails the run.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

APT_PACKAGES+=(clang libclang-rt-14-dev)
install_deps
declare -A RUNS=([fuzz_kinematics]=2000000 [fuzz_brush]=400 [fuzz_cylinder]=300000 [fuzz_estimator]=1500)
OUTDIR="$WS/fuzz"
mkdir -p "$OUTDIR"
CORE=("$REPO"/src/core/*.cpp)
rc=0
for target in fuzz_kinematics fuzz_brush fuzz_cylinder fuzz_estimator; do
  bin="$OUTDIR/$target"
  if [ ! -x "$bin" ] || [ -n "$(find "$REPO/src/core" "$REPO/include" "$REPO/fuzz" -newer "$bin" -print -quit)" ]; then
    log "building $target"
    clang++ -std=c++17 -O1 -g -fsanitize=fuzzer,address,undefined -fno-sanitize-recover=undefined \
      -I "$REPO/include" -I /usr/include/eigen3 "$REPO/fuzz/$target.cpp" "${CORE[@]}" -o "$bin"
  fi
  work="$OUTDIR/${target}_corpus"
  [ -n "${FUZZ_SECONDS:-}" ] || rm -rf "$work"  # the reproducible run starts from the seeds alone
  mkdir -p "$work"
  if [ -n "${FUZZ_SECONDS:-}" ]; then
    budget=(-max_total_time="$FUZZ_SECONDS")
    log "fuzzing $target for $FUZZ_SECONDS s"
  else
    budget=(-runs="${RUNS[$target]}" -seed=1)
    log "fuzzing $target: ${RUNS[$target]} runs, seed 1"
  fi
  if ! (cd "$OUTDIR" && UBSAN_OPTIONS=halt_on_error=1 "$bin" "${budget[@]}" -max_len=512 \
        -print_final_stats=1 "$work" "$REPO/fuzz/corpus/$target" 2>&1 | grep -E "^#[0-9]+ *DONE|stat::number_of_executed_units|ERROR|runtime error|Assertion|deadly signal|SUMMARY" ); then
    :
  fi
  found=$(find "$OUTDIR" -maxdepth 1 \( -name 'crash-*' -o -name 'leak-*' -o -name 'timeout-*' -o -name 'oom-*' \) -newer "$bin" | head -3)
  if [ -n "$found" ]; then
    log "$target found a failure: $found"
    rc=1
  fi
done
[ "$rc" -eq 0 ] && log "fuzzing found nothing" || log "fuzzing FAILED"
exit "$rc"
