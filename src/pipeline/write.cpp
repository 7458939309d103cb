// Write stage (write.hpp).
#include "pipeline/write.hpp"
#include "base/triangle_geometry.hpp"
#include "base/redact.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include "base/error.hpp"
#include "base/path_util.hpp"
#include "base/threads.hpp"
#include "base/version.hpp"
#include "pipeline/gis_backend.hpp"
#include "predicates/predicates.hpp"
#include "quality/rss.hpp"

namespace fdr::pipeline {
namespace {
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// The .cli written beside a Selafin output.
std::string cli_path_of(const std::string& slf) {
  const std::string e = lower_ext(slf);
  return (e == "slf" ? slf.substr(0, slf.size() - 4) : slf) + ".cli";
}

// The .ele written beside a .node output.
std::string ele_path_of(const std::string& node) {
  const auto dot = node.find_last_of('.');
  return (dot == std::string::npos ? node : node.substr(0, dot)) + ".ele";
}

// Per-triangle R/f(c), min angle and area in the metric frame, for outputs written in --output-crs.
struct MetricTriangleValues {
  std::vector<double> r_over_f, min_angle, area, quality;
};
MetricTriangleValues metric_triangle_values(const mesh::MeshView& m, const sizing::SizingField& f) {
  MetricTriangleValues v;
  v.r_over_f.resize(m.triangles.size());
  v.min_angle.resize(m.triangles.size());
  v.area.resize(m.triangles.size());
  v.quality.resize(m.triangles.size());
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const Point2 a = m.vertices[m.triangles[t][0]], b = m.vertices[m.triangles[t][1]], c = m.vertices[m.triangles[t][2]];
    double r2;
    const Point2 cc = geom::circumcentre(a, b, c, &r2);
    v.r_over_f[t] = std::sqrt(r2) / f(cc);
    v.min_angle[t] = geom::min_angle_deg(a, b, c);
    v.area[t] = 0.5 * geom::cross2(a, b, c);
    v.quality[t] = geom::mean_ratio_quality(a, b, c);
  }
  return v;
}

// The writers' options, with the run's metadata for the formats that store it.
io::WriteOptions write_options(const WriteInput& w, const WriteParams& p) {
  const sizing::SizingField& f = *w.in.f;
  io::WriteOptions wo;
  wo.f = &f;
  wo.bound_B = p.bound;
  wo.title = redact_passwords(p.source);  // a PostGIS source names its server, not its password
  wo.postgis = p.postgis;
  wo.slf_double = p.slf_double;
  wo.telemac_open_codes = p.telemac_codes;
  if (stores_metadata(p.formats)) {
    std::ostringstream js;
    quality::write_json(w.report, js);
    wo.metadata = {{"software", std::string("fdrmesh ") + kVersion},
                   {"command_line", redact_passwords(p.command_line)},
                   {"input", redact_passwords(p.source)},
                   {"spacing", f.describe()},
                   {"bound_B", std::to_string(p.bound)},
                   {"min_angle_deg", std::to_string(p.min_angle_deg)},
                   {"alpha", std::to_string(w.alpha)},
                   {"crs", w.in.crs_name}};
    wo.metadata.emplace_back("quality", std::move(js).str());  // moved, not copied: it can be large
    for (const auto& kv : w.in.metadata) wo.metadata.push_back(kv);
  }
  wo.repairs = w.in.repairs;
  return wo;
}

// The mesh files and what is written beside them (a Selafin's .cli, a .node's .ele): `written`
// gets the outputs as named, `beside` the others.
void write_meshes(const mesh::MeshView& m, const io::WriteOptions& wo, const WriteParams& p,
                  std::vector<std::string>& written, std::vector<std::string>& beside) {
  // The writers are on the GIS side (GeoPackage: SQLite, UGRID: netCDF): loaded only when there
  // are outputs. Concurrent writers are safe: only GPKG, VTU and UGRID would evaluate f, and they
  // get the report's values instead (or the --output-crs ones, with wo.f null).
  if (!p.outputs.empty()) gis_backend().write_meshes(m, p.outputs, p.formats, wo, fdr::max_threads());
  for (std::size_t i = 0; i < p.outputs.size(); ++i) {
    written.push_back(p.outputs[i]);
    if (p.formats[i] == io::Format::kSelafin) beside.push_back(cli_path_of(p.outputs[i]));
    if (p.formats[i] == io::Format::kNode) beside.push_back(ele_path_of(p.outputs[i]));
  }
}

}  // namespace

