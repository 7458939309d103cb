#!/usr/bin/env bash
# Builds fdrmesh-qgis-<version>.zip (folder fdrmesh/ at the zip root, as the QGIS plugin manager expects).
# Usage: tools/qgis/build_plugin_zip.sh OUTPUT_DIR [MDAL_DRIVER]   -> prints the path of the zip
# MDAL_DRIVER (build/lib/fdrmesh/mdal/libmdal_fdrmesh.so) goes to fdrmesh/mdal/, where the plugin
# looks for it first (plugins/qgis/fdrmesh/mdal_driver.py).
set -euo pipefail
if [ $# -lt 1 ] || [ $# -gt 2 ]; then
  echo "usage: $0 OUTPUT_DIR [MDAL_DRIVER]" >&2
  exit 2
fi
root="$(cd "$(dirname "$0")/../.." && pwd)"
src="$root/plugins/qgis/fdrmesh"
version="$(sed -n 's/^version=\s*//p' "$src/metadata.txt" | head -n1 | tr -d '[:space:]')"
[ -n "$version" ] || { echo "no version= in $src/metadata.txt" >&2; exit 1; }
mkdir -p "$1"
out="$(cd "$1" && pwd)/fdrmesh-qgis-$version.zip"
stage="$(mktemp -d)"
trap 'rm -rf "$stage"' EXIT
mkdir "$stage/fdrmesh"
# Only the plugin's own files: no caches, no editor leftovers.
for f in "$src"/*.py "$src"/metadata.txt "$src"/*.md "$src"/*.png "$src"/*.svg; do
  [ -e "$f" ] && cp "$f" "$stage/fdrmesh/"
done
if [ $# -eq 2 ]; then
  mkdir "$stage/fdrmesh/mdal"
  cp "$2" "$stage/fdrmesh/mdal/libmdal_fdrmesh.so"
fi
[ -f "$root/plugins/qgis/README.md" ] && cp "$root/plugins/qgis/README.md" "$stage/fdrmesh/README.md"
rm -f "$out"
# Python's zipfile keeps this independent of the zip package being installed.
(cd "$stage" && python3 - "$out" <<'PY'
import os, sys, zipfile
with zipfile.ZipFile(sys.argv[1], "w", zipfile.ZIP_DEFLATED) as z:
    for dirpath, _dirs, files in os.walk("fdrmesh"):
        for name in sorted(files):
            z.write(os.path.join(dirpath, name))
PY
)
echo "$out"
