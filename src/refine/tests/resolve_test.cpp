// Messy constraints resolved exactly (pslg::resolve) then triangulated and refined: crossings at
// many angles, near-parallel bundles down to 1e-12 of the extent, stars through one point,
// overlapping collinear chains, T-junctions, vertices 1 ulp off a segment, lattices with
// segments through vertices; each scaled (1e-6 ... 1e6) and translated (offsets up to 1e7).
// Oracles: mesh::check_all (valid, constrained Delaunay, every resolved constraint a chain of
// mesh edges), R/f(c) <= B after refinement, and CGAL's Constrained_Delaunay_triangulation_2 with
// Exact_intersections_tag on the same double input: its subdivided constraint edges, each
// vertex rounded to doubles, are the resolved segments (exactly where no snap/hot-vertex repair
// moved a cut point, within 1e-9 of the extent otherwise).
#include <gtest/gtest.h>
#include <numbers>
#include <cmath>
#include <map>
#include <random>
#include <set>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include "base/error.hpp"
#include "cdt/cdt.hpp"
#include "mesh/check.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resolve.hpp"
#include "pslg/validate.hpp"
#include "refine/refine.hpp"
#include "sizing/make_spacing.hpp"

using namespace fdr;

namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using XCDT = CGAL::Constrained_Delaunay_triangulation_2<EK, CGAL::Default, CGAL::Exact_intersections_tag>;

struct Case {
  std::string name;
  std::vector<Point2> pts;                    // unit-scale coordinates, about [0, 1]^2
  std::vector<std::pair<Index, Index>> segs;  // all boundary markers (1)
};

// Box [-0.25, 1.25]^2 around everything so that the domain is never empty.
Case boxed(std::string name) {
  Case c;
  c.name = std::move(name);
  c.pts = {{-0.25, -0.25}, {1.25, -0.25}, {1.25, 1.25}, {-0.25, 1.25}};
  c.segs = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return c;
}
Index add(Case& c, Point2 p) {
  c.pts.push_back(p);
  return static_cast<Index>(c.pts.size() - 1);
}
void seg(Case& c, Point2 a, Point2 b) { c.segs.push_back({add(c, a), add(c, b)}); }

