#!/usr/bin/env bash
# README command 1: install, build, and run the main job on the bundled demo scenario.
# Until the estimator node exists, the main job is the rolling-resistance sweep of the paper's rubber
# surface (config/rubber_cylinder_paper.yaml) and its plots, Figs. 2 and 3 of Poeschel et al., and the
# steady-state brush characteristics of Fig. 4 of Romano et al.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

OUT="${1:-${SCE_OUTPUT:-$WS/output}}"
install_deps
build
mkdir -p "$OUT"
log "rolling-resistance sweep and plots -> $OUT"
/usr/bin/python3 "$REPO/scripts/plot_rolling_resistance.py" --output "$OUT" \
  --config "$REPO/config/rubber_cylinder_paper.yaml"
log "brush characteristics of a spherical wheel (Fig. 4 of Romano et al.) -> $OUT"
/usr/bin/python3 "$REPO/scripts/plot_brush_characteristics.py" --output "$OUT"
