// Raster sizing rules: distance to shore (BVH), distance/slope/wavelength/curvature rules,
// cell-wise min and clamp.
#include "sizing/raster_rules.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>

#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "sizing/distance_transform.hpp"
#include "sizing/fields.hpp"
#include "base/parallel.hpp"

namespace fdr::sizing {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// g's geometry with zero values (without copying g's values first).
Grid like_grid(const Grid& g) {
  Grid out;
  out.nx = g.nx; out.ny = g.ny; out.x0 = g.x0; out.y0 = g.y0; out.dx = g.dx; out.dy = g.dy;
  out.v.assign(g.v.size(), 0.0);
  return out;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw Error(ExitCode::kUsage, what);
}

// ---------------------------------------------------------------- distance to shore

struct Seg {
  Point2 a, b;
  Point2 d;    // b - a
  double inv;  // 1 / |b - a|^2, 0 for a point
};

Seg make_seg(Point2 a, Point2 b) {
  const Point2 d = b - a;
  const double dd = dot(d, d);
  return {a, b, d, dd > 0 ? 1.0 / dd : 0.0};
}

// Squared distance from p to the segment: the nearest point a + t d, t = clamp((p - a).d / |d|^2).
// (The tests' brute force uses this same arithmetic.)
double seg_dist2(Point2 p, const Seg& s) {
  const double t = std::min(std::max(dot(p - s.a, s.d) * s.inv, 0.0), 1.0);  // = std::clamp, without branches
  return norm2(p - (s.a + t * s.d));
}

struct BNode {
  double lox, loy, hix, hiy;
  std::uint32_t first, count;  // leaf: segments [first, first+count); inner: count = 0, children first, first+1
};

double box_dist2(const BNode& n, Point2 p) {
  const double ex = std::max({n.lox - p.x, 0.0, p.x - n.hix});
  const double ey = std::max({n.loy - p.y, 0.0, p.y - n.hiy});
  return ex * ex + ey * ey;
}

class SegmentBvh {
 public:
  explicit SegmentBvh(std::vector<Seg> segs) : segs_(std::move(segs)) {
    nodes_.reserve(2 * segs_.size() / kLeaf + 2);
    nodes_.push_back({});
    build(0, 0, static_cast<std::uint32_t>(segs_.size()));
  }

  // Nearest segment to p; `hint` seeds the bound (any segment index). Returns squared distance.
  double nearest(Point2 p, std::uint32_t& hint) const {
    double best = seg_dist2(p, segs_[hint]);
    // Slack on pruning: a segment's rounded distance may undercut its box bound by an ulp,
    // and the answer must equal a brute-force minimum exactly.
    auto bound = [&] { return best * (1.0 + 1e-9); };
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const BNode& n = nodes_[stack[--top]];
      if (box_dist2(n, p) > bound()) continue;
      if (n.count > 0) {
        for (std::uint32_t k = n.first; k < n.first + n.count; ++k) {
          const double d = seg_dist2(p, segs_[k]);
          if (d < best) { best = d; hint = k; }
        }
        continue;
      }
      // Push the farther child first so the nearer one is searched first.
      const std::uint32_t c0 = n.first, c1 = n.first + 1;
      const double d0 = box_dist2(nodes_[c0], p), d1 = box_dist2(nodes_[c1], p);
      if (d0 <= d1) { stack[top++] = c1; stack[top++] = c0; }
      else { stack[top++] = c0; stack[top++] = c1; }
    }
    return best;
  }

 private:
  static constexpr std::uint32_t kLeaf = 4;

  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end) {
    BNode n{kInf, kInf, -kInf, -kInf, begin, end - begin};
    double clox = kInf, cloy = kInf, chix = -kInf, chiy = -kInf;
    for (std::uint32_t k = begin; k < end; ++k) {
      const Seg& s = segs_[k];
      n.lox = std::min({n.lox, s.a.x, s.b.x}); n.hix = std::max({n.hix, s.a.x, s.b.x});
      n.loy = std::min({n.loy, s.a.y, s.b.y}); n.hiy = std::max({n.hiy, s.a.y, s.b.y});
      const double mx = 0.5 * (s.a.x + s.b.x), my = 0.5 * (s.a.y + s.b.y);
      clox = std::min(clox, mx); chix = std::max(chix, mx);
      cloy = std::min(cloy, my); chiy = std::max(chiy, my);
    }
    if (end - begin <= kLeaf) { nodes_[node] = n; return; }
    // Median split on the longer axis of the midpoints' box.
    const bool by_x = (chix - clox) >= (chiy - cloy);
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(segs_.begin() + begin, segs_.begin() + mid, segs_.begin() + end, [by_x](const Seg& u, const Seg& v) {
      return by_x ? (u.a.x + u.b.x) < (v.a.x + v.b.x) : (u.a.y + u.b.y) < (v.a.y + v.b.y);
    });
    const auto child = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    nodes_.push_back({});
    n.first = child;
    n.count = 0;
    nodes_[node] = n;
    build(child, begin, mid);
    build(child + 1, mid, end);
  }

  std::vector<Seg> segs_;
  std::vector<BNode> nodes_;
};

