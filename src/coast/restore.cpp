// Coast restoration (restore.hpp).
#include "coast/restore.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <unordered_map>

#include "base/debug.hpp"
#include "base/parallel.hpp"
#include "coast/validity.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {

// Gives the input's exact coast back wherever a buffer result runs within `hair` of it. Why:
// GEOS rounds every corner of an offset with arc points, so after a closing or an opening the
// unchanged coast comes back as 2-5 points per input vertex, which every later overlay, the
// cleaning (thousands of snap/zero-length
// repairs) and the resampling pay for. A run of consecutive result vertices each within hair of
// the same input ring, advancing along it (each step no longer along the input than the step
// itself plus 2 hair), is replaced by its two end vertices and the input vertices between them;
// only places that moved more than hair (the closed inlets, the rounded corners that matter)
// keep the buffers' vertices. A polygon that the replacement would make invalid (checked with
// the exact contact finder, GEOS deciding when that is unsure) is left as it was.
struct CoastRestorer::Impl {
 public:
  Impl(const OGRGeometry* input, double hair, bool full_rounds)
      : hair_(hair), on_tol_(1e-3 * hair), full_rounds_(full_rounds) {
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(input, ps);
    Box2 box;
    std::size_t nseg = 0;
    double total = 0;
    for (const auto& w : ps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        InRing ir;
        for (int i = 0; i + 1 < r->getNumPoints(); ++i) ir.p.push_back({r->getX(i), r->getY(i)});
        if (ir.p.size() < 3) continue;
        ir.cum.resize(ir.p.size() + 1, 0.0);
        for (std::size_t i = 0; i < ir.p.size(); ++i) {
          box.add(ir.p[i]);
          ir.cum[i + 1] = ir.cum[i] + dist(ir.p[i], ir.p[(i + 1) % ir.p.size()]);
        }
        ir.first_seg = nseg;
        nseg += ir.p.size();
        total += ir.cum.back();
        rings_.push_back(std::move(ir));
      }
    if (rings_.empty() || !(hair > 0)) return;
    box.lo = box.lo - Point2{2 * hair, 2 * hair};
    box.hi = box.hi + Point2{2 * hair, 2 * hair};
    box_ = box;
    grid_ = std::make_unique<pslg::SegmentGrid>(box, nseg, std::max(total / static_cast<double>(nseg), hair));
    seg_ring_.reserve(nseg);
    for (std::size_t k = 0; k < rings_.size(); ++k) {
      const auto& ir = rings_[k];
      for (std::size_t i = 0; i < ir.p.size(); ++i) {
        grid_->add_segment(static_cast<Index>(seg_ring_.size()), ir.p[i], ir.p[(i + 1) % ir.p.size()]);
        seg_ring_.push_back({static_cast<std::uint32_t>(k), static_cast<std::uint32_t>(i)});
      }
    }
  }

  // g with the input's coast given back (a new geometry; g itself when nothing changes).
  GeomPtr restore(GeomPtr g) const {
    if (!grid_ || !g || g->IsEmpty()) return g;
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(g.get(), ps);
    bool any = false;
    for (auto& p : ps) {
      std::vector<Plan> plans(static_cast<std::size_t>(p->getNumInteriorRings() + 1));
      std::size_t points = 0;
      for (int k = -1; k < p->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? p->getExteriorRing() : p->getInteriorRing(k);
        Plan& pl = plans[static_cast<std::size_t>(k + 1)];
        pl.v.reserve(static_cast<std::size_t>(std::max(0, r->getNumPoints() - 1)));
        for (int i = 0; i + 1 < r->getNumPoints(); ++i) pl.v.push_back({r->getX(i), r->getY(i)});
        points += pl.v.size();
      }
      // Each ring is planned on its own (plan_ring reads only the input's rings and grid): on
      // two threads when there is enough work, rings claimed in order; the plans are the same.
      {
        std::atomic<std::size_t> next{0};
        auto work = [&] {
          for (std::size_t k; (k = next.fetch_add(1)) < plans.size();) plan_ring(plans[k]);
        };
        if (max_threads() >= 2 && points > 20000) run_beside(work, work);
        else work();
      }
      std::size_t nruns = 0;
      for (Plan& pl : plans) {
        pl.first_run = nruns;
        nruns += pl.runs.size();
      }
      if (nruns == 0) continue;
      std::vector<char> off(nruns, 0);
      Rings rings;
      int rounds = 0;
      const bool settled = settle(plans, off, rings, rounds);
      if (debug::value(debug::Aid::kFilter) && plans[0].v.size() > 5000) {
        std::size_t nin = 0, nout = 0, noff = 0;
        for (const auto& pl : plans) nin += pl.v.size();
        for (const auto& r : rings) nout += r.size();
        for (char c : off) noff += c != 0;
        std::fprintf(stderr, "restore: %zu -> %zu vertices, %zu runs, %zu given up, settled %d after %d rounds\n", nin,
                     nout, nruns, noff, settled, rounds);
      }
      if (!settled) continue;  // (cap reached: the buffer's coordinates stay)
      bool changed = false;
      for (std::size_t k = 0; k < rings.size() && !changed; ++k) changed = rings[k] != plans[k].v;
      if (!changed) continue;
      for (const auto& r : rings)
        if (r.size() < 3) changed = false;
      if (!changed) continue;
      *p = to_ogr_closed(rings);
      any = true;
    }
    if (!any) return g;
    return GeomPtr(multi(ps).release());
  }

