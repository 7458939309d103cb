// Long stress run of clean(): 20000 seeded adversarial soups (lattices, near-duplicates, thin far
// strips, almost-collinear fans) with snapping, island removal and simplification mixed in.
#include <gtest/gtest.h>
#include <cmath>
#include <random>
#include "base/error.hpp"
#include "pslg/clean.hpp"
#include "pslg/validate.hpp"

using namespace fdr;
using namespace fdr::pslg;

TEST(CleanStress, TwentyThousandSoups) {
  std::mt19937_64 rng(1);
  int failures = 0;
  for (int k = 0; k < 20000 && failures < 5; ++k) {
    Pslg g;
    const int n = 4 + static_cast<int>(rng() % 60), mode = k % 5;
    std::uniform_real_distribution<double> u(0, 100);
    for (int i = 0; i < n; ++i) {
      Point2 p{u(rng), u(rng)};
      if (mode == 1) p = {std::floor(p.x / 10), std::floor(p.y / 10)};
      if (mode == 2 && i > 0 && rng() % 3 == 0) p = g.points[rng() % i] + Point2{1e-9, -1e-9};
      if (mode == 3) p = {p.x * 1e-9 + 1e6, p.y};
      if (mode == 4) p = {p.x, p.x * 0.3 + 1e-12 * p.y};
      g.points.push_back(p);
    }
    const int m = 1 + static_cast<int>(rng() % 60);
    for (int i = 0; i < m; ++i)
      g.segments.push_back({static_cast<Index>(rng() % n), static_cast<Index>(rng() % n),
                            rng() % 4 ? 1 : kBreaklineMarker, static_cast<std::int32_t>(rng() % 3)});
    CleanOptions opt;
    opt.snap_distance = (k % 3 == 0) ? 1e-6 : 0;
    if (k % 7 == 0) {
      opt.min_island_area_factor = 1;
      opt.simplify_factor = 1;
      opt.simplify_tolerance = 0.5;
      opt.spacing = [](Point2) { return 2.0; };
    }
    try {
      const Pslg out = clean(g, opt, nullptr);
      validate(out, "stress");
      std::vector<Repair> again;
      clean(out, CleanOptions{}, &again);
      if (!again.empty()) {
        ++failures;
        ADD_FAILURE() << "case " << k << " not idempotent: " << again[0].kind;
      }
    } catch (const Error& e) {
      ++failures;
      ADD_FAILURE() << "case " << k << " (mode " << mode << "): " << e.what();
    }
  }
  EXPECT_EQ(failures, 0);
}