// ---------------------------------------------------------------- finite differences

bool valid(const Grid& g, std::int64_t i, std::int64_t j) {
  return i >= 0 && j >= 0 && i < static_cast<std::int64_t>(g.nx) && j < static_cast<std::int64_t>(g.ny) &&
         !std::isnan(g.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j)));
}
double val(const Grid& g, std::int64_t i, std::int64_t j) {
  return g.at(static_cast<std::size_t>(i), static_cast<std::size_t>(j));
}

// First derivative along (di, dj) (a unit index step of length h): central when both
// neighbours exist, one-sided otherwise, 0 without neighbours.
double first_diff(const Grid& g, std::int64_t i, std::int64_t j, int di, int dj, double h) {
  const bool m = valid(g, i - di, j - dj), p = valid(g, i + di, j + dj);
  const double c = val(g, i, j);
  if (m && p) return (val(g, i + di, j + dj) - val(g, i - di, j - dj)) / (2 * h);
  if (p) return (val(g, i + di, j + dj) - c) / h;
  if (m) return (c - val(g, i - di, j - dj)) / h;
  return 0.0;
}

// Second derivative along (di, dj): central, else the stencil shifted by one step forward or
// backward (exact for quadratics), else 0.
double second_diff(const Grid& g, std::int64_t i, std::int64_t j, int di, int dj, double h) {
  auto at = [&](int k) { return val(g, i + k * di, j + k * dj); };
  auto ok = [&](int k) { return valid(g, i + k * di, j + k * dj); };
  const double h2 = h * h;
  if (ok(-1) && ok(1)) return (at(-1) - 2 * at(0) + at(1)) / h2;
  if (ok(1) && ok(2)) return (at(0) - 2 * at(1) + at(2)) / h2;
  if (ok(-1) && ok(-2)) return (at(-2) - 2 * at(-1) + at(0)) / h2;
  return 0.0;
}

// Mixed derivative on the widest available stencil inside the grid; 0 if a corner is missing.
double mixed_diff(const Grid& g, std::int64_t i, std::int64_t j) {
  const std::int64_t ia = std::max<std::int64_t>(i - 1, 0), ib = std::min<std::int64_t>(i + 1, g.nx - 1);
  const std::int64_t ja = std::max<std::int64_t>(j - 1, 0), jb = std::min<std::int64_t>(j + 1, g.ny - 1);
  if (ia == ib || ja == jb) return 0.0;
  if (!valid(g, ia, ja) || !valid(g, ia, jb) || !valid(g, ib, ja) || !valid(g, ib, jb)) return 0.0;
  return (val(g, ib, jb) - val(g, ib, ja) - val(g, ia, jb) + val(g, ia, ja)) /
         (static_cast<double>(ib - ia) * g.dx * static_cast<double>(jb - ja) * g.dy);
}

// fn(cell index) for every cell, in row bands on max_threads() threads (cells are independent).
template <class Fn>
void for_cells(const Grid& g, Fn&& fn) {
  parallel_bands(g.ny, [&](std::size_t j0, std::size_t j1) {
    for (std::size_t c = j0 * g.nx; c < j1 * g.nx; ++c) fn(c);
  });
}

void check_grid(const Grid& g, const char* what) {
  if (g.v.size() != g.nx * g.ny || !(g.dx > 0) || !(g.dy > 0))
    throw Error(ExitCode::kInternal, std::string(what) + ": malformed grid (" + std::to_string(g.nx) + " x " +
                                         std::to_string(g.ny) + ", " + std::to_string(g.v.size()) + " values)");
}

}  // namespace

