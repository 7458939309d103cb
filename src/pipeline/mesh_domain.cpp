// fdrmesh GIS API: mesh_domain() over pipeline::run, write_mesh() over io::write_mesh.
#include "pipeline/mesh_domain.hpp"
#include "base/error.hpp"
#include "base/version.hpp"
#include "io/writer.hpp"
#include "pipeline/gis_backend.hpp"

namespace fdr {
namespace {
io::WriteOptions write_options(const Mesh& m) {
  io::WriteOptions wo;
  wo.f = m.f.get();
  wo.bound_B = m.bound;
  wo.title = m.source;
  wo.metadata = {{"software", std::string("fdrmesh ") + kVersion},
                 {"input", m.source},
                 {"spacing", m.f ? m.f->describe() : std::string("none")},
                 {"bound_B", std::to_string(m.bound)},
                 {"min_angle_deg", std::to_string(m.min_angle_deg)},
                 {"alpha", std::to_string(m.alpha)},
                 {"quality", report_json(m.report)}};
  return wo;
}
}  // namespace

GisMesh mesh_domain(const DomainOptions& options, const ProgressFn& progress, const LogFn& log) {
  pipeline::Result r = pipeline::run(options, progress, log ? log : LogFn([](LogLevel, std::string_view) {}));
  GisMesh g;
  g.view = std::move(r.mesh);
  g.report = std::move(r.report);
  g.f = r.f;
  g.bound = options.bound;
  g.min_angle_deg = r.min_angle_deg;  // the automatic value when options.min_angle_deg < 0
  g.alpha = g.report.alpha;
  g.source = !options.input.empty() ? options.input : options.land;
  g.crs_name = r.crs_name;
  g.repairs = std::move(r.repair_rows);
  g.written = std::move(r.written);
  g.stages = std::move(r.stages);
  g.output_crs = options.output_crs;
  return g;
}

void write_mesh(const Mesh& m, const std::string& path, const std::string& format) {
  pipeline::gis_backend().write_mesh(m.view, path, io::format_from_path(path, format), write_options(m));
}

void write_mesh(const GisMesh& m, const std::string& path, const std::string& format) {
  if (!m.output_crs.empty())
    throw Error(ExitCode::kUsage, path + ": a mesh made with --output-crs is written during the run (list it in the outputs)");
  const io::Format fmt = io::format_from_path(path, format);
  io::WriteOptions wo = write_options(m);
  wo.metadata.push_back({"crs", m.crs_name});
  wo.repairs = m.repairs;
  pipeline::gis_backend().write_mesh(m.view, path, fmt, wo);
}

}  // namespace fdr
