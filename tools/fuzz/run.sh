#!/usr/bin/env bash
# Builds the libFuzzer targets (clang, ASan + UBSan, separate build dir) and runs each for
# SECONDS, one at a time, niced, with seed corpora from testdata. Usage:
#   tools/fuzz/run.sh SECONDS [TARGET...]     (targets: poly_reader pslg_mesh expression ogr_vector)
# Environment: FUZZ_BUILD (default build-fuzz), FUZZ_OUT (default build-fuzz/fuzz-out).
# Needs clang-14, libfuzzer-14-dev, libclang-rt-14-dev (tools/install-deps.sh --fuzz).
# Each run's libFuzzer status lines (execs, cov, ft, crashes) go to FUZZ_OUT/<target>.log; crashes to
# FUZZ_OUT/<target>/crashes/. Exit status 1 if any target found a crash.
set -euo pipefail
secs=${1:?usage: run.sh SECONDS [TARGET...]}
shift || true
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${FUZZ_BUILD:-$root/build-fuzz}
out=${FUZZ_OUT:-$build/fuzz-out}
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(poly_reader pslg_mesh expression ogr_vector)

if [ ! -f "$build/build.ninja" ]; then
  CC=clang-14 CXX=clang++-14 cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DFDR_FUZZ=ON -DFDR_BUILD_TESTS=OFF -DFDR_BUILD_BENCH=OFF >/dev/null
fi
nice -n 19 cmake --build "$build" -j2 --target $(printf 'fuzz_%s ' "${targets[@]}")

seed() {  # seed corpus of a target
  local t=$1 dir=$out/$t/seeds
  mkdir -p "$dir" "$out/$t/corpus" "$out/$t/crashes"
  case $t in
    poly_reader|pslg_mesh)
      find "$root/testdata" -name '*.poly' -size -8k -exec cp {} "$dir/" \;
      [ -d "$root/testdata/regress" ] && find "$root/testdata/regress" -name 'fuzz_*' -exec cp {} "$dir/" \; ;;
    expression)
      printf '%s' '0.025*paper-f1' >"$dir/s1"; printf '%s' 'min(paper-f1, 0.3)' >"$dir/s2"
      printf '%s' '1 + 0.1*sqrt(x^2+y^2)' >"$dir/s3"; printf '%s' 'max(abs(sin(x)), exp(-y)) / 2' >"$dir/s4"
      printf '%s' '250' >"$dir/s5"; printf '%s' 'paper-f2 * 2' >"$dir/s6" ;;
    ogr_vector)
      find "$root/testdata" -name '*.geojson' -size -16k -exec cp {} "$dir/" \;
      local fc='{"type":"FeatureCollection","features":['
      printf '%s' "$fc"'{"type":"Feature","id":1,"properties":{},"geometry":{"type":"Polygon","coordinates":[[[-76.1,37.0],[-75.9,37.0],[-75.9,37.2],[-76.1,37.2],[-76.1,37.0]],[[-76.0,37.05],[-75.95,37.05],[-75.95,37.1],[-76.0,37.05]]]}}]}' >"$dir/square_hole.geojson"
      printf '%s' "$fc"'{"type":"Feature","id":7,"properties":{},"geometry":{"type":"MultiPolygon","coordinates":[[[[10,50],[10.1,50],[10.1,50.1],[10,50.1],[10,50]]],[[[10.05,50.02],[10.2,50.02],[10.2,50.05],[10.05,50.05],[10.05,50.02]]]]}}]}' >"$dir/overlap_multi.geojson"
      printf '%s' "$fc"'{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[[0,0],[1,1],[1,0],[0,1],[0,0]]]}}]}' >"$dir/bowtie.geojson" ;;
  esac
  if [ "$t" = pslg_mesh ]; then  # binary lattice seeds: a crossing star, overlaps, a hull point set
    python3 - "$dir" <<'PY'
import sys, struct, os
d = sys.argv[1]
def w(name, flags, pts, segs, holes=(), fine=6):
    b = bytes([ord('B'), flags, len(pts)]) + b''.join(struct.pack('bb', x, y) for x, y in pts)
    b += bytes([len(segs)]) + b''.join(bytes([a, c]) for a, c in segs)
    b += bytes([len(holes)]) + b''.join(struct.pack('bb', x, y) for x, y in holes) + bytes([fine])
    open(os.path.join(d, name), 'wb').write(b)
sq = [(0,0),(10,0),(10,10),(0,10)]
w('star', 4, sq + [(5,0),(5,10),(0,5),(10,5)], [(0,1),(1,2),(2,3),(3,0),(4,5),(6,7),(0,2),(1,3)])
w('overlap', 2|16, sq + [(2,0),(8,0),(5,0)], [(0,1),(1,2),(2,3),(3,0),(4,5),(6,1),(0,6)])
w('hull', 1, sq + [(3,3),(7,4),(4,8)], [(4,5),(5,6)])
w('hole', 0, sq + [(3,3),(7,3),(7,7),(3,7)], [(0,1),(1,2),(2,3),(3,0),(4,5),(5,6),(6,7),(7,4)], [(5,5)])
PY
  fi
}

status=0
for t in "${targets[@]}"; do
  seed "$t"
  bin=$build/tools/fuzz/fuzz_$t
  log=$out/$t.log
  echo "== $t: $secs s" >&2
  set +e
  cd "$out"  # fork mode writes fuzz-N.log into the working directory
  # -fork=1 (one worker process at a time): a crash is saved and fuzzing goes on, so one run
  # finds every crash; the status lines give execs, cov, ft and oom/timeout/crash counts.
  nice -n 19 "$bin" -max_total_time="$secs" -fork=1 -ignore_crashes=1 -ignore_timeouts=1 -ignore_ooms=1 \
    -print_final_stats=1 -timeout=20 -rss_limit_mb=2048 -max_len=4096 -artifact_prefix="$out/$t/crashes/" \
    "$out/$t/corpus" "$out/$t/seeds" >"$log" 2>&1
  rc=$?
  cd - >/dev/null
  set -e
  grep -E '^#[0-9]+: cov:' "$log" | tail -1 >&2 || true
  n=$(find "$out/$t/crashes" -type f | wc -l)
  if [ $rc -ne 0 ] || [ "$n" -gt 0 ]; then echo "!! $t: exit $rc, $n crash files (see $log, $out/$t/crashes)" >&2; status=1; fi
done
exit $status
