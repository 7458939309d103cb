#!/usr/bin/env python3
"""Python overhead of fdrmesh.triangulate over the C++ API at about 1M triangles.

Usage: PYTHONPATH=build/python /usr/bin/python3 tools/bench/python/bench_python.py [build/tools/bench/api/bench_api] [SPACING]
Prints the best of 3 wall times of the same meshing through C++ (bench_api) and Python, and the
overhead (target <= 10 %). Not a test: timing is never asserted."""
import os
import subprocess
import sys
import time

import numpy as np

import fdrmesh

exe = sys.argv[1] if len(sys.argv) > 1 else os.path.join("build", "tools", "bench", "api", "bench_api")
spacing = sys.argv[2] if len(sys.argv) > 2 else "0.0015"
out = subprocess.run([exe, spacing, "3"], check=True, capture_output=True, text=True).stdout
cpp = dict(kv.split("=") for kv in out.split())
v = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
s = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])
best, m = 1e300, None
for _ in range(3):
    m = None
    t0 = time.perf_counter()
    m = fdrmesh.triangulate(v, s, spacing=spacing)
    tri = m.triangles  # the arrays are views: no copy on return
    best = min(best, time.perf_counter() - t0)
cpp_s = float(cpp["cpp_s"])
print(f"triangles: C++ {cpp['triangles']}, Python {len(tri)}")
print(f"C++ fdr::triangulate {cpp_s:.3f} s, Python fdrmesh.triangulate {best:.3f} s "
      f"(refine {m.report['timings_s']['refine']:.3f} s): overhead {100 * (best / cpp_s - 1):+.1f} %")