std::vector<Case> cases() {
  std::vector<Case> out;
  {  // crossings at many angles: a fan of 24 segments through (0.5, 0.5) plus a pencil crossing
     // a fixed segment at angles from 90 degrees down to 1e-6 degrees
    Case c = boxed("fan_24_through_centre");
    for (int k = 0; k < 24; ++k) {
      const double t = k * 3.14159265358979 / 24;
      seg(c, {0.5 + 0.45 * std::cos(t), 0.5 + 0.45 * std::sin(t)}, {0.5 - 0.45 * std::cos(t), 0.5 - 0.45 * std::sin(t)});
    }
    out.push_back(c);
    Case d = boxed("angles_90_to_1em6_deg");
    seg(d, {0, 0.5}, {1, 0.5});
    for (int k = 0; k < 10; ++k) {
      const double t = 1.5707963267948966 * std::pow(10.0, -0.88 * k);
      const double x = 0.05 + 0.09 * k;
      seg(d, {x - 0.3 * std::cos(t), 0.5 - 0.3 * std::sin(t)}, {x + 0.3 * std::cos(t), 0.5 + 0.3 * std::sin(t)});
    }
    out.push_back(d);
  }
  {  // near-parallel bundles: lines at separations 10^-1 ... 10^-12 of the extent, one transversal
    Case c = boxed("near_parallel_1em1_to_1em12");
    double y = 0.2;
    for (int k = 1; k <= 12; ++k) {
      seg(c, {0.0, y}, {1.0, y + 1e-3});
      y += std::pow(10.0, -k);
    }
    seg(c, {0.3, 0.0}, {0.7, 1.0});
    seg(c, {0.9, 0.05}, {0.1, 0.95});
    out.push_back(c);
    Case d = boxed("nearly_parallel_crossing_pairs");
    for (int k = 1; k <= 12; ++k) {
      const double x = 0.08 * k - 0.04, e = std::pow(10.0, -k);
      seg(d, {x - 0.03, 0.1}, {x + 0.03, 0.9});
      seg(d, {x - 0.03 - e, 0.1}, {x + 0.03 + e, 0.9});  // crosses at the middle, angle ~e
    }
    out.push_back(d);
  }
  {  // stars of segments through one (exact) point, and a star around a vertex
    Case c = boxed("star_16_exact_centre");
    for (int k = 0; k < 16; ++k) {
      const double vx = (k % 4 + 1) / 8.0 * (k < 8 ? 1 : -1), vy = (k / 4 + 1) / 8.0;
      seg(c, {0.5 + vx, 0.5 + vy}, {0.5 - vx, 0.5 - vy});
    }
    out.push_back(c);
    Case d = boxed("star_around_vertex");
    const Index centre = add(d, {0.5, 0.5});
    for (int k = 0; k < 12; ++k) {
      const double t = k * (std::numbers::pi / 6);
      d.segs.push_back({centre, add(d, {0.5 + 0.4 * std::cos(t), 0.5 + 0.4 * std::sin(t)})});
      seg(d, {0.5 + 0.2 * std::cos(t + 0.1), 0.5 + 0.2 * std::sin(t + 0.1)}, {0.5 + 0.45 * std::cos(t - 0.3), 0.5 + 0.45 * std::sin(t - 0.3)});
    }
    out.push_back(d);
  }
  {  // overlapping collinear chains (exact: on y = x / 2 with dyadic x), duplicates, T-junctions
    Case c = boxed("collinear_chains_and_duplicates");
    for (int k = 0; k < 10; ++k) {
      const double a = k / 16.0, b = a + (3 + k % 4) / 16.0;
      seg(c, {a, a / 2}, {b, b / 2});
      if (k % 3 == 0) seg(c, {b, b / 2}, {a, a / 2});  // reversed duplicate
    }
    for (int k = 0; k < 8; ++k) seg(c, {k / 8.0, 0.75}, {(k + 2) / 8.0, 0.75});  // horizontal overlaps
    for (int k = 1; k < 8; ++k) seg(c, {k / 8.0, 0.75}, {k / 8.0, 0.95});       // T-junctions
    seg(c, {0.1, 0.1}, {0.1, 0.1});                                             // zero length
    out.push_back(c);
  }
  {  // vertices 1 ulp off a segment (both sides), and exactly on it
    Case c = boxed("vertices_1ulp_off_segment");
    seg(c, {0, 0.5}, {1, 0.5});
    seg(c, {0, 0}, {1, 1});
    for (int k = 1; k < 8; ++k) {
      const double x = k / 8.0;
      add(c, {x, std::nextafter(0.5, k % 2 ? 1.0 : 0.0)});
      add(c, {x, std::nextafter(x, k % 2 ? 0.0 : 1.0)});
      if (k == 4) add(c, {x, 0.5});
    }
    out.push_back(c);
  }
  {  // lattice 7 x 7 with segments between lattice points, passing through other vertices
    Case c = boxed("lattice_segments_through_vertices");
    std::vector<Index> lat;
    for (int j = 0; j < 7; ++j)
      for (int i = 0; i < 7; ++i) lat.push_back(add(c, {i / 6.0, j / 6.0}));
    std::mt19937 rng(7);
    for (int k = 0; k < 30; ++k) {
      const Index a = lat[rng() % lat.size()], b = lat[rng() % lat.size()];
      c.segs.push_back({a, b});
    }
    out.push_back(c);
  }
  return out;
}

pslg::Pslg transform(const Case& c, double scale, Point2 offset) {
  pslg::Pslg g;
  for (const Point2& p : c.pts) g.points.push_back({offset.x + scale * p.x, offset.y + scale * p.y});
  for (const auto& [a, b] : c.segs) g.segments.push_back({a, b, 1, -1});
  return g;
}

