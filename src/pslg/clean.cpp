// PSLG cleaning for messy GIS input: snap (grid hashing), parity cancellation of boundary
// copies, iterative splitting at crossings/overlaps, tiny-island removal, simplification.
#include "pslg/clean.hpp"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <utility>
#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "predicates/predicates.hpp"
#include "pslg/segment_grid.hpp"
#include "pslg/validate.hpp"

namespace fdr::pslg {
namespace {

using predicates::orient2d;

std::uint64_t bits(double v) {
  v += 0.0;  // -0.0 and +0.0 compare equal: give them one key
  std::uint64_t u;
  std::memcpy(&u, &v, sizeof u);
  return u;
}

// Open-addressing map from a key of two words to the head of a chain of indices (no per-key
// allocation: the snapping registers every input vertex).
class KeyHeads {
 public:
  Index head(std::uint64_t k1, std::uint64_t k2) const {
    if (slots_.empty()) return kNoId;
    for (std::size_t i = slot_of(k1, k2);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.head == kNoId) return kNoId;
      if (s.k1 == k1 && s.k2 == k2) return s.head;
    }
  }
  // Makes v the key's head; returns the previous head (kNoId if none).
  Index push_front(std::uint64_t k1, std::uint64_t k2, Index v) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    for (std::size_t i = slot_of(k1, k2);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.head == kNoId) {
        s = {k1, k2, v};
        ++used_;
        return kNoId;
      }
      if (s.k1 == k1 && s.k2 == k2) return std::exchange(s.head, v);
    }
  }

 private:
  struct Slot { std::uint64_t k1 = 0, k2 = 0; Index head = kNoId; };
  std::size_t slot_of(std::uint64_t k1, std::uint64_t k2) const {
    std::uint64_t h = k1 * 0x9E3779B97F4A7C15ULL ^ (k2 + 0x632BE59BD9B4E019ULL) * 0xC2B2AE3D27D4EB4FULL;
    h ^= h >> 29;
    return static_cast<std::size_t>(h) & mask_;
  }
  void grow() {
    std::vector<Slot> old = std::move(slots_);
    slots_.assign(std::max<std::size_t>(64, 2 * old.size()), Slot{});
    mask_ = slots_.size() - 1;
    used_ = 0;
    for (const Slot& s : old)
      if (s.head != kNoId)
        for (std::size_t i = slot_of(s.k1, s.k2);; i = (i + 1) & mask_)
          if (slots_[i].head == kNoId) { slots_[i] = s; ++used_; break; }
  }
  std::vector<Slot> slots_;
  std::size_t mask_ = 0, used_ = 0;
};

std::string fmt(Point2 p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", p.x, p.y);
  return buf;
}

Point2 mid(Point2 a, Point2 b) { return {0.5 * (a.x + b.x), 0.5 * (a.y + b.y)}; }

}  // namespace

