// Boundary resampling to f (see resample.hpp): chains, Douglas-Peucker corners, placement by
// integral ds / f, tolerance repair, exact conflict checks with restoration of input pieces.
#include "pslg/resample.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "predicates/predicates.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg {
namespace {

struct Chain {
  std::vector<Index> v;  // input vertex ids along the chain; closed: v.front() == v.back()
  std::int32_t marker = 0, part = -1;
  bool closed = false;
  // Per input segment: how many times a piece over it conflicted; the tolerance there is
  // halved each time, and at kMaxLevel the input vertices are kept.
  std::vector<std::uint8_t> level;
  Index first_a = 0, first_b = 0;  // the chain's first input segment (its side: chain_left_inside)
  bool free_seam = false;          // a ring without anchors: its seam may move (small_ring)
};

constexpr std::uint8_t kMaxLevel = 6;

// A piece of a chain between two key vertices v[k0] and v[k1]; `inner` are the new points
// strictly between them (an input vertex id when the point is an input vertex, else kNoId).
struct Piece {
  std::size_t chain = 0, k0 = 0, k1 = 0;
  std::vector<Point2> inner;
  std::vector<Index> inner_id;
  bool restored = false;  // tolerance 0: the input vertices
  double deviation = 0;   // max distance input vertex -> new piece
  bool changed() const { return inner_id.size() != k1 - k0 - 1 || std::any_of(inner_id.begin(), inner_id.end(), [](Index i) { return i == kNoId; }); }
};

double turn(Point2 a, Point2 b, Point2 c) {
  const Point2 u = b - a, w = c - b;
  return std::fabs(std::atan2(u.x * w.y - u.y * w.x, dot(u, w)));
}

class Resampler {
 public:
  Resampler(const Pslg& in, const ResampleOptions& o) : in_(in), o_(o) {
    if (!o_.spacing) throw Error(ExitCode::kInternal, "resample: no spacing function");
    if (!(o_.spacing_factor > 0) || !(o_.tolerance_factor >= 0))
      throw Error(ExitCode::kUsage, "resample: spacing factor must be > 0 and tolerance factor >= 0");
  }

  Pslg run(ResampleStats* st) {
    StepLaps lap(debug::Aid::kClean, "  resample");
    pts_ = in_.points;
    build_chains();
    lap("chains");
    chain_pieces_.resize(chains_.size());
    for (std::size_t c = 0; c < chains_.size(); ++c) plan_chain(c);
    lap("plan");
    Pslg out;
    std::size_t round = 0;
    for (;; ++round) {
      out = assemble();
      lap("assemble");
      std::vector<std::size_t> bad;
      const bool conflicts = find_conflicts(out, &bad);
      lap("conflicts");
      if (!conflicts) break;
      if (round + 1 >= o_.max_rounds) {  // give up: keep every input vertex
        for (auto& ch : chains_) std::fill(ch.level.begin(), ch.level.end(), kMaxLevel);
        for (std::size_t c = 0; c < chains_.size(); ++c) plan_chain(c);
        out = assemble();
        break;
      }
      // Why halve the tolerance instead of restoring the input at once: a conflict is almost
      // always two chains closer than the tolerance (a narrow channel); a closer chord fixes it
      // and keeps the coarse spacing along the chain.
      std::vector<char> dirty(chains_.size(), 0);
      for (std::size_t q : bad) {
        const auto& [c, k0, k1] = flat_[q];
        for (std::size_t k = k0; k < k1; ++k)
          chains_[c].level[k] = static_cast<std::uint8_t>(std::min<int>(chains_[c].level[k] + 1, kMaxLevel));
        dirty[c] = 1;
      }
      for (std::size_t c = 0; c < chains_.size(); ++c)
        if (dirty[c]) plan_chain(c);
    }
    if (st) {
      st->chains = chains_.size();
      st->pieces = flat_.size();
      st->pieces_restored = 0;
      for (const auto& ps : chain_pieces_)
        for (const auto& p : ps) st->pieces_restored += p.restored;
      st->rounds = round + 1;
      st->max_deviation = 0;
      for (const auto& ps : chain_pieces_)
        for (const auto& p : ps) st->max_deviation = std::max(st->max_deviation, p.deviation);
      std::vector<char> used(in_.points.size(), 0);
      for (const auto& s : in_.segments) used[s.a] = used[s.b] = 1;
      st->vertices_in = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
      std::vector<char> used2(out.points.size(), 0);
      for (const auto& s : out.segments) used2[s.a] = used2[s.b] = 1;
      st->vertices_out = static_cast<std::size_t>(std::count(used2.begin(), used2.end(), 1));
    }
    return out;
  }

 private:
  double f(Point2 p) const {
    const double v = o_.spacing(p);
    if (!(v > 0) || !std::isfinite(v))
      throw Error(ExitCode::kInvalidSpacing, "resample: spacing f = " + std::to_string(v) + " at (" +
                                                 std::to_string(in_.origin.x + p.x) + ", " +
                                                 std::to_string(in_.origin.y + p.y) + ") must be finite and > 0");
    return v;
  }
  Point2 P(std::size_t c, std::size_t k) const { return pts_[chains_[c].v[k]]; }
  // A point added on an input segment (the midpoint of a short piece, merge_short_pieces): a
  // candidate key, never kept as an input vertex.
  bool is_virtual(Index v) const { return v >= in_.points.size(); }

