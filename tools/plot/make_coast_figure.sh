#!/bin/bash
# The coastal-detail figure of docs/model-ready.md: one window of a real coast meshed with the
# default coast handling and with --keep-coast (every input vertex, no feature removal), side by
# side, the input coast drawn over both meshes and the repairs marked, so the two read at a glance.
#
# Usage: tools/plot/make_coast_figure.sh FDRMESH [OUT.png]
#   FDRMESH  path to the fdrmesh binary
#   OUT.png  default docs/img/coast_detail.png
# Environment: PYTHON (default /usr/bin/python3), DATA (default ../shared/data/chesapeake_mouth
#   next to the repository), NAME (chesapeake_mouth: DATA holds NAME.gpkg, layers water and
#   open_boundary, and NAME_etopo5.tif), HMIN (150), HMAX (5000), BBOX_LONLAT
#   (-75.80,37.47,-75.68,37.57), KEEP (a folder: keep the meshes and JSON reports there), COLORS
#   (PNG palette size, 128).
set -euo pipefail

if [[ $# -lt 1 || $# -gt 2 || "$1" == "-h" || "$1" == "--help" ]]; then
  sed -n '2,13p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
FDRMESH=$1
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
OUT=${2:-$ROOT/docs/img/coast_detail.png}
PYTHON=${PYTHON:-/usr/bin/python3}
DATA=${DATA:-$ROOT/../shared/data/chesapeake_mouth}
NAME=${NAME:-chesapeake_mouth}
HMIN=${HMIN:-150}
HMAX=${HMAX:-5000}
BBOX_LONLAT=${BBOX_LONLAT:--75.80,37.47,-75.68,37.57}
COLORS=${COLORS:-128}

if [[ ! -x "$FDRMESH" ]]; then
  echo "ERROR: fdrmesh binary '$FDRMESH' not found or not executable" >&2
  exit 2
fi
SRC=$DATA/$NAME.gpkg
RASTER=$DATA/${NAME}_etopo5.tif
for f in "$SRC" "$RASTER"; do
  if [[ ! -f "$f" ]]; then
    echo "ERROR: input '$f' missing (set DATA)" >&2
    exit 3
  fi
done
WORK=${KEEP:-$(mktemp -d)}
mkdir -p "$WORK"
[[ -n "${KEEP:-}" ]] || trap 'rm -rf "$WORK"' EXIT

common=("$SRC" --layer water --open-boundary "$SRC" --open-boundary-layer open_boundary
        --raster "$RASTER" --hmin "$HMIN" --hmax "$HMAX" -q)
"$FDRMESH" mesh "${common[@]}" -o "$WORK/default.gpkg" --report "$WORK/default.json"
"$FDRMESH" mesh "${common[@]}" --keep-coast --min-angle 0 --smooth 0 -o "$WORK/keep_coast.gpkg" --report "$WORK/keep_coast.json"

"$PYTHON" "$HERE/plot_mesh.py" "$WORK/default.gpkg" --compare "$WORK/keep_coast.gpkg" \
  --bbox-lonlat "$BBOX_LONLAT" --coast "$SRC:water" --repairs \
  --title "default (coast resampled to f, sub-resolution features removed)" \
  --compare-title "--keep-coast --min-angle 0 --smooth 0 (fdrmesh 0.1)" \
  --size 6 --dpi 100 -o "$WORK/figure.png"
# A palette PNG (no dithering) keeps the picture small enough to keep in the repository.
"$PYTHON" - "$WORK/figure.png" "$OUT" "$COLORS" <<'EOF'
import sys
from PIL import Image
src, dst, n = sys.argv[1], sys.argv[2], int(sys.argv[3])
im = Image.open(src).convert("RGB")
im.quantize(colors=n, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(dst + ".tmp.png", optimize=True)
EOF
mv "$OUT.tmp.png" "$OUT"

# The figures of both runs beside the picture (model readiness from the JSON reports).
"$PYTHON" - "$WORK/default.json" "$WORK/keep_coast.json" <<'EOF'
import json, sys
print("| run | triangles | min angle | < 30° | mean quality | shortest edge / hmin | coast p99 in→mesh / mesh→in (hmin) | pieces mesh/input | time step (s) |")
print("|---|---|---|---|---|---|---|---|---|")
for name, path in zip(("default", "--keep-coast --min-angle 0 --smooth 0"), sys.argv[1:]):
    j = json.load(open(path)); m = j["model_ready"]; d = m["coast_deviation"]
    print(f"| {name} | {j['triangles']} | {j['min_angle_deg']:.2f}° | {m['triangles_below_30_deg_pct']:.2f} % | "
          f"{m['mean_quality']:.3f} | {m['shortest_edge_over_hmin']:.3f} | "
          f"{d['input_to_mesh']['p99_over_hmin']:.2f} / {d['mesh_to_input']['p99_over_hmin']:.2f} | "
          f"{m['pieces']['mesh']}/{m['pieces']['input']} | {m['time_step']['dt_s']:.2f} |")
EOF
echo "wrote $OUT ($(stat -c %s "$OUT") bytes)"
