#!/usr/bin/env bash
# Speed and accuracy of every model: Google Benchmark timings and the accuracy on the documented
# operating points, joined into docs/benchmarks.md and docs/figures/pareto.png (commit both).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

OUT="${SCE_OUTPUT:-$WS/output}"
install_deps
build bench_models model_accuracy
mkdir -p "$OUT"
BIN="$WS/devel/lib/$PKG"
log "timing (Google Benchmark, 3 repetitions, medians)"
"$BIN/bench_models" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_min_time=0.2 \
  --benchmark_format=console --benchmark_out_format=json --benchmark_out="$OUT/bench.json" 2>&1 | grep -v WARNING
log "accuracy on the operating points"
"$BIN/model_accuracy" > "$OUT/accuracy.json"
/usr/bin/python3 "$REPO/scripts/benchmark_report.py" --bench "$OUT/bench.json" --accuracy "$OUT/accuracy.json" \
  --docs "$REPO/docs"
