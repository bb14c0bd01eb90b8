#!/usr/bin/env bash
# A recorded bag to an analysis and figures, on a fresh Debian 12 machine or an existing build:
#   ./scripts/analyze_bag.sh BAG [OUT_DIR] [bag_analyze options...]
# installs and builds what is missing (scripts/lib.sh), runs bag_analyze (output bag, CSV and summary), then
# scripts/plot_analysis.py (PNG figures). OUT_DIR defaults to ./<bag name>_analysis.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib.sh"

if [ $# -lt 1 ]; then
  echo "usage: $0 BAG [OUT_DIR] [bag_analyze options...]" >&2
  exit 2
fi
BAG="$(realpath "$1")"
NAME="$(basename "${BAG%.bag}")"
OUT="$(realpath -m "${2:-${NAME}_analysis}")"
shift $(( $# >= 2 ? 2 : 1 ))
install_deps
build bag_analyze > "$WS.analyze_build.log" 2>&1 || { tail -30 "$WS.analyze_build.log"; exit 1; }
mkdir -p "$OUT"
"$WS/devel/lib/$PKG/bag_analyze" --input "$BAG" --output "$OUT/${NAME}_analysis.bag" --csv "$OUT/$NAME.csv" "$@"
/usr/bin/python3 "$REPO/scripts/plot_analysis.py" "$OUT/$NAME.csv" --output "$OUT"