namespace {

// The BVH path: segments reaching outside the grid (never in the pipeline, whose grid covers the
// domain). Exact minimum for every cell.
void distance_bvh(Grid& out, std::vector<Seg> segs) {
  const SegmentBvh bvh(std::move(segs));
  // Why serpentine order: consecutive cells are neighbours, so the previous answer is a
  // tight initial bound and each query prunes almost everything.
  parallel_bands(out.ny, [&](std::size_t j0, std::size_t j1) {
    std::uint32_t hint = 0;
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t k = 0; k < out.nx; ++k) {
        const std::size_t i = (j % 2 == 0) ? k : out.nx - 1 - k;
        out.at(i, j) = std::sqrt(bvh.nearest(out.center(i, j), hint));
      }
  }, 8);
}

// Cells whose closed square meets segment s (a superset: the segment's range in each column
// slab, widened by a millionth of a cell against rounding), as calls visit(cell index).
template <class Visit>
void cells_of_segment(const Grid& g, const Seg& s, Visit&& visit) {
  const double ex = 1e-6 * g.dx, ey = 1e-6 * g.dy;
  const auto nx = static_cast<std::int64_t>(g.nx), ny = static_cast<std::int64_t>(g.ny);
  auto col_of = [&](double x) { return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((x - g.x0) / g.dx)), 0, nx - 1); };
  auto row_of = [&](double y) { return std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor((y - g.y0) / g.dy)), 0, ny - 1); };
  const double xlo = std::min(s.a.x, s.b.x), xhi = std::max(s.a.x, s.b.x);
  const std::int64_t i0 = col_of(xlo - ex), i1 = col_of(xhi + ex);
  const double sx = s.b.x - s.a.x, sy = s.b.y - s.a.y;
  for (std::int64_t i = i0; i <= i1; ++i) {
    // The segment's part inside the slab [xl, xr] of column i (the whole segment when vertical).
    double ylo = std::min(s.a.y, s.b.y), yhi = std::max(s.a.y, s.b.y);
    if (i0 != i1 && sx != 0) {
      const double xl = std::max(xlo, g.x0 + static_cast<double>(i) * g.dx - ex);
      const double xr = std::min(xhi, g.x0 + static_cast<double>(i + 1) * g.dx + ex);
      const double ya = s.a.y + (xl - s.a.x) / sx * sy, yb = s.a.y + (xr - s.a.x) / sx * sy;
      ylo = std::max(ylo, std::min(ya, yb));
      yhi = std::min(yhi, std::max(ya, yb));
      if (ylo > yhi) std::swap(ylo, yhi);
    }
    const std::int64_t j0 = row_of(ylo - ey), j1 = row_of(yhi + ey);
    for (std::int64_t j = j0; j <= j1; ++j) visit(static_cast<std::size_t>(j * nx + i));
  }
}

// Largest distance, in cells of the larger side, within which distance_to_shore is exact.
constexpr double kExactCells = 3.5;

}  // namespace

Grid distance_to_shore(const Grid& like, const std::vector<std::pair<Point2, Point2>>& shore_segments) {
  return distance_to_shore(like, shore_segments, false);
}

