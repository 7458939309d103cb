#!/usr/bin/env bash
# Whole-write time of a 1 M-triangle mesh into PostGIS (tables, COPY, GiST indexes, ANALYZE,
# commit) beside the GeoPackage writer, on a throw-away server with PostgreSQL's durable
# defaults (fsync on; tools/postgis/cluster.sh --durable).
#   tools/bench/postgis_write.sh [FDRMESH] [RUNS] [durable|fast]   (default build/bin/fdrmesh, 3, durable)
# fast: the tests' server settings (fsync off, minimal WAL), for comparison.
# Prints, per output, the writer's time from the report (timings_s.write), the whole process's
# wall time and CPU time (user + system, the meshing included) and, for PostGIS, the server's CPU
# time during the run (every server process's); each run and the medians. On a shared machine
# the CPU times move less than the wall times.
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

cluster_dir="$(cat "$state/cluster")"
postmaster="$(head -n 1 "$cluster_dir/data/postmaster.pid")"
# CPU seconds the server has used so far: the postmaster, its live children and those it reaped.
server_cpu() {
  /usr/bin/python3 - "$postmaster" <<'PY'
import os, sys
pm, tick = sys.argv[1], os.sysconf("SC_CLK_TCK")
def fields(pid):  # /proc/PID/stat after the command name: state, ppid, ... utime at 11
    with open(f"/proc/{pid}/stat") as f:
        return f.read().rsplit(")", 1)[1].split()
t = sum(int(x) for x in fields(pm)[11:15])
for d in os.listdir("/proc"):
    if d.isdigit() and d != pm:
        try:
            f = fields(d)
        except OSError:
            continue
        if f[1] == pm:
            t += int(f[11]) + int(f[12])
print("%.2f" % (t / tick))
PY
}

one() {  # one run to $1; prints "write_s wall_s client_cpu_s server_cpu_s triangles"
  local t0 t1 s0 s1
  s0=$(server_cpu)
  t0=$(date +%s.%N)
  /usr/bin/time -f "%U %S" -o "$work/cpu.txt" "$fdrmesh" mesh "${input[@]}" -o "$1" "${@:2}" --report "$work/r.json"
  t1=$(date +%s.%N)
  sleep 0.3  # the server's sessions end and are counted
  s1=$(server_cpu)
  /usr/bin/python3 - "$work/r.json" "$t0" "$t1" "$work/cpu.txt" "$s0" "$s1" <<'PY'
import json, sys
r = json.load(open(sys.argv[1]))
u, s = map(float, open(sys.argv[4]).read().split()[-2:])
print("%.3f %.3f %.2f %.2f %d" % (r["timings_s"]["write"], float(sys.argv[3]) - float(sys.argv[2]), u + s,
                                  float(sys.argv[6]) - float(sys.argv[5]), r["triangles"]))
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
    read -r w wall cpu srv tri <<< "$line"
    server=""
    [ "$target" = postgis ] && server=", server CPU $srv s"
    echo "$target run $i: write $w s, whole process $wall s (CPU $cpu s$server), $tri triangles"
    echo "$line" >> "$work/$target.txt"
  done
  server=""
  [ "$target" = postgis ] && server=", server CPU $(cut -d' ' -f4 "$work/$target.txt" | median) s"
  echo "$target median: write $(cut -d' ' -f1 "$work/$target.txt" | median) s, whole process $(cut -d' ' -f2 "$work/$target.txt" | median) s (CPU $(cut -d' ' -f3 "$work/$target.txt" | median) s$server)"
done
echo "(server settings: $mode; machine: $(nproc) cores, load average $(cut -d' ' -f1-3 /proc/loadavg))"
