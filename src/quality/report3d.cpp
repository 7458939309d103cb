// Measuring a tetrahedral mesh: per tetrahedron (R/f(c), radius-edge, dihedral angles, volume),
// per edge (l/f at the midpoint), per vertex (shortest and longest incident edge over f) and the
// 3D theorem table.
#include "quality/report3d.hpp"
#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <type_traits>
#include <utility>
#include "tet/tet_geometry.hpp"

namespace fdr::quality {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

double volume_of(Point3 a, Point3 b, Point3 c, Point3 d) { return dot(b - a, cross(c - a, d - a)) / 6.0; }

// Calls fn(a, b) once per edge (a < b), vertex by vertex: each vertex's neighbours come from its
// incident tetrahedra (a compact vertex -> tetrahedra table), sorted in a short local list. Cheaper
// than sorting the six edges of every tetrahedron of a large mesh as one array.
template <class Fn>
void for_each_edge(const tet::TetMesh& m, Fn&& fn) {
  const std::size_t n = m.points.size();
  std::vector<Index> start(n + 1, 0);  // Index: 4 bytes per incidence with 32-bit ids
  for (const auto& t : m.tets)
    for (VertexId v : t) ++start[v + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  std::vector<Index> fill(start.begin(), start.end() - 1);
  std::vector<Index> incident(start[n]);
  for (std::size_t i = 0; i < m.tets.size(); ++i)
    for (VertexId v : m.tets[i]) incident[fill[v]++] = static_cast<Index>(i);
  std::vector<VertexId> nb;
  for (std::size_t v = 0; v < n; ++v) {
    nb.clear();
    for (Index k = start[v]; k < start[v + 1]; ++k)
      for (VertexId w : m.tets[incident[k]])
        if (w > v) nb.push_back(w);
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    for (VertexId w : nb) fn(static_cast<VertexId>(v), w);
  }
}

void measure_edges(const tet::TetMesh& m, const sizing::SizingField3& f, Report3& r) {
  const std::size_t n = m.points.size();
  std::vector<double> fp(n), shortest(n, std::numeric_limits<double>::infinity()), longest(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) fp[i] = f(m.points[i]);
  r.min_l_over_f = m.tets.empty() ? 0 : std::numeric_limits<double>::infinity();
  r.max_l_over_f = 0;
  for_each_edge(m, [&](VertexId va, VertexId vb) {
    const Point3 a = m.points[va], b = m.points[vb];
    const double l = dist(a, b);
    const double lf = l / f(0.5 * (a + b));
    r.min_l_over_f = std::min(r.min_l_over_f, lf);
    r.max_l_over_f = std::max(r.max_l_over_f, lf);
    for (VertexId v : {va, vb}) {
      shortest[v] = std::min(shortest[v], l);
      longest[v] = std::max(longest[v], l);
    }
  });
  r.nn_over_f_min = std::numeric_limits<double>::infinity();
  r.el_over_f_max = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (longest[i] == 0) continue;  // a vertex of no tetrahedron
    r.nn_over_f_min = std::min(r.nn_over_f_min, shortest[i] / fp[i]);
    r.el_over_f_max = std::max(r.el_over_f_max, longest[i] / fp[i]);
  }
  if (!std::isfinite(r.nn_over_f_min)) r.nn_over_f_min = 0;
}

void add_theorems(Report3& r) {
  const Guarantees3& g = r.guarantees;
  auto add = [&](const char* key, const char* label, bool upper, double bound, double measured) {
    TheoremRow row{key, label, upper, bound, measured, false, g.valid};
    row.holds = g.valid && (upper ? measured <= bound : measured >= bound);
    r.theorems.push_back(row);
  };
  // The refiner's invariant, the hypothesis of the theorems below; it needs no alpha.
  TheoremRow inv{"R_over_f_max", "R/f(c) max (<= B)", true, r.bound_B, r.max_R_over_f, r.max_R_over_f <= r.bound_B, true};
  r.theorems.push_back(inv);
  add("theorem_4_2_beta", "beta (Thm 4.2, > 0)", false, 0.0, g.beta);
  add("theorem_4_3_R_over_l_max", "R/l max (Thm 4.3)", true, g.R_over_l_max, r.max_radius_edge);
  // Theorems 4.4 and 4.5 speak of the vertices FDR inserts. Sliver removal's points lie only
  // (1 - delta) R from their neighbours, nearer than the protection spheres allow, so the theorems
  // are judged on the mesh rule 3 left and the final mesh's figures are shown beside them.
  const tet::TetStats& s = r.stats;
  const bool split = s.fdr_vertex_figures;
  const double nn = split ? s.fdr_nn_over_f_min : r.nn_over_f_min;
  const double el = split ? s.fdr_el_over_f_max : r.el_over_f_max;
  add("theorem_4_4_nn_over_f_min", split ? "nn/f min (Thm 4.4, before sliver removal)" : "nn/f min (Thm 4.4)", false,
      g.nn_over_f_min, nn);
  add("theorem_4_5_el_over_f_max", split ? "el/f max (Thm 4.5, before sliver removal)" : "el/f max (Thm 4.5)", true,
      g.el_over_f_max, el);
  add("theorem_4_5_corrected_el_over_f_max", split ? "el/f max (4.5 fixed, before sliver removal)" : "el/f max (4.5 fixed)",
      true, g.el_over_f_max_corrected, el);
  if (!split) return;
  auto beyond = [&](const char* key, const char* label, bool upper, double bound, double measured) {
    TheoremRow row{key, label, upper, bound, measured, upper ? measured <= bound : measured >= bound, false};
    row.beyond_paper = true;
    r.theorems.push_back(row);
  };
  beyond("after_slivers_nn_over_f_min", "nn/f min after sliver removal", false, g.nn_over_f_min, r.nn_over_f_min);
  beyond("after_slivers_el_over_f_max", "el/f max after sliver removal", true, g.el_over_f_max_corrected, r.el_over_f_max);
}

}  // namespace

