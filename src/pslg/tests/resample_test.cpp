// Boundary resampling to f (pslg/resample.hpp): spacing follows f, the shape stays within the
// tolerance, no crossings appear, rings are neither merged nor lost, anchors and fixed points stay,
// the result is deterministic.
#include <gtest/gtest.h>

#include <numbers>
#include <cmath>
#include <random>

#include "pslg/resample.hpp"
#include "pslg/segment_grid.hpp"
#include "pslg/validate.hpp"

namespace fdr::pslg {
namespace {

// A closed ring of n vertices (marker m) appended to g; returns the first vertex id.
Index add_ring(Pslg& g, const std::vector<Point2>& pts, std::int32_t marker, std::int32_t part) {
  const Index base = static_cast<Index>(g.points.size());
  g.points.insert(g.points.end(), pts.begin(), pts.end());
  for (std::size_t i = 0; i < pts.size(); ++i)
    g.segments.push_back({base + static_cast<Index>(i), base + static_cast<Index>((i + 1) % pts.size()), marker, part});
  return base;
}

// A wiggly circle: radius r, n vertices, amplitude a (digitising noise).
std::vector<Point2> wiggly_circle(Point2 c, double r, std::size_t n, double a, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-a, a);
  std::vector<Point2> p;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(n);
    const double rr = r + u(rng);
    p.push_back({c.x + rr * std::cos(t), c.y + rr * std::sin(t)});
  }
  return p;
}

double dist_to_chain(Point2 p, const Pslg& g, std::int32_t part) {
  double d = 1e300;
  for (const auto& s : g.segments)
    if (s.part == part) d = std::min(d, dist_to_segment(p, g.points[s.a], g.points[s.b]));
  return d;
}

ResampleOptions opts(double f, double tol = 0.25) {
  ResampleOptions o;
  o.spacing = [f](Point2) { return f; };
  o.tolerance_factor = tol;
  return o;
}

TEST(Resample, DenseRingFollowsSpacingWithinTolerance) {
  Pslg g;
  add_ring(g, wiggly_circle({0, 0}, 1000, 1200, 0.5, 1), 1, 0);  // 5 m digitising, 0.5 m noise
  ResampleStats st;
  const Pslg r = resample(g, opts(100), &st);
  validate(r, "resampled");  // no duplicates, crossings or overlaps
  // Perimeter 6283 m at spacing 1.3 * 100: about 48 vertices.
  EXPECT_GE(r.points.size(), 40u);
  EXPECT_LE(r.points.size(), 60u);
  EXPECT_EQ(r.segments.size(), r.points.size());  // still one closed ring
  for (const auto& s : r.segments) {
    const double l = dist(r.points[s.a], r.points[s.b]);
    EXPECT_GT(l, 80.0);
    EXPECT_LT(l, 200.0);
  }
  // Every input vertex within the tolerance (0.25 f) of the new ring, and the reverse.
  for (const auto& p : g.points) EXPECT_LE(dist_to_chain(p, r, 0), 25.0 + 1e-9);
  for (const auto& p : r.points) EXPECT_LE(dist_to_chain(p, g, 0), 1e-6);
  EXPECT_LE(st.max_deviation, 25.0 + 1e-9);
}

TEST(Resample, SpacingFollowsF) {
  Pslg g;
  std::vector<Point2> line;
  for (int i = 0; i <= 10000; ++i) line.push_back({static_cast<double>(i), 0.0});
  const Index base = static_cast<Index>(g.points.size());
  g.points = line;
  for (Index i = 0; i + 1 < line.size(); ++i) g.segments.push_back({base + i, base + i + 1, 4, 0});
  ResampleOptions o;
  o.spacing = [](Point2 p) { return 10.0 + 0.05 * p.x; };  // 10 m .. 510 m, alpha 0.05
  const Pslg r = resample(g, o);
  validate(r, "resampled");
  for (const auto& s : r.segments) {
    const Point2 a = r.points[s.a], b = r.points[s.b];
    const double l = dist(a, b), fm = 10.0 + 0.05 * 0.5 * (a.x + b.x);
    EXPECT_GT(l, 0.8 * 1.3 * fm) << a.x;
    EXPECT_LT(l, 1.2 * 1.3 * fm) << a.x;
  }
  // The chain ends (degree-1 anchors) are kept.
  bool has0 = false, has_end = false;
  for (const auto& p : r.points) {
    has0 |= p == Point2{0, 0};
    has_end |= p == Point2{10000, 0};
  }
  EXPECT_TRUE(has0 && has_end);
}

