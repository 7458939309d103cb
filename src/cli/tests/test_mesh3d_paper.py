"""The paper's experiments lifted to the cube [0,10]^3 (testdata/3d/cube10.poly) through the CLI with
--check, judged on the written VTU by tools/verify/tets.py: valid, empty circumspheres, R/f(c) <= B
with the spacing recomputed at each circumcentre, radius-edge <= 2, the cube's six facets tiled by
boundary faces, volume 1000. The full-size paper-f2 run takes minutes: it runs only when
FDR_PAPER_LONG is set (CTest `cli_mesh3d_paper_long`, label long)."""
import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[3]
FDRMESH = os.environ.get("FDRMESH", str(ROOT / "build" / "bin" / "fdrmesh"))
CUBE10 = ROOT / "testdata" / "3d" / "cube10.poly"
VERIFY = ROOT / "tools" / "verify" / "tets.py"
LONG = bool(os.environ.get("FDR_PAPER_LONG"))

# The presets as numpy expressions for tets.py (docs/3d.md gives the same formulas).
F1 = "(abs(x-5)+abs(y-5)+abs(z-5))*0.1+0.1"
F2 = "(abs(sin(x+y+z))+abs(cos(x+y+z)))*0.1"

CASES = [
    # (spacing option, numpy expression, needs the long run)
    ("paper-f1", F1, False),
    ("4*paper-f2", f"4*({F2})", False),
    ("2*paper-f2", f"2*({F2})", True),
    ("paper-f2", F2, True),
]


def verify(vtu, *args, want_json):
    out = Path(vtu).with_suffix(".verify.json")
    extra = ["--json", str(out)] if want_json else []
    p = subprocess.run([sys.executable, str(VERIFY), str(vtu), *extra, *map(str, args)],
                       capture_output=True, text=True, timeout=3600)
    return p, json.loads(out.read_text()) if want_json and out.exists() else {}


@pytest.mark.parametrize("spacing,expr,long_run", CASES, ids=[c[0] for c in CASES])
def test_cube10_paper_spacing_checked_and_verified(tmp_path, spacing, expr, long_run):
    if long_run != LONG:
        pytest.skip("the long cases run under FDR_PAPER_LONG, the quick ones without it")
    p = subprocess.run([FDRMESH, "mesh", str(CUBE10), "--spacing", spacing, "--check", "-o", "c.vtu",
                        "--report", "r.json", "-q"], cwd=tmp_path, capture_output=True, text=True, timeout=3600)
    assert p.returncode == 0, p.stderr
    rep = json.loads((tmp_path / "r.json").read_text())
    assert rep["check_passed"] is True
    bound = rep["bound_B"]
    assert rep["max_R_over_f"] <= bound * (1 + 1e-9)
    assert rep["max_radius_edge"] <= 2 * (1 + 1e-9)
    assert rep["volume"] == pytest.approx(1000, rel=1e-12)

    q, v = verify(tmp_path / "c.vtu", "--spacing", expr, "--bound", bound, "--max-radius-edge", 2, want_json=True)
    assert q.returncode == 0, q.stdout + q.stderr
    assert v["valid"] and v["nonpositive_volume"] == 0 and v["faces_shared_gt2"] == 0
    assert v["boundary_open_edges"] == 0
    assert v["not_delaunay"] == 0
    assert v["r_over_f_max"] <= bound * (1 + 1e-9)
    assert v["radius_edge_max"] <= 2 * (1 + 1e-9)
    assert v["volume"] == pytest.approx(1000, rel=1e-12)
    assert v["tetrahedra"] == rep["counts"]["tetrahedra"]

    # Conforming: the facet table of tets.py has no JSON form, so its summary line is read.
    c, _ = verify(tmp_path / "c.vtu", "--plc", CUBE10, want_json=False)
    assert c.returncode == 0, c.stdout + c.stderr
    assert "facets conforming 6/6 (0 boundary faces off facets)" in c.stdout
