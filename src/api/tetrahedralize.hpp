// fdr::tetrahedralize: the 3D mesher as a library call (the facade over plc, tet and tetio), the
// same mesh as `fdrmesh mesh IN.poly` for the same input, spacing and bound.
#pragma once
#include <string>
#include "plc/plc.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/tetrahedralize.hpp"

namespace fdr {

using tet::TetMesh;
using tet::TetOptions;
using tet::TetResult;
using tet::TetStats;

// A conforming Delaunay tetrahedralization of `plc` refined until every tetrahedron has
// R/f(c) <= B (options.bound; 0 takes the 3D default). Throws fdr::Error on bad input (exit codes
// of base/error.hpp), on a spacing that is not positive, and when the vertex cap is reached
// (kWorkLimit), since a capped mesh breaks the bound.
TetResult tetrahedralize(const plc::Plc& plc, const sizing::SizingField3& f, const TetOptions& options = {});

// The same with the spacing as `--spacing` takes it in 3D: a number, paper-f1, paper-f2, K*preset,
// or an expression in x, y, z (sizing::make_spacing3).
TetResult tetrahedralize(const plc::Plc& plc, const std::string& spacing, const TetOptions& options = {});

// The spacing of a run without one, as in 2D: a twentieth of the PLC's bounding-box diagonal, as
// a --spacing number (shortest round-trip digits).
std::string default_spacing3(const plc::Plc& plc);

// f sampled on a regular 3D grid (cell centres), trilinear in between (sizing::GridField3): the
// spacing of a Python callable.
sizing::SizingPtr3 grid_spacing3(sizing::Grid3 grid, const std::string& label);

// The PLC of a 3D input file (.poly with dimension 3, .smesh, .node, .off, .stl, .ply).
plc::Plc read_plc(const std::string& path);

// Whether `path` is a 3D input: a .poly whose dimension line says 3, or one of the 3D-only
// extensions. A .poly that cannot be read counts as 2D (the 2D reader then names the problem).
bool is_3d_input(const std::string& path);

}  // namespace fdr