  void build_chains() {
    const std::size_t n = in_.points.size();
    std::vector<std::uint32_t> deg(n, 0);
    for (const auto& s : in_.segments) {
      if (s.a == s.b) continue;
      ++deg[s.a];
      ++deg[s.b];
    }
    std::vector<std::size_t> start(n + 1, 0);
    for (std::size_t v = 0; v < n; ++v) start[v + 1] = start[v] + deg[v];
    std::vector<std::size_t> adj(start[n]);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (std::size_t s = 0; s < in_.segments.size(); ++s) {
      const auto& g = in_.segments[s];
      if (g.a == g.b) continue;
      adj[fill[g.a]++] = s;
      adj[fill[g.b]++] = s;
    }
    auto other = [&](std::size_t s, Index v) { return in_.segments[s].a == v ? in_.segments[s].b : in_.segments[s].a; };
    std::vector<char> anchor(n, 0);
    for (std::size_t v = 0; v < n; ++v) {
      if (deg[v] == 0) continue;
      if (deg[v] != 2) { anchor[v] = 1; continue; }
      const auto& s0 = in_.segments[adj[start[v]]];
      const auto& s1 = in_.segments[adj[start[v] + 1]];
      if (s0.marker != s1.marker || s0.part != s1.part) anchor[v] = 1;
      if (!in_.point_markers.empty() && in_.point_markers[v] != 0) anchor[v] = 1;
    }
    std::vector<char> used(in_.segments.size(), 0);
    auto walk = [&](Index v0, std::size_t s0) {
      Chain c;
      c.marker = in_.segments[s0].marker;
      c.part = in_.segments[s0].part;
      c.v.push_back(v0);
      Index cur = v0;
      std::size_t seg = s0;
      for (;;) {
        used[seg] = 1;
        const Index nx = other(seg, cur);
        c.v.push_back(nx);
        if (anchor[nx] || nx == v0) break;
        const std::size_t a0 = adj[start[nx]], a1 = adj[start[nx] + 1];
        seg = a0 == seg ? a1 : a0;
        cur = nx;
        if (used[seg]) break;
      }
      c.closed = c.v.front() == c.v.back();
      c.level.assign(c.v.size() - 1, 0);
      c.first_a = c.v[0];
      c.first_b = c.v[1];
      return c;
    };
    for (std::size_t v = 0; v < n; ++v) {
      if (!anchor[v]) continue;
      for (std::size_t k = start[v]; k < start[v + 1]; ++k)
        if (!used[adj[k]] && in_.segments[adj[k]].a != in_.segments[adj[k]].b) chains_.push_back(walk(static_cast<Index>(v), adj[k]));
    }
    // Rings without an anchor: start at their sharpest corner, so that the seam is a corner.
    for (std::size_t s = 0; s < in_.segments.size(); ++s) {
      if (used[s] || in_.segments[s].a == in_.segments[s].b) continue;
      Chain c = walk(in_.segments[s].a, s);
      if (c.closed && c.v.size() > 3) {
        const std::size_t m = c.v.size() - 1;
        std::size_t best = 0;
        double bt = -1;
        for (std::size_t k = 0; k < m; ++k) {
          const double t = turn(in_.points[c.v[(k + m - 1) % m]], in_.points[c.v[k]], in_.points[c.v[(k + 1) % m]]);
          if (t > bt) { bt = t; best = k; }
        }
        std::vector<Index> r(c.v.begin(), c.v.end() - 1);
        std::rotate(r.begin(), r.begin() + static_cast<std::ptrdiff_t>(best), r.end());
        r.push_back(r.front());
        c.v = std::move(r);
        c.first_a = c.v[0];
        c.first_b = c.v[1];
        c.free_seam = true;
      }
      chains_.push_back(std::move(c));
    }
  }

  double tol(Point2 a, Point2 b) const { return o_.tolerance_factor * std::min(f(a), f(b)); }

  // Tolerance scale over input segments [i, j): 0.5^level, 0 once a segment is at kMaxLevel.
  double tol_scale(std::size_t c, std::size_t i, std::size_t j) const {
    std::uint8_t L = 0;
    for (std::size_t k = i; k < j; ++k) L = std::max(L, chains_[c].level[k]);
    return L >= kMaxLevel ? 0.0 : std::ldexp(1.0, -static_cast<int>(L));
  }

  void plan_chain(std::size_t c) {
    const Chain& ch = chains_[c];
    const std::size_t m = ch.v.size() - 1;
    std::vector<char> key(m + 1, 0);
    key[0] = key[m] = 1;
    // Douglas-Peucker with a local tolerance: the corners that must stay.
    std::vector<std::pair<std::size_t, std::size_t>> stack{{0, m}};
    while (!stack.empty()) {
      const auto [i, j] = stack.back();
      stack.pop_back();
      if (j <= i + 1) continue;
      const Point2 a = P(c, i), b = P(c, j);
      double dmax = -1;
      std::size_t kmax = i + 1;
      for (std::size_t k = i + 1; k < j; ++k) {
        const double d = dist_to_segment(P(c, k), a, b);
        if (d > dmax) { dmax = d; kmax = k; }
      }
      const double sc = tol_scale(c, i, j);
      if (dmax > tol(a, b) * sc || a == b || sc == 0) {
        key[kmax] = 1;
        stack.push_back({i, kmax});
        stack.push_back({kmax, j});
      }
    }
    // Keys where the simplified chain hardly turns are not corners, only where Douglas-Peucker
    // happened to cut a smooth curve: dropping them lets the spacing run evenly along the curve
    // (the tolerance repair in place() puts back what the chord would miss).
    {
      std::vector<std::size_t> ks;
      for (std::size_t k = 0; k <= m; ++k)
        if (key[k]) ks.push_back(k);
      std::size_t prev = ks.front();
      for (std::size_t i = 1; i + 1 < ks.size(); ++i) {
        const std::size_t k = ks[i], nx = ks[i + 1];
        if (tol_scale(c, prev, nx) == 0) { prev = k; continue; }
        if (turn(P(c, prev), P(c, k), P(c, nx)) < kCornerTurn) key[k] = 0;
        else prev = k;
      }
    }
    merge_short_pieces(c, key);  // may add midpoints to the chain
    const std::size_t m2 = ch.v.size() - 1;
    // A ring keeps at least three pieces (a non-degenerate polygon): add keys at a third and two
    // thirds of its length.
    if (ch.closed) {
      std::size_t nkeys = static_cast<std::size_t>(std::count(key.begin(), key.end(), 1)) - 1;
      if (nkeys < 3 && m2 >= 3) {
        std::vector<double> cum(m2 + 1, 0);
        for (std::size_t k = 0; k < m2; ++k) cum[k + 1] = cum[k] + dist(P(c, k), P(c, k + 1));
        for (double frac : {1.0 / 3.0, 2.0 / 3.0}) {
          const auto it = std::lower_bound(cum.begin(), cum.end(), frac * cum[m2]);
          std::size_t k = static_cast<std::size_t>(it - cum.begin());
          k = std::clamp<std::size_t>(k, 1, m2 - 1);
          key[k] = 1;
        }
      }
    }
    auto& pieces = chain_pieces_[c];
    pieces.clear();
    std::size_t k0 = 0;
    for (std::size_t k = 1; k <= m2; ++k) {
      if (!key[k]) continue;
      Piece p;
      p.chain = c;
      p.k0 = k0;
      p.k1 = k;
      const double sc = tol_scale(c, k0, k);
      if (sc == 0) p.restored = true;
      else place(p, sc);
      pieces.push_back(std::move(p));
      k0 = k;
    }
    // A closed chain of two pieces would be two segments between the same two vertices.
    if (ch.closed && m2 >= 3) {
      std::size_t pts = 0;
      for (const auto& p : pieces) pts += 1 + (p.restored ? p.k1 - p.k0 - 1 : p.inner.size());
      if (pts < 3)
        for (auto& p : pieces) p.restored = true;
    }
    if (ch.free_seam && o_.small_rings) small_ring(c);
  }

