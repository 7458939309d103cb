// The wells of a terrain run (--wells): matched to the terrain TIN's vertices (the 2D run took them
// as fixed points), placed between the top and the base, added to the PLC, and their mesh edges
// marked as one physical group per well.
#pragma once
#include <array>
#include <string>
#include <vector>
#include "base/point3.hpp"
#include "base/progress.hpp"
#include "gis/crs.hpp"
#include "pipeline/options.hpp"
#include "tet/tet_mesh.hpp"
#include "terrain/terrain_plc.hpp"
#include "terrain/wells_gis.hpp"

namespace fdr::pipeline {

struct TerrainWells {
  std::vector<terrain::WellColumn> columns;                // per well, as placed
  std::vector<std::vector<VertexId>> chains;               // per well, its PLC vertices from the top down
  std::vector<std::array<Point3, 2>> lines;                // per well, top and bottom end (local frame)
  std::int32_t marker0 = 0;                                // well k's edges get marker marker0 + k
};

// The in-memory layers the 2D run reads: the domain (the DEM's valid-data box when there is no
// INPUT and no --land) and the wells' positions as fixed points (with --wells). Empty when not needed.
struct TerrainInputs {
  terrain::MemLayer domain, points;
};
TerrainInputs terrain_inputs(const Options& opt);

// Reads the wells (lines may stray well_h / 2 from vertical in plan), finds each at a TIN vertex
// (none within `match` metres: Error(kInvalidGeometry) naming the well, its feature and coordinates:
// outside the domain), places it between the stack's top and base (ends within well_h / 2 of a
// surface move onto it; clipped ends and moves are logged as repairs), and adds its segments to the
// PLC with marker names `well_<name>` after the horizons'.
TerrainWells add_terrain_wells(const Options& opt, const gis::Frame& frame, const terrain::Tin& tin,
                               const std::vector<terrain::Surface>& stack, terrain::TerrainPlc& tp, double well_h,
                               double match, const LogFn& log);

// Gives every mesh edge on well k (marker 0: a free segment's piece) the marker marker0 + k, the
// well found by its plan position (world coordinates; pieces of a vertical segment keep its x and y).
void mark_well_edges(tet::TetMesh& m, const TerrainWells& w, const plc::Plc& world_plc);

// The wells as the GeoPackage layer shows them (world coordinates).
std::vector<terrain::WellLine> well_lines(const TerrainWells& w, const plc::Plc& world_plc);

}  // namespace fdr::pipeline
