#!/usr/bin/env bash
# Whole-write time of a 1 M-triangle mesh into PostGIS (tables, COPY, GiST indexes, ANALYZE,
# commit) beside the GeoPackage writer, on a throw-away server with PostgreSQL's durable
# defaults (fsync on; tools/postgis/cluster.sh --durable).
#   tools/bench/postgis_write.sh [FDRMESH] [RUNS] [durable|fast]   (default build/bin/fdrmesh, 3, durable)
# fast: the tests' server settings (fsync off, minimal WAL), for comparison.
# Prints, per output, the writer's time from the report (timings_s.write) and the whole
# process's wall time, each run and the median.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
fdrmesh="${1:-$root/build/bin/fdrmesh}"
runs="${2:-3}"
mode="${3:-durable}"
work="$(mktemp -d "${TMPDIR:-/tmp}/fdrbench.XXXXXX")"
state="$work/pg"
trap 'bash "$root/tools/postgis/cluster.sh" stop "$state" > /dev/null 2>&1 || true; rm -rf "$work"' EXIT
if [ "$mode" = fast ]; then
  bash "$root/tools/postgis/cluster.sh" start "$state"
else
  bash "$root/tools/postgis/cluster.sh" start "$state" --durable
fi
conn="$(cat "$state/conninfo")"
case "$conn" in SKIP:*) echo "no PostgreSQL server: $conn" >&2; exit 77 ;; esac
input=("$root/testdata/poly/square10.poly" --spacing "0.025*paper-f1" -q)

one() {  # one run to $1; prints "write_s wall_s triangles"
  local t0 t1
  t0=$(date +%s.%N)
  "$fdrmesh" mesh "${input[@]}" -o "$1" "${@:2}" --report "$work/r.json"
  t1=$(date +%s.%N)
  /usr/bin/python3 - "$work/r.json" "$t0" "$t1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
print("%.3f %.3f %d" % (r["timings_s"]["write"], float(sys.argv[3]) - float(sys.argv[2]), r["triangles"]))
PY
}

median() { sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }

for target in gpkg postgis; do
  : > "$work/$target.txt"
  for i in $(seq "$runs"); do
    if [ "$target" = gpkg ]; then
      line="$(one "$work/x.gpkg")"
      rm -f "$work/x.gpkg"
    else
      line="$(one "$conn" --overwrite)"
    fi
    echo "$target run $i: write $(echo "$line" | cut -d' ' -f1) s, whole process $(echo "$line" | cut -d' ' -f2) s, $(echo "$line" | cut -d' ' -f3) triangles"
    echo "$line" >> "$work/$target.txt"
  done
  echo "$target median: write $(cut -d' ' -f1 "$work/$target.txt" | median) s, whole process $(cut -d' ' -f2 "$work/$target.txt" | median) s"
done
echo "(server settings: $mode; machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg))"
