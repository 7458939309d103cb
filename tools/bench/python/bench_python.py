#!/usr/bin/env python3
"""Python overhead of fdrmesh.triangulate over the C++ API at about 1M triangles.

Usage: PYTHONPATH=build/python /usr/bin/python3 tools/bench/python/bench_python.py [build/tools/bench/api/bench_api] [SPACING]
Prints the best of 5 wall and CPU times of the same meshing through C++ (bench_api) and Python, and the
overhead (target <= 10 %). Not a test: timing is never asserted."""
import os
import subprocess
import sys
import time

import numpy as np

import fdrmesh

exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join("build", "tools", "bench", "api", "bench_api")
spacing = sys.argv[2] if len(sys.argv) > 2 else "0.0011"
REPEATS = 5
out = subprocess.run([exe, spacing, str(REPEATS)], check=True, capture_output=True, text=True).stdout
cpp = dict(kv.split("=") for kv in out.split())
v = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
s = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
best, best_cpu, m = 1e300, 1e300, None
for _ in range(REPEATS):
    m = None
    t0, c0 = time.perf_counter(), time.process_time()
    m = fdrmesh.triangulate(v, s, spacing=spacing)
    tri, xy = m.triangles, m.vertices  # views into the C++ mesh: no copy on return
    best = min(best, time.perf_counter() - t0)
    best_cpu = min(best_cpu, time.process_time() - c0)
cpp_s, cpp_cpu = float(cpp["cpp_s"]), float(cpp["cpp_cpu_s"])
print(f"triangles: C++ {cpp['triangles']}, Python {len(tri)} (best of {REPEATS})")
print(f"wall: C++ fdr::triangulate {cpp_s:.3f} s, Python fdrmesh.triangulate {best:.3f} s: "
      f"overhead {100 * (best / cpp_s - 1):+.1f} %")
print(f"CPU:  C++ {cpp_cpu:.3f} s, Python {best_cpu:.3f} s (refine {m.report['timings_s']['refine']:.3f} s wall): "
      f"overhead {100 * (best_cpu / cpp_cpu - 1):+.1f} %")