  // Shortest segment of chain c's planned pieces over f (at the nearer end's smaller f).
  double planned_min_ratio(std::size_t c) const {
    double r = std::numeric_limits<double>::infinity();
    for (const Piece& p : chain_pieces_[c]) {
      std::vector<Point2> seq{P(c, p.k0)};
      if (p.restored) {
        for (std::size_t k = p.k0 + 1; k < p.k1; ++k) seq.push_back(P(c, k));
      } else {
        seq.insert(seq.end(), p.inner.begin(), p.inner.end());
      }
      seq.push_back(P(c, p.k1));
      for (std::size_t i = 0; i + 1 < seq.size(); ++i)
        r = std::min(r, dist(seq[i], seq[i + 1]) / std::min(f(seq[i]), f(seq[i + 1])));
    }
    return r;
  }

  // Small rings (islands a few elements round): Douglas-Peucker keeps the corners the tolerance
  // needs, and two of them often end up a fraction of f apart (the blunt end of a small
  // island), so the mesh refines to their distance all around it. A ring of at most
  // kSmallRing steps of ds / (spacing_factor f) whose plan has a piece under kShortPiece * f is
  // planned again as n points at equal steps along it, n near its step count, from the
  // starting point (on the input line) that makes the shortest chord longest while every input
  // vertex stays within the tolerance; the seam moves to the first of them. Only when no
  // conflict was found on the ring yet (every level 0), and only when it gains.
  void small_ring(std::size_t c) {
    Chain& ch = chains_[c];
    const std::size_t m = ch.v.size() - 1;
    if (m < 3 || m > kSmallRingVertices) return;
    for (auto L : ch.level)
      if (L != 0) return;
    const double old = planned_min_ratio(c);
    if (!(old < kShortPiece)) return;
    // lambda at every vertex: integral ds / (spacing_factor f) along the ring
    std::vector<double> lam(m + 1, 0.0), seg_f(m);
    for (std::size_t k = 0; k < m; ++k) {
      const Point2 a = P(c, k), b = P(c, k + 1);
      seg_f[k] = f(0.5 * (a + b));
      lam[k + 1] = lam[k] + dist(a, b) / (o_.spacing_factor * seg_f[k]);
    }
    const double total = lam[m];
    if (!(total > 0) || total > kSmallRing) return;
    const long n0 = std::max(3L, std::lround(total));
    struct Cand { double score = -1, dev = 0; long n = 0; double off = 0; };
    Cand best;
    std::vector<std::size_t> qk(16);  // segment of each new point
    std::vector<double> qt(16);
    std::vector<Point2> q(16);
    auto point_at = [&](double L, std::size_t* k, double* t) {
      while (L >= total) L -= total;
      std::size_t j = static_cast<std::size_t>(std::upper_bound(lam.begin(), lam.end(), L) - lam.begin());
      j = std::clamp<std::size_t>(j, 1, m) - 1;
      const double span = lam[j + 1] - lam[j];
      double w = span > 0 ? (L - lam[j]) / span : 0.0;
      w = std::clamp(w, 0.0, 1.0);
      if (w >= 1.0) { j = (j + 1) % m; w = 0.0; }
      *k = j;
      *t = w;
      const Point2 a = P(c, j), b = P(c, j + 1);
      return w == 0.0 ? a : a + w * (b - a);
    };
    std::vector<double> offs;
    for (long n = std::max(3L, n0 - 1); n <= n0 + 1; ++n) {
      if (n > 16) break;
      const double step = total / static_cast<double>(n);
      offs.clear();
      for (int i = 0; i < kSmallRingOffsets; ++i) offs.push_back(step * i / kSmallRingOffsets);
      for (std::size_t k = 0; k < m; ++k) offs.push_back(std::fmod(lam[k], step));
      for (double off : offs) {
        for (long i = 0; i < n; ++i) q[i] = point_at(off + step * static_cast<double>(i), &qk[i], &qt[i]);
        double score = std::numeric_limits<double>::infinity(), dev = 0;
        bool ok = true;
        for (long i = 0; i < n && ok; ++i) {
          const long i2 = (i + 1) % n;
          const Point2 a = q[i], b = q[i2];
          const double fa = f(a), fb = f(b);
          score = std::min(score, dist(a, b) / std::min(fa, fb));
          const double tl = o_.tolerance_factor * std::min(fa, fb);
          // input vertices strictly after point i and up to before point i2 along the ring
          std::size_t k = (qk[i] + 1) % m;
          const std::size_t kend = qt[i2] > 0 ? (qk[i2] + 1) % m : qk[i2];
          for (std::size_t guard = 0; k != kend && guard < m; k = (k + 1) % m, ++guard) {
            const double d = dist_to_segment(P(c, k), a, b);
            dev = std::max(dev, d);
            if (d > tl) { ok = false; break; }
          }
        }
        if (!ok) continue;
        if (score > best.score + 1e-12 || (std::fabs(score - best.score) <= 1e-12 && dev < best.dev)) best = {score, dev, n, off};
      }
    }
    if (best.n == 0 || !(best.score > old + kSmallRingGain)) return;
    // Rebuild the ring: the new points as vertices of the chain (virtual ones inside input
    // segments), the first of them as the seam.
    const long n = best.n;
    const double step = total / static_cast<double>(n);
    std::vector<Index> ring(ch.v.begin(), ch.v.end() - 1);
    std::vector<std::uint8_t> lev(ch.level.begin(), ch.level.end());
    std::vector<std::pair<std::size_t, double>> at;  // (segment, t) of each new point
    for (long i = 0; i < n; ++i) {
      std::size_t k;
      double t;
      point_at(best.off + step * static_cast<double>(i), &k, &t);
      at.push_back({k, t});
    }
    std::vector<std::vector<std::pair<double, long>>> on_seg(m);
    for (long i = 0; i < n; ++i) on_seg[at[i].first].push_back({at[i].second, i});
    std::vector<Index> nv;
    std::vector<std::uint8_t> nl;
    std::vector<std::size_t> key_of(n, 0);
    for (std::size_t k = 0; k < m; ++k) {
      auto& os = on_seg[k];
      std::sort(os.begin(), os.end());
      std::size_t o = 0;
      if (!os.empty() && os[0].first == 0.0) { key_of[os[0].second] = nv.size(); ++o; }
      nv.push_back(ring[k]);
      nl.push_back(lev[k]);
      const Point2 a = pts_[ring[k]], b = pts_[ring[(k + 1) % m]];
      for (; o < os.size(); ++o) {
        if (os[o].first == 0.0) { key_of[os[o].second] = nv.size() - 1; continue; }
        key_of[os[o].second] = nv.size();
        nv.push_back(static_cast<Index>(pts_.size()));
        pts_.push_back(a + os[o].first * (b - a));
        nl.push_back(lev[k]);
      }
    }
    const std::size_t s0 = key_of[0];
    std::rotate(nv.begin(), nv.begin() + static_cast<std::ptrdiff_t>(s0), nv.end());
    std::rotate(nl.begin(), nl.begin() + static_cast<std::ptrdiff_t>(s0), nl.end());
    nv.push_back(nv.front());
    ch.v = std::move(nv);
    ch.level = std::move(nl);
    const std::size_t m2 = ch.v.size() - 1;
    std::vector<std::size_t> keys;
    for (long i = 0; i < n; ++i) keys.push_back((key_of[i] + m2 - s0) % m2);
    keys.push_back(m2);
    std::sort(keys.begin(), keys.end());
    auto& pieces = chain_pieces_[c];
    pieces.clear();
    for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
      Piece p;
      p.chain = c;
      p.k0 = keys[i];
      p.k1 = keys[i + 1];
      place(p, 1.0);
      pieces.push_back(std::move(p));
    }
  }

