// Times read_poly + clean + validate on a .poly file (a measurement helper, not a test).
#include <chrono>
#include <cstdio>
#include <map>
#include "pslg/clean.hpp"
#include "pslg/poly_io.hpp"
#include "pslg/validate.hpp"

int main(int argc, char** argv) {
  using clk = std::chrono::steady_clock;
  if (argc < 2) return 2;
  try {
    auto t0 = clk::now();
    const auto in = fdr::pslg::read_poly(argv[1]);
    auto t1 = clk::now();
    fdr::pslg::CleanOptions opt;
    opt.snap_distance = argc > 2 ? std::atof(argv[2]) : 0;
    std::vector<fdr::pslg::Repair> rep;
    const auto out = fdr::pslg::clean(in, opt, &rep);
    auto t2 = clk::now();
    fdr::pslg::validate(out, argv[1]);
    auto t3 = clk::now();
    std::map<std::string, int> kinds;
    for (const auto& r : rep) ++kinds[r.kind];
    std::printf("%zu pts %zu segs -> %zu pts %zu segs; read %.3f s, clean %.3f s, validate %.3f s\n", in.points.size(),
                in.segments.size(), out.points.size(), out.segments.size(),
                std::chrono::duration<double>(t1 - t0).count(), std::chrono::duration<double>(t2 - t1).count(),
                std::chrono::duration<double>(t3 - t2).count());
    for (auto& [k, n] : kinds) std::printf("  %s: %d\n", k.c_str(), n);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ERROR: %s\n", e.what());
    return 1;
  }
}
