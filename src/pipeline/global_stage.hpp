// The stages of a --global run that differ from a regional GIS run: the spacing computed on the
// sphere, depths sampled in lon/lat and the mesh measured on the sphere (GIS side).
#pragma once
#include "gis/global_spacing.hpp"
#include "pipeline/gis_stage.hpp"

namespace fdr::pipeline {

// Spacing stage, --global: the rules on a lon/lat grid in ground metres (distance to shore along
// great circles, the depth rules from a lon/lat --raster), gradient-limited on the sphere, read
// in the stereographic plane times its exact scale factor (gis/global_spacing.hpp). Laps
// "raster", "sizing".
GisSpacing global_spacing(const Options& opt, const gis::GisInput& g, StageClock& clock, const LogFn& log);

// Depths stage, --global: the lon/lat raster sampled at the vertices' lon/lat.
std::vector<double> global_depths(const mesh::MeshView& m, const PreparedInput& in);

// What PreparedInput::sphere_figures runs: the mesh measured on the sphere (gis/global_measure.hpp),
// its figures appended to `out` and logged.
void add_sphere_figures(const mesh::MeshView& m, const GisSpacing& sp, double bound, double hmin, double min_depth_m,
                        const LogFn& log, std::vector<std::pair<std::string, double>>& out);

// The coast deviation on the sphere, both ways between `input_boundary` (the input coast, segments
// in the frame of m.vertices) and the mesh's land and island edges, both taken as great-circle
// arcs, sampled every hmin/2 on the ground (gis/global_coast.hpp): figures
// sphere_coast_{input_to_mesh,mesh_to_input}_{max,p99}_m appended to `out` and logged.
void add_sphere_coast_deviation(const mesh::MeshView& m, const std::vector<std::pair<Point2, Point2>>& input_boundary,
                                const gis::SphereStereo& proj, double hmin, const LogFn& log,
                                std::vector<std::pair<std::string, double>>& out);

// The vertices of `m` (in the stereographic frame of `proj`) on its sphere: Earth-centred x, y, z in
// metres, x towards (0, 0), z towards the north pole.
std::vector<Point3> sphere_points(const mesh::MeshView& m, const gis::SphereStereo& proj);

// The --global parts of the prepared input: the spacing on the sphere, the lon/lat raster, the
// sphere's radius in the metadata, PreparedInput::sphere_figures (add_sphere_figures) and
// PreparedInput::sphere_xyz (sphere_points) for the VTU and msh outputs.
void attach_sphere(PreparedInput& out, const GisSpacing& sp, const Options& opt, const LogFn& log);

}  // namespace fdr::pipeline
