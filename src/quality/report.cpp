// Mesh quality measurement and report writers (FDR paper: Definition 2.1, Theorems 4.3-4.5).
#include "quality/compensated_sum.hpp"
#include "quality/report.hpp"
#include <cstdio>
#include <fstream>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <ostream>
#include <string>
#include <exception>
#include <thread>
#include <nlohmann/json.hpp>

#include "base/error.hpp"
#include "base/threads.hpp"
#include "predicates/predicates.hpp"
#include "quality/mesh_adjacency.hpp"

namespace fdr::quality {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = 180.0 / kPi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Kahan-Babuska (Neumaier) compensated sum: areas of millions of triangles of very different size.

// Static 2-d tree (implicit: the median of each range is its node) over copies of the points
// kept in tree order, so a query reads contiguous memory and consecutive queries in tree order
// share most of it.
class KdTree {
 public:
  explicit KdTree(const std::vector<Point2>& p) : t_(p.size()) {
    for (std::size_t i = 0; i < p.size(); ++i) t_[i] = {p[i], static_cast<Index>(i)};
    build(0, t_.size(), 0);
  }
  std::size_t size() const { return t_.size(); }
  Index id_at(std::size_t pos) const { return t_[pos].id; }
  // Squared distance from the point at tree position `pos` to the nearest point with another
  // index. `bound` is an upper bound that is itself such a squared distance norm2(p_v - p_self)
  // (or +inf): only points strictly closer are searched, so the result is the same value either way.
  double nearest_sq_at(std::size_t pos, double bound = kInf) const {
    double best = bound;
    query(t_[pos].p, t_[pos].id, 0, t_.size(), 0, best);
    return best;
  }