  // Largest distance of the input vertices strictly between keys i and j from their chord.
  double chord_deviation(std::size_t c, std::size_t i, std::size_t j) const {
    const Point2 a = P(c, i), b = P(c, j);
    double d = 0;
    for (std::size_t k = i + 1; k < j; ++k) d = std::max(d, dist_to_segment(P(c, k), a, b));
    return d;
  }

  // Short pieces: two corners much closer than f (the rounded end of a cut spit, two bends of a
  // small bay) would make the mesh refine to their distance all around them. Douglas-Peucker
  // keeps both when each is needed on its own; often one key, or one input vertex between them,
  // serves both within the same tolerance. A piece shorter than kShortPiece * f loses a key
  // (or its two keys become one input vertex between them) when every input vertex stays
  // within the tolerance of the new chords; chain ends never move.
  void merge_short_pieces(std::size_t c, std::vector<char>& key) {
    const std::size_t m = key.size() - 1;
    std::vector<std::size_t> ks;
    for (std::size_t k = 0; k <= m; ++k)
      if (key[k]) ks.push_back(k);
    // slack: a tiny piece (shorter than kTinyPiece * f) may move the coast by its own length
    // beyond the (possibly halved) tolerance: one of its two keys serves both within that length.
    // Crossings are still excluded (checked after placing, as for every piece).
    double slack = 0;
    auto ok = [&](std::size_t i, std::size_t j) {
      const double sc = tol_scale(c, i, j);
      return sc > 0 && chord_deviation(c, i, j) <= tol(P(c, i), P(c, j)) * sc + slack;
    };
    // Bounded: every change removes at least one key.
    for (std::size_t i = 0; i + 1 < ks.size();) {
      const std::size_t a = ks[i], b = ks[i + 1];
      const double len = dist(P(c, a), P(c, b));
      if (!(len < kShortPiece * std::min(f(P(c, a)), f(P(c, b))))) { ++i; continue; }
      slack = len < kTinyPiece * std::min(f(P(c, a)), f(P(c, b))) ? len : 0.0;
      const bool a_free = i > 0, b_free = i + 2 < ks.size();
      std::size_t b_now = b;
      // A piece that is one input segment between two corners (a small headland's blunt tip, a
      // notch): its midpoint is a candidate too, which moves the coast by at most half the piece.
      if (a_free && b_free && b == a + 1 && !is_virtual(chains_[c].v[a]) && !is_virtual(chains_[c].v[b])) {
        Chain& ch = chains_[c];
        const Index mid = static_cast<Index>(pts_.size());
        pts_.push_back(0.5 * (P(c, a) + P(c, b)));
        ch.v.insert(ch.v.begin() + static_cast<std::ptrdiff_t>(b), mid);
        ch.level.insert(ch.level.begin() + static_cast<std::ptrdiff_t>(a), ch.level[a]);
        key.insert(key.begin() + static_cast<std::ptrdiff_t>(b), 0);
        for (std::size_t j = i + 1; j < ks.size(); ++j) ++ks[j];
        b_now = b + 1;
      }
      const std::size_t pa = a_free ? ks[i - 1] : a, nb = b_free ? ks[i + 2] : b_now;
      // Candidates: one input vertex k in [a, b] replaces both keys (k == a: b dropped, k == b:
      // a dropped); the one with the smallest deviation wins (ties: the first).
      double best = -1;
      std::size_t bk = 0;
      for (std::size_t k = a; k <= b_now; ++k) {
        if ((k != a && !a_free) || (k != b_now && !b_free)) continue;
        if (!ok(pa, k) || !ok(k, nb)) continue;
        const double d = std::max(chord_deviation(c, pa, k), chord_deviation(c, k, nb));
        if (best < 0 || d < best) { best = d; bk = k; }
      }
      if (best < 0) { ++i; continue; }
      key[a] = key[b_now] = 0;
      key[bk] = 1;
      ks.erase(ks.begin() + static_cast<std::ptrdiff_t>(i), ks.begin() + static_cast<std::ptrdiff_t>(i + 2));
      ks.insert(ks.begin() + static_cast<std::ptrdiff_t>(i), bk);
      if (i > 0) --i;  // the piece before may be short now
    }
  }

