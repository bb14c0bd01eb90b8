#!/usr/bin/env bash
# Speed and accuracy of every model: Google Benchmark timings, the accuracy program over random operating
# points, the auto model along the demo bag (before: bench/demo_bag_before.json, measured on the release before
# issue 11), the node over roscpp and bag_analyze's replay path, joined into docs/benchmarks.md and docs/figures/pareto.png (commit both).
# With --stream-targets (about 10 minutes): only issue 21's measures (the recorded manoeuvres' streams, the node on them,
# their replay, the transient model's 10-ms message), rewriting only their rows of the Targets table.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

OUT="${SCE_OUTPUT:-$WS/output}"
# the parameter file's brush model as a number (it may be written as a name)
default_brush_model() {
  local m
  m=$(sed -n 's/^brush_model: *\([a-z0-9]*\).*/\1/p' "$REPO/config/contact_estimator.yaml")
  case "$m" in off) echo 0 ;; linear) echo 1 ;; steady) echo 2 ;; transient) echo 3 ;; auto) echo 4 ;; *) echo "$m" ;; esac
}
# record_scenario SCENARIO RATE NAME: the scenario recorded by demo.launch at RATE into $OUT/NAME.bag (with the live
# node's CSV beside it), unless that bag is already there; a failed recording shows as the missing bag further on
record_scenario() {
  [ -s "$OUT/$3.bag" ] && return 0
  roslaunch sphere_contact_estimator demo.launch scenario:="$1" rate:="$2" record:="$OUT/$3.bag" \
    output_csv:="$OUT/$3_live.csv" > "$OUT/$3_record.log" 2>&1 || true
}
# the recorded manoeuvre at 100 Hz (data/manoeuvre.bag) and 1 kHz (recorded now), every message against a converged
# reference
streams() {
  record_scenario "$REPO/config/manoeuvre_scenario.yaml" 1000 manoeuvre_1khz
  /usr/bin/python3 "$REPO/scripts/stream_benchmark.py" --bag-analyze "$BIN/bag_analyze" --params "$REPO/config/contact_estimator.yaml" \
    --scenario "$REPO/config/manoeuvre_scenario.yaml" --reference-resolution 128 --confirm-resolution 256 \
    --bags "$REPO/data/manoeuvre.bag" "$OUT/manoeuvre_1khz.bag" --out "$OUT/streams.json"
}
# the node over roscpp on loopback (the node pinned to one core), the recorded manoeuvres at their pace
node_on_streams() {
  export ROS_MASTER_URI="http://localhost:$((20000 + RANDOM % 20000))"
  roscore -p "${ROS_MASTER_URI##*:}" > "$OUT/roscore.log" 2>&1 &
  ROSCORE=$!
  NODE=""
  trap 'kill $NODE $ROSCORE 2>/dev/null || true' EXIT
  until rostopic list > /dev/null 2>&1; do sleep 0.2; done
  rosparam load "$REPO/config/contact_estimator.yaml" /contact_estimator
  taskset -c 1 "$BIN/contact_estimator_node" __name:=contact_estimator > "$OUT/node.log" 2>&1 &
  NODE=$!
  taskset -c 0 "$BIN/node_benchmark" _duration:=2.0 _streams:="$REPO/data/manoeuvre.bag,$OUT/manoeuvre_1khz.bag" > "$OUT/node.json"
  kill $NODE $ROSCORE 2>/dev/null || true
  wait 2>/dev/null || true
  trap - EXIT
}
# the recorded manoeuvres through bag_analyze's replay path, each brush model
replay_streams() {
  taskset -c 0 "$BIN/replay_benchmark" --streams "$REPO/data/manoeuvre.bag" "$OUT/manoeuvre_1khz.bag" \
    --params "$REPO/config/contact_estimator.yaml" --models off linear steady transient auto > "$OUT/replay_streams.json"
}
case "${1:-}" in "" | --stream-targets) ;; *) echo "usage: $0 [--stream-targets]" >&2; exit 2 ;; esac
install_deps
mkdir -p "$OUT"
BIN="$WS/devel/lib/$PKG"
if [ "${1:-}" = "--stream-targets" ]; then
  build bench_models node_benchmark contact_estimator_node bag_analyze replay_benchmark
  log "the transient model's 10-ms message, each stepping and law (Google Benchmark, 3 repetitions, medians, one core)"
  taskset -c 1 "$BIN/bench_models" --benchmark_filter=BM_BrushTransientMessage --benchmark_repetitions=3 \
    --benchmark_report_aggregates_only=true --benchmark_format=console --benchmark_out_format=json \
    --benchmark_out="$OUT/bench_message.json" 2>&1 | grep -v WARNING
  log "the recorded manoeuvres: every message against a converged reference (about 3 minutes)"
  streams
  log "the node on the recorded manoeuvres at their pace"
  node_on_streams
  log "the recorded manoeuvres through bag_analyze's replay path, each brush model"
  replay_streams
  /usr/bin/python3 "$REPO/scripts/benchmark_report.py" --bench "$OUT/bench_message.json" --node "$OUT/node.json" \
    --streams "$OUT/streams.json" --replay-streams "$OUT/replay_streams.json" --docs "$REPO/docs" \
    --stream-targets "$(hostname), $(nproc) CPUs, library of $(git -C "$REPO" rev-parse --short HEAD)$(git -C "$REPO" diff --quiet HEAD -- src/core || echo ' with changes')"
  exit 0
