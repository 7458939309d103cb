#!/usr/bin/env python3
"""Write docs/benchmarks.md from saved outputs of the tools/bench programs (docs/bench/*.txt).

Usage: make_benchmarks_md.py [--bench-dir DIR] [OUTPUT.md]     write the page (default: docs/benchmarks.md)
       make_benchmarks_md.py [--bench-dir DIR] --check OUTPUT.md   exit 1 when OUTPUT.md is stale

Each saved output starts with header lines `# command: ...`, `# machine: ...`, `# date: ...` (and
optionally `# source: ...`), followed by what the program printed. bench_fdr and bench_gis outputs
become tables; any other output is shown as printed. A figure only means something with the command,
machine and date it came from, so every table carries them.
"""
import glob
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "docs"))
from generated_page import write_or_check  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
HEADER_KEYS = ("command", "machine", "date", "source")


def read_saved(path):
    """(header dict, body lines) of one saved output; the header needs command, machine and date."""
    head, body = {}, []
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            line = line.rstrip("\n")
            m = re.match(r"#\s*(\w+):\s*(.*)", line)
            if m and not body and m.group(1) in HEADER_KEYS:
                head[m.group(1)] = m.group(2).strip()
            elif line.strip():
                body.append(line)
    missing = [k for k in HEADER_KEYS[:3] if k not in head]
    if missing:
        raise ValueError(f"{path}: header lacks {', '.join('# ' + k + ':' for k in missing)}")
    return head, body


def kind_of(body):
    first = body[0] if body else ""
    if first.startswith("FDR benchmark:"):
        return "fdr"
    if first.startswith("bench_gis:"):
        return "gis"
    if first.startswith("Terrain benchmark:"):
        return "terrain"
    return "verbatim"


FDR_ROW = re.compile(r"^(\S+)\s+k=(\S+)\s+refine\s+(\S+) s\s+whole\s+(\S+) s \(\s*(\S+)x\)\s+(\d+) tri\s+(\S+) "
                     r"tri/int\(1/f\^2\)\s+(\S+) tri/s\s+peak\s+(\S+) MiB\s+(\S+) B/tri\s+min angle\s+(\S+)")
TOOL_NAMES = {"fdrmesh": "**fdrmesh** (in-process)", "fdrmesh-cli": "**fdrmesh-cli** (the command line)",
              "cgal": "CGAL Mesh_2, largest R/f first", "gmsh-del": "Gmsh (Delaunay)", "gmsh-front": "Gmsh (Frontal-Delaunay)"}


def dash(v):
    return "—" if v.strip("-x") == "" else v


def thousands(n):
    return f"{int(n):,}".replace(",", " ")


def fdr_rows(body):
    rows = []
    for line in body:
        m = FDR_ROW.match(line)
        if m:
            tool, k, refine, whole, ratio, tris, tri_int, _, peak, btri, amin = m.groups()
            rows.append(f"| {TOOL_NAMES.get(tool, tool)} | {k} | {thousands(tris)} | {tri_int} | {refine} | "
                        f"{dash(whole)} | {dash(ratio)} | {peak} | {float(btri):.0f} | {float(amin):.1f}° |")
    return rows


def code_then_note(command):
    """`command` (note): the words before a parenthesised note are the command to type."""
    cmd, sep, note = command.partition(" (")
    return f"`{cmd}`" + (f" ({note}" if sep else "")


def provenance(saved):
    """Command, machine and date lines under a table (each value once when they agree)."""
    out = []
    for key, title in (("command", "Command"), ("machine", "Machine"), ("date", "Date"), ("source", "Source")):
        values = []
        for head, _ in saved:
            if head.get(key) and head[key] not in values:
                values.append(head[key])
        if not values:
            continue
        if key == "command":
            out += [f"* {title}{'s' if len(values) > 1 else ''}:"] + [f"  * {code_then_note(v)}" for v in values]
        else:
            out.append(f"* {title}: " + "; ".join(values))
    return out


def fdr_section(saved):
    out = ["| tool | k | triangles | tri/∫ | refine s | whole s | whole/refine | peak MiB | bytes/triangle | min angle |",
           "|---|---|---|---|---|---|---|---|---|---|"]
    for _, body in saved:
        out += fdr_rows(body)
    return out + [""] + provenance(saved) + [""]


GIS_STAGE = re.compile(r"^\s+(\w+)\s+([\d.]+|-)\s+([\d.]+|-)\s+(\d+|-)\s*$")
GIS_WHOLE = re.compile(r"whole process: wall (\S+) s \((\S+)x refine\), peak RSS \(VmHWM\) (\S+) MiB = (\S+) "
                       r"B/triangle; outputs (.*)$")
