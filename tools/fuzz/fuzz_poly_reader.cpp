// libFuzzer target: Triangle .poly reader (bytes -> temporary file -> pslg::read_poly), then the
// resolver on whatever parses. Oracle: no crash/sanitizer report; only fdr::Error may escape
// read_poly/resolve, and a resolved PSLG must validate.
#include <unistd.h>
#include <cstdint>
#include <cstdio>
#include <string>
#include "base/error.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/resolve.hpp"
#include "pslg/validate.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string path = "/tmp/fdr_fuzz_poly_" + std::to_string(getpid()) + ".poly";
  if (FILE* f = std::fopen(path.c_str(), "wb")) {
    std::fwrite(data, 1, size, f);
    std::fclose(f);
  } else {
    return 0;
  }
  fdr::pslg::Pslg g;
  try {
    g = fdr::pslg::read_poly(path);
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) __builtin_trap();
    return 0;
  }
  if (g.points.size() > 200 || g.segments.size() > 400) return 0;  // keep executions fast
  try {
    std::vector<fdr::pslg::Repair> reps;
    const fdr::pslg::Pslg r = fdr::pslg::resolve(g, {}, &reps);
    fdr::pslg::validate(r, "resolved");
  } catch (const fdr::Error& e) {
    if (e.code() == fdr::ExitCode::kInternal) {
      std::fprintf(stderr, "internal error: %s\n", e.what());
      __builtin_trap();
    }
  }
  return 0;
}