fi
build bench_models model_accuracy node_benchmark contact_estimator_node bag_analyze replay_benchmark calibration_accuracy \
  work_units
log "timing (Google Benchmark, 3 repetitions, medians)"
"$BIN/bench_models" --benchmark_repetitions=3 --benchmark_report_aggregates_only=true --benchmark_min_time=0.2 \
  --benchmark_format=console --benchmark_out_format=json --benchmark_out="$OUT/bench.json" 2>&1 | grep -v WARNING
log "time per counted unit of work: random robots, every model and law, with and without tilt (about a minute)"
taskset -c 0 "$BIN/work_units" 1 60 > "$OUT/work_units.json"
log "accuracy on the operating points"
"$BIN/model_accuracy" > "$OUT/accuracy.json"
log "the transient model at held inputs over random robots, any resolution to 512 (about 5 minutes)"
for seed in 1 2; do
  "$BIN/model_accuracy" --held-transient "$seed" 600 > "$OUT/held_transient_$seed.json" || true
done
log "the parked robot's random-walk covariance against Monte Carlo over random robots (docs/uncertainty.md; about 10 minutes)"
"$BIN/model_accuracy" --parked-walk 7 60 > "$OUT/parked_walk.json"
log "the same parked after a lateral skid, the rear bristles on their bounds (docs/uncertainty.md; about 10 minutes)"
"$BIN/model_accuracy" --parked-walk 11 60 --after-skid > "$OUT/parked_walk_after_skid.json"
log "the held estimate against the noise-free truth at every parked message of 300 random robots (docs/uncertainty.md; under a minute)"
"$BIN/model_accuracy" --parked-truth 13 300 > "$OUT/parked_truth.json"
log "auto along the demo bag against the transient model at resolution 256 (about 3 minutes)"
/usr/bin/python3 "$REPO/scripts/bag_model_accuracy.py" --bag-analyze "$BIN/bag_analyze" --reference-resolution 256 \
  --before "$REPO/bench/demo_bag_before.json" --noise-fraction 0.25 --out "$OUT/bag.json"
log "the recorded manoeuvre at 100 Hz (data/manoeuvre.bag) and 1 kHz (recorded now): every message against a converged reference (about 3 minutes)"
streams
log "a hostile stream (config/hostile_scenario.yaml: nearly every bristle sliding) at 100 and 30 Hz: does the work budget keep a message within 1 ms"
for rate in 100 30; do
  record_scenario "$REPO/config/hostile_scenario.yaml" "$rate" "hostile_$rate"
done
/usr/bin/python3 "$REPO/scripts/stream_benchmark.py" --bag-analyze "$BIN/bag_analyze" --params "$REPO/config/contact_estimator.yaml" \
  --scenario "$REPO/config/hostile_scenario.yaml" --reference-resolution 128 --confirm-resolution 256 \
  --bags "$OUT/hostile_100.bag" "$OUT/hostile_30.bag" --out "$OUT/hostile.json"
log "random robots on random manoeuvres (scripts/stream_sweep.py, 24 seeded streams; about 12 minutes)"
/usr/bin/python3 "$REPO/scripts/stream_sweep.py" --bag-analyze "$BIN/bag_analyze" --dir "$OUT/sweep" --streams 24 \
  --seed 1000 --out "$OUT/sweep.json"
log "node over roscpp on loopback (the node pinned to one core), the recorded manoeuvres at their pace, and bag replay"
node_on_streams
log "bag_analyze's replay path on a generated bag of 1.1e5 odometry messages, one core (about 3 minutes)"
taskset -c 0 "$BIN/replay_benchmark" > "$OUT/replay.json"
taskset -c 0 "$BIN/replay_benchmark" --tf --models off linear steady > "$OUT/replay_tf.json"
taskset -c 0 "$BIN/replay_benchmark" --writers > "$OUT/writers.json"
log "the recorded manoeuvres through the same path, each brush model (replay_benchmark --streams)"
replay_streams
log "the calibration over 100 seeds, a 60-s run's time, runs that are not the model's, 100 runs fitting the floor too,"
log "100 random robots (about 50 minutes)"
"$BIN/calibration_accuracy" --seeds 100 --floors 100 --robots 100 > "$OUT/calibration.json"
/usr/bin/python3 "$REPO/scripts/benchmark_report.py" --bench "$OUT/bench.json" --accuracy "$OUT/accuracy.json" \
  --node "$OUT/node.json" --bag "$OUT/bag.json" --default-brush-model "$(default_brush_model)" \
  --replay "$OUT/replay.json" "$OUT/replay_tf.json" "$OUT/writers.json" --replay-streams "$OUT/replay_streams.json" --streams "$OUT/streams.json" --hostile "$OUT/hostile.json" --sweep "$OUT/sweep.json" --replay-profile "$REPO/bench/replay_profile.md" \
  --calibration "$OUT/calibration.json" --work-units "$OUT/work_units.json" \
  --held-transient "$OUT/held_transient_1.json" "$OUT/held_transient_2.json" \
  --docs "$REPO/docs"