 private:
  struct Node {
    Point2 p;
    Index id;
  };
  static constexpr std::size_t kScan = 8;  // ranges this small are scanned
  static double coord(Point2 q, int axis) { return axis == 0 ? q.x : q.y; }
  void build(std::size_t lo, std::size_t hi, int axis) {
    if (hi - lo <= kScan) return;  // queries scan such ranges whole: no order needed inside
    const std::size_t mid = lo + (hi - lo) / 2;
    std::nth_element(t_.begin() + static_cast<std::ptrdiff_t>(lo), t_.begin() + static_cast<std::ptrdiff_t>(mid),
                     t_.begin() + static_cast<std::ptrdiff_t>(hi),
                     [axis](const Node& a, const Node& b) { return coord(a.p, axis) < coord(b.p, axis); });
    build(lo, mid, 1 - axis);
    build(mid + 1, hi, 1 - axis);
  }
  // Why the far side is visited only conditionally: points across the splitting line are at
  // least |diff| away, so they cannot beat a best distance already below diff^2.
  void query(Point2 q, Index self, std::size_t lo, std::size_t hi, int axis, double& best) const {
    if (hi - lo <= kScan) {
      for (std::size_t k = lo; k < hi; ++k)
        if (t_[k].id != self) best = std::min(best, norm2(t_[k].p - q));
      return;
    }
    const std::size_t mid = lo + (hi - lo) / 2;
    const Node& n = t_[mid];
    if (n.id != self) best = std::min(best, norm2(n.p - q));
    const double diff = coord(q, axis) - coord(n.p, axis);
    if (diff < 0) {
      query(q, self, lo, mid, 1 - axis, best);
      if (diff * diff < best) query(q, self, mid + 1, hi, 1 - axis, best);
    } else {
      query(q, self, mid + 1, hi, 1 - axis, best);
      if (diff * diff < best) query(q, self, lo, mid, 1 - axis, best);
    }
  }
  std::vector<Node> t_;
};

double angle_at(Point2 apex, Point2 p, Point2 q) {
  const Point2 u = p - apex, v = q - apex;
  const double cr = u.x * v.y - u.y * v.x;
  return std::atan2(std::fabs(cr), dot(u, v)) * kDeg;
}

void update_min(std::optional<double>& m, double v) { if (!m || v < *m) m = v; }
void update_max(std::optional<double>& m, double v) { if (!m || v > *m) m = v; }

// The angle histograms and extremes without trigonometry for most triangles, with the same
// figures as atan2 (angle_at) for every triangle. The three angles of a triangle share |cross|
// (twice its area), so an angle t at a corner with dot product d satisfies cot t = d/|cross|:
// t >= phi  <=>  d <= |cross| cot(phi) (0 < phi < 180 deg). The smallest angle is at the largest d,
// the largest at the smallest. fast() decides both bins that way when every comparison is clear
// by a margin of 1e-9 L^2 (L the longest edge; rounding is ~1e-15 L^2, and atan2's ~1e-15 rad,
// far inside the margin) on triangles that are not slivers (|cross| >= 1e-3 L^2, i.e. every angle
// >= 0.057 deg), and calls atan2 only when the triangle may hold the smallest or the largest angle
// so far; otherwise (false) the caller measures the angles with atan2 as before.
class AngleBins {
 public:
  AngleBins(const Histogram& lo, const Histogram& hi) : lo_(edges(lo)), hi_(edges(hi)) {}
  bool fast(Point2 a, Point2 b, Point2 c, double cross, QualityReport& r) {
    const Point2 ab = b - a, bc = c - b, ca = a - c;
    const double l2 = std::max({norm2(ab), norm2(bc), norm2(ca)});
    const double acr = std::fabs(cross);
    if (!(acr >= 1e-3 * l2) || !(l2 < kInf)) return false;  // slivers, degenerate, NaN, inf
    const double d0 = -dot(ab, ca), d1 = -dot(bc, ab), d2 = -dot(ca, bc);  // at a, b, c
    const double dmax = std::max({d0, d1, d2}), dmin = std::min({d0, d1, d2});
    const double tol = 1e-9 * l2;
    std::size_t bmin, bmax;
    if (!bin(lo_, dmax, acr, tol, bmin) || !bin(hi_, dmin, acr, tol, bmax)) return false;
    // Possibly a new extreme: the angles with atan2, as the slow path would.
    if (!r.min_angle_deg || !r.max_angle_deg || dmax >= acr * cot_min_ - tol || dmin <= acr * cot_max_ + tol) {
      const double ang[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
      update(r, std::min({ang[0], ang[1], ang[2]}), std::max({ang[0], ang[1], ang[2]}));
    }
    ++r.min_angle_histogram.counts[bmin];
    ++r.max_angle_histogram.counts[bmax];
    return true;
  }
  void update(QualityReport& r, double amin, double amax) {
    if (!r.min_angle_deg || amin < *r.min_angle_deg) {
      r.min_angle_deg = amin;
      cot_min_ = cot_deg(amin);
    }
    if (!r.max_angle_deg || amax > *r.max_angle_deg) {
      r.max_angle_deg = amax;
      cot_max_ = cot_deg(amax);
    }
  }

 private:
  struct Edges {
    std::vector<double> cot;  // cot of the inner bin edges lo + k*width, k = 1..n-1
    bool ok = false;          // edges strictly inside (0, 180) deg
  };
  static double cot_deg(double deg) {
    if (!(deg > 0)) return kInf;
    if (!(deg < 180)) return -kInf;
    return std::cos(deg / kDeg) / std::sin(deg / kDeg);
  }
  static Edges edges(const Histogram& h) {
    Edges e;
    e.ok = h.counts.size() >= 1 && h.width > 0;
    for (std::size_t k = 1; e.ok && k < h.counts.size(); ++k) {
      const double phi = h.lo + static_cast<double>(k) * h.width;
      if (!(phi > 1 && phi < 179)) e.ok = false;
      e.cot.push_back(cot_deg(phi));
    }
    return e;
  }
  // The bin of the angle with dot product d: the number of inner edges phi_k <= t (the first and
  // last bins take the values outside, as Histogram::add). False when a comparison is unclear.
  static bool bin(const Edges& e, double d, double acr, double tol, std::size_t& out) {
    if (!e.ok) return false;
    std::size_t k = 0;
    for (; k < e.cot.size(); ++k) {  // d - acr cot(phi_k) increases with k; <= 0 means t >= phi_k
      const double g = d - acr * e.cot[k];
      if (std::fabs(g) <= tol) return false;
      if (g > 0) break;
    }
    out = k;
    return true;
  }
  Edges lo_, hi_;
  double cot_min_ = kInf, cot_max_ = -kInf;
};

bool usable_spacing(double v) { return std::isfinite(v) && v > 0; }

}  // namespace

void Histogram::add(double v) {
  if (counts.empty()) return;
  double b = std::floor((v - lo) / width);
  if (!(b >= 0)) b = 0;  // also catches NaN
  std::size_t i = b >= static_cast<double>(counts.size()) ? counts.size() - 1 : static_cast<std::size_t>(b);
  ++counts[i];
}

Guarantees compute_guarantees(double alpha, double bound_B) {
  Guarantees g;
  if (!std::isfinite(alpha) || alpha < 0) {
    g.note = "no guarantee: the Lipschitz constant alpha of f is unknown";
    return g;
  }
  if (!std::isfinite(bound_B) || bound_B <= 0) {
    g.note = "no guarantee: the bound B must be positive";
    return g;
  }
  const double ab = alpha * bound_B;
  if (ab >= 1) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "no guarantee: alpha*B = %.6g >= 1 (Section 4 requires B < 1/alpha)", ab);
    g.note = buf;
    return g;
  }
  const double s = 2.0 * std::sqrt(2.0) + 3.0 * ab;
  g.valid = true;
  g.beta = bound_B / s;
  g.R_over_l_max = s / (2.0 * (1.0 - ab));
  g.min_angle_deg = std::asin((1.0 - ab) / s) * kDeg;
  g.nn_over_f_min = 2.0 * g.beta / (1.0 + alpha * g.beta);
  g.el_over_f_max = 2.0 * bound_B / (1.0 + ab);
  g.el_over_f_max_corrected = 2.0 * bound_B / (1.0 - ab);
  g.note = "2D, beta = B/(2*sqrt(2)+3*alpha*B), assuming beta <= D/(2+alpha*D) (Section 4)";
  return g;
}

