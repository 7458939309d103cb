// Step 1, union of overlaps (union.hpp).
#include "coast/union.hpp"

#include "coast/report.hpp"
#include "coast/validity.hpp"

namespace fdr::coast {
namespace {

// Overlaps: pairs whose envelopes meet and whose intersection has an area, reported.
void report_overlaps(const OwnedPolygons& valid, Result& res) {
  std::vector<OGREnvelope> env(valid.size());
  for (std::size_t i = 0; i < valid.size(); ++i) valid[i]->getEnvelope(&env[i]);
  std::vector<std::unique_ptr<Prepared>> prep(valid.size());
  for (std::size_t i = 0; i < valid.size(); ++i)
    for (std::size_t j = i + 1; j < valid.size(); ++j) {
      if (!env[i].Intersects(env[j])) continue;
      // A prepared test first (the plain predicates are slow on a polygon with thousands of
      // holes); polygons that only touch have no overlap area.
      if (!prep[i]) prep[i] = std::make_unique<Prepared>(valid[i].get());
      if (!prep[i]->intersects(valid[j].get())) continue;
      GeomPtr x(valid[i]->Intersection(valid[j].get()));
      const double a = x ? area_of(x.get()) : 0;
      if (!(a > 0)) continue;
      ++res.united;
      res.united_overlap_area += a;
      res.repairs.push_back({"polygons_united", inside_point(x.get()), a,
                             "two water polygons overlap by " + num(a) +
                                 " m^2; they were united (the overlap stays water)",
                             -1});
    }
}

}  // namespace

GeomPtr unite(const Polygons& input, Result& res) {
  FilterLaps lap("  union");
  std::vector<std::unique_ptr<OGRPolygon>> valid;
  for (const auto& rings : input) {
    OGRPolygon p = to_ogr(rings);
    if (p.IsEmpty()) continue;
    if (!surely_valid(rings) && !p.IsValid()) {
      GeomPtr v = checked(p.MakeValid(), "making a polygon valid");
      polygons_of(v.get(), valid);
    } else {
      valid.emplace_back(p.clone());
    }
  }
  lap("valid");
  report_overlaps(valid, res);
  lap("overlaps");
  GeomPtr W;
  {
    std::vector<std::unique_ptr<OGRPolygon>> vs;
    for (auto& p : valid) vs.emplace_back(p->clone());
    W = union_pieces(vs, 0, "union of the water polygons");
  }
  lap("union");
  res.input_area = area_of(W.get());
  std::vector<std::unique_ptr<OGRPolygon>> ps;
  polygons_of(W.get(), ps);
  res.input_pieces = ps.size();
  return W;
}

}  // namespace fdr::coast