TEST(Resample, CornersBeyondToleranceStay) {
  // A square with 1 m digitising: its corners deviate far more than the tolerance.
  Pslg g;
  std::vector<Point2> sq;
  for (int i = 0; i < 1000; ++i) sq.push_back({static_cast<double>(i), 0});
  for (int i = 0; i < 1000; ++i) sq.push_back({1000, static_cast<double>(i)});
  for (int i = 0; i < 1000; ++i) sq.push_back({1000.0 - i, 1000});
  for (int i = 0; i < 1000; ++i) sq.push_back({0, 1000.0 - i});
  add_ring(g, sq, 1, 0);
  const Pslg r = resample(g, opts(100));
  for (Point2 c : {Point2{0, 0}, Point2{1000, 0}, Point2{1000, 1000}, Point2{0, 1000}}) {
    bool found = false;
    for (const auto& p : r.points) found |= p == c;
    EXPECT_TRUE(found) << c.x << "," << c.y;
  }
}

TEST(Resample, NarrowChannelDoesNotCross) {
  // Two wiggly banks 6 m apart, f = 100 m (tolerance 25 m > width): chords that would cross the
  // other bank are put back closer, never crossing; the rings stay two.
  Pslg g;
  std::vector<Point2> a, b;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i <= 2000; ++i) a.push_back({static_cast<double>(i), 3.0 + u(rng)});
  for (int i = 2000; i >= 0; --i) a.push_back({static_cast<double>(i), 60.0});
  for (int i = 0; i <= 2000; ++i) b.push_back({static_cast<double>(i), -60.0});
  for (int i = 2000; i >= 0; --i) b.push_back({static_cast<double>(i), -3.0 + u(rng)});
  add_ring(g, a, 1, 0);
  add_ring(g, b, 2, 1);
  ResampleStats st;
  const Pslg r = resample(g, opts(100), &st);
  validate(r, "resampled");
  EXPECT_LT(r.points.size(), g.points.size() / 4);
  std::size_t m1 = 0, m2 = 0;
  for (const auto& s : r.segments) (s.part == 0 ? m1 : m2) += 1;
  EXPECT_GT(m1, 2u);
  EXPECT_GT(m2, 2u);
  // Every vertex of one bank stays on its side of the channel's centre line.
  for (const auto& s : r.segments) {
    const double ya = r.points[s.a].y, yb = r.points[s.b].y;
    if (s.part == 0) EXPECT_TRUE(ya > 0 && yb > 0);
    else EXPECT_TRUE(ya < 0 && yb < 0);
  }
}

TEST(Resample, SmallIslandInsideBayIsNotSweptOut) {
  // A bay whose mouth chord would pass over a small island: the island must stay in the water.
  Pslg g;
  std::vector<Point2> coast;
  for (int i = 0; i <= 100; ++i) coast.push_back({static_cast<double>(i) * 10, 0});
  // bay 20 m deep between x = 400 and 600
  for (auto& p : coast)
    if (p.x > 400 && p.x < 600) p.y = -20;
  coast.push_back({1000, -500});
  coast.push_back({0, -500});
  add_ring(g, coast, 1, 0);
  add_ring(g, {{495, -15}, {505, -15}, {500, -10}}, 2, 1);
  const Pslg r = resample(g, opts(100));
  validate(r, "resampled");
  // The island's three vertices are still above the coast line under them.
  for (const auto& s : r.segments) {
    if (s.part != 1) continue;
    const Point2 p = r.points[s.a];
    double ybelow = -1e300;
    for (const auto& c : r.segments) {
      if (c.part != 0) continue;
      const Point2 a = r.points[c.a], b = r.points[c.b];
      if ((a.x - p.x) * (b.x - p.x) <= 0 && a.x != b.x && std::max(a.y, b.y) > -400)
        ybelow = std::max(ybelow, a.y + (b.y - a.y) * (p.x - a.x) / (b.x - a.x));
    }
    EXPECT_GT(p.y, ybelow) << p.x;
  }
}