 private:
  struct InRing {
    std::vector<Point2> p;    // without the closing repeat
    std::vector<double> cum;  // arc length at each vertex (cum[n] = perimeter)
    std::size_t first_seg = 0;
  };
  struct Where {
    int ring = -1;
    double s = 0;  // position: segment index + fraction
    double d = 0;  // distance to the input
  };

  // A segment by its exact coordinates (bit patterns) and the run it belongs to.
  using SegKey = std::array<std::uint64_t, 5>;
  static SegKey seg_key(Point2 a, Point2 b, long tag) {
    SegKey k;
    std::memcpy(&k[0], &a.x, 8);
    std::memcpy(&k[1], &a.y, 8);
    std::memcpy(&k[2], &b.x, 8);
    std::memcpy(&k[3], &b.y, 8);
    k[4] = static_cast<std::uint64_t>(tag);
    return k;
  }
  static Box2 seg_box(Point2 a, Point2 b) {
    Box2 bx;
    bx.add(a);
    bx.add(b);
    return bx;
  }
  static bool boxes_meet(const Box2& p, const Box2& q) {
    return p.lo.x <= q.hi.x && q.lo.x <= p.hi.x && p.lo.y <= q.hi.y && q.lo.y <= p.hi.y;
  }
  // sub = the segments not in `prev` (sorted) or repeated (new) and every segment whose bounding box
  // meets a new one's: any contact with a new segment or with an end of one is among them.
  static void local_subset(const std::vector<Point2>& pts, const std::vector<pslg::Segment>& segs,
                           const std::vector<SegKey>& keys, const std::vector<char>& repeated,
                           const std::vector<SegKey>& prev, std::vector<std::size_t>& sub) {
    sub.clear();
    std::vector<std::size_t> fresh;
    Box2 fb;
    double len = 0;
    auto P = [&](Index i) { return pts[static_cast<std::size_t>(i)]; };
    for (std::size_t si = 0; si < segs.size(); ++si)
      if (repeated[si] || !std::binary_search(prev.begin(), prev.end(), keys[si])) {
        fresh.push_back(si);
        fb.add(P(segs[si].a));
        fb.add(P(segs[si].b));
        len += dist(P(segs[si].a), P(segs[si].b));
      }
    if (fresh.empty()) return;
    pslg::SegmentGrid grid(fb, fresh.size(), len / static_cast<double>(fresh.size()));
    for (std::size_t k = 0; k < fresh.size(); ++k)
      grid.add_segment(static_cast<Index>(k), P(segs[fresh[k]].a), P(segs[fresh[k]].b));
    std::vector<Index> near;
    for (std::size_t si = 0; si < segs.size(); ++si) {
      const Box2 b = seg_box(P(segs[si].a), P(segs[si].b));
      if (!boxes_meet(b, fb)) continue;
      grid.segments_near(b, &near);
      for (Index k : near)
        if (boxes_meet(b, seg_box(P(segs[fresh[k]].a), P(segs[fresh[k]].b)))) {
          sub.push_back(si);
          break;
        }
    }
  }

