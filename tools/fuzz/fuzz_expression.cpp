// libFuzzer target: spacing specification parser (sizing::make_spacing: numbers, presets,
// muparser expressions), then evaluation, description and Lipschitz estimate.
#include <cstdint>
#include <string>
#include "base/error.hpp"
#include "sizing/make_spacing.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 512) return 0;
  const std::string spec(reinterpret_cast<const char*>(data), size);
  try {
    fdr::sizing::SizingPtr f = fdr::sizing::make_spacing(spec);
    volatile double sink = 0;
    for (double x : {-1e7, -1.0, 0.0, 0.5, 3.0, 1e7})
      for (double y : {-2.0, 0.0, 0.25, 9.0}) sink = sink + (*f)({x, y});
    (void)f->describe();
    (void)f->lipschitz();
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) __builtin_trap();
  }
  return 0;
}