  // Points on the input polyline v[k0..k1] at equal steps of integral ds / (factor * f).
  void place(Piece& p, double tol_sc) {
    const std::size_t c = p.chain;
    struct Step { std::size_t k; double t0, t1, lam; };
    std::vector<Step> steps;
    double lam = 0;
    for (std::size_t k = p.k0; k < p.k1; ++k) {
      const Point2 a = P(c, k), b = P(c, k + 1);
      const double len = dist(a, b);
      if (!(len > 0)) continue;
      const double fa = f(a);
      const double h = 0.5 * o_.spacing_factor * fa;
      const std::size_t nsub = static_cast<std::size_t>(std::clamp(std::ceil(len / h), 1.0, 4096.0));
      for (std::size_t s = 0; s < nsub; ++s) {
        const double t0 = static_cast<double>(s) / static_cast<double>(nsub);
        const double t1 = static_cast<double>(s + 1) / static_cast<double>(nsub);
        const Point2 mid = a + (0.5 * (t0 + t1)) * (b - a);
        lam += len * (t1 - t0) / (o_.spacing_factor * f(mid));
        steps.push_back({k, t0, t1, lam});
      }
    }
    const long n = std::max(1L, std::lround(lam));
    struct Pos { std::size_t k; double t; };
    std::vector<Pos> pos;
    std::size_t si = 0;
    double prev = 0;
    for (long t = 1; t < n; ++t) {
      const double target = lam * static_cast<double>(t) / static_cast<double>(n);
      while (si < steps.size() && steps[si].lam < target) { prev = steps[si].lam; ++si; }
      if (si >= steps.size()) break;
      const Step& s = steps[si];
      const double w = s.lam > prev ? (target - prev) / (s.lam - prev) : 0.5;
      pos.push_back({s.k, s.t0 + w * (s.t1 - s.t0)});
    }
    // Sequence of points: ends are key vertices; inner points on the polyline.
    struct Q { Point2 p; Index id; std::size_t k; double t; };
    std::vector<Q> seq;
    seq.push_back({P(c, p.k0), chains_[c].v[p.k0], p.k0, 0.0});
    for (const auto& q : pos) {
      if (q.t <= 0) {
        seq.push_back({P(c, q.k), chains_[c].v[q.k], q.k, 0.0});
      } else {
        const Point2 a = P(c, q.k), b = P(c, q.k + 1);
        seq.push_back({a + q.t * (b - a), kNoId, q.k, q.t});
      }
    }
    seq.push_back({P(c, p.k1), chains_[c].v[p.k1], p.k1, 0.0});
    // Tolerance: an input vertex between two consecutive points further than tol from their
    // chord comes back as a point.
    for (std::size_t i = 0; i + 1 < seq.size();) {
      const Q& a = seq[i];
      const Q& b = seq[i + 1];
      // Input vertices strictly between a and b: after a (index > a.k) and before b (index <
      // b.k, or == b.k when b lies inside segment b.k).
      const std::size_t first = a.k + 1;
      const std::size_t end = b.t > 0 ? b.k + 1 : b.k;  // one past the last
      double dmax = 0;
      std::size_t kmax = 0;
      for (std::size_t k = first; k < end; ++k) {
        const double d = dist_to_segment(P(c, k), a.p, b.p);
        if (d > dmax) { dmax = d; kmax = k; }
      }
      if (kmax != 0 && dmax > tol(a.p, b.p) * tol_sc) {
        seq.insert(seq.begin() + static_cast<std::ptrdiff_t>(i + 1), Q{P(c, kmax), chains_[c].v[kmax], kmax, 0.0});
        continue;
      }
      p.deviation = std::max(p.deviation, dmax);
      ++i;
    }
    for (std::size_t i = 1; i + 1 < seq.size(); ++i) {
      p.inner.push_back(seq[i].p);
      p.inner_id.push_back(seq[i].id);
    }
  }

