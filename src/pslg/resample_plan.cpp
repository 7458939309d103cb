// Resampling plans per chain: Douglas-Peucker corners, short pieces merged, small rings
// planned as equal steps, and the points on the input polyline at equal steps of
// integral ds / f (see resample.hpp).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>
#include "predicates/predicates.hpp"
#include "pslg/resampler.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg::resampling {

void Resampler::plan_chain(std::size_t c) {
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

double Resampler::planned_min_ratio(std::size_t c) const {
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

void Resampler::small_ring(std::size_t c) {
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

double Resampler::chord_deviation(std::size_t c, std::size_t i, std::size_t j) const {
  const Point2 a = P(c, i), b = P(c, j);
  double d = 0;
  for (std::size_t k = i + 1; k < j; ++k) d = std::max(d, dist_to_segment(P(c, k), a, b));
  return d;
}

void Resampler::merge_short_pieces(std::size_t c, std::vector<char>& key) {
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

void Resampler::place(Piece& p, double tol_sc) {
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

}  // namespace fdr::pslg::resampling
