// Wells in a terrain run (terrain_wells.hpp).
#include "pipeline/terrain_wells.hpp"
#include <cmath>
#include <map>
#include <utility>
#include "base/error.hpp"
#include "base/num_format.hpp"
#include "tet/tet_mesh.hpp"

namespace fdr::pipeline {

TerrainInputs terrain_inputs(const Options& opt) {
  TerrainInputs in;
  if (opt.input.empty() && opt.land.empty()) in.domain = terrain::dem_extent_layer(opt.dem);
  if (!opt.wells.empty()) in.points = terrain::wells_point_layer({opt.wells, opt.wells_layer, opt.s_srs});
  return in;
}

TerrainWells add_terrain_wells(const Options& opt, const gis::Frame& frame, const terrain::Tin& tin,
                               const std::vector<terrain::Surface>& stack, terrain::TerrainPlc& tp, double well_h,
                               double match, const LogFn& log) {
  TerrainWells out;
  const std::vector<terrain::Well> wells = terrain::read_wells({opt.wells, opt.wells_layer, opt.s_srs}, frame, 0.5 * well_h);
  std::vector<std::uint8_t> on_boundary(tin.xy.size(), 0);
  for (const auto& e : terrain::boundary_edges(tin)) on_boundary[e[0]] = on_boundary[e[1]] = 1;
  std::map<VertexId, std::size_t> taken;
  int clipped = 0, snapped = 0;
  for (std::size_t k = 0; k < wells.size(); ++k) {
    const terrain::Well& w = wells[k];
    const auto [v, d2] = terrain::nearest_vertex(tin.xy, w.xy);
    if (v >= tin.xy.size() || !(d2 <= match * match))
      throw Error(ExitCode::kInvalidGeometry, w.where + ": the well lies outside the domain (or within the boundary's "
                                                        "repairs), so it is no vertex of the terrain TIN");
    if (on_boundary[v])
      throw Error(ExitCode::kInvalidGeometry, w.where + ": the well lies on the domain's boundary (it would be in a side "
                                                        "wall); move it inside");
    const auto [it, fresh] = taken.emplace(static_cast<VertexId>(v), k);
    if (!fresh)
      throw Error(ExitCode::kInvalidGeometry, w.where + ": the well is at the place of " + wells[it->second].where +
                                                  "; give one feature per well");
    terrain::WellRepairs rep;
    out.columns.push_back(terrain::place_well(w, static_cast<VertexId>(v), terrain::column_at(stack, static_cast<VertexId>(v)),
                                              0.5 * well_h, &rep));
    if (log && (rep.clipped_top || rep.clipped_base || rep.snapped)) {
      std::vector<std::string> what;
      if (rep.clipped_top) what.push_back("clipped to the DEM");
      if (rep.clipped_base) what.push_back("clipped to the base");
      if (rep.snapped)
        what.push_back(std::to_string(rep.snapped) + " end(s) moved onto a surface nearer than " + num6(0.5 * well_h) + " m");
      std::string msg = w.where + ": ";
      for (std::size_t i = 0; i < what.size(); ++i) msg += (i ? "; " : "") + what[i];
      log(LogLevel::kWarning, msg);
    }
    clipped += rep.clipped_top + rep.clipped_base;
    snapped += rep.snapped;
  }
  out.chains = terrain::add_well_segments(tp, tin, stack, out.columns);
  plc::Plc& p = tp.plc;
  out.marker0 = static_cast<std::int32_t>(p.marker_names.size());
  for (std::size_t k = 0; k < out.columns.size(); ++k) {
    const Point3 a = p.points[out.chains[k].front()], b = p.points[out.chains[k].back()];
    out.lines.push_back({a, b});
    p.marker_names.push_back("well_" + out.columns[k].name);
  }
  if (log)
    log(LogLevel::kInfo, "wells: " + std::to_string(wells.size()) + " as " + std::to_string(p.segments.size()) +
                             " vertical segments, spacing " + num6(well_h) + " m along them; " +
                             std::to_string(clipped) + " ends clipped, " + std::to_string(snapped) + " moved onto a surface");
  return out;
}

void mark_well_edges(tet::TetMesh& m, const TerrainWells& w, const plc::Plc& world_plc) {
  std::map<std::pair<double, double>, std::int32_t> at;
  for (std::size_t k = 0; k < w.chains.size(); ++k) {
    const Point3 q = world_plc.points[w.chains[k].front()];
    at.emplace(std::make_pair(q.x, q.y), w.marker0 + static_cast<std::int32_t>(k));
  }
  m.marker_names = world_plc.marker_names;
  for (std::size_t e = 0; e < m.edges.size(); ++e) {
    if (m.edge_marker[e] != 0) continue;
    const Point3 a = m.points[m.edges[e][0]];
    const auto it = at.find({a.x, a.y});
    if (it == at.end()) throw Error(ExitCode::kInternal, "a free mesh edge off every well");
    m.edge_marker[e] = it->second;
  }
}

std::vector<terrain::WellLine> well_lines(const TerrainWells& w, const plc::Plc& world_plc) {
  std::vector<terrain::WellLine> out;
  for (std::size_t k = 0; k < w.chains.size(); ++k)
    out.push_back({w.columns[k].name, {world_plc.points[w.chains[k].front()], world_plc.points[w.chains[k].back()]}});
  return out;
}

}  // namespace fdr::pipeline