std::vector<TheoremCheck> theorem_checks(const QualityReport& r) {
  std::vector<TheoremCheck> rows;
  auto add = [&](const char* key, const char* label, bool upper, double bound, std::optional<double> meas,
                 bool counts = true) {
    std::optional<bool> holds;
    if (meas) holds = upper ? *meas <= bound : *meas >= bound;  // NaN measured: false
    rows.push_back({key, label, upper, bound, meas, holds, counts});
  };
  // The refiner's invariant, the hypothesis of every theorem below (needs f).
  if (r.max_R_over_f) add("fdr_R_over_f_max", "R/f(c) max (FDR, B)", true, r.bound_B, r.max_R_over_f);
  const Guarantees& g = r.guarantees;
  if (!g.valid) return rows;
  add("theorem_4_3_R_over_l_max", "R/l max (Thm 4.3)", true, g.R_over_l_max, r.max_radius_edge);
  add("theorem_4_3_min_angle_deg", "min angle deg", false, g.min_angle_deg, r.min_angle_deg);
  add("theorem_4_4_nn_over_f_min", "nn/f min (Thm 4.4)", false, g.nn_over_f_min, r.nn_over_f_min);
  add("theorem_4_5_el_over_f_max", "el/f max (Thm 4.5)", true, g.el_over_f_max, r.el_over_f_max, false);
  add("theorem_4_5_corrected_el_over_f_max", "el/f max (4.5 fixed)", true, g.el_over_f_max_corrected, r.el_over_f_max);
  return rows;
}

bool guarantees_hold(const QualityReport& r) {
  if (!r.guarantees.valid) return false;
  for (const auto& c : theorem_checks(r))
    if (c.counts && c.holds && !*c.holds) return false;
  return true;
}

std::vector<double> nearest_neighbour_distances(const std::vector<Point2>& pts) {
  std::vector<double> nn(pts.size(), kInf);
  if (pts.size() < 2) return nn;
  const KdTree tree(pts);
  for (std::size_t k = 0; k < tree.size(); ++k) nn[tree.id_at(k)] = std::sqrt(tree.nearest_sq_at(k));
  return nn;
}

namespace {
// Same values as nearest_neighbour_distances(m.vertices), faster on a mesh. With the mesher's
// adjacency (m.neighbours) a walk over the mesh from each vertex (mesh_adjacency.hpp); else every
// mesh edge gives an upper bound (the squared length of the nearest edge, computed exactly as the
// tree computes distances), so each tree query only visits the few nodes closer than that.
std::vector<double> mesh_nearest_neighbour_distances(const mesh::MeshView& m, unsigned threads,
                                                     OrthogonalityStats* ortho) {
  const std::vector<Point2>& p = m.vertices;
  bool ids_ok = true;
  for (const auto& tr : m.triangles)
    if (tr[0] >= p.size() || tr[1] >= p.size() || tr[2] >= p.size()) ids_ok = false;
  if (ids_ok && m.neighbours.size() == 3 * m.triangles.size() && p.size() >= 2) {
    // The mesher's own triangulation: one pass for the orthogonality and the walk's bounds, then
    // the walk (exact, see mesh_adjacency.hpp).
    MeshWalkPrep prep;
    *ortho = compute_orthogonality(m, m.neighbours, &prep);
    std::vector<double> nn = mesh_nearest_neighbour_sq(m, m.neighbours, threads, &prep);
    if (!nn.empty()) {
      for (double& d : nn) d = std::sqrt(d);
      return nn;
    }
  } else {
    *ortho = compute_orthogonality(m, threads);
  }
  std::vector<double> nn(p.size(), kInf);
  if (p.size() < 2) return nn;
  for (const auto& tri : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const Index a = tri[k], b = tri[(k + 1) % 3];
      if (a == b || a >= p.size() || b >= p.size()) continue;
      nn[a] = std::min(nn[a], norm2(p[b] - p[a]));
      nn[b] = std::min(nn[b], norm2(p[a] - p[b]));
    }
  const KdTree tree(p);
  for (std::size_t k = 0; k < tree.size(); ++k) {
    const Index i = tree.id_at(k);
    nn[i] = std::sqrt(tree.nearest_sq_at(k, nn[i]));
  }
  return nn;
}
}  // namespace

