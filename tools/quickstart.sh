#!/usr/bin/env bash
# README's first command: installs what is missing, builds fdrmesh, meshes the bundled real
# example (Chesapeake Bay mouth: GSHHG coast + NOAA ETOPO5 bathymetry) and writes a GeoPackage,
# an SMS 2DM, an ADCIRC fort.14, a UGRID NetCDF, a JSON quality report and PNG pictures to out/.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
bash "$root/tools/build.sh"
out="$root/out"
mkdir -p "$out"
td="$root/testdata/chesapeake"
"$root/build/bin/fdrmesh" mesh "$td/chesapeake_mouth_water.geojson" \
  --open-boundary "$td/chesapeake_mouth_open_boundary.geojson" \
  --raster "$td/chesapeake_mouth_etopo5.tif" --hmin 150 --dist-grade 0.08 \
  -o "$out/chesapeake.gpkg" -o "$out/chesapeake.2dm" -o "$out/chesapeake.14" -o "$out/chesapeake.nc" \
  --report "$out/chesapeake.json" --check
export MPLBACKEND=Agg
/usr/bin/python3 "$root/tools/plot/plot_mesh.py" "$out/chesapeake.gpkg" --color r_over_f --bound 1 \
  -o "$out/chesapeake_r_over_f.png"
/usr/bin/python3 "$root/tools/plot/plot_mesh.py" "$out/chesapeake.gpkg" --color depth -o "$out/chesapeake_depth.png"
/usr/bin/python3 "$root/tools/plot/plot_histograms.py" "$out/chesapeake.gpkg" -o "$out/chesapeake_histograms.png"
echo "quickstart: results in $out"
ls -l "$out"
