// libFuzzer target: PSLG -> resolve -> CDT -> FDR with the mesh checkers as oracle (see
// pslg_mesh_oracle.hpp for the input format and the checks).
#include <cstdio>
#include "pslg_mesh_oracle.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string failure = fdr_fuzz::pslg_mesh_case(data, size);
  if (!failure.empty()) {
    std::fprintf(stderr, "ORACLE FAILURE: %s\n", failure.c_str());
    std::fflush(stderr);
    __builtin_trap();
  }
  return 0;
}