  static OGRPolygon to_ogr_closed(const Rings& rings) {
    OGRPolygon p;
    for (const auto& ring : rings) {
      OGRLinearRing r = closed_ring(ring);
      p.addRing(&r);
    }
    return p;
  }

  Where locate(Point2 q, std::vector<Index>& cand) const {
    Where w;
    if (!box_.contains(q)) return w;
    Box2 b;
    b.add(q - Point2{hair_, hair_});
    b.add(q + Point2{hair_, hair_});
    // Every segment of the cells near q, some more than once: the nearest (ties to the smaller
    // id) does not depend on repeats, and reading the cells directly keeps locate() free of the
    // grid's shared stamps, so rings are planned on several threads.
    cand.clear();
    grid_->for_box_cells(b, [&](std::size_t c) {
      const auto& in = grid_->segments_in(c);
      cand.insert(cand.end(), in.begin(), in.end());
    });
    double best = hair_;
    Index best_id = 0;
    for (Index id : cand) {
      const auto [k, i] = seg_ring_[static_cast<std::size_t>(id)];
      const auto& ir = rings_[k];
      const Point2 a = ir.p[i], c = ir.p[(i + 1) % ir.p.size()];
      const double d = dist_to_segment(q, a, c);
      if (d < best || (d == best && w.ring >= 0 && id < best_id)) {
        best = d;
        best_id = id;
        w.d = d;
        const Point2 ac = c - a;
        const double l2 = ac.x * ac.x + ac.y * ac.y;
        double t = l2 > 0 ? ((q.x - a.x) * ac.x + (q.y - a.y) * ac.y) / l2 : 0.0;
        t = std::clamp(t, 0.0, 1.0);
        w.ring = static_cast<int>(k);
        // (the end of the last segment is position 0, not n: positions stay in [0, n))
        w.s = t < 1 ? static_cast<double>(i) + t : static_cast<double>((i + 1) % ir.p.size());
      }
    }
    return w;
  }
  double arc_at(const InRing& ir, double s) const {
    const std::size_t i = static_cast<std::size_t>(s);
    const double t = s - static_cast<double>(i);
    return ir.cum[i] + t * (ir.cum[i + 1] - ir.cum[i]);
  }

  struct Run {
    std::size_t a = 0, len = 0;  // from vertex a, len links
    int dir = 0;                 // along the input ring: +1, -1, 0 (no input vertex between)
  };
  struct Plan {
    std::vector<Point2> v;       // the buffer's ring
    std::vector<Where> at;
    std::size_t start = 0;       // walk from here
    std::vector<Run> runs;       // in walking order; vertices not in a run stay
    std::size_t first_run = 0;   // global id of runs[0]
  };

  void plan_ring(Plan& pl) const {
    const auto& v = pl.v;
    const std::size_t n = v.size();
    if (n < 3) return;
    std::vector<Index> cand;
    pl.at.resize(n);
    for (std::size_t i = 0; i < n; ++i) pl.at[i] = locate(v[i], cand);
    // link[i]: v[i] -> v[i+1] follows the input: +1 forwards, -1 backwards, 2 either (same
    // place), 0 no.
    std::vector<int> link(n, 0);
    for (std::size_t i = 0; i < n; ++i) {
      const Where a = pl.at[i], b = pl.at[(i + 1) % n];
      if (a.ring < 0 || a.ring != b.ring) continue;
      const auto& ir = rings_[static_cast<std::size_t>(a.ring)];
      const double L = ir.cum.back();
      double fwd = arc_at(ir, b.s) - arc_at(ir, a.s);
      if (fwd < 0) fwd += L;
      const double bwd = fwd > 0 ? L - fwd : 0;
      const double lim = dist(v[i], v[(i + 1) % n]) + 2 * hair_;
      if (fwd == 0) link[i] = 2;
      else if (fwd <= lim && fwd <= bwd) link[i] = 1;
      else if (bwd <= lim) link[i] = -1;
    }
    // Start after a broken link (a ring that follows the input all the way round: anywhere).
    bool broken = false;
    for (std::size_t i = 0; i < n; ++i)
      if (link[i] == 0) { pl.start = (i + 1) % n; broken = true; break; }
    std::size_t i = 0;
    while (i < n) {
      // Longest run from here with one direction (a ring that follows the input all the way
      // round closes onto its start: n links).
      Run run;
      run.a = (pl.start + i) % n;
      const std::size_t max_len = broken ? n - 1 - i : n - i;
      while (run.len < max_len) {
        const int l = link[(pl.start + i + run.len) % n];
        if (l == 0) break;
        if (l != 2) {
          if (run.dir == 0) run.dir = l;
          else if (l != run.dir) break;
        }
        ++run.len;
      }
      if (run.len == 0) { ++i; continue; }
      const std::size_t step = run.len;
      // Its ends must lie on the input (up to rounding): a run ending at an arc point off the
      // coast would replace the coast's own points next to it by a chord from there.
      if (run.len < n) {
        while (run.len > 0 && pl.at[run.a].d > on_tol_) { run.a = (run.a + 1) % n; --run.len; }
        while (run.len > 0 && pl.at[(run.a + run.len) % n].d > on_tol_) --run.len;
      }
      // A run of one link with no input vertex between changes nothing: not a run.
      if (run.len >= 2 || (run.len == 1 && run.dir != 0)) pl.runs.push_back(run);
      i += step;
    }
  }