TEST(Resample, FixedPointsAndJunctionsStay) {
  Pslg g;
  add_ring(g, wiggly_circle({0, 0}, 500, 2000, 1.0, 3), 1, 0);
  g.points.push_back({10, 10});  // a fixed point
  // A breakline from the ring to the centre: its ring vertex is a junction (anchor).
  const Index ring0 = 0;
  const Index c = static_cast<Index>(g.points.size());
  g.points.push_back({0, 0});
  g.segments.push_back({ring0, c, 4, 1});
  const Pslg r = resample(g, opts(50));
  validate(r, "resampled");
  bool fixed = false, junction = false, centre = false;
  for (const auto& p : r.points) {
    fixed |= p == Point2{10, 10};
    junction |= p == g.points[ring0];
    centre |= p == Point2{0, 0};
  }
  EXPECT_TRUE(fixed);
  EXPECT_TRUE(junction);
  EXPECT_TRUE(centre);
}

TEST(Resample, Deterministic) {
  Pslg g;
  add_ring(g, wiggly_circle({0, 0}, 1000, 3000, 5.0, 11), 1, 0);
  add_ring(g, wiggly_circle({100, 50}, 200, 800, 3.0, 12), 2, 1);
  const Pslg a = resample(g, opts(80)), b = resample(g, opts(80));
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) EXPECT_TRUE(a.points[i] == b.points[i]);
  ASSERT_EQ(a.segments.size(), b.segments.size());
  for (std::size_t i = 0; i < a.segments.size(); ++i) {
    EXPECT_EQ(a.segments[i].a, b.segments[i].a);
    EXPECT_EQ(a.segments[i].b, b.segments[i].b);
  }
}

TEST(Resample, TinyRingKeepsThreeVertices) {
  Pslg g;
  add_ring(g, wiggly_circle({0, 0}, 10, 40, 0.1, 5), 2, 0);  // perimeter 63 m, f = 100 m
  const Pslg r = resample(g, opts(100));
  validate(r, "resampled");
  EXPECT_GE(r.segments.size(), 3u);
  EXPECT_EQ(r.segments.size(), r.points.size());
}

// A needle 3 km long, 400 m wide at its base and 40 m at its blunt tip (two vertices 40 m apart),
// digitised every 50 m along its sides, pointing along +x to (0, 0).
std::vector<Point2> needle() {
  std::vector<Point2> p;
  for (int i = 0; i <= 60; ++i) p.push_back({-3000.0 + 50.0 * i, 200.0 - 3.0 * i});   // top, to (0, 20)
  for (int i = 0; i <= 60; ++i) p.push_back({-50.0 * i, -20.0 - 3.0 * i});           // bottom, from (0, -20)
  return p;
}

double shortest_segment(const Pslg& g) {
  double m = 1e300;
  for (const auto& s : g.segments) m = std::min(m, dist(g.points[s.a], g.points[s.b]));
  return m;
}

