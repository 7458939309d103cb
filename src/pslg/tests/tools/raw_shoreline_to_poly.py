#!/usr/bin/python3
"""Converts a GMT multisegment shoreline dump (gmt coast -M -W) to a Triangle .poly segment soup.

Each GMT piece becomes a polyline (part = piece number, marker 1); pieces with fewer than 2 points
are skipped. Pieces are kept whole if any point lies in the lon/lat box. Coordinates are projected
equirectangularly (metres) about the box centre, so the output is a raw, unrepaired local-frame PSLG.
Usage: raw_shoreline_to_poly.py RAW.txt W/E/S/N OUT.poly
"""
import math
import sys

R = 6371008.8


def main():
    src, box, out = sys.argv[1], sys.argv[2], sys.argv[3]
    w, e, s, n = (float(v) for v in box.split('/'))
    lon0, lat0 = 0.5 * (w + e), 0.5 * (s + n)
    kx = R * math.cos(math.radians(lat0)) * math.pi / 180
    ky = R * math.pi / 180
    pieces, cur = [], None
    for line in open(src):
        if line.startswith('#'):
            continue
        if line.startswith('>'):
            cur = []
            pieces.append(cur)
            continue
        f = line.split()
        if len(f) >= 2 and cur is not None:
            cur.append((float(f[0]), float(f[1])))
    keep = [p for p in pieces if len(p) >= 2 and any(w <= x <= e and s <= y <= n for x, y in p)]
    pts, segs = [], []
    for part, p in enumerate(keep):
        base = len(pts)
        pts.extend(((x - lon0) * kx, (y - lat0) * ky) for x, y in p)
        segs.extend((base + i, base + i + 1, part) for i in range(len(p) - 1))
    with open(out, 'w') as f:
        f.write('# GSHHG 2.3.7 (h) raw shoreline pieces from %s, box %s (LGPL-3+, see PROVENANCE.md)\n' % (src.split('/')[-1], box))
        f.write('# equirectangular metres about lon %.6f lat %.6f; parts = GMT pieces; UNREPAIRED\n' % (lon0, lat0))
        f.write('%d 2 0 0\n' % len(pts))
        for i, (x, y) in enumerate(pts):
            f.write('%d %.17g %.17g\n' % (i, x, y))
        f.write('%d 1\n' % len(segs))
        for i, (a, b, part) in enumerate(segs):
            f.write('%d %d %d 1\n' % (i, a, b))
        f.write('0\n')


if __name__ == '__main__':
    main()
