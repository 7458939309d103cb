// Read stage of .poly/.node runs (core: no GDAL/PROJ): the PSLG in its
// local frame, repairs reported, f from --spacing.
#include "base/num_format.hpp"
#include <map>
#include <sstream>
#include "api/core_stages.hpp"
#include "pipeline/gis_stage.hpp"
#include "pslg/poly_io.hpp"

namespace fdr::pipeline {
namespace {
std::string num(double v) { return num6(v); }
}  // namespace

PreparedInput prepare_poly_input(const Options& opt, const LogFn& log) {
  PreparedInput in;
  std::vector<pslg::Repair> reps;
  in.pslg = fdr::prepare_pslg(fdr::read_pslg(opt.input), opt.input, opt.strict, &reps);
  for (const auto& r : reps) {
    const Point2 w = in.pslg.origin + r.where;
    io::RepairRow row{r.kind, w.x, w.y, r.size, r.reason, r.part};
    row.ids = r.ids;
    in.repairs.push_back(std::move(row));
  }
  if (!reps.empty() && log) {
    // Text report: counts per kind, then the first fixes (all of them in the JSON report).
    std::map<std::string, std::size_t> kinds;
    for (const auto& r : in.repairs) ++kinds[r.kind];
    std::string line = "repairs: " + std::to_string(in.repairs.size());
    for (const auto& [k, n] : kinds) line += ", " + k + " " + std::to_string(n);
    log(LogLevel::kInfo, line + " (--strict refuses conflicting constraints instead)");
    for (std::size_t i = 0; i < in.repairs.size() && i < 20; ++i) {
      const auto& r = in.repairs[i];
      std::string l = "  " + r.kind + " at (" + num(r.x) + ", " + num(r.y) + ")";
      if (!r.ids.empty()) {
        l += " ids";
        for (auto id : r.ids) l += " " + std::to_string(id);
      }
      log(LogLevel::kInfo, l + ": " + r.reason);
    }
    if (in.repairs.size() > 20) log(LogLevel::kInfo, "  ... " + std::to_string(in.repairs.size() - 20) + " more (see the JSON report)");
  }
  // Default spacing for a bare PSLG: a twentieth of the bounding-box diagonal.
  const std::string spec = opt.spacing.empty() ? fdr::default_spacing_spec(in.pslg) : opt.spacing;
  in.f = fdr::spacing_in_frame(spec, in.pslg.origin);
  return in;
}

}  // namespace fdr::pipeline
