#!/usr/bin/python3
"""Writes the surface and bad-input files of testdata/3d/ (run from anywhere; idempotent).

The octahedron |x|+|y|+|z| = 1 as .off, ASCII and binary .stl, ASCII and binary (both byte orders)
.ply; the bad inputs the 3D readers and the PLC checks must reject."""
import os
import struct

HERE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "testdata", "3d")

PTS = [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)]
# Outward-oriented triangles of the octahedron.
TRIS = [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)]


def write(name, data):
    mode = "wb" if isinstance(data, bytes) else "w"
    with open(os.path.join(HERE, name), mode) as f:
        f.write(data)


def off(tris, header="OFF"):
    lines = [header, "# the octahedron |x|+|y|+|z| = 1", f"{len(PTS)} {len(tris)} 0"]
    lines += [f"{x} {y} {z}" for x, y, z in PTS]
    lines += [f"3 {a} {b} {c}" for a, b, c in tris]
    return "\n".join(lines) + "\n"


def normal(t):
    a, b, c = (PTS[i] for i in t)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def stl_ascii(tris):
    out = ["solid octahedron"]
    for t in tris:
        out.append("  facet normal %g %g %g" % normal(t))
        out.append("    outer loop")
        out += ["      vertex %r %r %r" % tuple(float(c) for c in PTS[i]) for i in t]
        out += ["    endloop", "  endfacet"]
    out.append("endsolid octahedron")
    return "\n".join(out) + "\n"


def stl_binary(tris):
    # Header beginning with "solid" on purpose: the size, not the first word, tells binary apart.
    data = b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(tris))
    for t in tris:
        data += struct.pack("<3f", *normal(t))
        for i in t:
            data += struct.pack("<3f", *PTS[i])
        data += b"\0\0"
    return data


def ply(fmt):
    head = ["ply", f"format {fmt} 1.0", "comment the octahedron |x|+|y|+|z| = 1",
            f"element vertex {len(PTS)}", "property float x", "property float y", "property float z",
            "property uchar red",  # an extra property the reader must read past
            f"element face {len(TRIS)}", "property list uchar int vertex_indices", "property int marker",
            "end_header"]
    text = "\n".join(head) + "\n"
    if fmt == "ascii":
        text += "".join(f"{x} {y} {z} 200\n" for x, y, z in PTS)
        text += "".join(f"3 {a} {b} {c} {5 if c == 4 else 6}\n" for a, b, c in TRIS)
        return text
    e = "<" if fmt == "binary_little_endian" else ">"
    data = text.encode()
    for p in PTS:
        data += struct.pack(e + "3fB", *p, 200)
    for a, b, c in TRIS:
        data += struct.pack(e + "B3ii", 3, a, b, c, 5 if c == 4 else 6)
    return data


def main():
    write("octahedron.off", off(TRIS))
    write("octahedron.stl", stl_ascii(TRIS))
    write("octahedron_binary.stl", stl_binary(TRIS))
    write("octahedron.ply", ply("ascii"))
    write("octahedron_le.ply", ply("binary_little_endian"))
    write("octahedron_be.ply", ply("binary_big_endian"))
    write("bad_open.off", off(TRIS[:-1]))
    write("bad_open.stl", stl_ascii(TRIS[1:]))
    write("bad_truncated.ply", ply("binary_little_endian")[:-7])
    write("bad_garbage.stl", b"\x00\x01garbage that is neither ASCII nor binary STL\xff")


if __name__ == "__main__":
    main()
