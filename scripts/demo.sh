#!/usr/bin/env bash
# README command 1: install, build, and run the main job: the contact estimator node on the bundled
# spherical-robot manoeuvre (launch/demo.launch: accelerate, cruise, turn, brake with slip, spin in place,
# with sensor noise), headless; it prints a summary per phase and writes every estimate to a CSV. Then the
# models' characteristic figures: Figs. 2-3 of Poeschel et al. and Fig. 4 of Romano et al., and the
# bundled recorded run (data/demo.bag) through the offline analyser and its figures.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

OUT="${1:-${SCE_OUTPUT:-$WS/output}}"
install_deps
build
mkdir -p "$OUT"
log "contact estimator on the demo manoeuvre (roslaunch sphere_contact_estimator demo.launch)"
rm -f "$OUT/estimates.csv"
roslaunch sphere_contact_estimator demo.launch output_csv:="$OUT/estimates.csv" 2>&1 \
  | grep -vE '^( \* /|\s*$|\.\.\. |started roslaunch server|SUMMARY|=+$|PARAMETERS|NODES|  /|    |auto-starting|process\[|setting /run_id|ROS_MASTER_URI|started core service|\[.*\] killing on exit|shutting down processing monitor|log file:|Initiating shutdown|done$)' || true
rows=$(($(wc -l < "$OUT/estimates.csv" 2>/dev/null || echo 1) - 1))
if [ "$rows" -le 0 ]; then
  log "the demo produced no estimates"
  exit 1
fi
log "$rows estimates in $OUT/estimates.csv"

log "rolling-resistance sweep and plots -> $OUT"
/usr/bin/python3 "$REPO/scripts/plot_rolling_resistance.py" --output "$OUT" \
  --config "$REPO/config/rubber_cylinder_paper.yaml"
log "brush characteristics of a spherical wheel (Fig. 4 of Romano et al.) -> $OUT"
/usr/bin/python3 "$REPO/scripts/plot_brush_characteristics.py" --output "$OUT"
log "the recorded demo run (data/demo.bag) through bag_analyze and plot_analysis.py -> $OUT/demo_bag"
mkdir -p "$OUT/demo_bag"
"$WS/devel/lib/$PKG/bag_analyze" --input "$REPO/data/demo.bag" --output "$OUT/demo_bag/demo_analysis.bag" \
  --csv "$OUT/demo_bag/demo.csv" --progress never
/usr/bin/python3 "$REPO/scripts/plot_analysis.py" "$OUT/demo_bag/demo.csv" --output "$OUT/demo_bag"
