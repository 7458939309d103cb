#!/bin/bash
# Reproduce the FDR paper's Figures 2-3: mesh [0,10]^2 for f1/f2 at several B, draw PNGs and a table.
#
# Usage: tools/plot/paper_figures.sh FDRMESH [OUTDIR]
#   FDRMESH  path to the fdrmesh binary
#   OUTDIR   output folder (default ./paper_figures); receives per case <case>.node/.ele,
#            <case>.json (quality report), <case>.png (Figure 2), hist_<f>.png (Figure 3), table.md
# Environment: PYTHON (default /usr/bin/python3), FDR_PAPER_BOUNDS (default "1 0.5 sqrt2").
set -euo pipefail

if [[ $# -lt 1 || $# -gt 2 || "$1" == "-h" || "$1" == "--help" ]]; then
  sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'
  exit 2
fi
FDRMESH=$1
OUT=${2:-paper_figures}
PYTHON=${PYTHON:-/usr/bin/python3}
HERE=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
POLY=$ROOT/testdata/poly/square10.poly
BOUNDS=${FDR_PAPER_BOUNDS:-"1 0.5 sqrt2"}

if [[ ! -x "$FDRMESH" ]]; then
  echo "ERROR: fdrmesh binary '$FDRMESH' not found or not executable" >&2
  exit 2
fi
if [[ ! -f "$POLY" ]]; then
  echo "ERROR: input '$POLY' missing" >&2
  exit 3
fi
mkdir -p "$OUT"

cases=()
for f in f1 f2; do
  nodes=()
  labels=()
  for b in $BOUNDS; do
    case $b in
      sqrt2) bval=1.4142135623730951 ;;
      *) bval=$b ;;
    esac
    name=${f}_B${b}
    echo "== $name: fdrmesh mesh square10.poly --spacing paper-$f --bound $bval"
    start=$(date +%s%N)
    "$FDRMESH" mesh "$POLY" -o "$OUT/$name.node" --spacing "paper-$f" --bound "$bval" \
      --report "$OUT/$name.json" -q
    end=$(date +%s%N)
    echo "   done in $(( (end - start) / 1000000 )) ms"
    for need in "$OUT/$name.node" "$OUT/$name.ele" "$OUT/$name.json"; do
      if [[ ! -s "$need" ]]; then
        echo "ERROR: fdrmesh did not write $need" >&2
        exit 8
      fi
    done
    "$PYTHON" "$HERE/plot_mesh.py" "$OUT/$name.node" -o "$OUT/$name.png" --color r_over_f \
      --spacing "paper-$f" --bound "$bval" --title "paper-$f, B = $b"
    nodes+=("$OUT/$name.node")
    labels+=("B=$b")
    cases+=("$name $f $bval")
  done
  "$PYTHON" "$HERE/plot_histograms.py" "${nodes[@]}" -o "$OUT/hist_$f.png" --spacing "paper-$f" \
    --labels "$(IFS=,; echo "${labels[*]}")" --title "paper-$f: angle quality and spacing conformity"
done

# Markdown table from the quality reports (the JSON schema of fdr::quality::write_json).
"$PYTHON" - "$OUT" "${cases[@]}" > "$OUT/table.md" <<'PY'
import json, os, sys
out = sys.argv[1]
def g(v, fmt):
    return "n/a" if v is None else fmt.format(v)
print("| case | B | N vertices | triangles | θmin (°) | θmax (°) | max R/f(c) | conformity min / mean |")
print("|---|---|---|---|---|---|---|---|")
for c in sys.argv[2:]:
    name, f, b = c.split()
    r = json.load(open(os.path.join(out, name + ".json")))
    conf = r.get("conformity") or {}
    print(f"| paper-{f} | {float(b):.4g} | {r['vertices']} | {r['triangles']} | "
          f"{g(r.get('min_angle_deg'), '{:.2f}')} | {g(r.get('max_angle_deg'), '{:.2f}')} | "
          f"{g(r.get('max_R_over_f'), '{:.3f}')} | "
          f"{g(conf.get('min'), '{:.3f}')} / {g(conf.get('mean'), '{:.3f}')} |")
PY
echo "== wrote $OUT/table.md"
cat "$OUT/table.md"