GIS_CPU = re.compile(r"process CPU (\S+) s \(user (\S+) \+ system (\S+)\)")


def gis_section(saved):
    runs, stages = [], []
    for head, body in saved:
        run = {"stages": {}, "triangles": ""}
        for line in body:
            m = re.search(r"triangles (\d+)", line)
            if m and not run["triangles"]:
                run["triangles"] = thousands(m.group(1))
            m = GIS_STAGE.match(line)
            if m and m.group(1) not in ("stage", "stages"):
                run["stages"][m.group(1)] = m.group(2)
                if m.group(1) not in stages:
                    stages.append(m.group(1))
            m = GIS_WHOLE.search(line)
            if m:
                run.update(wall=m.group(1), ratio=m.group(2), peak=m.group(3), btri=m.group(4), outputs=m.group(5))
            m = GIS_CPU.search(line)
            if m:
                run.update(cpu=m.group(1), system=m.group(3))
        runs.append(run)
    out = ["| outputs | triangles | " + " | ".join(stages) + " | whole process s | whole/refine | peak MiB | "
           "bytes/triangle | process CPU s (system) |", "|---" * (len(stages) + 7) + "|"]
    for r in runs:
        cells = [r.get("outputs", "?"), r["triangles"]] + [r["stages"].get(s, "—") for s in stages]
        cells += [r.get("wall", "—"), r.get("ratio", "—"), r.get("peak", "—"), r.get("btri", "—"),
                  f"{r.get('cpu', '—')} ({r.get('system', '—')})"]
        out.append("| " + " | ".join(cells) + " |")
    return out + ["", "Stage columns are seconds; a stage the saved output does not list is left out.", ""] + \
        provenance(saved) + [""]


INTRO = """\
# Benchmarks

Every table below is generated by `tools/bench/make_benchmarks_md.py` from the saved output of a
`tools/bench` program in `docs/bench/` (one text file per command, starting with the command, the
machine and the date). To refresh a table, run the command on an idle machine, save its output with
the same three header lines, and regenerate this page:

```sh
python3 tools/bench/make_benchmarks_md.py        # writes docs/benchmarks.md
```

The CTest `docs_benchmarks` fails when this page differs from what the saved outputs give.
Times on a shared 2-core virtual machine drift by 10–25 % from minute to minute: compare rows of one
table, not figures of different days.
"""

FDR_INTRO = """\
## Refinement on the square (`bench_fdr`)

`build/tools/bench/fdr/bench_fdr [k ...]` meshes [0,10]² with f = k·paper-f1 and B = 1, each tool in a
process of its own: fdrmesh's refiner in-process, the real command line (`fdrmesh mesh square10.poly
--spacing K*paper-f1 -q --report R.json`: read, CDT, refinement, quality report, JSON; no mesh file),
CGAL's `Delaunay_mesher_2` with the same R/f(c) test refining the largest R/f(c) first, and Gmsh with a
MathEval size field calibrated to fdrmesh's triangle count (`--no-gmsh`, `--no-cgal`, `--only` choose).
**refine** is the meshing time (the command line: the report's `timings_s.refine`), **whole** the wall
clock of the process from start to exit, **peak** its VmHWM (bytes/triangle = peak / triangles), **tri/∫**
the triangles per unit of ∫ 1/f² dA (fewer is a leaner mesh at the same bound).
"""

GIS_INTRO = """\
## A GIS run end to end (`bench_gis`)

`build/tools/bench/gis/bench_gis [--formats gpkg,2dm,14] [--no-write]` meshes the bundled Gulf of
Maine extract (GSHHG coast, ETOPO5; hmin 120 m, distance grade 0.04; about 1 M triangles) through
`pipeline::run`, with every model-ready default, and prints each stage's time, peak and page faults,
then the whole process's wall clock, peak and CPU time (user + system over every thread: how much of
the second core the run used).
"""

TERRAIN_INTRO = """\
## Terrain volumes from GIS layers against the cube

`tools/bench/tet/bench_terrain.py --size large` runs two whole `fdrmesh` processes at about a million
tetrahedra each: the terrain volume of [terrain3d.md](terrain3d.md) on the Luxembourg DEM under its
border polygon (base −500 m, no horizons) and `bench_tet.py`'s cube. The target of the terrain
work is a GIS run within 2× the cube's time; the last line gives the ratio of the user+sys CPU
times and of the times per tetrahedron.
"""

