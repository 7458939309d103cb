// Neumaier compensated summation (areas of many triangles of very different size).
#pragma once
#include <cmath>

namespace fdr::quality {

struct CompensatedSum {
  double sum = 0, c = 0;
  void add(double v) {
    const double t = sum + v;
    if (std::fabs(sum) >= std::fabs(v)) c += (sum - t) + v;
    else c += (v - t) + sum;
    sum = t;
  }
  double value() const { return sum + c; }
};

}  // namespace fdr::quality