Grid distance_to_shore(const Grid& like, const std::vector<std::pair<Point2, Point2>>& shore_segments, bool exact) {
  check_grid(like, "distance_to_shore");
  Grid out = like_grid(like);
  if (shore_segments.empty()) {
    std::fill(out.v.begin(), out.v.end(), kInf);
    return out;
  }
  std::vector<Seg> segs;
  segs.reserve(shore_segments.size());
  Box2 sbox;
  for (std::size_t k = 0; k < shore_segments.size(); ++k) {
    const auto& [a, b] = shore_segments[k];
    if (!std::isfinite(a.x) || !std::isfinite(a.y) || !std::isfinite(b.x) || !std::isfinite(b.y))
      throw Error(ExitCode::kInvalidGeometry, "shore segment " + std::to_string(k) + " (" + format_number(a.x) + ", " +
                                                  format_number(a.y) + ") - (" + format_number(b.x) + ", " +
                                                  format_number(b.y) + ") has a non-finite coordinate");
    segs.push_back(make_seg(a, b));
    sbox.add(a);
    sbox.add(b);
  }
  if (out.v.empty()) return out;
  const Box2 gbox = like.extent();
  if (sbox.lo.x < gbox.lo.x || sbox.lo.y < gbox.lo.y || sbox.hi.x > gbox.hi.x || sbox.hi.y > gbox.hi.y ||
      like.v.size() >= kNoFeature || exact) {
    distance_bvh(out, std::move(segs));
    return out;
  }
  StepLaps lap(debug::Aid::kSizing, "  distance");  // developer aid (base/step_laps.hpp)
  // Segments by cell (compressed rows): every point of a segment lies in a cell that lists it.
  // first[c] counts cell c's segments, then (prefix sums) where its list ends; filling the lists
  // backwards (last segment first) leaves each cell's start there and its list in segment order,
  // with no second array.
  const std::size_t n = out.v.size();
  std::vector<std::uint32_t> first(n + 1, 0);
  std::vector<char> seed(n, 0);
  for (const Seg& s : segs)
    cells_of_segment(like, s, [&](std::size_t c) {
      ++first[c];
      seed[c] = 1;
    });
  for (std::size_t c = 1; c <= n; ++c) first[c] += first[c - 1];
  std::vector<std::uint32_t> by_cell(first[n]);
  for (std::size_t k = segs.size(); k-- > 0;)
    cells_of_segment(like, segs[k], [&](std::size_t c) { by_cell[--first[c]] = static_cast<std::uint32_t>(k); });
  // Chains: segment k continues segment k - 1 when they share that endpoint.
  std::vector<char> joins_prev(segs.size(), 0);
  for (std::size_t k = 1; k < segs.size(); ++k)
    joins_prev[k] = segs[k].a.x == segs[k - 1].b.x && segs[k].a.y == segs[k - 1].b.y;
  std::vector<std::uint32_t> feature;
  lap("cells, seeds");
  nearest_seed(like.nx, like.ny, like.dx, like.dy, seed, feature);
  seed = {};
  lap("nearest seed");
  // Per shore cell, the segment nearest to its centre goes first in its list: where the descent
  // below starts (first of the nearest in list order, so the choice is deterministic).
  parallel_bands(like.ny, [&](std::size_t j0, std::size_t j1) {
    for (std::size_t c = j0 * like.nx; c < j1 * like.nx; ++c) {
      if (first[c + 1] - first[c] < 2) continue;
      const Point2 p = like.center(c % like.nx, c / like.nx);
      double best = kInf;
      std::uint32_t at = first[c];
      for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) {
        const double d = seg_dist2(p, segs[by_cell[k]]);
        if (d < best) { best = d; at = k; }
      }
      std::swap(by_cell[first[c]], by_cell[at]);
    }
  }, 8);
  // Per cell: the segment nearest to the centre of its nearest shore cell, then along its chain
  // while the distance decreases (the nearest shore cell may sit a few cells along a nearly
  // straight coast from the nearest point): d~ >= d. Every shore point at distance d lies in a
  // cell whose centre is within d + dx/2 (d + dy/2) of the cell centre along x (y), so when d~ is
  // at most kExactCells cells the window of cells within d~ + half a cell holds the nearest
  // segment and the minimum over it is exact.
  lap("first per shore cell");
  const double wmax = kExactCells * std::max(like.dx, like.dy);
  const auto nx = static_cast<std::int64_t>(like.nx), ny = static_cast<std::int64_t>(like.ny);
  const std::size_t ns = segs.size();
  // Phase 1 writes each cell's segment over its own feature entry (same cell: in place).
  std::vector<std::uint32_t>& near = feature;
  parallel_bands(like.ny, [&](std::size_t j0, std::size_t j1) {
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t i = 0; i < like.nx; ++i) {
        const Point2 p = like.center(i, j);
        const std::size_t f = feature[j * like.nx + i];
        std::size_t arg = by_cell[first[f]];
        double best = seg_dist2(p, segs[arg]);
        // Descent along the chain, both ways (capped: a chain is at most all segments).
        const std::size_t arg0 = arg;
        for (std::size_t k = arg0, steps = 0; k > 0 && joins_prev[k] && steps < ns; --k, ++steps) {
          const double d = seg_dist2(p, segs[k - 1]);
          if (!(d < best)) break;
          best = d;
          arg = k - 1;
        }
        for (std::size_t k = arg0, steps = 0; k + 1 < ns && joins_prev[k + 1] && steps < ns; ++k, ++steps) {
          const double d = seg_dist2(p, segs[k + 1]);
          if (!(d < best)) break;
          best = d;
          arg = k + 1;
        }
        near[j * like.nx + i] = static_cast<std::uint32_t>(arg);
      }
  }, 8);
  lap("phase 1");
  // Phase 2: the best of the 3 x 3 cells' phase-1 segments (one step of vector propagation: the
  // neighbour may have found a nearer coast), then the exact window near the shore. Reads phase
  // 1 only, so row bands do not interact.
  parallel_bands(like.ny, [&](std::size_t j0, std::size_t j1) {
    for (std::size_t j = j0; j < j1; ++j)
      for (std::size_t i = 0; i < like.nx; ++i) {
        const Point2 p = like.center(i, j);
        const auto ii = static_cast<std::int64_t>(i), jj = static_cast<std::int64_t>(j);
        // Neighbours mostly share their segment: skip repeats of the cell's own and the last one.
        const std::uint32_t own = near[j * like.nx + i];
        double best = seg_dist2(p, segs[own]);
        std::uint32_t last = own;
        const std::size_t ilo = i > 0 ? i - 1 : 0, ihi = i + 1 < like.nx ? i + 1 : i;
        for (std::int64_t b = std::max<std::int64_t>(jj - 1, 0); b <= std::min(jj + 1, ny - 1); ++b) {
          const std::uint32_t* row = &near[static_cast<std::size_t>(b) * like.nx];
          for (std::size_t a = ilo; a <= ihi; ++a) {
            const std::uint32_t k = row[a];
            if (k == own || k == last) continue;
            last = k;
            best = std::min(best, seg_dist2(p, segs[k]));
          }
        }
        const double reach = std::sqrt(best) * (1 + 1e-9);
        if (reach <= wmax) {
          const auto wi = static_cast<std::int64_t>(reach / like.dx + 0.5), wj = static_cast<std::int64_t>(reach / like.dy + 0.5);
          for (std::int64_t b = std::max<std::int64_t>(jj - wj, 0); b <= std::min(jj + wj, ny - 1); ++b) {
            const std::size_t row = static_cast<std::size_t>(b * nx);
            const double ey = std::max(0.0, (static_cast<double>(std::abs(b - jj)) - 0.5) * like.dy);
            for (std::int64_t a = std::max<std::int64_t>(ii - wi, 0); a <= std::min(ii + wi, nx - 1); ++a) {
              const std::size_t c = row + static_cast<std::size_t>(a);
              if (first[c] == first[c + 1]) continue;
              // Skip a cell whose square is already farther than the best (with the BVH's slack:
              // a rounded segment distance may undercut its box bound by an ulp).
              const double ex = std::max(0.0, (static_cast<double>(std::abs(a - ii)) - 0.5) * like.dx);
              if (ex * ex + ey * ey > best * (1.0 + 1e-9)) continue;
              for (std::uint32_t k = first[c]; k < first[c + 1]; ++k) best = std::min(best, seg_dist2(p, segs[by_cell[k]]));
            }
          }
        }
        out.at(i, j) = std::sqrt(best);
      }
  }, 8);
  lap("phase 2");
  return out;
}