QualityReport compute_quality(const mesh::MeshView& m, const sizing::SizingField* f, double bound_B,
                              double alpha, const RunInfo& run, TriangleValues* per_triangle,
                              const std::vector<double>* f_at_vertices, std::vector<double>* fill_f_at_vertices) {
  QualityReport r;
  r.vertices = m.num_vertices();
  r.triangles = m.num_triangles();
  r.bound_B = bound_B;
  // An unknown alpha (negative) falls back to the field's own Lipschitz constant, if it knows one.
  if (!(alpha >= 0) && f != nullptr && f->lipschitz() >= 0) alpha = f->lipschitz();
  r.alpha = alpha;
  r.spacing = f ? f->describe() : (!run.spacing.empty() ? run.spacing : std::string("none"));
  r.guarantees = compute_guarantees(alpha, bound_B);
  r.run = run;

  const std::size_t nv = m.num_vertices();
  // Orthogonality and nearest neighbours do not need f: with a second thread they are measured
  // while the triangles are (same values either way).
  std::vector<double> nn;
  std::exception_ptr side_error;
  const bool two = max_threads() > 1 && nv >= 4096;
  auto side = [&](unsigned threads) {
    try {
      nn = mesh_nearest_neighbour_distances(m, threads, &r.orthogonality);
    } catch (...) {
      side_error = std::current_exception();
    }
  };
  std::thread side_thread;
  if (two) side_thread = std::thread(side, 1u);
  struct Join {
    std::thread& t;
    ~Join() { if (t.joinable()) t.join(); }
  } join_side{side_thread};
  if (f && fill_f_at_vertices) {
    fill_f_at_vertices->resize(nv);
    for (std::size_t i = 0; i < nv; ++i) (*fill_f_at_vertices)[i] = (*f)(m.vertices[i]);
    f_at_vertices = fill_f_at_vertices;
  }
  std::vector<double> el(nv, 0.0);  // longest edge of the triangles around each vertex
  CompensatedSum area, r_over_f_sum;
  std::size_t r_over_f_count = 0;
  if (f) r.bad_triangles = 0;
  if (per_triangle) {
    per_triangle->area.assign(m.triangles.size(), 0.0);
    per_triangle->min_angle_deg.assign(m.triangles.size(), 0.0);
    if (f) per_triangle->r_over_f.assign(m.triangles.size(), kInf);
    else per_triangle->r_over_f.clear();
  }

  AngleBins angles(r.min_angle_histogram, r.max_angle_histogram);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (t + 8 < m.triangles.size())  // corners are scattered in memory: fetch them ahead
      for (Index v : m.triangles[t + 8])
        if (v < nv) {
          __builtin_prefetch(&m.vertices[v]);
          __builtin_prefetch(&el[v], 1);
        }
    const auto& tri = m.triangles[t];
    for (int k = 0; k < 3; ++k) {
      if (tri[k] >= nv) {
        throw Error(ExitCode::kInternal, "quality: triangle " + std::to_string(t) + " references vertex " +
                                             std::to_string(tri[k]) + " but the mesh has " +
                                             std::to_string(nv) + " vertices");
      }
    }
    const Point2 a = m.vertices[tri[0]], b = m.vertices[tri[1]], c = m.vertices[tri[2]];
    const int o = predicates::orient2d(a, b, c);
    if (o == 0) ++r.degenerate_triangles;
    if (o < 0) ++r.inverted_triangles;

    const Point2 d = b - a, e = c - a;
    const double cr = d.x * e.y - d.y * e.x;  // twice the signed area
    area.add(0.5 * cr);

    const double la = dist(b, c), lb = dist(c, a), lc = dist(a, b);
    const double lmin = std::min({la, lb, lc}), lmax = std::max({la, lb, lc});
    for (Index v : tri) el[v] = std::max(el[v], lmax);

    if (per_triangle) per_triangle->area[t] = 0.5 * cr;
    if (per_triangle || !angles.fast(a, b, c, cr, r)) {  // the angles themselves (atan2)
      const double ang[3] = {angle_at(a, b, c), angle_at(b, c, a), angle_at(c, a, b)};
      const double amin = std::min({ang[0], ang[1], ang[2]});
      if (per_triangle) per_triangle->min_angle_deg[t] = amin;
      const double amax = std::max({ang[0], ang[1], ang[2]});
      angles.update(r, amin, amax);
      r.min_angle_histogram.add(amin);
      r.max_angle_histogram.add(amax);
    }

    // Circumcenter relative to a; a zero determinant means collinear corners (R infinite).
    double radius = kInf;
    Point2 center{};
    const double den = 2.0 * cr;
    if (o != 0 && den != 0) {
      const double d2 = norm2(d), e2 = norm2(e);
      const Point2 u{(e.y * d2 - d.y * e2) / den, (d.x * e2 - e.x * d2) / den};
      radius = std::sqrt(norm2(u));
      center = a + u;
    }
    update_max(r.max_radius_edge, lmin > 0 ? radius / lmin : kInf);

    if (f) {
      double ratio = kInf;
      if (std::isfinite(radius)) {
        const double fc = (*f)(center);
        if (per_triangle) per_triangle->r_over_f[t] = radius / fc;
        if (!usable_spacing(fc)) { ++r.spacing_invalid; continue; }
        ratio = radius / fc;
      }
      update_max(r.max_R_over_f, ratio);
      r_over_f_sum.add(ratio);
      ++r_over_f_count;
      if (ratio > bound_B) ++*r.bad_triangles;
    }
  }
  r.area = area.value();
  if (r_over_f_count > 0) r.mean_R_over_f = r_over_f_sum.value() / static_cast<double>(r_over_f_count);

  // Vertex metrics: nn(p) is exact over all vertices (not only mesh neighbours).
  if (side_thread.joinable()) side_thread.join();
  else side(1);
  if (side_error) std::rethrow_exception(side_error);
  if (nv >= 2) r.nn_min = *std::min_element(nn.begin(), nn.end());
  const bool have_vertex_f = f != nullptr || m.f.size() == nv;
  if (!have_vertex_f || nv < 2) return r;

  // Which vertices are corners of some triangle: el(p) is only defined there.
  std::vector<char> used(nv, 0);
  for (const auto& tri : m.triangles) for (Index v : tri) used[v] = 1;

  std::vector<double> conf;
  conf.reserve(nv);
  CompensatedSum conf_sum;
  for (std::size_t i = 0; i < nv; ++i) {
    const double fp = !f ? m.f[i] : f_at_vertices && f_at_vertices->size() == nv ? (*f_at_vertices)[i] : (*f)(m.vertices[i]);
    if (!usable_spacing(fp)) { ++r.spacing_invalid; continue; }
    const double q = nn[i] / fp;
    const double ci = std::min(q, fp / nn[i]);  // nn = 0 (duplicate point) gives 0
    conf.push_back(ci);
    conf_sum.add(ci);
    r.conformity_histogram.add(ci);
    update_min(r.nn_over_f_min, q);
    if (used[i]) update_max(r.el_over_f_max, el[i] / fp);
  }
  if (!conf.empty()) {
    r.conformity_mean = conf_sum.value() / static_cast<double>(conf.size());
    // p05 by nearest rank: the smallest value with at least 5 % of the vertices at or below it.
    const std::size_t rank = static_cast<std::size_t>(std::ceil(0.05 * static_cast<double>(conf.size())));
    const std::size_t k = rank == 0 ? 0 : rank - 1;
    std::nth_element(conf.begin(), conf.begin() + k, conf.end());
    r.conformity_p05 = conf[k];
    r.conformity_min = *std::min_element(conf.begin(), conf.end());
  }
  return r;
}