  // The ring with every run not switched off replaced by the input's vertices; seg_tag gets,
  // per segment (from vertex k to k+1), the global run id it belongs to or -1.
  std::vector<Point2> build_ring(const Plan& pl, const std::vector<char>& off, std::vector<long>& seg_tag) const {
    const auto& v = pl.v;
    const std::size_t n = v.size();
    std::vector<Point2> out;
    out.reserve(n);
    seg_tag.clear();
    auto push = [&](Point2 p, long tag) {
      if (!out.empty() && out.back() == p) {
        if (tag >= 0) seg_tag.back() = tag;
        return;
      }
      out.push_back(p);
      seg_tag.push_back(tag);
    };
    std::size_t r = 0;  // next run
    for (std::size_t i = 0; i < n;) {
      const std::size_t a = (pl.start + i) % n;
      if (r < pl.runs.size() && pl.runs[r].a == a && !off[pl.first_run + r]) {
        const Run& run = pl.runs[r];
        const long tag = static_cast<long>(pl.first_run + r);
        push(v[a], tag);
        const std::size_t b = (a + run.len) % n;
        if (run.dir != 0) {
          const auto& ir = rings_[static_cast<std::size_t>(pl.at[a].ring)];
          const double m = static_cast<double>(ir.p.size());
          const double s0 = pl.at[a].s;
          double s1 = pl.at[b].s;
          const bool whole = run.len == n;
          if (run.dir > 0) {
            if (s1 < s0 || (whole && s1 == s0)) s1 += m;
            for (double k = std::floor(s0) + 1; k < s1; k += 1)
              push(ir.p[static_cast<std::size_t>(k) % ir.p.size()], tag);
          } else {
            if (s1 > s0 || (whole && s1 == s0)) s1 -= m;
            for (double k = std::ceil(s0) - 1; k > s1; k -= 1)
              push(ir.p[static_cast<std::size_t>(k + 2 * m) % ir.p.size()], tag);
          }
        }
        i += run.len;
        ++r;
        continue;
      }
      if (r < pl.runs.size() && pl.runs[r].a == a) ++r;  // switched off: the buffer's vertices
      push(v[a], -1);
      ++i;
    }
    while (out.size() > 1 && out.front() == out.back()) {
      out.pop_back();
      seg_tag.pop_back();
    }
    return out;
  }

