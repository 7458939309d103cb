#include "tet/spatial_sort.hpp"
#include <algorithm>
#include <bit>
#include <cmath>

namespace fdr::tet {

std::uint64_t hilbert_key(std::uint32_t x, std::uint32_t y, std::uint32_t z, int bits) {
  // Skilling's transform ("Programming the Hilbert curve", 2004): axes to the transposed Hilbert
  // index, whose bits are then interleaved most significant first.
  std::uint32_t X[3] = {x, y, z};
  const std::uint32_t m = 1u << (bits - 1);
  for (std::uint32_t q = m; q > 1; q >>= 1) {
    const std::uint32_t p = q - 1;
    for (auto& xi : X) {
      if (xi & q) {
        X[0] ^= p;
      } else {
        const std::uint32_t t = (X[0] ^ xi) & p;
        X[0] ^= t;
        xi ^= t;
      }
    }
  }
  X[1] ^= X[0];
  X[2] ^= X[1];
  std::uint32_t t = 0;
  for (std::uint32_t q = m; q > 1; q >>= 1)
    if (X[2] & q) t ^= q - 1;
  for (auto& xi : X) xi ^= t;
  std::uint64_t key = 0;
  for (int b = bits - 1; b >= 0; --b)
    for (const std::uint32_t xi : X) key = (key << 1) | ((xi >> b) & 1u);
  return key;
}

int brio_round(std::uint64_t i, int rounds) {
  // splitmix64: a fixed bijective mix, so the rounds look random but never change.
  std::uint64_t h = i + 0x9E3779B97F4A7C15ull;
  h = (h ^ (h >> 30)) * 0xBF58476D1CE4E5B9ull;
  h = (h ^ (h >> 27)) * 0x94D049BB133111EBull;
  h ^= h >> 31;
  const int level = std::countr_one(h);  // level k with probability 2^-(k+1)
  return std::max(0, rounds - 1 - level);
}

int brio_rounds(std::size_t n) {
  int r = 1;
  while (r < 15 && (n >> r) >= 1000) ++r;
  return r;
}

std::vector<Index> brio_order(std::span<const Point3> pts) {
  constexpr int kBits = 20;
  Box3 box;
  for (const Point3& p : pts) box.add(p);
  const double span = std::max({box.hi.x - box.lo.x, box.hi.y - box.lo.y, box.hi.z - box.lo.z});
  const double scale = span > 0 ? ((1u << kBits) - 1) / span : 0.0;
  auto cell = [&](double v, double lo) {
    const double c = std::floor((v - lo) * scale);
    return static_cast<std::uint32_t>(std::clamp(c, 0.0, double((1u << kBits) - 1)));
  };
  const int rounds = brio_rounds(pts.size());
  struct Entry {
    std::uint64_t key;
    Index i;
  };
  std::vector<Entry> e(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Point3 p = pts[i];
    const auto h = hilbert_key(cell(p.x, box.lo.x), cell(p.y, box.lo.y), cell(p.z, box.lo.z), kBits);
    e[i] = {(std::uint64_t(brio_round(i, rounds)) << (3 * kBits)) | h, static_cast<Index>(i)};
  }
  std::sort(e.begin(), e.end(), [](const Entry& a, const Entry& b) {
    return a.key != b.key ? a.key < b.key : a.i < b.i;
  });
  std::vector<Index> order(pts.size());
  for (std::size_t k = 0; k < e.size(); ++k) order[k] = e[k].i;
  return order;
}

}  // namespace fdr::tet