// A needle of land (an island ring inside the water) may become one sharp tip: the wedge it makes
// lies outside the domain, where no element goes. The two tip vertices 40 m apart would make the
// mesh refine to 40 m around the tip (f = 500 m).
TEST(Resample, NeedleOfLandMayGetSharperWhenTheDomainIsByParity) {
  Pslg g;
  add_ring(g, {{-6000, -6000}, {6000, -6000}, {6000, 6000}, {-6000, 6000}}, 1, 0);
  add_ring(g, needle(), 2, 1);
  ResampleOptions o = opts(500);
  o.domain_by_parity = true;
  const Pslg r = resample(g, o);
  validate(r, "resampled");
  EXPECT_GT(shortest_segment(r), 300.0);
  // Without knowing the domain's side the tip keeps both vertices (the wedge check).
  const Pslg k = resample(g, opts(500));
  validate(k, "resampled");
  EXPECT_LT(shortest_segment(k), 41.0);
}

// The same needle as a wedge of water (the domain is the needle: an inlet's end) keeps its blunt
// tip: a sharp wedge of water would need elements as narrow as itself.
TEST(Resample, NeedleOfWaterKeepsItsBluntTip) {
  for (bool mirrored : {false, true}) {  // mirrored: x <-> y, the horizontal-segment branch
    Pslg g;
    auto p = needle();
    if (mirrored)
      for (auto& q : p) std::swap(q.x, q.y);
    add_ring(g, p, 1, 0);
    ResampleOptions o = opts(500);
    o.domain_by_parity = true;
    const Pslg r = resample(g, o);
    validate(r, "resampled");
    EXPECT_LT(shortest_segment(r), 41.0) << mirrored;
    // As a hole in a water box (a needle of land), mirrored or not, the tip merges.
    Pslg h;
    add_ring(h, {{-6000, -6000}, {6000, -6000}, {6000, 6000}, {-6000, 6000}}, 1, 0);
    add_ring(h, p, 2, 1);
    const Pslg rh = resample(h, o);
    validate(rh, "resampled");
    EXPECT_GT(shortest_segment(rh), 300.0) << mirrored;
  }
}

// A tongue of land 1200 m wide at its base, 200 m at its square tip (f = 500, tolerance 125 m): neither tip corner can
// stand for the other (each is 200 m from the chord through the other), but the tip's midpoint
// serves both within 100 m, so the 200 m tip segment goes and no segment is shorter than f/2.
TEST(Resample, SquareTipOfLandBecomesItsMidpoint) {
  Pslg g;
  add_ring(g, {{-6000, -6000}, {6000, -6000}, {6000, 6000}, {-6000, 6000}}, 1, 0);
  std::vector<Point2> tongue;
  for (int i = 0; i <= 60; ++i) tongue.push_back({-3000.0 + 50.0 * i, 600.0 - 500.0 * i / 60.0});
  for (int i = 0; i <= 60; ++i) tongue.push_back({-50.0 * i, -100.0 - 500.0 * i / 60.0});
  add_ring(g, tongue, 2, 1);
  ResampleOptions o = opts(500);
  o.domain_by_parity = true;
  const Pslg r = resample(g, o);
  validate(r, "resampled");
  EXPECT_GT(shortest_segment(r), 250.0);
  bool mid = false;
  for (const auto& q : r.points) mid = mid || (q.x == 0 && q.y == 0);
  EXPECT_TRUE(mid);
  for (const auto& q : tongue) EXPECT_LE(dist_to_chain(q, r, 1), 125.0 + 1e-9);
}