// CGAL's subdivided constraint edges with their vertices converted to doubles.
std::vector<std::pair<Point2, Point2>> cgal_constraint_edges(const pslg::Pslg& g) {
  XCDT cdt;
  for (const auto& s : g.segments) {
    const Point2 a = g.points[s.a], b = g.points[s.b];
    if (a == b) continue;
    cdt.insert_constraint(EK::Point_2(a.x, a.y), EK::Point_2(b.x, b.y));
  }
  for (const Point2& p : g.points) cdt.insert(EK::Point_2(p.x, p.y));
  std::vector<std::pair<Point2, Point2>> out;
  for (auto e = cdt.finite_edges_begin(); e != cdt.finite_edges_end(); ++e) {
    if (!cdt.is_constrained(*e)) continue;
    const auto& pa = e->first->vertex(XCDT::cw(e->second))->point();
    const auto& pb = e->first->vertex(XCDT::ccw(e->second))->point();
    out.push_back({{CGAL::to_double(CGAL::exact(pa.x())), CGAL::to_double(CGAL::exact(pa.y()))},
                   {CGAL::to_double(CGAL::exact(pb.x())), CGAL::to_double(CGAL::exact(pb.y()))}});
  }
  return out;
}

void run_case(const Case& c, double scale, Point2 offset) {
  const std::string what = c.name + " scale " + std::to_string(scale) + " offset " + std::to_string(offset.x);
  const pslg::Pslg g = transform(c, scale, offset);
  std::vector<pslg::Repair> reps;
  pslg::Pslg r;
  ASSERT_NO_THROW(r = pslg::resolve(g, {}, &reps)) << what;
  ASSERT_NO_THROW(pslg::validate(r, what)) << what;
  bool moved = false;  // a cut point was snapped or a segment rerouted: compare within a tolerance
  for (const auto& rp : reps) moved |= rp.kind == "snap" || rp.kind == "hot_vertex" || rp.kind == "snap_to_segment";

  // Oracle 1: CGAL's exact subdivision (vertices within 1e-9 of the extent, or equal).
  const auto ce = cgal_constraint_edges(g);
  const double ext = scale * 1.5;
  auto near_id = [&](Point2 p, double tol) -> Index {
    Index best = kNoId;
    double bd = tol;
    for (Index i = 0; i < r.points.size(); ++i) {
      const double d = std::max(std::fabs(r.points[i].x - p.x), std::fabs(r.points[i].y - p.y));
      if (d <= bd) bd = d, best = i;
    }
    return best;
  };
  // Nothing moved: CGAL's vertices rounded to the nearest doubles are ours (we round the exact
  // intersection to nearest; to_double is within an ulp), and the subdivided edges are ours.
  const double mag = std::max(std::fabs(offset.x), std::fabs(offset.y)) + 2 * scale;
  if (!moved) {
    const double tol = 4 * mag * 0x1p-52;
    std::set<std::pair<Index, Index>> from_cgal, ours;
    for (const auto& [a, b] : ce) {
      const Index ia = near_id(a, tol), ib = near_id(b, tol);
      ASSERT_NE(ia, kNoId) << what << ": CGAL vertex (" << a.x << ", " << a.y << ") has no resolved vertex";
      ASSERT_NE(ib, kNoId) << what << ": CGAL vertex (" << b.x << ", " << b.y << ") has no resolved vertex";
      if (ia != ib) from_cgal.insert({std::min(ia, ib), std::max(ia, ib)});
    }
    for (const auto& s : r.segments) ours.insert({std::min(s.a, s.b), std::max(s.a, s.b)});
    EXPECT_EQ(from_cgal, ours) << what << " (" << ce.size() << " CGAL constraint edges)";
  } else {
    // Snap rounding moved cut points by at most the snap tolerance (2^-36 of the extent, or 16
    // ulps) per cascade round: both constraint sets lie within a few tolerances of each other.
    const double pixel = std::max(std::ldexp(ext, -36), std::ldexp(mag, -48));
    const double tol = 16 * pixel + 8 * mag * 0x1p-52;
    auto dist_to_set = [](Point2 p, const std::vector<std::pair<Point2, Point2>>& set) {
      double d = HUGE_VAL;
      for (const auto& [a, b] : set) d = std::min(d, a == b ? dist(p, a) : dist_to_segment(p, a, b));
      return d;
    };
    std::vector<std::pair<Point2, Point2>> ours;
    for (const auto& s : r.segments) ours.push_back({r.points[s.a], r.points[s.b]});
    for (const auto& [a, b] : ce) {
      EXPECT_LE(dist_to_set(a, ours), tol) << what << ": CGAL vertex (" << a.x << ", " << a.y << ") far from the resolved set";
      EXPECT_LE(dist_to_set(b, ours), tol) << what;
    }
    for (const auto& [a, b] : ours) {
      EXPECT_LE(dist_to_set(a, ce), tol) << what << ": resolved vertex (" << a.x << ", " << a.y << ") far from CGAL's set";
      EXPECT_LE(dist_to_set(b, ce), tol) << what;
    }
  }

  // Oracle 2: the CDT and the FDR mesh satisfy every checker.
  cdt::CdtOptions co;
  co.regions = cdt::CdtOptions::Regions::kSeeds;
  co.source = what;
  mesh::Triangulation tri;
  ASSERT_NO_THROW(tri = cdt::build_cdt(r, co)) << what;
  auto cr = mesh::check_all(tri);
  ASSERT_TRUE(cr.ok()) << what << " CDT: " << cr.problems.front();
  char spec[64];
  std::snprintf(spec, sizeof spec, "%.17g", scale / 4);
  const auto f = sizing::make_spacing(spec);
  refine::RefineOptions ro;
  ro.max_steiner = 200000;
  refine::Refiner refiner(tri, *f, ro);
  refiner.init();
  bool stopped = false;  // by the Steiner cap or floating-point resolution (kWorkLimit)
  try {
    refiner.run();
  } catch (const Error& e) {
    stopped = true;
    // Features far below the spacing at large offsets may hit floating-point resolution.
    ASSERT_EQ(e.code(), ExitCode::kWorkLimit) << what << ": " << e.what();
    GTEST_LOG_(INFO) << what << ": " << e.what();
  }
  cr = mesh::check_all(tri);
  ASSERT_TRUE(cr.ok()) << what << " FDR: " << cr.problems.front();
  if (!stopped) { EXPECT_EQ(refiner.leftovers().r_over_f_bad, 0u) << what; }
}

