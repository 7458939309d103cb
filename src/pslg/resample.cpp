// Boundary resampling to f (see resample.hpp): the rounds of planning, assembly and conflict
// checks; the chains between anchors; the output PSLG from the planned pieces.
#include "pslg/resample.hpp"
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <vector>
#include "base/step_laps.hpp"
#include "predicates/predicates.hpp"
#include "pslg/resampler.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::pslg::resampling {

Pslg Resampler::run(ResampleStats* st) {
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

void Resampler::build_chains() {
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

Pslg Resampler::assemble() {
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

}  // namespace fdr::pslg::resampling

namespace fdr::pslg {

Pslg resample(const Pslg& in, const ResampleOptions& options, ResampleStats* stats) {
  resampling::Resampler r(in, options);
  return r.run(stats);
}

}  // namespace fdr::pslg