std::vector<std::pair<Index, Index>> vertices_near_segments(const std::vector<Point2>& pts_,
                                                            const std::vector<Segment>& segs_,
                                                            const std::vector<char>* present, double tol) {
  std::vector<std::pair<Index, Index>> found;
  if (segs_.empty() || !(tol > 0)) return found;
  Box2 box;
  double total = 0;
  for (const Segment& s : segs_) box.add(pts_[s.a]), box.add(pts_[s.b]), total += dist(pts_[s.a], pts_[s.b]);
  SegmentGrid grid(box, segs_.size(), total / static_cast<double>(segs_.size()));
  for (Index i = 0; i < segs_.size(); ++i) grid.add_segment(i, pts_[segs_[i].a], pts_[segs_[i].b]);
  // The cells each vertex's tol box touches, as (cell, vertex) pairs grouped by cell.
  std::vector<std::pair<std::size_t, Index>> at;
  for (Index v = 0; v < pts_.size(); ++v) {
    if (present && !(*present)[v]) continue;
    const Point2 p = pts_[v];
    if (!(p.x >= box.lo.x - tol && p.x <= box.hi.x + tol && p.y >= box.lo.y - tol && p.y <= box.hi.y + tol)) continue;
    Box2 q;
    q.add({p.x - tol, p.y - tol});
    q.add({p.x + tol, p.y + tol});
    grid.for_box_cells(q, [&](std::size_t c) { at.push_back({c, v}); });
  }
  std::sort(at.begin(), at.end());
  // Farther than tol from a segment's box (with a margin for rounding): not near, decided
  // without a predicate (whose exact path collinear chains would take every time).
  const double m = 2 * tol;
  auto check = [&](Index v, Index s) {
    const Segment& sg = segs_[s];
    if (sg.a == v || sg.b == v) return;
    const Point2 p = pts_[v], a = pts_[sg.a], b = pts_[sg.b];
    if (p.x < std::min(a.x, b.x) - m || p.x > std::max(a.x, b.x) + m || p.y < std::min(a.y, b.y) - m ||
        p.y > std::max(a.y, b.y) + m)
      return;
    if (p == a || p == b || orient2d(a, b, p) == 0) return;  // exact cases: find_contacts
    const Point2 d = b - a;
    const double t = dot(p - a, d) / dot(d, d);
    if (!(t > 0 && t < 1) || dist(p, a) <= tol || dist(p, b) <= tol) return;
    if (dist_to_segment(p, a, b) <= tol) found.push_back({v, s});
  };
  // Why a sweep per cell: a long straight chain crowds ~sqrt(n) segments into each cell it
  // passes; sorted by their lower end along the cell's longer extent, a vertex looks only at the
  // segments whose lower end lies within the longest such segment's reach of it.
  std::vector<std::pair<double, Index>> by_lo;
  for (std::size_t k = 0; k < at.size();) {
    const std::size_t c = at[k].first;
    std::size_t e = k;
    while (e < at.size() && at[e].first == c) ++e;
    const auto& ids = grid.segments_in(c);
    Box2 cb;
    for (Index i : ids) cb.add(pts_[segs_[i].a]), cb.add(pts_[segs_[i].b]);
    const bool along_x = cb.width() >= cb.height();
    auto coord = [along_x](Point2 p) { return along_x ? p.x : p.y; };
    by_lo.clear();
    double reach = 0;
    for (Index i : ids) {
      const double u = coord(pts_[segs_[i].a]), w = coord(pts_[segs_[i].b]);
      by_lo.push_back({std::min(u, w), i});
      reach = std::max(reach, std::fabs(w - u));
    }
    std::sort(by_lo.begin(), by_lo.end());
    for (std::size_t j = k; j < e; ++j) {
      const Index v = at[j].second;
      const double x = coord(pts_[v]);
      auto it = std::lower_bound(by_lo.begin(), by_lo.end(), std::pair{x - m - reach, Index{0}});
      for (; it != by_lo.end() && it->first <= x + m; ++it) check(v, it->second);
    }
    k = e;
  }
  std::sort(found.begin(), found.end());
  found.erase(std::unique(found.begin(), found.end()), found.end());
  return found;
}

namespace {

class Cleaner {
 public:
  Cleaner(const Pslg& in, const CleanOptions& opt, std::vector<Repair>* repairs)
      : in_(in), opt_(opt), repairs_(repairs) {}

  Pslg run() {
    StepLaps lap(debug::Aid::kClean, "  clean");
    check_input();
    lap("check");
    snap_input();
    lap("snap");
    split_until_clean();
    lap("split");
    if (opt_.min_island_area_factor > 0) drop_tiny_islands();
    if (opt_.simplify_factor > 0 && opt_.simplify_tolerance > 0) simplify();
    Pslg out = compact();
    lap("compact");
    return out;
  }

 private:
  void report(const char* kind, Point2 where, double size, std::string reason, std::int32_t part,
              std::vector<std::int64_t> ids = {}) {
    if (repairs_) repairs_->push_back(Repair{kind, where, size, std::move(reason), part, std::move(ids)});
  }

  Point2 world(Point2 p) const { return in_.origin + p; }

  double spacing_at(Point2 p, const char* what) const {
    if (!opt_.spacing)
      throw Error(ExitCode::kInvalidSpacing, std::string("clean: ") + what + " needs a spacing function f");
    const double f = opt_.spacing(p);
    if (!(f > 0) || !std::isfinite(f))
      throw Error(ExitCode::kInvalidSpacing, std::string("clean: spacing f = ") + std::to_string(f) +
                                                 " at " + fmt(world(p)) + " (" + what + ") must be finite and > 0");
    return f;
  }

  void check_input() const {
    for (std::size_t i = 0; i < in_.points.size(); ++i)
      if (!std::isfinite(in_.points[i].x) || !std::isfinite(in_.points[i].y))
        throw Error(ExitCode::kInvalidGeometry, "clean: vertex " + std::to_string(i) + " has a non-finite coordinate");
    for (std::size_t s = 0; s < in_.segments.size(); ++s)
      if (in_.segments[s].a >= in_.points.size() || in_.segments[s].b >= in_.points.size())
        throw Error(ExitCode::kInvalidGeometry, "clean: segment " + std::to_string(s) +
                                                    " refers to a vertex beyond the " +
                                                    std::to_string(in_.points.size()) + " vertices");
    if (!(opt_.snap_distance >= 0) || !std::isfinite(opt_.snap_distance))
      throw Error(ExitCode::kUsage, "clean: snap distance must be finite and >= 0");
  }

