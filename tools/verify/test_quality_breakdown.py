"""Tests of tools/verify/quality_breakdown.py (the split of a mesh's quality deficit)."""
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import quality_breakdown as qb  # noqa: E402


def hexagon_with_centre():
    """Six equilateral triangles around a centre vertex: the centre is interior (ring 1, degree
    6), the rim is the boundary."""
    xy = [(0.0, 0.0)] + [(math.cos(k * math.pi / 3), math.sin(k * math.pi / 3)) for k in range(6)]
    tv = [(0, 1 + k, 1 + (k + 1) % 6) for k in range(6)]
    return np.array(xy), np.array(tv)


def test_equilateral_triangles_have_quality_one():
    xy, tv = hexagon_with_centre()
    assert np.allclose(qb.quality(xy, tv), 1.0)


def test_rings_boundary_edges_and_degrees():
    xy, tv = hexagon_with_centre()
    f = np.full(len(xy), 2.0)
    c = qb.classes(xy, f, tv)
    assert (c["ring"] == 0).all()  # every triangle has rim vertices
    assert np.allclose(c["boundary_edge_over_f"], 0.5)  # rim edges of length 1, f = 2
    assert np.allclose(c["f_grading"], 1.0)
    assert (c["worst_degree_off"] == 3).all()  # rim vertices have degree 3
    assert np.allclose(c["fan_angle_off_60"], 0.0)  # each rim vertex: 120 degrees in two triangles
    assert (c["fan_count_off_best"] == 0).all()


def test_shares_add_up_to_the_whole_deficit():
    xy, tv = hexagon_with_centre()
    xy[0] = (0.3, 0.1)  # the centre off its ideal place: all six triangles lose quality
    f = np.linspace(1.0, 1.3, len(xy))
    rf = np.linspace(0.4, 0.99, len(tv))
    out = qb.breakdown(xy, f, tv, rf)
    q = qb.quality(xy, tv)
    assert math.isclose(out["mean_q"], q.mean())
    for name, rows in out["tables"].items():
        assert math.isclose(sum(r["pct_deficit"] for r in rows), 100.0, rel_tol=1e-9), name
        assert math.isclose(sum(r["pct_tri"] for r in rows), 100.0, rel_tol=1e-9), name