  Pslg assemble() {
    Pslg out;
    out.origin = in_.origin;
    out.holes = in_.holes;
    out.regions = in_.regions;
    out.points = pts_;  // input points, then the midpoints added (dropped below unless used)
    if (!in_.point_markers.empty()) out.point_markers = in_.point_markers;
    seg_piece_.clear();
    seg_chain_.clear();
    flat_.clear();
    pt_piece_.assign(pts_.size(), kNoPiece);
    for (std::size_t c = 0; c < chains_.size(); ++c) {
      const Chain& ch = chains_[c];
      for (const Piece& p : chain_pieces_[c]) {
        const std::size_t q = flat_.size();
        flat_.push_back({c, p.k0, p.k1});
        std::vector<Index> seq;
        seq.push_back(ch.v[p.k0]);
        if (p.restored) {
          for (std::size_t k = p.k0 + 1; k < p.k1; ++k)
            if (!is_virtual(ch.v[k])) seq.push_back(ch.v[k]);
        } else {
          for (std::size_t i = 0; i < p.inner.size(); ++i) {
            if (p.inner_id[i] != kNoId) {
              seq.push_back(p.inner_id[i]);
              pt_piece_[p.inner_id[i]] = q;
            } else {
              seq.push_back(static_cast<Index>(out.points.size()));
              out.points.push_back(p.inner[i]);
              if (!out.point_markers.empty()) out.point_markers.push_back(0);
              pt_piece_.push_back(q);
            }
          }
        }
        seq.push_back(ch.v[p.k1]);
        for (std::size_t i = 0; i + 1 < seq.size(); ++i) {
          out.segments.push_back({seq[i], seq[i + 1], ch.marker, ch.part});
          seg_piece_.push_back(p.restored ? kNoPiece : q);
          seg_chain_.push_back(c);
        }
      }
    }
    // Compact: input points that are on no segment any more are dropped, isolated input points
    // (fixed points) stay.
    std::vector<char> keep(out.points.size(), 0);
    std::vector<char> had_seg(in_.points.size(), 0);
    for (const auto& s : in_.segments) had_seg[s.a] = had_seg[s.b] = 1;
    for (std::size_t v = 0; v < in_.points.size(); ++v) keep[v] = !had_seg[v];
    for (const auto& s : out.segments) keep[s.a] = keep[s.b] = 1;
    std::vector<Index> map(out.points.size(), kNoId);
    Pslg c = out;
    c.points.clear();
    c.point_markers.clear();
    std::vector<std::size_t> pp;
    for (std::size_t v = 0; v < out.points.size(); ++v) {
      if (!keep[v]) continue;
      map[v] = static_cast<Index>(c.points.size());
      c.points.push_back(out.points[v]);
      if (!out.point_markers.empty()) c.point_markers.push_back(out.point_markers[v]);
      pp.push_back(pt_piece_[v]);
    }
    for (auto& s : c.segments) {
      s.a = map[s.a];
      s.b = map[s.b];
    }
    pt_piece_ = std::move(pp);
    return c;
  }

  // Collects the (flat) pieces in conflict; returns true if any was found.
  bool find_conflicts(const Pslg& out, std::vector<std::size_t>* bad) {
    std::vector<char> mark(flat_.size(), 0);
    auto restore = [&](std::size_t q) {
      if (q != kNoPiece && !mark[q]) {
        mark[q] = 1;
        bad->push_back(q);
      }
    };
    const Contacts ct = find_contacts(out.points, out.segments, nullptr);
    for (const auto& [s, t] : ct.segment_pairs) {
      restore(seg_piece_[s]);
      restore(seg_piece_[t]);
    }
    for (const auto& [v, s] : ct.vertex_on_segment) {
      restore(pt_piece_[v]);
      restore(seg_piece_[s]);
    }
    if (!bad->empty()) return true;
    // Angles: resampling may not create a wedge between two segments at a vertex that is much
    // sharper than any the input had there (a rounded inlet end simplified into a spike, two
    // chains leaving a junction almost together): refinement would need tiny elements in it.
    {
      const std::size_t n = out.points.size();
      std::vector<std::uint32_t> deg(n + 1, 0);
      for (const auto& sg : out.segments) { ++deg[sg.a + 1]; ++deg[sg.b + 1]; }
      for (std::size_t v = 0; v < n; ++v) deg[v + 1] += deg[v];
      std::vector<std::size_t> inc(deg[n]);
      std::vector<std::uint32_t> fill(deg.begin(), deg.end() - 1);
      for (std::size_t k = 0; k < out.segments.size(); ++k) {
        inc[fill[out.segments[k].a]++] = k;
        inc[fill[out.segments[k].b]++] = k;
      }
      std::vector<std::pair<double, std::size_t>> dirs;
      for (std::size_t v = 0; v < n; ++v) {
        if (deg[v + 1] - deg[v] < 2) continue;
        dirs.clear();
        for (std::uint32_t k = deg[v]; k < deg[v + 1]; ++k) {
          const auto& sg = out.segments[inc[k]];
          const Point2 o = out.points[v], q = out.points[sg.a == v ? sg.b : sg.a];
          dirs.push_back({std::atan2(q.y - o.y, q.x - o.x), inc[k]});
        }
        std::sort(dirs.begin(), dirs.end());
        for (std::size_t i = 0; i < dirs.size(); ++i) {
          const auto& [d1, s1] = dirs[i];
          const auto& [d2, s2] = dirs[(i + 1) % dirs.size()];
          double wedge = d2 - d1;
          if (wedge <= 0) wedge += 2 * kPi;
          if (wedge >= kSharp) continue;
          const std::size_t q1 = seg_piece_[s1], q2 = seg_piece_[s2];
          if (q1 == kNoPiece && q2 == kNoPiece) continue;
          // A wedge outside the domain (the tip of a needle of land) needs no small elements:
          // the water around it spans the rest of the turn.
          if (o_.domain_by_parity && !wedge_is_inside(out, static_cast<Index>(v), s1, s2)) continue;
          const double ref = std::min(q1 == kNoPiece ? kPi : piece_min_angle(q1), q2 == kNoPiece ? kPi : piece_min_angle(q2));
          if (wedge < 0.7 * ref) {
            restore(q1);
            restore(q2);
          }
        }
      }
      if (!bad->empty()) return true;
    }
    // Swept regions: no other vertex may lie between a new chain piece and its input polyline.
    if (out.points.empty()) return false;
    Box2 box = out.bbox();
    double mean = 0;
    for (const auto& s : out.segments) mean += dist(out.points[s.a], out.points[s.b]);
    mean = out.segments.empty() ? 1 : mean / static_cast<double>(out.segments.size());
    for (const auto& p : in_.points) box.add(p);
    SegmentGrid grid(box, out.points.size(), std::max(mean, 1e-300));
    for (Index v = 0; v < out.points.size(); ++v) grid.add_point(v, out.points[v]);
    std::vector<Index> near;
    std::vector<Point2> poly;
    std::size_t q = 0;
    for (std::size_t c = 0; c < chains_.size(); ++c)
      for (const Piece& p : chain_pieces_[c]) {
        const std::size_t qi = q++;
        if (p.restored || !p.changed()) continue;
        poly.clear();
        for (std::size_t k = p.k0; k <= p.k1; ++k) poly.push_back(P(p.chain, k));
        for (std::size_t i = p.inner.size(); i-- > 0;) poly.push_back(p.inner[i]);
        Box2 pb;
        for (const auto& x : poly) pb.add(x);
        grid.points_near(pb, &near);
        const Point2 e0 = P(p.chain, p.k0), e1 = P(p.chain, p.k1);
        for (Index v : near) {
          if (pt_piece_[v] == qi) continue;
          const Point2 x = out.points[v];
          if (x == e0 || x == e1) continue;
          if (inside_or_on(x, poly)) {
            restore(qi);
            break;
          }
        }
      }
    return !bad->empty();
  }