  // --- point registry: exact coordinates, plus a hash grid for snapping -------------------------
  std::pair<std::int64_t, std::int64_t> snap_cell(Point2 p) const {
    auto c = [&](double v) {
      const double q = std::floor(v / opt_.snap_distance);
      return static_cast<std::int64_t>(std::clamp(q, -4e18, 4e18));
    };
    return {c(p.x), c(p.y)};
  }

  // Lowest-index representative equal to p or within the snap distance of it; kNoId if none.
  // (A representative with p's exact coordinates wins, the lowest-index one; it lies in p's own
  // cell.)
  Index find_rep(Point2 p) const {
    if (opt_.snap_distance <= 0) {
      Index best = kNoId;
      for (Index q = reps_.head(bits(p.x), bits(p.y)); q != kNoId; q = next_rep_[q]) best = std::min(best, q);
      return best;
    }
    const auto [cx, cy] = snap_cell(p);
    Index same = kNoId;
    for (Index q = reps_.head(static_cast<std::uint64_t>(cx), static_cast<std::uint64_t>(cy)); q != kNoId; q = next_rep_[q])
      if (pts_[q].x == p.x && pts_[q].y == p.y) same = std::min(same, q);
    if (same != kNoId) return same;
    Index best = kNoId;
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dx = -1; dx <= 1; ++dx)
        for (Index q = reps_.head(static_cast<std::uint64_t>(cx + dx), static_cast<std::uint64_t>(cy + dy)); q != kNoId;
             q = next_rep_[q])
          if (q < best && dist(pts_[q], p) <= opt_.snap_distance) best = q;
    return best;
  }

  void register_rep(Index id) {
    if (next_rep_.size() <= id) next_rep_.resize(std::max<std::size_t>(id + 1, 2 * next_rep_.size()), kNoId);
    std::uint64_t k1, k2;
    if (opt_.snap_distance <= 0) {
      k1 = bits(pts_[id].x);
      k2 = bits(pts_[id].y);
    } else {
      const auto [cx, cy] = snap_cell(pts_[id]);
      k1 = static_cast<std::uint64_t>(cx);
      k2 = static_cast<std::uint64_t>(cy);
    }
    next_rep_[id] = reps_.push_front(k1, k2, id);
  }

  Index add_point(Point2 p) {
    if (Index r = find_rep(p); r != kNoId) return r;
    const Index id = static_cast<Index>(pts_.size());
    pts_.push_back(p);
    alive_.push_back(1);
    input_free_.push_back(0);
    markers_.push_back(0);
    register_rep(id);
    return id;
  }

  // --- step 1: snap input points (index order; the lowest index in reach wins) ------------------
  void snap_input() {
    const std::size_t n = in_.points.size();
    pts_ = in_.points;
    alive_.assign(n, 1);
    input_free_.assign(n, 1);
    markers_.assign(n, 0);
    if (in_.point_markers.size() == n) markers_ = in_.point_markers;
    std::vector<std::int32_t> point_part(n, -1);
    for (const Segment& s : in_.segments) {
      input_free_[s.a] = input_free_[s.b] = 0;
      if (point_part[s.a] < 0) point_part[s.a] = s.part;
      if (point_part[s.b] < 0) point_part[s.b] = s.part;
    }
    std::vector<Index> map(n);
    for (Index i = 0; i < n; ++i) {
      const Index r = find_rep(pts_[i]);
      if (r == kNoId) {
        register_rep(i);
        map[i] = i;
        continue;
      }
      map[i] = r;
      alive_[i] = 0;
      if (markers_[r] == 0) markers_[r] = markers_[i];
      if (!input_free_[i]) input_free_[r] = 0;
      const double d = dist(pts_[i], pts_[r]);
      report(d == 0 && !opt_.boundary_parity ? "duplicate_vertex" : "snap", pts_[r], d,
             "vertex " + std::to_string(i) + (d == 0 ? " duplicates" : " snapped onto") + " vertex " +
                 std::to_string(r) + (d == 0 ? "" : " (" + std::to_string(d) + " m away)"),
             point_part[i], {static_cast<std::int64_t>(i), static_cast<std::int64_t>(r)});
    }
    segs_.reserve(in_.segments.size());
    for (Index s = 0; s < in_.segments.size(); ++s) {
      Segment sg = in_.segments[s];
      const Point2 a = in_.points[sg.a], b = in_.points[sg.b];
      sg.a = map[sg.a];
      sg.b = map[sg.b];
      if (sg.a == sg.b) {
        report("zero_length", pts_[sg.a], dist(a, b),
               "segment " + std::to_string(s) + " collapsed to a point and was removed", sg.part,
               {static_cast<std::int64_t>(s)});
        continue;
      }
      segs_.push_back(sg);
    }
  }