bool stores_triangle_values(const std::vector<io::Format>& formats) {
  return std::any_of(formats.begin(), formats.end(), [](io::Format fm) {
    return fm == io::Format::kGpkg || fm == io::Format::kVtu || fm == io::Format::kUgrid || fm == io::Format::kPostgis;
  });
}

bool writes_on_sphere(const std::vector<io::Format>& formats) {
  return std::any_of(formats.begin(), formats.end(),
                     [](io::Format fm) { return fm == io::Format::kVtu || fm == io::Format::kMsh; });
}

bool stores_metadata(const std::vector<io::Format>& formats) {
  return std::any_of(formats.begin(), formats.end(), [](io::Format fm) {
    return fm == io::Format::kGpkg || fm == io::Format::kUgrid || fm == io::Format::kDflowfm ||
           fm == io::Format::kPostgis;
  });
}

WrittenOutputs write_outputs(const WriteInput& w, const WriteParams& p, Clock::time_point t_start,
                             const ProgressFn& progress) {
  const auto t_write = Clock::now();
  io::WriteOptions wo = write_options(w, p);
  // --output-crs: quality columns are computed in the metric frame, then the copy is reprojected.
  mesh::MeshView projected;
  MetricTriangleValues metric;
  const mesh::MeshView* to_write = &w.mesh;
  if (p.gis && !p.output_crs.empty() && !p.outputs.empty()) {
    metric = metric_triangle_values(w.mesh, *w.in.f);
    projected = w.mesh;
    gis_backend().reproject_mesh(projected, w.in, p.output_crs);
    // A global mesh in lon/lat: its GeoPackage geometries continue across the antimeridian.
    wo.continue_across_antimeridian = w.in.sphere_f != nullptr && p.output_crs == "EPSG:4326";
    wo.f = nullptr;
    wo.triangle_r_over_f = &metric.r_over_f;
    wo.triangle_min_angle = &metric.min_angle;
    wo.triangle_area = &metric.area;
    wo.triangle_quality = &metric.quality;
    to_write = &projected;
  }
  // A global mesh: VTU and msh on the sphere, from the plane mesh (whatever --output-crs says).
  std::vector<Point3> sphere;
  if (w.in.sphere_xyz && writes_on_sphere(p.formats)) {
    sphere = w.in.sphere_xyz(w.mesh);
    wo.sphere_xyz = &sphere;
    wo.sphere_radius = w.in.sphere_radius;
  }
  if (w.triangle_values) {
    wo.f = nullptr;  // m.f holds f at the vertices; the triangles' values come from the report
    wo.triangle_r_over_f = &w.triangle_values->r_over_f;
    wo.triangle_min_angle = &w.triangle_values->min_angle_deg;
    wo.triangle_area = &w.triangle_values->area;
  }
  // All or nothing: if a later output (mesh, spacing GeoTIFF, report) fails or the run is
  // cancelled, the files already written are removed again.
  WrittenOutputs out;
  std::vector<std::string> beside;
  if (!p.write_spacing.empty()) beside.push_back(p.write_spacing);
  try {
    write_meshes(*to_write, wo, p, out.paths, beside);
    if (p.gis && !p.write_spacing.empty()) gis_backend().write_spacing_geotiff(w.in, p.write_spacing);
    w.report.run.write_s = since(t_write);
    w.report.run.total_s = since(t_start);
    w.report.run.peak_rss_mb = quality::peak_rss_mb_value();
    if (!p.report_json.empty()) {
      quality::write_json_file(w.report, p.report_json);
      out.paths.push_back(p.report_json);
    }
    if (progress && !progress(1.0, "done")) throw Error(ExitCode::kCancelled, "cancelled during done");
  } catch (...) {
    for (const auto& f : out.paths) std::remove(f.c_str());
    for (const auto& f : beside) std::remove(f.c_str());
    throw;
  }
  return out;
}

}  // namespace fdr::pipeline