// Small rocky islands (4-7 corners 100-700 m from their centre, f = 500 m, digitised every 40 m): Douglas-Peucker
// keeps the corners the tolerance needs and two of them often end up a fraction of f apart. With
// small_rings the ring is planned again at equal steps from its best start: every input vertex
// stays within the tolerance, no island gets a shorter shortest segment, and far fewer have one
// under f/2.
TEST(Resample, SmallIslandsGetEqualStepsFromTheirBestStart) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  int short_on = 0, short_off = 0, better = 0;
  for (int it = 0; it < 150; ++it) {
    // k corners at increasing angles, radii in [0.4 R, R], straight sides digitised every 40 m
    const double R = 250 + 450 * u(rng);
    const int k = 4 + static_cast<int>(4 * u(rng));
    std::vector<Point2> cs;
    for (int i = 0; i < k; ++i) {
      const double t = 2 * std::numbers::pi * (i + 0.7 * u(rng)) / k, r = R * (0.4 + 0.6 * u(rng));
      cs.push_back({r * std::cos(t), r * std::sin(t)});
    }
    std::vector<Point2> isl;
    for (int i = 0; i < k; ++i) {
      const Point2 p = cs[i], q = cs[(i + 1) % k];
      const int steps = std::max(1, static_cast<int>(dist(p, q) / 40));
      for (int j = 0; j < steps; ++j) isl.push_back(p + (static_cast<double>(j) / steps) * (q - p));
    }
    Pslg g;
    add_ring(g, {{-6000, -6000}, {6000, -6000}, {6000, 6000}, {-6000, 6000}}, 1, 0);
    add_ring(g, isl, 2, 1);
    ResampleOptions o = opts(500);
    o.domain_by_parity = true;
    const Pslg on = resample(g, o);
    o.small_rings = false;
    const Pslg off = resample(g, o);
    validate(on, "resampled");
    auto shortest_island = [](const Pslg& r) {
      double m = 1e300;
      for (const auto& s : r.segments)
        if (s.part == 1) m = std::min(m, dist(r.points[s.a], r.points[s.b]));
      return m;
    };
    const double son = shortest_island(on), soff = shortest_island(off);
    EXPECT_GE(son, soff - 1e-9) << it;
    short_on += son < 250;
    short_off += soff < 250;
    better += son > soff + 1e-9;
    for (const auto& q : isl) EXPECT_LE(dist_to_chain(q, on, 1), 125.0 + 1e-9) << it;
    std::size_t ring = 0;
    for (const auto& s : on.segments) ring += s.part == 1;
    EXPECT_GE(ring, 3u);
  }
  EXPECT_GT(better, 10);
  EXPECT_LT(2 * short_on, short_off) << short_on << " vs " << short_off;
}

// Clusters of small rocky islands 40-150 m apart (f = 500 m): the re-planned rings must neither
// cross nor touch each other (the conflict rounds put back what would), and keep the tolerance.
TEST(Resample, SmallIslandClustersDoNotCross) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (int it = 0; it < 30; ++it) {
    Pslg g;
    add_ring(g, {{-6000, -6000}, {6000, -6000}, {6000, 6000}, {-6000, 6000}}, 1, 0);
    std::vector<std::vector<Point2>> isl;
    double x = -2500;
    for (int i = 0; i < 5; ++i) {
      const double R = 150 + 350 * u(rng);
      x += (i ? R : 0);
      std::vector<Point2> cs, ring;
      const int k = 4 + static_cast<int>(4 * u(rng));
      for (int j = 0; j < k; ++j) {
        const double t = 2 * std::numbers::pi * (j + 0.7 * u(rng)) / k, r = R * (0.5 + 0.5 * u(rng));
        cs.push_back({x + r * std::cos(t), r * std::sin(t)});
      }
      for (int j = 0; j < k; ++j) {
        const Point2 p = cs[j], q = cs[(j + 1) % k];
        const int steps = std::max(1, static_cast<int>(dist(p, q) / 40));
        for (int m = 0; m < steps; ++m) ring.push_back(p + (static_cast<double>(m) / steps) * (q - p));
      }
      add_ring(g, ring, 2, 1 + i);
      isl.push_back(ring);
      x += R + 40 + 110 * u(rng);
    }
    ResampleOptions o = opts(500);
    o.domain_by_parity = true;
    const Pslg r = resample(g, o);
    validate(r, "resampled");  // throws on crossings, touching or duplicate segments
    for (std::size_t i = 0; i < isl.size(); ++i)
      for (const auto& q : isl[i]) EXPECT_LE(dist_to_chain(q, r, static_cast<std::int32_t>(1 + i)), 125.0 + 1e-9) << it;
  }
}

}  // namespace
}  // namespace fdr::pslg
