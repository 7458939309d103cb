// The resampler behind pslg::resample (see resample.hpp), shared by its three files: chains
// and assembly (resample.cpp), planning and point placement (resample_plan.cpp), and the exact
// conflict checks (resample_conflicts.cpp).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <vector>
#include "base/error.hpp"
#include "predicates/predicates.hpp"
#include "pslg/resample.hpp"

namespace fdr::pslg::resampling {

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

// The turning angle at b of the path a -> b -> c, in [0, pi].
inline double turn(Point2 a, Point2 b, Point2 c) {
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

  Pslg run(ResampleStats* st);

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

  void build_chains();

  double tol(Point2 a, Point2 b) const { return o_.tolerance_factor * std::min(f(a), f(b)); }

  // Tolerance scale over input segments [i, j): 0.5^level, 0 once a segment is at kMaxLevel.
  double tol_scale(std::size_t c, std::size_t i, std::size_t j) const {
    std::uint8_t L = 0;
    for (std::size_t k = i; k < j; ++k) L = std::max(L, chains_[c].level[k]);
    return L >= kMaxLevel ? 0.0 : std::ldexp(1.0, -static_cast<int>(L));
  }

  void plan_chain(std::size_t c);

  // Shortest segment of chain c's planned pieces over f (at the nearer end's smaller f).
  double planned_min_ratio(std::size_t c) const;

  // Small rings (islands a few elements round): Douglas-Peucker keeps the corners the tolerance
  // needs, and two of them often end up a fraction of f apart (the blunt end of a small
  // island), so the mesh refines to their distance all around it. A ring of at most
  // kSmallRing steps of ds / (spacing_factor f) whose plan has a piece under kShortPiece * f is
  // planned again as n points at equal steps along it, n near its step count, from the
  // starting point (on the input line) that makes the shortest chord longest while every input
  // vertex stays within the tolerance; the seam moves to the first of them. Only when no
  // conflict was found on the ring yet (every level 0), and only when it gains.
  void small_ring(std::size_t c);

  // Largest distance of the input vertices strictly between keys i and j from their chord.
  double chord_deviation(std::size_t c, std::size_t i, std::size_t j) const;

  // Short pieces: two corners much closer than f (the rounded end of a cut spit, two bends of a
  // small bay) would make the mesh refine to their distance all around them. Douglas-Peucker
  // keeps both when each is needed on its own; often one key, or one input vertex between them,
  // serves both within the same tolerance. A piece shorter than kShortPiece * f loses a key
  // (or its two keys become one input vertex between them) when every input vertex stays
  // within the tolerance of the new chords; chain ends never move.
  void merge_short_pieces(std::size_t c, std::vector<char>& key);

  // Points on the input polyline v[k0..k1] at equal steps of integral ds / (factor * f).
  void place(Piece& p, double tol_sc);

  Pslg assemble();

  // Collects the (flat) pieces in conflict; returns true if any was found.
  bool find_conflicts(const Pslg& out, std::vector<std::size_t>* bad);

  // Whether the wedge at v from segment s1 counter-clockwise to s2 (consecutive around v) lies
  // inside the domain (parity of the boundary segments). It lies left of the ray from v along
  // s1 (and right of the one along s2): a breakline has the domain on both sides; a boundary
  // segment's side is its chain's, which resampling does not change.
  bool wedge_is_inside(const Pslg& out, Index v, std::size_t s1, std::size_t s2);

  // Whether the domain lies left of chain c (from v[0] towards v[1]); constant along a chain,
  // whose inner vertices touch no other segment. Exact: a ray from the midpoint m of the chain's
  // first input segment (a, b), counting the boundary segments it crosses (half-open in y); m
  // off the segment by rounding counts the segment too, m on it does not, and then the count is
  // that of the point just beside m in the ray's direction. A horizontal (a, b) uses the
  // mirrored plane (x <-> y), which turns left into right.
  bool chain_left_inside(std::size_t c);

  // The boundary segments whose y-range (x-range when mirrored) meets the horizontal band of y:
  // every segment a ray at height y can cross. Built on first use, about 32 segments a band.
  std::pair<const std::uint32_t*, const std::uint32_t*> band_segments(bool mirror, double y);

  // Smallest wedge angle at the input vertices v[k0..k1] of a (flat) piece, between the
  // input segments at each vertex.
  double piece_min_angle(std::size_t q);
  double input_wedge(Index v);

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
  static constexpr double kSharp = std::numbers::pi / 6;       // wedges under 30 degrees are checked
  static constexpr double kCornerTurn = std::numbers::pi / 9;  // a key turning less than 20 degrees is no corner
  static constexpr double kShortPiece = 0.6;  // pieces shorter than this * f lose a key if they can
  static constexpr double kTinyPiece = 0.05;  // ... and below this * f, by their own length beyond the tolerance
  static constexpr double kSmallRing = 12;    // small_ring: at most this many steps round
  static constexpr std::size_t kSmallRingVertices = 4000;  // small_ring: at most this many input vertices
  static constexpr int kSmallRingOffsets = 48;             // small_ring: starting points tried per step
  static constexpr double kSmallRingGain = 0.02;           // small_ring: least gain in shortest chord / f
  std::vector<double> wedge_;  // input_wedge per input vertex, filled on first use
  const Pslg& in_;
  std::vector<Point2> pts_;  // in_.points, then the midpoints merge_short_pieces adds
  ResampleOptions o_;
  std::vector<Chain> chains_;
  std::vector<std::vector<Piece>> chain_pieces_;
  struct Flat { std::size_t chain, k0, k1; };
  std::vector<Flat> flat_;  // pieces of the last assembly, in order
  std::vector<std::size_t> seg_piece_, pt_piece_, seg_chain_;
  std::vector<signed char> chain_side_;  // per chain: 1 domain on its left, 0 right, -1 unknown
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
  Bands bands_[2];  // band_segments: [0] plain, [1] mirrored
};

}  // namespace fdr::pslg::resampling