class ResolveCases : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ResolveCases, ScaledAndTranslated) {
  const Case c = cases()[GetParam()];
  for (double scale : {1e-6, 1e-3, 1.0, 1e3, 1e6})
    for (Point2 off : {Point2{0, 0}, Point2{1e7, -3e6}, Point2{-4.2e5, 5.5e6}}) {
      if (off.x != 0 && scale < 1e-3) continue;  // features below the ulp of the offset: see below
      SCOPED_TRACE(c.name);
      run_case(c, scale, off);
      if (::testing::Test::HasFatalFailure()) return;
    }
}

// Tiny features at a large offset (1e-6 at 1e7: a few hundred ulps): the coordinates collapse
// onto few doubles, everything must still resolve and mesh.
TEST_P(ResolveCases, TinyAtLargeOffset) {
  const Case c = cases()[GetParam()];
  run_case(c, 1e-6, {1e7, 1e7});
}

INSTANTIATE_TEST_SUITE_P(Resolve, ResolveCases, ::testing::Range<std::size_t>(0, 9),
                         [](const ::testing::TestParamInfo<std::size_t>& i) { return cases()[i.param].name; });

TEST(Resolve, StrictThrowsNamingFirstConflict) {
  Case c = cases()[0];
  pslg::ResolveOptions o;
  o.strict = true;
  o.source = "fan.poly";
  try {
    (void)pslg::resolve(transform(c, 1, {0, 0}), o, nullptr);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::kInvalidGeometry);
    EXPECT_NE(std::string(e.what()).find("fan.poly: "), std::string::npos) << e.what();
  }
}