  // --- step 2: parity cancellation of boundary copies, merging of breakline copies --------------
  void normalize() {
    std::vector<std::size_t> order(segs_.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    auto key = [&](std::size_t i) {
      return std::make_pair(std::min(segs_[i].a, segs_[i].b), std::max(segs_[i].a, segs_[i].b));
    };
    std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
      const auto kx = key(x), ky = key(y);
      return kx < ky || (kx == ky && x < y);
    });
    std::vector<char> keep(segs_.size(), 1);
    bool changed = false;
    for (std::size_t g = 0; g < order.size();) {
      std::size_t e = g + 1;
      while (e < order.size() && key(order[e]) == key(order[g])) ++e;
      if (e - g > 1 && !opt_.boundary_parity) {
        // Triangle .poly semantics: every copy merges into the first (lowest index) one.
        changed = true;
        const Segment& kept = segs_[order[g]];
        for (std::size_t k = g + 1; k < e; ++k) {
          const Segment& s = segs_[order[k]];
          keep[order[k]] = 0;
          report("duplicate_segment", mid(pts_[s.a], pts_[s.b]), dist(pts_[s.a], pts_[s.b]),
                 "segment between vertices " + std::to_string(s.a) + " and " + std::to_string(s.b) +
                     " duplicates another segment and was merged into it",
                 s.part, {s.part, kept.part});
        }
      } else if (e - g > 1) {
        changed = true;
        std::size_t nb = 0;
        for (std::size_t k = g; k < e; ++k) nb += segs_[order[k]].is_boundary();
        // Boundary copies cancel in pairs (the domain is defined by crossing parity): an odd
        // count keeps the first copy. Breakline copies merge into the first one, and vanish
        // under a surviving boundary segment.
        bool kept_boundary = false, kept_break = false;
        std::size_t cancelled = 0;
        for (std::size_t k = g; k < e; ++k) {
          const std::size_t i = order[k];
          const Segment& s = segs_[i];
          const Point2 m = mid(pts_[s.a], pts_[s.b]);
          const double len = dist(pts_[s.a], pts_[s.b]);
          if (s.is_boundary()) {
            if (nb % 2 == 1 && !kept_boundary) {
              kept_boundary = true;
              continue;
            }
            keep[i] = 0;
            if (++cancelled % 2 == 0)
              report("backtrack", m, len,
                     "two coincident boundary segments between vertices " + std::to_string(s.a) + " and " +
                         std::to_string(s.b) + " cancel (a spike or a shared edge)",
                     s.part);
          } else {
            if (nb % 2 == 0 && !kept_break) {
              kept_break = true;
              continue;
            }
            keep[i] = 0;
            report("duplicate_segment", m, len,
                   "breakline between vertices " + std::to_string(s.a) + " and " + std::to_string(s.b) +
                       " duplicates another segment and was merged",
                   s.part);
          }
        }
      }
      g = e;
    }
    if (!changed) return;
    std::size_t w = 0;
    for (std::size_t i = 0; i < segs_.size(); ++i)
      if (keep[i]) segs_[w++] = segs_[i];
    segs_.resize(w);
  }

  // --- step 3: split at crossings, at vertices on segments and at collinear overlaps ------------

  // Why: a rounded crossing point p lies a few ulps off segment ab, so the pieces a-p, p-b sweep
  // the thin triangle (a, p, b); a vertex q inside it (or on a-p, p-b) would change sides of the
  // constraint. Such a q is made a cut point of ab too (snap rounding's "hot pixel" rule), so the
  // subdivided segment passes through it and no orientation flips. New contacts this creates are
  // found by the exact re-check of the next round (capped by max_iterations).
  void route_through_hot_vertices(std::vector<std::vector<Index>>* splits, const std::vector<char>& present) {
    bool any = false;
    for (std::size_t i = 0; i < segs_.size() && !any; ++i)
      for (Index v : (*splits)[i])
        if (orient2d(pts_[segs_[i].a], pts_[segs_[i].b], pts_[v]) != 0) { any = true; break; }
    if (!any) return;
    Box2 box;
    std::size_t n = 0;
    for (std::size_t v = 0; v < pts_.size(); ++v)
      if (v >= present.size() || present[v]) box.add(pts_[v]), ++n;
    SegmentGrid grid(box, n, std::max(box.width(), box.height()) / std::sqrt(static_cast<double>(n) + 1));
    for (Index v = 0; v < pts_.size(); ++v)
      if (v >= present.size() || present[v]) grid.add_point(v, pts_[v]);
    std::vector<Index> extra;
    for (std::size_t i = 0; i < segs_.size(); ++i) {
      auto& sp = (*splits)[i];
      if (sp.empty()) continue;
      const Point2 a = pts_[segs_[i].a], b = pts_[segs_[i].b];
      extra.clear();
      for (Index v : sp) {
        const Point2 p = pts_[v];
        const int o = orient2d(a, b, p);
        if (o == 0) continue;
        auto test_cell = [&](std::size_t cell) {
          for (Index q : grid.points_in(cell)) {
            if (q == segs_[i].a || q == segs_[i].b || q == v) continue;
            const Point2 x = pts_[q];
            // Closed triangle (a, b, p) without its corners and without the open side ab
            // (a vertex there already is a cut point).
            const int s1 = orient2d(a, b, x) * o, s2 = orient2d(b, p, x) * o, s3 = orient2d(p, a, x) * o;
            if (s1 > 0 && s2 >= 0 && s3 >= 0) extra.push_back(q);
          }
        };
        grid.for_segment_cells(a, p, test_cell);
        grid.for_segment_cells(p, b, test_cell);
      }
      for (Index q : extra) {
        if (std::find(sp.begin(), sp.end(), q) != sp.end()) continue;
        sp.push_back(q);
        report("hot_vertex", pts_[q], dist_to_segment(pts_[q], a, b),
               "segment routed through vertex " + std::to_string(q) +
                   " so that a rounded cut point does not move the constraint across it",
               segs_[i].part, {static_cast<std::int64_t>(q), segs_[i].part});
      }
    }
  }

  void add_vertices_near_segments(Contacts* c, const std::vector<char>& present) const {
    const auto found = vertices_near_segments(pts_, segs_, &present, opt_.segment_snap);
    c->vertex_on_segment.insert(c->vertex_on_segment.end(), found.begin(), found.end());
  }

  void split_until_clean() {
    std::size_t xround = 0;  // rounds that split crossings (the snap tolerance grows with them)
    for (std::size_t round = 0;; ++round) {
      normalize();
      // Points orphaned by cancellation are no cut candidates; used and free points are.
      std::vector<char> present(pts_.size(), 0);
      for (const Segment& s : segs_) present[s.a] = present[s.b] = 1;
      for (std::size_t v = 0; v < pts_.size(); ++v) present[v] = alive_[v] && (present[v] || kept_unused(v));
      Contacts c = find_contacts(pts_, segs_, &present);
      const std::size_t n_exact = c.vertex_on_segment.size();
      if (opt_.segment_snap > 0) add_vertices_near_segments(&c, present);
      if (c.segment_pairs.empty() && c.vertex_on_segment.empty()) return;
      if (round >= opt_.max_iterations) {
        Point2 where;
        std::string what;
        if (!c.segment_pairs.empty()) {
          const Segment &s = segs_[c.segment_pairs[0].first], &t = segs_[c.segment_pairs[0].second];
          where = mid(pts_[s.a], pts_[s.b]);
          what = "segments " + fmt(world(pts_[s.a])) + "-" + fmt(world(pts_[s.b])) + " and " +
                 fmt(world(pts_[t.a])) + "-" + fmt(world(pts_[t.b])) + " still intersect";
        } else {
          where = pts_[c.vertex_on_segment[0].first];
          what = "a vertex at " + fmt(world(where)) + " still lies on a segment";
        }
        throw Error(ExitCode::kInvalidGeometry,
                    "clean: crossings remain after " + std::to_string(opt_.max_iterations) +
                        " splitting rounds near " + fmt(world(where)) + ": " + what +
                        " (raise the snap distance or repair the input there)");
      }
      double mag = 0;
      for (std::size_t v = 0; v < pts_.size(); ++v)
        if (present[v]) mag = std::max({mag, std::fabs(pts_[v].x), std::fabs(pts_[v].y)});
      std::vector<std::vector<Index>> splits(segs_.size());
      const bool defer_crossings = !c.vertex_on_segment.empty();  // overlaps imply a vertex on a segment
      const std::size_t xr = defer_crossings ? xround : xround++;  // 0-based crossing round
      for (std::size_t k = 0; k < c.vertex_on_segment.size(); ++k) {
        const auto [v, s] = c.vertex_on_segment[k];
        splits[s].push_back(v);
        if (k < n_exact)
          report("vertex_on_segment", pts_[v], 0,
                 "segment split at vertex " + std::to_string(v) + " lying on it", segs_[s].part,
                 {static_cast<std::int64_t>(v), segs_[s].part});
        else
          report("snap_to_segment", pts_[v], dist_to_segment(pts_[v], pts_[segs_[s].a], pts_[segs_[s].b]),
                 "segment routed through vertex " + std::to_string(v) + " lying within the snap tolerance of it",
                 segs_[s].part, {static_cast<std::int64_t>(v), segs_[s].part});
      }
      for (std::size_t k = 0; k < c.segment_pairs.size(); ++k) {
        const auto [i, j] = c.segment_pairs[k];
        const Segment s = segs_[i], t = segs_[j];
        if (c.kinds[k] == Contact::kOverlap) {
          // The overlapping stretch is cut at each other's endpoints (found as vertex_on_segment).
          report("overlap_split", mid(pts_[s.a], pts_[s.b]), 0,
                 "collinear overlapping segments split at each other's endpoints", s.part, {s.part, t.part});
          continue;
        }
        if (c.kinds[k] != Contact::kProper) continue;  // a touch is a vertex_on_segment
        // Why defer: collinear overlapping copies that both cross a third segment would each get
        // their own rounded crossing point, ulps apart, leaving a sliver between two near-copies
        // of the line (fuzz_pslg_mesh_1). Overlaps and touches are cut first; the copies then
        // merge (normalize) and the crossing is computed once.
        if (defer_crossings) continue;
        const Point2 p = crossing_point(pts_[s.a], pts_[s.b], pts_[t.a], pts_[t.b]);
        // Why snap here: in near-parallel bundles rounded crossing points keep creating new
        // crossings next to each other. From round 2 on, a crossing point within a tolerance that
        // grows 4x per round merges with a nearby endpoint or cut point of the same two segments.
        Index id = kNoId;
        if (xr >= 2) {
          const double eps = std::ldexp(mag * 0x1p-52, 2 * static_cast<int>(std::min<std::size_t>(xr, 400)));
          double best = eps;
          auto consider = [&](Index q) {
            const double d = dist(pts_[q], p);
            if (d <= best && (id == kNoId || d < best || q < id)) best = d, id = q;
          };
          for (Index q : {s.a, s.b, t.a, t.b}) consider(q);
          for (Index q : splits[i]) consider(q);
          for (Index q : splits[j]) consider(q);
          if (id != kNoId)
            report("snap", pts_[id], best,
                   "crossing point snapped onto a vertex " + std::to_string(best) + " m away (round " +
                       std::to_string(xr) + " of splitting)",
                   s.part, {static_cast<std::int64_t>(id)});
        }
        if (id == kNoId) {
          id = add_point(p);
          if (pts_[id] != p)  // merged with a vertex within the snap distance
            report("snap", pts_[id], dist(pts_[id], p),
                   "crossing point merged with vertex " + std::to_string(id) + " within the snap distance", s.part,
                   {static_cast<std::int64_t>(id)});
        }
        splits[i].push_back(id);
        splits[j].push_back(id);
        report("crossing_split", pts_[id], 0,
               "crossing segments split at their intersection" +
                   std::string(s.part == t.part && s.part >= 0 ? " (self-intersecting ring)" : ""),
               s.part, {s.part, t.part});
      }
      route_through_hot_vertices(&splits, present);
      std::vector<Segment> out;
      out.reserve(segs_.size() + 2 * c.segment_pairs.size() + c.vertex_on_segment.size());
      for (std::size_t i = 0; i < segs_.size(); ++i) {
        const Segment s = segs_[i];
        auto& sp = splits[i];
        if (sp.empty()) {
          out.push_back(s);
          continue;
        }
        const Point2 a = pts_[s.a], d = pts_[s.b] - pts_[s.a];
        // Order the cut points along the segment (a metric sort; ties by id for determinism).
        std::sort(sp.begin(), sp.end(), [&](Index x, Index y) {
          const double tx = dot(pts_[x] - a, d), ty = dot(pts_[y] - a, d);
          return tx < ty || (tx == ty && x < y);
        });
        sp.erase(std::unique(sp.begin(), sp.end()), sp.end());
        Index prev = s.a;
        for (Index v : sp) {
          if (v == s.a || v == s.b || v == prev) continue;
          out.push_back(Segment{prev, v, s.marker, s.part});
          prev = v;
        }
        if (prev != s.b) out.push_back(Segment{prev, s.b, s.marker, s.part});
      }
      segs_ = std::move(out);
    }
  }

  // --- step 4: drop closed boundary components whose area is below factor * f(centroid)^2 -------
  void drop_tiny_islands() {
    const std::size_t np = pts_.size();
    std::vector<Index> bsegs;
    for (Index s = 0; s < segs_.size(); ++s)
      if (segs_[s].is_boundary()) bsegs.push_back(s);
    // Incidence lists (CSR) over boundary segments.
    std::vector<Index> start(np + 1, 0);
    for (Index s : bsegs) ++start[segs_[s].a + 1], ++start[segs_[s].b + 1];
    for (std::size_t v = 0; v < np; ++v) start[v + 1] += start[v];
    std::vector<Index> inc(start[np]);
    std::vector<Index> fill(start.begin(), start.end() - 1);
    for (Index s : bsegs) inc[fill[segs_[s].a]++] = s, inc[fill[segs_[s].b]++] = s;
    std::vector<char> seen(segs_.size(), 0), used(segs_.size(), 0), drop(segs_.size(), 0);
    std::vector<Index> comp, stack;
    for (Index s0 : bsegs) {
      if (seen[s0]) continue;
      // Collect the connected component of s0 (segments sorted for deterministic walks).
      comp.clear();
      stack.assign(1, s0);
      seen[s0] = 1;
      bool closed = true;
      while (!stack.empty()) {
        const Index s = stack.back();
        stack.pop_back();
        comp.push_back(s);
        for (Index v : {segs_[s].a, segs_[s].b}) {
          if ((start[v + 1] - start[v]) % 2) closed = false;
          for (Index k = start[v]; k < start[v + 1]; ++k)
            if (!seen[inc[k]]) seen[inc[k]] = 1, stack.push_back(inc[k]);
        }
      }
      if (!closed) continue;
      std::sort(comp.begin(), comp.end());
      // Why walk cycles: an even-degree component splits into closed walks (Euler); the area is
      // the sum of their absolute shoelace areas, the centroid their area-weighted centroid.
      const Point2 ref = pts_[segs_[comp[0]].a];
      double area = 0, cx = 0, cy = 0;
      for (Index s : comp) {
        if (used[s]) continue;
        const Index v0 = segs_[s].a;
        Index cur = v0, e = s;
        double a2 = 0, sx = 0, sy = 0;
        do {
          used[e] = 1;
          const Index nxt = segs_[e].a == cur ? segs_[e].b : segs_[e].a;
          const Point2 p = pts_[cur] - ref, q = pts_[nxt] - ref;
          const double cr = p.x * q.y - q.x * p.y;
          a2 += cr;
          sx += (p.x + q.x) * cr;
          sy += (p.y + q.y) * cr;
          cur = nxt;
          if (cur == v0) break;
          e = kNoId;
          for (Index k = start[cur]; k < start[cur + 1]; ++k)
            if (!used[inc[k]] && (e == kNoId || inc[k] < e)) e = inc[k];
        } while (e != kNoId);
        const double ai = std::fabs(a2) / 2;
        area += ai;
        if (a2 != 0) cx += ai * sx / (3 * a2), cy += ai * sy / (3 * a2);
      }
      Point2 c;
      if (area > 0) {
        c = ref + Point2{cx / area, cy / area};
      } else {
        Box2 b;
        for (Index s : comp) b.add(pts_[segs_[s].a]);
        c = b.center();
      }
      const double f = spacing_at(c, "min_island_area_factor");
      const double limit = opt_.min_island_area_factor * f * f;
      if (!(area < limit)) continue;
      for (Index s : comp) drop[s] = 1;
      report("tiny_island", c, area,
             "closed ring of " + std::to_string(comp.size()) + " segments with area " + std::to_string(area) +
                 " m^2 < " + std::to_string(limit) + " m^2 (factor * f^2) was removed",
             segs_[comp[0]].part);
    }
    std::size_t w = 0;
    for (std::size_t i = 0; i < segs_.size(); ++i)
      if (!drop[i]) segs_[w++] = segs_[i];
    segs_.resize(w);
  }

  // --- step 5: remove short-edged degree-2 boundary vertices where safe -------------------------
  void simplify() {
    const std::size_t np = pts_.size();
    std::vector<std::vector<Index>> inc(np);
    std::vector<char> seg_dead(segs_.size(), 0), simplified(segs_.size(), 0);
    Box2 box;
    double total = 0;
    for (Index s = 0; s < segs_.size(); ++s) {
      inc[segs_[s].a].push_back(s);
      inc[segs_[s].b].push_back(s);
      total += dist(pts_[segs_[s].a], pts_[segs_[s].b]);
    }
    // Points that will appear in the output (used or free) block a removal that would jump them.
    std::vector<char> present(np, 0);
    for (Index v = 0; v < np; ++v) {
      present[v] = alive_[v] && (!inc[v].empty() || input_free_[v]);
      if (present[v]) box.add(pts_[v]);
    }
    if (segs_.empty()) return;
    SegmentGrid grid(box, segs_.size() + np, total / static_cast<double>(segs_.size()));
    for (Index s = 0; s < segs_.size(); ++s) grid.add_segment(s, pts_[segs_[s].a], pts_[segs_[s].b]);
    for (Index v = 0; v < np; ++v)
      if (present[v]) grid.add_point(v, pts_[v]);
    std::vector<Index> near;
    for (Index v = 0; v < np; ++v) {
      if (inc[v].size() != 2 || input_free_[v]) continue;  // free input points are fixed vertices
      const Index s1 = inc[v][0], s2 = inc[v][1];
      const Segment &g1 = segs_[s1], &g2 = segs_[s2];
      if (!g1.is_boundary() || !g2.is_boundary() || g1.marker != g2.marker || g1.part != g2.part) continue;
      // A segment made by an earlier removal is not shortened again: the move stays bounded.
      if (simplified[s1] || simplified[s2]) continue;
      const Index u = g1.a == v ? g1.b : g1.a, w = g2.a == v ? g2.b : g2.a;
      if (u == w) continue;
      const Point2 pu = pts_[u], pv = pts_[v], pw = pts_[w];
      const double f = spacing_at(pv, "simplify_factor");
      const double lim = opt_.simplify_factor * f;
      if (!(dist(pu, pv) < lim && dist(pv, pw) < lim)) continue;
      const double dev = dist_to_segment(pv, pu, pw);
      if (!(dev < opt_.simplify_tolerance)) continue;
      bool ok = true;
      for (Index s : inc[u])
        if (segs_[s].a == w || segs_[s].b == w) ok = false;
      if (!ok) continue;
      Box2 tb;
      tb.add(pu), tb.add(pv), tb.add(pw);
      grid.segments_near(tb, &near);
      for (Index s : near) {
        if (s == s1 || s == s2 || seg_dead[s]) continue;
        const Contact k = classify(pu, pw, pts_[segs_[s].a], pts_[segs_[s].b]);
        if (k != Contact::kNone && k != Contact::kEndpoint) { ok = false; break; }
      }
      if (!ok) continue;
      const int o = orient2d(pu, pv, pw);
      grid.points_near(tb, &near);
      for (Index p : near) {
        if (p == u || p == v || p == w || !present[p]) continue;
        const Point2 q = pts_[p];
        const bool inside = o == 0 ? in_interior(pu, pw, q)
                                   : orient2d(pu, pv, q) * o >= 0 && orient2d(pv, pw, q) * o >= 0 &&
                                         orient2d(pw, pu, q) * o >= 0;
        if (inside) { ok = false; break; }
      }
      if (!ok) continue;
      segs_[s1] = Segment{u, w, g1.marker, g1.part};
      seg_dead[s2] = 1;
      simplified[s1] = 1;
      for (Index& s : inc[w])
        if (s == s2) s = s1;
      inc[v].clear();
      present[v] = 0;
      grid.add_segment(s1, pu, pw);
      report("simplify", pv, dev,
             "boundary vertex " + std::to_string(v) + " with edges shorter than simplify_factor * f removed",
             g1.part);
    }
    std::size_t k = 0;
    for (std::size_t i = 0; i < segs_.size(); ++i)
      if (!seg_dead[i]) segs_[k++] = segs_[i];
    segs_.resize(k);
  }

  // --- final: renumber, dropping points no segment uses (input free points stay) -----------------
  Pslg compact() {
    const std::size_t np = pts_.size();
    std::vector<char> used(np, 0);
    for (const Segment& s : segs_) used[s.a] = used[s.b] = 1;
    Pslg out;
    out.origin = in_.origin;
    out.holes = in_.holes;
    out.regions = in_.regions;
    const bool with_markers = in_.point_markers.size() == in_.points.size() && !in_.points.empty();
    std::vector<Index> map(np, kNoId);
    for (Index v = 0; v < np; ++v) {
      if (!alive_[v]) continue;
      if (!used[v] && !kept_unused(v)) continue;  // orphaned by cancellation/removal
      map[v] = static_cast<Index>(out.points.size());
      out.points.push_back(pts_[v]);
      if (with_markers) out.point_markers.push_back(markers_[v]);
    }
    out.segments.reserve(segs_.size());
    for (Segment s : segs_) {
      s.a = map[s.a];
      s.b = map[s.b];
      out.segments.push_back(s);
    }
    try {
      validate(out, "clean result");
    } catch (const Error& e) {
      throw Error(ExitCode::kInternal, std::string("internal error: ") + e.what());
    }
    return out;
  }

  // A point kept even when no segment uses it: a free input point, or (Triangle semantics) any
  // input vertex, e.g. the end of a dropped zero-length segment.
  bool kept_unused(std::size_t v) const {
    return input_free_[v] || (!opt_.boundary_parity && v < in_.points.size());
  }

  const Pslg& in_;
  const CleanOptions& opt_;
  std::vector<Repair>* repairs_;
  std::vector<Point2> pts_;
  std::vector<char> alive_, input_free_;
  std::vector<std::int32_t> markers_;
  std::vector<Segment> segs_;
  // Representatives by key (exact coordinates without snapping, else the snap cell): the table
  // holds each key's most recent representative, next_rep_ the chain to the earlier ones.
  KeyHeads reps_;
  std::vector<Index> next_rep_;
};

}  // namespace

Pslg clean(const Pslg& in, const CleanOptions& options, std::vector<Repair>* repairs) {
  return Cleaner(in, options, repairs).run();
}

}  // namespace fdr::pslg