  // Runs whose new segments meet anything (other than at a shared end) are given up, round after
  // round, until the only contacts left are the buffer's own (valid in GEOS); `rings` gets the
  // last round's rings. False when the cap on rounds came first.
  // Rounds after the first examine only what the previous round changed: a contact between
  // segments (same coordinates, same run) that were there before was found then and its runs
  // given up, so only contacts near a new segment can give up more (the same result for a
  // fraction of the work; full_rounds_: every round examines everything, for the test of that).
  bool settle(const std::vector<Plan>& plans, std::vector<char>& off, Rings& rings, int& rounds) const {
    const bool full_rounds = full_rounds_;
    std::vector<SegKey> prev_keys;  // the previous round's segments
    bool settled = false;
    for (int round = 0; round < 8 && !settled; ++round, ++rounds) {
      rings.clear();
      std::vector<Point2> pts;
      std::vector<pslg::Segment> segs;
      std::vector<long> tag;  // per segment: global run id, or -1 (the buffer's own)
      for (const auto& pl : plans) {
        std::vector<long> st;
        std::vector<Point2> w = build_ring(pl, off, st);
        const auto base = static_cast<Index>(pts.size());
        for (std::size_t i = 0; i < w.size(); ++i) {
          pts.push_back(w[i]);
          segs.push_back({base + static_cast<Index>(i), base + static_cast<Index>((i + 1) % w.size())});
          tag.push_back(st[i]);
        }
        rings.push_back(std::move(w));
      }
      std::vector<std::size_t> seg_of_pt_prev(pts.size()), seg_of_pt_next(pts.size());
      for (std::size_t si = 0; si < segs.size(); ++si) {
        seg_of_pt_next[static_cast<std::size_t>(segs[si].a)] = si;
        seg_of_pt_prev[static_cast<std::size_t>(segs[si].b)] = si;
      }
      std::vector<std::size_t> bad;  // segments in a contact
      std::vector<SegKey> keys(segs.size());
      for (std::size_t si = 0; si < segs.size(); ++si)
        keys[si] = seg_key(pts[static_cast<std::size_t>(segs[si].a)], pts[static_cast<std::size_t>(segs[si].b)], tag[si]);
      // The segments to examine (all in the first round) and the points among their ends.
      const bool all = round == 0 || full_rounds;
      std::vector<std::size_t> sub;
      std::vector<char> alive;
      if (all) {
        sub.resize(segs.size());
        for (std::size_t si = 0; si < segs.size(); ++si) sub[si] = si;
      } else {
        // Sorted copies, not hash sets: a set of every segment of a ring with hundreds of
        // thousands of vertices costs more in its nodes than the sort.
        std::sort(prev_keys.begin(), prev_keys.end());
        // A key found twice in this round counts as new in every copy (the previous round
        // may have had one copy only).
        std::vector<SegKey> cur(keys), dup;
        std::sort(cur.begin(), cur.end());
        for (std::size_t i = 1; i < cur.size(); ++i)
          if (cur[i] == cur[i - 1] && (dup.empty() || dup.back() != cur[i])) dup.push_back(cur[i]);
        std::vector<char> repeated(segs.size(), 0);
        if (!dup.empty())
          for (std::size_t si = 0; si < segs.size(); ++si)
            repeated[si] = std::binary_search(dup.begin(), dup.end(), keys[si]) ? 1 : 0;
        local_subset(pts, segs, keys, repeated, prev_keys, sub);
        alive.assign(pts.size(), 0);
        for (std::size_t si : sub) {
          alive[static_cast<std::size_t>(segs[si].a)] = 1;
          alive[static_cast<std::size_t>(segs[si].b)] = 1;
        }
      }
      prev_keys = std::move(keys);
      std::vector<pslg::Segment> sub_segs;
      sub_segs.reserve(sub.size());
      for (std::size_t si : sub) sub_segs.push_back(segs[si]);
      const pslg::Contacts ct = find_contacts_2(pts, sub_segs, all ? nullptr : &alive);
      for (const auto& [x, y] : ct.segment_pairs) { bad.push_back(sub[static_cast<std::size_t>(x)]); bad.push_back(sub[static_cast<std::size_t>(y)]); }
      for (const auto& [v, sg] : ct.vertex_on_segment) {
        bad.push_back(sub[static_cast<std::size_t>(sg)]);
        bad.push_back(seg_of_pt_prev[static_cast<std::size_t>(v)]);
        bad.push_back(seg_of_pt_next[static_cast<std::size_t>(v)]);
      }
      {  // a vertex repeated (rings touching there): the runs that brought it
        std::vector<std::size_t> order;
        order.reserve(pts.size());
        for (std::size_t i = 0; i < pts.size(); ++i)
          if (all || alive[i]) order.push_back(i);
        std::sort(order.begin(), order.end(), [&](std::size_t x, std::size_t y) {
          return pts[x].x != pts[y].x ? pts[x].x < pts[y].x : (pts[x].y != pts[y].y ? pts[x].y < pts[y].y : x < y);
        });
        for (std::size_t i = 0; i + 1 < order.size(); ++i)
          if (pts[order[i]] == pts[order[i + 1]])
            for (std::size_t q : {order[i], order[i + 1]}) {
              bad.push_back(seg_of_pt_prev[q]);
              bad.push_back(seg_of_pt_next[q]);
            }
      }
      settled = true;
      for (std::size_t si : bad)
        if (tag[si] >= 0 && !off[static_cast<std::size_t>(tag[si])]) {
          off[static_cast<std::size_t>(tag[si])] = 1;
          settled = false;
        }
    }
    return settled;
  }