Grid rule_distance(const Grid& dist, double hmin, double g) {
  Grid out = dist;
  return rule_distance(std::move(out), hmin, g);
}

Grid rule_distance(Grid&& dist, double hmin, double g) {
  check_grid(dist, "rule_distance");
  require(hmin > 0 && std::isfinite(hmin), "distance rule: hmin must be a positive number, got " + format_number(hmin));
  require(g >= 0 && std::isfinite(g), "distance rule: growth g must be a finite number >= 0, got " + format_number(g));
  Grid out = std::move(dist);
  for_cells(out, [&](std::size_t k) {
    const double d = out.v[k];
    out.v[k] = std::isnan(d) ? kNaN : std::isinf(d) ? (g > 0 ? kInf : hmin) : hmin + g * std::max(d, 0.0);
  });
  return out;
}

Grid rule_slope(const Grid& depth, double slp) {
  check_grid(depth, "rule_slope");
  require(slp > 0 && std::isfinite(slp), "slope rule: slp must be a positive number, got " + format_number(slp));
  Grid out = like_grid(depth);
  const double k = 2.0 * std::numbers::pi / slp;
  parallel_bands(depth.ny, [&](std::size_t j0, std::size_t j1) {
  for (std::size_t j = j0; j < j1; ++j)
    for (std::size_t i = 0; i < depth.nx; ++i) {
      const double d = depth.at(i, j);
      double h = kInf;
      if (std::isnan(d)) {
        h = kNaN;
      } else if (d > 0) {
        const auto ii = static_cast<std::int64_t>(i), jj = static_cast<std::int64_t>(j);
        const double gx = first_diff(depth, ii, jj, 1, 0, depth.dx), gy = first_diff(depth, ii, jj, 0, 1, depth.dy);
        const double gm = std::hypot(gx, gy);
        if (gm > 0) h = k * d / gm;
      }
      out.at(i, j) = h;
    }
  });
  return out;
}

