// Long-running stress (CTest label "long"): thousands of random PSLGs with random interior
// segments, spacing and bounds; every mesh must satisfy all FDR invariants.
#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include <random>
#include "cdt/cdt.hpp"
#include "base/triangle_geometry.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "refine/tests/fn_field.hpp"
#include "mesh/check.hpp"
#include "predicates/predicates.hpp"
#include "refine/refine.hpp"

using namespace fdr;

namespace {
using fdr::testing::FnField;
}  // namespace

TEST(RefineStress, ThousandsOfRandomPslgs) {
  for (unsigned seed = 1000; seed < 3000; ++seed) {
    auto p = fdr::testing::random_pslg(seed, 5 + seed % 60, static_cast<int>(seed % 30));
    const double h = 0.15 + 0.05 * (seed % 9);
    const double cx = (seed % 10), cy = (seed / 10) % 10;
    FnField f([=](Point2 q) { return h + 0.12 * std::hypot(q.x - cx, q.y - cy); });
    refine::RefineOptions o;
    o.bound = 0.6 + 0.1 * (seed % 6);
    o.min_angle_deg = (seed % 4 == 0) ? 25.0 : 0.0;
    auto T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "stress"});
    refine::Refiner r(T, f, o);
    r.init();
    try {
      r.run();
    } catch (const std::exception& e) {
      FAIL() << "seed " << seed << ": " << e.what();
    }
    auto c = mesh::check_all(T);
    ASSERT_TRUE(c.ok()) << "seed " << seed << ": " << (c.problems.empty() ? "" : c.problems[0]);
    ASSERT_NEAR(T.area(), 100.0, 1e-9) << seed;
    for (TriangleId t = 0; t < T.num_slots(); ++t) {
      if (T.dead(t)) continue;
      double r2;
      const Point2 cc = geom::circumcentre(T.point(T.corner(t, 0)), T.point(T.corner(t, 1)), T.point(T.corner(t, 2)), &r2);
      ASSERT_LE(std::sqrt(r2) / f(cc), o.bound * (1 + 1e-12)) << "seed " << seed;
    }
  }
}

// Lattice inputs: exact collinearity and cocircularity everywhere, segments through vertices.
TEST(RefineStress, LatticePslgsWithSegmentsThroughVertices) {
  for (unsigned seed = 0; seed < 1500; ++seed) {
    std::mt19937 rng(seed);
    const int n = 6 + static_cast<int>(seed % 10);
    pslg::Pslg p = fdr::testing::lattice_square(n);

    auto id = [&](int i, int j) { return static_cast<Index>(j * (n + 1) + i); };
    std::uniform_int_distribution<int> u(0, n);
    for (int k = 0; k < 4 + static_cast<int>(seed % 12); ++k) {
      const Index a = id(u(rng), u(rng)), b = id(u(rng), u(rng));
      if (a == b) continue;
      bool ok = true;
      for (const auto& s : p.segments) {
        if (s.a == a || s.a == b || s.b == a || s.b == b) {  // reject collinear overlaps
          const Index sh = (s.a == a || s.a == b) ? s.a : s.b, o = sh == s.a ? s.b : s.a, other = sh == a ? b : a;
          if (predicates::orient2d(p.points[sh], p.points[other], p.points[o]) == 0 &&
              dot(p.points[other] - p.points[sh], p.points[o] - p.points[sh]) > 0) { ok = false; break; }
          continue;
        }
        if (fdr::testing::segments_cross_or_touch(p.points[a], p.points[b], p.points[s.a], p.points[s.b])) { ok = false; break; }
      }
      if (ok) p.segments.push_back({a, b, 4, 1});
    }
    auto T = cdt::build_cdt(p, {cdt::CdtOptions::Regions::kSeeds, "lattice"});
    auto c = mesh::check_all(T);
    ASSERT_TRUE(c.ok()) << "seed " << seed << ": " << (c.problems.empty() ? "" : c.problems[0]);
    FnField f([](Point2 q) { return 0.3 + 0.05 * q.x; });
    refine::RefineOptions o;
    o.min_angle_deg = (seed % 2) ? 28.0 : 0.0;
    refine::Refiner r(T, f, o);
    r.init();
    r.run();
    c = mesh::check_all(T);
    ASSERT_TRUE(c.ok()) << "seed " << seed << " refined: " << (c.problems.empty() ? "" : c.problems[0]);
    ASSERT_NEAR(T.area(), double(n) * n, 1e-9 * n * n);
  }
}
