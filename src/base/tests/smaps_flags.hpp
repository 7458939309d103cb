// Test helper: what /proc/self/smaps says about the mapping that holds an address.
#pragma once
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

namespace fdr::test {

// True when the mapping that holds p is advised for huge pages ("hg" in its VmFlags).
inline bool advised_huge(const void* p) {
  std::ifstream smaps("/proc/self/smaps");
  const auto a = reinterpret_cast<std::uintptr_t>(p);
  bool inside = false;
  for (std::string line; std::getline(smaps, line);) {
    std::uintptr_t lo = 0, hi = 0;
    char dash = 0;
    std::istringstream ls(line);
    if (ls >> std::hex >> lo >> dash >> hi && dash == '-') {
      inside = a >= lo && a < hi;
      continue;
    }
    if (inside && line.rfind("VmFlags:", 0) == 0) return line.find(" hg") != std::string::npos;
  }
  return false;
}

}  // namespace fdr::test