Guarantees3 compute_guarantees3(double alpha, double B) {
  Guarantees3 g;
  if (!std::isfinite(alpha) || alpha < 0) {
    g.note = "no guarantee: the Lipschitz constant alpha of f is unknown";
    return g;
  }
  if (!std::isfinite(B) || B <= 0) {
    g.note = "no guarantee: the bound B must be positive";
    return g;
  }
  const double ab = alpha * B;
  if (ab >= 1) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "no guarantee: alpha*B = %.6g >= 1 (Section 4 requires B < 1/alpha)", ab);
    g.note = buf;
    return g;
  }
  g.valid = true;
  g.beta = B / (4.0 + (3.0 + 2.0 * std::sqrt(2.0)) * ab);
  g.R_over_l_max = B / (2.0 * g.beta * (1.0 - ab));
  g.nn_over_f_min = 2.0 * g.beta / (1.0 + alpha * g.beta);
  g.el_over_f_max = 2.0 * B / (1.0 + ab);
  g.el_over_f_max_corrected = 2.0 * B / (1.0 - ab);
  g.note = "3D, beta = B/(4+(3+2*sqrt(2))*alpha*B), assuming beta <= D/(2+alpha*D) (Section 4)";
  return g;
}

std::pair<double, double> dihedral_range_deg(Point3 a, Point3 b, Point3 c, Point3 d) {
  // The four faces' normals, each pointing away from its opposite vertex (orientation-free: the
  // sign is fixed against that vertex). The interior angle at the edge two faces share is pi minus
  // the angle between their outward normals, so the smallest dihedral has the largest cosine
  // -n_i.n_j: two acos per tetrahedron instead of six atan2.
  const Point3 p[4] = {a, b, c, d};
  Point3 n[4];
  for (int i = 0; i < 4; ++i) {
    const Point3 q0 = p[(i + 1) % 4], q1 = p[(i + 2) % 4], q2 = p[(i + 3) % 4];
    Point3 v = cross(q1 - q0, q2 - q0);
    if (dot(v, p[i] - q0) > 0) v = -1.0 * v;
    n[i] = (1.0 / std::sqrt(norm2(v))) * v;
  }
  double cmax = -1, cmin = 1;  // cosines of the interior angles
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const double cs = std::clamp(-dot(n[i], n[j]), -1.0, 1.0);
      cmax = std::max(cmax, cs);
      cmin = std::min(cmin, cs);
    }
  return {std::acos(cmax) * kDeg, std::acos(cmin) * kDeg};
}

Report3 measure_tets(const tet::TetMesh& m, const sizing::SizingField3& f, const tet::TetStats& stats,
                     TetValues* values) {
  Report3 r;
  r.spacing = f.describe();
  r.alpha = f.lipschitz();
  r.bound_B = stats.bound;
  r.stats = stats;
  r.vertices = m.points.size();
  r.tets = m.tets.size();
  r.subfacets = m.faces.size();
  r.subsegments = m.edges.size();
  r.dihedral_hist.assign(18, 0);
  r.min_dihedral_deg = m.tets.empty() ? 0 : 180.0;
  if (values) {
    values->r_over_f.resize(m.tets.size());
    values->radius_edge.resize(m.tets.size());
    values->min_dihedral_deg.resize(m.tets.size());
  }
  std::map<std::int32_t, MaterialFigures> mats;
  MaterialFigures* last = nullptr;
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    const Point3 a = m.points[t[0]], b = m.points[t[1]], c = m.points[t[2]], d = m.points[t[3]];
    const tet::Sphere s = tet::circumsphere(a, b, c, d);
    const double rf = s.radius / f(s.centre);
    const double re = s.radius / tet::shortest_edge(a, b, c, d);
    const auto [lo, hi] = dihedral_range_deg(a, b, c, d);
    r.max_R_over_f = std::max(r.max_R_over_f, rf);
    r.max_radius_edge = std::max(r.max_radius_edge, re);
    if (rf > r.bound_B) ++r.bad_tets;
    r.min_dihedral_deg = std::min(r.min_dihedral_deg, lo);
    r.max_dihedral_deg = std::max(r.max_dihedral_deg, hi);
    ++r.dihedral_hist[std::min<std::size_t>(17, static_cast<std::size_t>(std::max(0.0, lo) / 10.0))];
    if (lo < 5) ++r.tets_under_5deg;
    if (lo < 10) ++r.tets_under_10deg;
    const std::int32_t mat = i < m.tet_material.size() ? m.tet_material[i] : 0;
    if (!last || last->material != mat) {  // materials come in runs: one map look-up per run
      last = &mats[mat];
      last->material = mat;
    }
    MaterialFigures& mf = *last;
    ++mf.tets;
    const double v = volume_of(a, b, c, d);
    mf.volume += v;
    r.volume += v;
    if (values) {
      values->r_over_f[i] = rf;
      values->radius_edge[i] = re;
      values->min_dihedral_deg[i] = lo;
    }
  }
  for (const auto& [id, mf] : mats) r.materials.push_back(mf);
  measure_edges(m, f, r);
  r.guarantees = compute_guarantees3(r.alpha, r.bound_B);
  add_theorems(r);
  return r;
}

}  // namespace fdr::quality
