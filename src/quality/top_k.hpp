// Percentiles from the top of a stream without keeping every value: the report's p99 of
// orthogonality and smoothness and p05 of conformity.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>
#include "quality/extremes.hpp"

namespace fdr::quality {

// At least the k largest values of a stream (as a multiset), in a buffer of fewer than 2k: a value
// below thr_ (the k-th largest at the last trim) cannot be among the k largest. NaN counts as the
// largest value.
class TopK {
 public:
  explicit TopK(std::size_t k = 1) : k_(std::max<std::size_t>(k, 1)) {}
  __attribute__((always_inline)) void add(double x) {
    if (!(x < thr_)) {
      v_.push_back(x);
      if (v_.size() >= 2 * k_) trim();
    }
  }
  struct Less {  // a type (not a function pointer) so that sorting inlines it
    bool operator()(double a, double b) const { return a < b || (!std::isnan(a) && std::isnan(b)); }
  };
  static constexpr Less less{};
  std::vector<double>& values() { return v_; }
  // Adds the values another TopK kept (the union keeps at least the k largest of both streams).
  void absorb(TopK& o) { v_.insert(v_.end(), o.v_.begin(), o.v_.end()); }
  void release() { std::vector<double>().swap(v_); }

 private:
  __attribute__((noinline)) void trim() {
    const auto cut = v_.begin() + static_cast<std::ptrdiff_t>(v_.size() - k_);
    std::nth_element(v_.begin(), cut, v_.end(), less);
    thr_ = *cut;
    v_.erase(v_.begin(), cut);
  }
  std::size_t k_;
  double thr_ = -kInf;
  std::vector<double> v_;
};

// The nearest-rank q-quantile of n values (rank ceil(q n)) from `top`, which holds at least the
// `keep` largest values of each part of the n (or all of a part's); nullopt when the quantile may
// lie below them (more than `keep` values from that rank up). NaN sorts last.
inline std::optional<double> quantile_from_top(std::vector<double>& top, std::size_t keep, std::size_t n, double q) {
  const std::size_t rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(n)));
  const std::size_t k = rank == 0 ? 0 : std::min(rank - 1, n - 1);  // 0-based
  const std::size_t from_top = n - k;                                // k is the from_top-th largest
  if (from_top > keep || from_top > top.size()) return std::nullopt;
  const auto at = top.end() - static_cast<std::ptrdiff_t>(from_top);
  std::nth_element(top.begin(), at, top.end(), TopK::less);
  return *at;
}

}  // namespace fdr::quality