  // Whether the wedge at v from segment s1 counter-clockwise to s2 (consecutive around v) lies
  // inside the domain (parity of the boundary segments). It lies left of the ray from v along
  // s1 (and right of the one along s2): a breakline has the domain on both sides; a boundary
  // segment's side is its chain's, which resampling does not change.
  bool wedge_is_inside(const Pslg& out, Index v, std::size_t s1, std::size_t s2) {
    for (std::size_t s : {s1, s2}) {
      const auto& sg = out.segments[s];
      if (!sg.is_boundary()) continue;
      const bool forward = sg.a == v;  // the ray from v runs along the chain
      const bool left = chain_left_inside(seg_chain_[s]);
      return s == s1 ? (left == forward) : (left != forward);
    }
    return true;
  }

  // Whether the domain lies left of chain c (from v[0] towards v[1]); constant along a chain,
  // whose inner vertices touch no other segment. Exact: a ray from the midpoint m of the chain's
  // first input segment (a, b), counting the boundary segments it crosses (half-open in y); m
  // off the segment by rounding counts the segment too, m on it does not, and then the count is
  // that of the point just beside m in the ray's direction. A horizontal (a, b) uses the
  // mirrored plane (x <-> y), which turns left into right.
  bool chain_left_inside(std::size_t c) {
    if (chain_side_.empty()) chain_side_.assign(chains_.size(), -1);
    if (chain_side_[c] >= 0) return chain_side_[c] == 1;
    const Index ia = chains_[c].first_a, ib = chains_[c].first_b;
    const bool mirror = in_.points[ia].y == in_.points[ib].y;
    auto pt = [&](Index i) { const Point2 q = in_.points[i]; return mirror ? Point2{q.y, q.x} : q; };
    const Point2 a = pt(ia), b = pt(ib);
    const Point2 m{0.5 * (a.x + b.x), 0.5 * (a.y + b.y)};
    const int o = predicates::orient2d(a, b, m);
    std::size_t count = 0;
    const auto [first, last] = band_segments(mirror, m.y);
    for (const std::uint32_t* it = first; it != last; ++it) {
      const auto& t = in_.segments[*it];
      if (o == 0 && ((t.a == ia && t.b == ib) || (t.a == ib && t.b == ia))) continue;
      Point2 lo = pt(t.a), hi = pt(t.b);
      if ((lo.y > m.y) == (hi.y > m.y)) continue;
      if (lo.y > hi.y) std::swap(lo, hi);
      if (predicates::orient2d(lo, hi, m) > 0) ++count;  // the segment passes right of m
    }
    const bool in_at = count % 2 == 1;  // m, or (o == 0) the point just right of m
    // Whether that point lies left of (a, b): by o, or for o == 0 (m + (e, 0) left iff b.y < a.y).
    const bool point_left = o != 0 ? o > 0 : b.y < a.y;
    bool left = point_left ? in_at : !in_at;
    if (mirror) left = !left;
    chain_side_[c] = left ? 1 : 0;
    return left;
  }