VERBATIM_INTRO = """\
## Other saved outputs

Shown as the programs printed them.
"""

AB_SECTION = """\
## Comparing two builds: `tools/bench/ab.py`

A change is judged against the previous build on the same machine, never against a figure of another
day:

```sh
tools/bench/ab.py -n 10 -- OLD/build/bin/fdrmesh mesh ARGS... ::: build/bin/fdrmesh mesh ARGS...
```

* **Interleaved rounds.** The two commands run in turns A B, B A, A B, ...: neither always runs first,
  and a drift of the host's speed during the comparison hits both alike.
* **Medians.** For each command the script prints the median and the range of the wall time, the user
  and system CPU time and the peak RSS (the child's `ru_maxrss`); then the median of the per-round
  differences B − A and in how many rounds B was faster. One pair of runs says little; the median of
  ten does.
* **The 3 % rule.** A change that is not meant to be faster (a refactoring, a new check, a new
  output) must keep the whole process's wall time and its peak memory within 3 % of the previous
  build's: the median of the per-round differences B − A, over A's median, and B's median peak over
  A's. Anything smaller than 3 % is within the host's noise; anything larger is a cost to explain. A
  change meant to be faster shows it in the median difference and in most rounds.
* `--env-a K=V` / `--env-b K=V` set a variable for one side only (for example `FDR_THREADS=1` against
  2); `--label-a` / `--label-b` name the sides. The CTest `bench_ab` checks the script itself.

## The other bench programs

| program | what it measures |
|---|---|
| `build/tools/bench/gis/bench_sizing [--region DIR/NAME] [--hmin M]` | each step of the spacing stage (distance to shore, rules, gradient limiter) on a region's grid, in M cells/s |
| `build/tools/bench/api/bench_report [k] [repeats]` | the quality report alone on the square's refined mesh (best and median wall and CPU time) |
| `build/tools/bench/api/bench_api SPACING [repeats]` with `tools/bench/python/bench_python.py` | `fdr::triangulate` from C++ and `fdrmesh.triangulate` from Python on the unit square at about 1 M triangles: the Python module's overhead (target ≤ 10 %) |
| `build/tools/bench/limiter/bench_limiter [alpha] [n ...]` | the gradient limiter on random n × n grids and `distance_to_shore` against 10⁵ segments |

Save any of their outputs in `docs/bench/` with the three header lines and it appears on this page.
"""


def render(bench_dir):
    saved = {"fdr": [], "gis": [], "terrain": [], "verbatim": []}
    for path in sorted(glob.glob(os.path.join(bench_dir, "*.txt"))):
        head, body = read_saved(path)
        saved[kind_of(body)].append((head, body, os.path.basename(path)))
    out = [INTRO]
    if saved["fdr"]:
        out.append(FDR_INTRO)
        for head, body, name in saved["fdr"]:  # one table a saved output: its own command, machine, date
            out += [f"### `docs/bench/{name}`", ""] + fdr_section([(head, body)])
    if saved["gis"]:
        out += [GIS_INTRO] + gis_section([(h, b) for h, b, _ in saved["gis"]])
    if saved["terrain"]:
        out.append(TERRAIN_INTRO)
        for head, body, name in saved["terrain"]:
            out += [f"### `docs/bench/{name}`", "", "```"] + body + ["```", ""] + provenance([(head, body)]) + [""]
    if saved["verbatim"]:
        out.append(VERBATIM_INTRO)
        for head, body, name in saved["verbatim"]:
            out += [f"### `docs/bench/{name}`", "", "```"] + body + ["```", ""] + provenance([(head, body)]) + [""]
    out.append(AB_SECTION)
    return "\n".join(out)


def main(argv):
    args = list(argv[1:])
    bench_dir = os.path.join(ROOT, "docs", "bench")
    if "--bench-dir" in args:
        i = args.index("--bench-dir")
        bench_dir = args[i + 1]
        del args[i:i + 2]
    check = "--check" in args
    args = [a for a in args if a != "--check"]
    if any(a.startswith("-") for a in args):
        print(__doc__, file=sys.stderr)
        return 2
    target = args[0] if args else os.path.join(ROOT, "docs", "benchmarks.md")
    try:
        text = render(bench_dir)
    except (OSError, ValueError) as e:
        print(f"ERROR: {e}", file=sys.stderr)
        return 1
    return write_or_check(target, text, check, "regenerate it with python3 tools/bench/make_benchmarks_md.py")


if __name__ == "__main__":
    sys.exit(main(sys.argv))