  double hair_;
  double on_tol_ = 0;  // a vertex this close to the input is on it (rounding of the buffers)
  bool full_rounds_ = false;
  Box2 box_;
  std::vector<InRing> rings_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> seg_ring_;  // segment id -> (ring, index)
  std::unique_ptr<pslg::SegmentGrid> grid_;
};

CoastRestorer::CoastRestorer(const OGRGeometry* input, double hair, bool full_rounds)
    : impl_(std::make_unique<Impl>(input, hair, full_rounds)) {}
CoastRestorer::~CoastRestorer() = default;
GeomPtr CoastRestorer::restore(GeomPtr g) const { return impl_->restore(std::move(g)); }

// Moves every vertex within `hair` of an input vertex onto the nearest one (ties: the smaller
// x, then y), so boundaries the buffers left unchanged up to rounding are bitwise the input's.
struct Snapper::Impl {
 public:
  Impl(const OGRGeometry* input, double hair) : hair_(hair) {
    std::vector<std::unique_ptr<OGRPolygon>> ps;
    polygons_of(input, ps);
    for (const auto& w : ps)
      for (int k = -1; k < w->getNumInteriorRings(); ++k) {
        const OGRLinearRing* r = k < 0 ? w->getExteriorRing() : w->getInteriorRing(k);
        for (int i = 0; i < r->getNumPoints(); ++i)
          cells_[key(cell(r->getX(i)), cell(r->getY(i)))].push_back({r->getX(i), r->getY(i)});
      }
  }
  void snap(OGRPolygon* p) const {
    snap_ring(p->getExteriorRing());
    for (int k = 0; k < p->getNumInteriorRings(); ++k) snap_ring(p->getInteriorRing(k));
  }

 private:
  std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / hair_)); }
  static std::uint64_t key(std::int64_t i, std::int64_t j) {
    return (static_cast<std::uint64_t>(i) << 32) ^ static_cast<std::uint64_t>(j & 0xffffffff);
  }
  void snap_ring(OGRLinearRing* r) const {
    for (int i = 0; i < r->getNumPoints(); ++i) {
      const double x = r->getX(i), y = r->getY(i);
      double best = hair_;
      Point2 to{x, y};
      bool found = false;
      const std::int64_t ci = cell(x), cj = cell(y);
      for (std::int64_t di = -1; di <= 1; ++di)
        for (std::int64_t dj = -1; dj <= 1; ++dj) {
          const auto it = cells_.find(key(ci + di, cj + dj));
          if (it == cells_.end()) continue;
          for (const Point2 q : it->second) {
            const double d = std::hypot(q.x - x, q.y - y);
            if (d < best || (d == best && found && (q.x < to.x || (q.x == to.x && q.y < to.y)))) {
              best = d;
              to = q;
              found = true;
            }
          }
        }
      if (found) r->setPoint(i, to.x, to.y);
    }
  }
  double hair_;
  std::unordered_map<std::uint64_t, std::vector<Point2>> cells_;
};

Snapper::Snapper(const OGRGeometry* input, double hair) : impl_(std::make_unique<Impl>(input, hair)) {}
Snapper::~Snapper() = default;
void Snapper::snap(OGRPolygon* p) const { impl_->snap(p); }

void snap_to_input(std::vector<std::unique_ptr<OGRPolygon>>& outp, const Snapper& snapper) {
  for (auto& p : outp) {
    std::unique_ptr<OGRPolygon> q(p->clone());
    snapper.snap(q.get());
    // (the exact sufficient test first: GEOS's IsValid on a polygon with a thousand holes is
    // slow)
    Rings qr;
    qr.push_back(ring_points(q->getExteriorRing(), true));
    for (int k = 0; k < q->getNumInteriorRings(); ++k) qr.push_back(ring_points(q->getInteriorRing(k), false));
    if (surely_valid(qr) || q->IsValid()) p = std::move(q);
  }
}

}  // namespace fdr::coast