// ---------------------------------------------------------------- writers

namespace {

using Json = nlohmann::ordered_json;
constexpr const char* kRepairsPlaceholder = "\x01" "fdrmesh repairs" "\x01";

Json num(std::optional<double> v) {
  if (!v || !std::isfinite(*v)) return nullptr;
  return *v;
}
Json num(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }
Json count(std::optional<std::size_t> v) { return v ? Json(*v) : Json(nullptr); }

Json histogram_json(const Histogram& h) {
  Json j;
  // Integral widths (5 degrees) are written as integers: {"bin_deg": 5}.
  if (h.width == std::floor(h.width)) j["bin_deg"] = static_cast<long long>(h.width);
  else j["bin_deg"] = h.width;
  j["from_deg"] = h.lo;
  j["counts"] = h.counts;
  return j;
}

}  // namespace

void write_json(const QualityReport& r, std::ostream& out) {
  Json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["min_angle_deg"] = num(r.min_angle_deg);
  j["max_angle_deg"] = num(r.max_angle_deg);
  j["max_radius_edge"] = num(r.max_radius_edge);
  j["max_R_over_f"] = num(r.max_R_over_f);
  j["mean_R_over_f"] = num(r.mean_R_over_f);
  j["bad_triangles"] = count(r.bad_triangles);
  j["exempt_small_angle_triangles"] = r.run.exempt_small_angle_triangles;
  j["conformity"] = {{"min", num(r.conformity_min)}, {"mean", num(r.conformity_mean)},
                     {"p05", num(r.conformity_p05)}};
  j["el_over_f_max"] = num(r.el_over_f_max);
  if (r.vertical_error_max_m) {
    j["vertical_error_max_m"] = num(r.vertical_error_max_m);
    j["vertical_error_rms_m"] = num(r.vertical_error_rms_m);
  }
  j["nn_over_f_min"] = num(r.nn_over_f_min);
  j["orthogonality"] = {{"max", num(r.orthogonality.orthogonality_max)}, {"p99", num(r.orthogonality.orthogonality_p99)}};
  j["smoothness"] = {{"max", num(r.orthogonality.smoothness_max)}, {"p99", num(r.orthogonality.smoothness_p99)}};
  j["min_angle_histogram"] = histogram_json(r.min_angle_histogram);
  j["max_angle_histogram"] = histogram_json(r.max_angle_histogram);
  {
    Json h;
    h["bin"] = r.conformity_histogram.width;
    h["counts"] = r.conformity_histogram.counts;
    j["conformity_histogram"] = h;
  }
  j["timings_s"] = {{"cdt", num(r.run.cdt_s)}, {"refine", num(r.run.refine_s)},
                    {"write", num(r.run.write_s)}, {"total", num(r.run.total_s)}};
  j["peak_rss_mb"] = num(r.run.peak_rss_mb);
  j["predicate_calls"] = {{"filtered", r.run.predicate_filtered}, {"exact", r.run.predicate_exact}};
  j["steiner_points"] = {{"segment", r.run.steiner_segment}, {"interior", r.run.steiner_interior},
                         {"total", r.run.steiner_total()}};
  j["area"] = num(r.area);
  j["degenerate_triangles"] = r.degenerate_triangles;
  j["inverted_triangles"] = r.inverted_triangles;
  j["nn_min"] = num(r.nn_min);
  j["spacing_invalid_evaluations"] = r.spacing_invalid;
  j["bound_B"] = num(r.bound_B);
  j["alpha"] = r.alpha >= 0 ? num(r.alpha) : Json(nullptr);
  j["spacing"] = r.spacing;
  j["input_file"] = r.run.input_file;
  j["min_angle_option_deg"] = num(r.run.min_angle_option_deg);
  // The repairs (up to hundreds of thousands on real coasts) are streamed below instead of held as
  // one document: a placeholder marks their place.
  j["repairs"] = kRepairsPlaceholder;
  const Guarantees& g = r.guarantees;
  auto gv = [&](double v) { return g.valid ? num(v) : Json(nullptr); };
  j["guarantees"] = {{"beta", gv(g.beta)},
                     {"R_over_l_max", gv(g.R_over_l_max)},
                     {"min_angle_deg", gv(g.min_angle_deg)},
                     {"nn_over_f_min", gv(g.nn_over_f_min)},
                     {"el_over_f_max", gv(g.el_over_f_max)},
                     {"el_over_f_max_corrected", gv(g.el_over_f_max_corrected)},
                     {"valid", guarantees_hold(r)},  // applicable and every counted bound holds
                     {"applicable", g.valid},
                     {"note", g.note}};
  for (const auto& c : theorem_checks(r))
    j["guarantees"][c.key] = {{"relation", c.upper ? "<=" : ">="}, {"bound", num(c.bound)},
                              {"measured", num(c.measured)},
                              {"holds", c.holds ? Json(*c.holds) : Json(nullptr)},
                              {"counts_for_valid", c.counts}};
  j["measured"] = {{"R_over_l_max", num(r.max_radius_edge)},
                   {"min_angle_deg", num(r.min_angle_deg)},
                   {"nn_over_f_min", num(r.nn_over_f_min)},
                   {"el_over_f_max", num(r.el_over_f_max)}};
  if (r.model_ready) j["model_ready"] = model_ready_json(*r.model_ready);
  const std::string text = j.dump(2);
  const std::string mark = Json(kRepairsPlaceholder).dump();
  const std::size_t at = text.find(mark);
  if (at == std::string::npos) throw Error(ExitCode::kInternal, "quality: report JSON without its repairs");
  out.write(text.data(), static_cast<std::streamsize>(at));
  // Pretty printing nests: a repair object printed on its own with indent 2, its lines after
  // the first shifted by its depth (4 spaces), is the text the whole document would hold.
  if (r.repairs.empty()) {
    out << "[]";
  } else {
    out << "[\n";
    std::string obj;
    for (std::size_t i = 0; i < r.repairs.size(); ++i) {
      const auto& rp = r.repairs[i];
      obj = Json({{"kind", rp.kind}, {"x", num(rp.x)}, {"y", num(rp.y)}, {"ids", rp.ids}, {"reason", rp.reason}}).dump(2);
      out << "    ";
      std::size_t from = 0;
      for (std::size_t nl = obj.find('\n'); nl != std::string::npos; nl = obj.find('\n', from)) {
        out.write(obj.data() + from, static_cast<std::streamsize>(nl + 1 - from));
        out << "    ";
        from = nl + 1;
      }
      out.write(obj.data() + from, static_cast<std::streamsize>(obj.size() - from));
      out << (i + 1 < r.repairs.size() ? ",\n" : "\n");
    }
    out << "  ]";
  }
  out.write(text.data() + at + mark.size(), static_cast<std::streamsize>(text.size() - at - mark.size()));
  out << '\n';
}

