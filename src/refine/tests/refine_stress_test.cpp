// Long-running stress (CTest label "long"): thousands of random PSLGs with random interior
// segments, spacing and bounds; every mesh must satisfy all FDR invariants.
#include <gtest/gtest.h>
#include <cmath>
#include <functional>
#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
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
      const Point2 cc = predicates::circumcenter(T.pts[T.tv[3 * t]], T.pts[T.tv[3 * t + 1]], T.pts[T.tv[3 * t + 2]], &r2);
      ASSERT_LE(std::sqrt(r2) / f(cc), o.bound * (1 + 1e-12)) << "seed " << seed;
    }
  }
}