TEST(Resolve, CdtOptionResolvesForLibraryCallers) {
  Case c = cases()[0];
  const pslg::Pslg g = transform(c, 1, {0, 0});
  EXPECT_THROW(cdt::build_cdt(g, {}), Error);
  cdt::CdtOptions o;
  o.resolve = true;
  std::vector<pslg::Repair> reps;
  o.repairs = &reps;
  const auto tri = cdt::build_cdt(g, o);
  EXPECT_TRUE(mesh::check_all(tri).ok());
  EXPECT_FALSE(reps.empty());
}

TEST(Resolve, HoleSeedErrorsNameSeed) {
  pslg::Pslg g = transform(boxed("box"), 1, {0, 0});
  g.holes.push_back({5, 5});
  try {
    (void)cdt::build_cdt(g, {cdt::CdtOptions::Regions::kSeeds, "h.poly"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("hole 0 seed at (5, 5) lies outside the domain"), std::string::npos) << e.what();
  }
  g.holes[0] = {1.25, 0.5};
  try {
    (void)cdt::build_cdt(g, {cdt::CdtOptions::Regions::kSeeds, "h.poly"});
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("lies on segment 1"), std::string::npos) << e.what();
  }
}

TEST(Resolve, ConvexHullMeshesPointsAndDanglingBreaklines) {
  pslg::Pslg g;
  g.points = {{0, 0}, {8, 0}, {9, 6}, {1, 7}, {3, 2}, {6, 5}};
  g.segments = {{4, 5, 4, -1}};
  auto t = cdt::build_cdt(g, {cdt::CdtOptions::Regions::kSeeds, "p"});
  EXPECT_EQ(t.num_live_triangles(), 0u);
  t = cdt::build_cdt(g, {cdt::CdtOptions::Regions::kHull, "p"});
  EXPECT_EQ(t.num_live_triangles(), 6u);  // 6 points, 4 on the hull: 2n - h - 2
  EXPECT_TRUE(mesh::check_all(t).ok());
}

}  // namespace

namespace {
// Triangle .poly regions: the seed's region (bounded by segments) gets its area constraint, and
// refinement makes every triangle there at most that large; the other region is unaffected.
TEST(Regions, AreaConstraintBoundsTriangleAreaInItsRegionOnly) {
  pslg::Pslg g;
  g.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}, {3, 3}, {6, 3}, {6, 6}, {3, 6}};
  for (Index k = 0; k < 4; ++k) {
    g.segments.push_back({k, (k + 1) % 4, 1, -1});
    g.segments.push_back({4 + k, 4 + (k + 1) % 4, 2, -1});
  }
  g.regions.push_back({{4.5, 4.5}, 7, 0.02});  // inner square
  g.regions.push_back({{1, 1}, 3, -1});        // outer ring: attribute only
  mesh::Triangulation tri = cdt::build_cdt(g, {cdt::CdtOptions::Regions::kSeeds, "r"});
  const auto f = sizing::make_spacing("4");
  refine::RefineOptions ro;
  ro.region_max_area = {0.02, -1};
  refine::Refiner refiner(tri, *f, ro);
  refiner.init();
  refiner.run();
  ASSERT_TRUE(mesh::check_all(tri).ok());
  ASSERT_TRUE(tri.has_regions());
  double inner_max = 0, outer_max = 0, inner_area = 0;
  for (TriangleId t = 0; t < tri.num_slots(); ++t) {
    if (tri.dead(t)) continue;
    const Point2 a = tri.point(tri.corner(t, 0)), b = tri.point(tri.corner(t, 1)), c = tri.point(tri.corner(t, 2));
    const double area = 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    ASSERT_GE(tri.region(t), 0);
    if (tri.region(t) == 0) inner_max = std::max(inner_max, area), inner_area += area;
    else outer_max = std::max(outer_max, area);
  }
  EXPECT_LE(inner_max, 0.02);
  EXPECT_NEAR(inner_area, 9.0, 1e-9);  // the inner square keeps its triangles: region 0 exactly
  EXPECT_GT(outer_max, 0.5);           // no constraint there
}
}  // namespace