namespace {

std::string fmt(std::optional<double> v, const char* spec = "%.6g") {
  if (!v) return "n/a";
  if (std::isinf(*v)) return *v > 0 ? "inf" : "-inf";
  if (std::isnan(*v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, spec, *v);
  return buf;
}

void line(std::ostream& out, const char* label, const std::string& value) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "  %-30s: ", label);
  out << buf << value << '\n';
}

}  // namespace

void write_text(const QualityReport& r, std::ostream& out) {
  out << "Mesh quality\n";
  if (!r.run.input_file.empty()) line(out, "input", r.run.input_file);
  line(out, "spacing f", r.spacing);
  line(out, "vertices / triangles", std::to_string(r.vertices) + " / " + std::to_string(r.triangles));
  line(out, "area", fmt(r.area, "%.10g"));
  if (r.degenerate_triangles || r.inverted_triangles) {
    line(out, "degenerate / inverted", std::to_string(r.degenerate_triangles) + " / " +
                                           std::to_string(r.inverted_triangles));
  }
  line(out, "angle min / max (deg)", fmt(r.min_angle_deg, "%.4f") + " / " + fmt(r.max_angle_deg, "%.4f"));
  line(out, "max radius-edge R/l", fmt(r.max_radius_edge, "%.4f"));
  line(out, "orthogonality max / p99", fmt(r.orthogonality.orthogonality_max, "%.3g") + " / " +
                                           fmt(r.orthogonality.orthogonality_p99, "%.3g"));
  line(out, "smoothness max / p99", fmt(r.orthogonality.smoothness_max, "%.4f") + " / " +
                                        fmt(r.orthogonality.smoothness_p99, "%.4f"));
  if (r.max_R_over_f) {
    line(out, "R/f(c) max / mean", fmt(r.max_R_over_f, "%.4f") + " / " + fmt(r.mean_R_over_f, "%.4f"));
    line(out, "bad triangles (R/f(c) > B)", std::to_string(*r.bad_triangles) + "  (B = " + fmt(r.bound_B) + ")");
  }
  if (r.conformity_min) {
    line(out, "conformity min / mean / p05", fmt(r.conformity_min, "%.4f") + " / " +
                                                 fmt(r.conformity_mean, "%.4f") + " / " +
                                                 fmt(r.conformity_p05, "%.4f"));
    line(out, "nn/f min, el/f max", fmt(r.nn_over_f_min, "%.4f") + ", " + fmt(r.el_over_f_max, "%.4f"));
    if (r.vertical_error_max_m)
      line(out, "TIN vs DEM error max / RMS (m)",
           fmt(r.vertical_error_max_m, "%.3f") + " / " + fmt(r.vertical_error_rms_m, "%.3f"));
  }
  if (r.spacing_invalid) line(out, "f <= 0 or not finite (skipped)", std::to_string(r.spacing_invalid));
  line(out, "exempt small-angle triangles", std::to_string(r.run.exempt_small_angle_triangles));
  line(out, "Steiner points seg/interior", std::to_string(r.run.steiner_segment) + " / " +
                                                 std::to_string(r.run.steiner_interior));
  line(out, "time s cdt/refine/write/total",
       fmt(r.run.cdt_s, "%.3f") + " / " + fmt(r.run.refine_s, "%.3f") + " / " + fmt(r.run.write_s, "%.3f") +
           " / " + fmt(r.run.total_s, "%.3f"));
  line(out, "peak RSS (MB)", fmt(r.run.peak_rss_mb, "%.1f"));
  line(out, "predicates filtered / exact",
       std::to_string(r.run.predicate_filtered) + " / " + std::to_string(r.run.predicate_exact));

  // Triangle-style histogram: min angles with a bar, max angles as a compact second column.
  out << "\n  Min-angle histogram" << std::string(32, ' ') << "| Max-angle histogram\n";
  std::uint64_t peak = 1;
  for (auto c : r.min_angle_histogram.counts) peak = std::max(peak, c);
  const auto& hmin = r.min_angle_histogram;
  const auto& hmax = r.max_angle_histogram;
  const std::size_t rows = std::max(hmin.counts.size(), (hmax.counts.size() + 1) / 2);
  for (std::size_t i = 0; i < rows; ++i) {
    char left[80] = "";
    if (i < hmin.counts.size()) {
      const double lo = hmin.lo + static_cast<double>(i) * hmin.width;
      const int bar = static_cast<int>(std::lround(24.0 * static_cast<double>(hmin.counts[i]) /
                                                   static_cast<double>(peak)));
      std::snprintf(left, sizeof left, "  %3.0f - %3.0f deg: %10llu %-24s", lo, lo + hmin.width,
                    static_cast<unsigned long long>(hmin.counts[i]), std::string(bar, '#').c_str());
    }
    out << left;
    // Two max-angle bins per row keep the table as tall as the min-angle one.
    for (std::size_t k = 2 * i; k < 2 * i + 2 && k < hmax.counts.size(); ++k) {
      const double lo = hmax.lo + static_cast<double>(k) * hmax.width;
      char right[64];
      std::snprintf(right, sizeof right, " | %3.0f-%3.0f: %9llu", lo, lo + hmax.width,
                    static_cast<unsigned long long>(hmax.counts[k]));
      out << right;
    }
    out << '\n';
  }

  if (r.model_ready) write_model_ready_text(*r.model_ready, out);

  const Guarantees& g = r.guarantees;
  out << "\n  Theory vs measured (alpha = " << (r.alpha >= 0 ? fmt(r.alpha) : std::string("unknown"))
      << ", B = " << fmt(r.bound_B) << ")\n";
  if (!g.valid) out << "    " << g.note << '\n';
  else out << "    beta = " << fmt(g.beta, "%.6f") << "; " << g.note << '\n';
  const auto checks = theorem_checks(r);
  if (!checks.empty()) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", "quantity", "", "theory", "measured", "holds");
    out << buf;
    for (const auto& c : checks) {
      const char* ok = !c.holds ? "n/a" : *c.holds ? "yes" : (c.counts ? "NO" : "no (printed bound)");
      std::snprintf(buf, sizeof buf, "    %-22s %-4s %12s %12s  %s\n", c.label, c.upper ? "<=" : ">=",
                    fmt(c.bound, "%.4f").c_str(), fmt(c.measured, "%.4f").c_str(), ok);
      out << buf;
    }
    if (g.valid) out << "    all bounds hold: " << (guarantees_hold(r) ? "yes" : "NO") << '\n';
  }
}

void write_json_file(const QualityReport& r, const std::string& path) {
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    if (!out) throw Error(ExitCode::kOutputError, path + ": cannot write");
    write_json(r, out);
    out.flush();
    if (!out) {
      out.close();
      std::remove(tmp.c_str());
      throw Error(ExitCode::kOutputError, path + ": write failed");
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::kOutputError, path + ": cannot rename the temporary file");
  }
}

}  // namespace fdr::quality