Grid rule_wavelength(const Grid& depth, double period_s, double wl) {
  check_grid(depth, "rule_wavelength");
  require(period_s > 0 && std::isfinite(period_s), "wavelength rule: period must be a positive number of seconds, got " +
                                                       format_number(period_s));
  require(wl > 0 && std::isfinite(wl), "wavelength rule: wl must be a positive number, got " + format_number(wl));
  Grid out = like_grid(depth);
  for_cells(out, [&](std::size_t k) {
    const double d = depth.v[k];
    out.v[k] = std::isnan(d) ? kNaN : d > 0 ? period_s * std::sqrt(9.81 * d) / wl : kInf;
  });
  return out;
}

Grid rule_curvature(const Grid& dem, double tol) {
  check_grid(dem, "rule_curvature");
  require(tol > 0 && std::isfinite(tol), "curvature rule: tol must be a positive number, got " + format_number(tol));
  Grid out = like_grid(dem);
  parallel_bands(dem.ny, [&](std::size_t j0, std::size_t j1) {
  for (std::size_t j = j0; j < j1; ++j)
    for (std::size_t i = 0; i < dem.nx; ++i) {
      if (std::isnan(dem.at(i, j))) {
        out.at(i, j) = kNaN;
        continue;
      }
      const auto ii = static_cast<std::int64_t>(i), jj = static_cast<std::int64_t>(j);
      const double a = second_diff(dem, ii, jj, 1, 0, dem.dx), c = second_diff(dem, ii, jj, 0, 1, dem.dy);
      const double b = mixed_diff(dem, ii, jj);
      // Eigenvalues of [[a, b], [b, c]] are m +- r; the larger in magnitude is |m| + r.
      const double m = 0.5 * (a + c), r = std::hypot(0.5 * (a - c), b);
      const double kappa = std::abs(m) + r;
      out.at(i, j) = kappa > 0 ? std::sqrt(8.0 * tol / kappa) : kInf;
    }
  });
  return out;
}

Grid combine_min(const std::vector<Grid>& grids) {
  if (grids.empty()) throw Error(ExitCode::kInternal, "combine_min: no grids");
  const Grid& g0 = grids.front();
  check_grid(g0, "combine_min");
  for (std::size_t k = 1; k < grids.size(); ++k) {
    const Grid& g = grids[k];
    if (g.nx != g0.nx || g.ny != g0.ny || g.x0 != g0.x0 || g.y0 != g0.y0 || g.dx != g0.dx || g.dy != g0.dy ||
        g.v.size() != g0.v.size())
      throw Error(ExitCode::kInternal, "combine_min: grid " + std::to_string(k) + " (" + std::to_string(g.nx) + " x " +
                                           std::to_string(g.ny) + ") differs in geometry from grid 0 (" +
                                           std::to_string(g0.nx) + " x " + std::to_string(g0.ny) + ")");
  }
  Grid out = g0;
  for (std::size_t k = 1; k < grids.size(); ++k) {
    const double* other = grids[k].v.data();
    for_cells(out, [&](std::size_t c) { out.v[c] = std::fmin(out.v[c], other[c]); });
  }
  return out;
}

Grid clamp(const Grid& g, double hmin, double hmax) {
  check_grid(g, "clamp");
  require(hmin > 0 && std::isfinite(hmin) && hmin <= hmax,
          "spacing clamp: need 0 < hmin <= hmax, got hmin = " + format_number(hmin) + ", hmax = " + format_number(hmax));
  Grid out = g;
  for_cells(out, [&](std::size_t c) {
    double& v = out.v[c];
    if (!std::isnan(v)) v = std::min(std::max(v, hmin), hmax);
  });
  return out;
}

Grid fill_nan(const Grid& g, double value) {
  check_grid(g, "fill_nan");
  Grid out = g;
  for_cells(out, [&](std::size_t c) {
    if (std::isnan(out.v[c])) out.v[c] = value;
  });
  return out;
}

}  // namespace fdr::sizing
