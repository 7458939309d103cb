#!/usr/bin/env python3
"""Module seams: every #include "m/..." in src/<module>/ must name the module itself, base, or a
module it may use according to src/modules.txt (DESIGN.md §2), transitively; a module marked
`facade` (pipeline, api) is entered but not seen through: its users include its headers only.

Usage: check_includes.py [SRC_DIR]   (exit 1 and one line per crossing include)."""
import os
import re
import sys

src = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", "src")
uses, facade = {}, set()
for line in open(os.path.join(src, "modules.txt")):
    line = line.split("#", 1)[0].strip()
    if not line:
        continue
    name, _, rest = line.partition(":")
    deps = rest.split()
    if "facade" in deps:
        facade.add(name)
        deps.remove("facade")
    uses[name.strip()] = deps


def allowed(m):
    seen, pending = set(), list(uses[m])
    while pending:
        d = pending.pop()
        if d in seen:
            continue
        seen.add(d)
        if d not in facade:
            pending.extend(uses[d])
    return seen | {m, "base"}


include = re.compile(r'^\s*#\s*include\s*"([A-Za-z_0-9]+)/')
bad = []
for m in sorted(os.listdir(src)):
    root = os.path.join(src, m)
    if not os.path.isdir(root):
        continue
    if m not in uses:
        bad.append(f"src/{m}: module missing from src/modules.txt")
        continue
    ok = allowed(m)
    for dirpath, _, files in os.walk(root):
        for fn in sorted(files):
            if not fn.endswith((".hpp", ".cpp", ".h", ".cc")):
                continue
            path = os.path.join(dirpath, fn)
            for no, text in enumerate(open(path, encoding="utf-8", errors="replace"), 1):
                hit = include.match(text)
                if hit and hit.group(1) in uses and hit.group(1) not in ok:
                    rel = os.path.relpath(path, os.path.join(src, ".."))
                    bad.append(f"{rel}:{no}: {m} -> {hit.group(1)} ({text.strip()}) crosses the module table")
for b in bad:
    print(b)
print(f"check_includes: {len(bad)} crossing include(s)")
sys.exit(1 if bad else 0)