  // The boundary segments whose y-range (x-range when mirrored) meets the horizontal band of y:
  // every segment a ray at height y can cross. Built on first use, about 32 segments a band.
  std::pair<const std::uint32_t*, const std::uint32_t*> band_segments(bool mirror, double y) {
    Bands& b = bands_[mirror ? 1 : 0];
    auto coord = [&](Index i) { return mirror ? in_.points[i].x : in_.points[i].y; };
    if (b.start.empty()) {
      b.lo = 1e300;
      double hi = -1e300;
      std::vector<std::uint32_t> segs;
      for (std::size_t k = 0; k < in_.segments.size(); ++k) {
        const auto& t = in_.segments[k];
        if (!t.is_boundary() || t.a == t.b) continue;
        segs.push_back(static_cast<std::uint32_t>(k));
        b.lo = std::min({b.lo, coord(t.a), coord(t.b)});
        hi = std::max({hi, coord(t.a), coord(t.b)});
      }
      const std::size_t nb = std::max<std::size_t>(1, segs.size() / 32);
      b.step = hi > b.lo ? (hi - b.lo) / static_cast<double>(nb) : 1.0;
      b.start.assign(nb + 1, 0);
      auto range = [&](std::uint32_t k) {
        const auto& t = in_.segments[k];
        const double y0 = std::min(coord(t.a), coord(t.b)), y1 = std::max(coord(t.a), coord(t.b));
        return std::pair<std::size_t, std::size_t>{b.band(y0, nb), b.band(y1, nb)};
      };
      for (std::uint32_t k : segs) {
        const auto [i0, i1] = range(k);
        for (std::size_t i = i0; i <= i1; ++i) ++b.start[i + 1];
      }
      for (std::size_t i = 0; i < nb; ++i) b.start[i + 1] += b.start[i];
      b.items.resize(b.start[nb]);
      std::vector<std::size_t> fill(b.start.begin(), b.start.end() - 1);
      for (std::uint32_t k : segs) {
        const auto [i0, i1] = range(k);
        for (std::size_t i = i0; i <= i1; ++i) b.items[fill[i]++] = k;
      }
    }
    const std::size_t nb = b.start.size() - 1;
    const std::size_t i = b.band(y, nb);
    return {b.items.data() + b.start[i], b.items.data() + b.start[i + 1]};
  }

  // Smallest wedge angle at the input vertices v[k0..k1] of a (flat) piece, between the
  // input segments at each vertex.
  double piece_min_angle(std::size_t q) {
    const auto& [c, k0, k1] = flat_[q];
    double m = kPi;
    for (std::size_t k = k0; k <= k1; ++k) m = std::min(m, input_wedge(chains_[c].v[k]));
    return m;
  }
  double input_wedge(Index v) {
    if (is_virtual(v)) return kPi;  // on an input segment
    if (wedge_.empty()) {
      // Smallest angle between consecutive input segments around every input vertex.
      const std::size_t n = in_.points.size();
      wedge_.assign(n, kPi);
      std::vector<std::vector<double>> dirs(n);
      for (const auto& sg : in_.segments) {
        if (sg.a == sg.b) continue;
        const Point2 a = in_.points[sg.a], b = in_.points[sg.b];
        dirs[sg.a].push_back(std::atan2(b.y - a.y, b.x - a.x));
        dirs[sg.b].push_back(std::atan2(a.y - b.y, a.x - b.x));
      }
      for (std::size_t u = 0; u < n; ++u) {
        auto& d = dirs[u];
        if (d.size() < 2) continue;
        std::sort(d.begin(), d.end());
        for (std::size_t i = 0; i < d.size(); ++i) {
          double w = d[(i + 1) % d.size()] - d[i];
          if (w <= 0) w += 2 * kPi;
          wedge_[u] = std::min(wedge_[u], w);
        }
      }
    }
    return wedge_[v];
  }

  // Parity test with exact orientation; points on the polygon's boundary count as inside.
  static bool inside_or_on(Point2 p, const std::vector<Point2>& poly) {
    bool in = false;
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Point2 a = poly[i], b = poly[(i + 1) % n];
      if (a == b) continue;
      if (predicates::orient2d(a, b, p) == 0 && std::min(a.x, b.x) <= p.x && p.x <= std::max(a.x, b.x) &&
          std::min(a.y, b.y) <= p.y && p.y <= std::max(a.y, b.y))
        return true;
      if ((a.y > p.y) == (b.y > p.y)) continue;
      const int o = predicates::orient2d(a, b, p);
      if ((b.y > a.y) ? (o > 0) : (o < 0)) in = !in;
    }
    return in;
  }

  static constexpr std::size_t kNoPiece = static_cast<std::size_t>(-1);
  static constexpr double kPi = 3.14159265358979323846;
  static constexpr double kSharp = kPi / 6;  // wedges under 30 degrees are checked
  static constexpr double kCornerTurn = kPi / 9;  // a key turning less than 20 degrees is no corner
  static constexpr double kTinyPiece = 0.05;      // ... and below this * f, by their own length beyond the tolerance
  static constexpr double kShortPiece = 0.6;
  static constexpr double kSmallRing = 12;              // small_ring: at most this many steps round
  static constexpr std::size_t kSmallRingVertices = 4000;
  static constexpr int kSmallRingOffsets = 48;
  static constexpr double kSmallRingGain = 0.02;
  std::size_t small_rings_planned_ = 0;      // pieces shorter than this * f lose a key if they can
  std::vector<double> wedge_;
  const Pslg& in_;
  std::vector<Point2> pts_;  // in_.points, then the midpoints merge_short_pieces adds
  ResampleOptions o_;
  std::vector<Chain> chains_;
  std::vector<std::vector<Piece>> chain_pieces_;
  struct Flat { std::size_t chain, k0, k1; };
  std::vector<Flat> flat_;  // pieces of the last assembly, in order
  std::vector<std::size_t> seg_piece_, pt_piece_, seg_chain_;
  std::vector<signed char> chain_side_;
  struct Bands {
    double lo = 0, step = 1;
    std::vector<std::size_t> start;
    std::vector<std::uint32_t> items;
    // Band of coordinate y, clamped (a y outside every segment's range meets none of them).
    std::size_t band(double y, std::size_t nb) const {
      const double t = (y - lo) / step;
      if (!(t > 0)) return 0;
      return std::min(nb - 1, static_cast<std::size_t>(t));
    }
  };
  Bands bands_[2];  // per chain: 1 domain on its left, 0 right, -1 unknown
};

}  // namespace

Pslg resample(const Pslg& in, const ResampleOptions& options, ResampleStats* stats) {
  Resampler r(in, options);
  return r.run(stats);
}

}  // namespace fdr::pslg
