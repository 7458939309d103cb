// GIS API example: `fdrmesh mesh INPUT --spacing S -o OUT` as one library call.
// Usage: mesh_domain_example INPUT SPACING OUT
#include <cstdio>
#include "pipeline/mesh_domain.hpp"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: mesh_domain_example INPUT SPACING OUT\n");
    return 2;
  }
  try {
    fdr::DomainOptions o;
    o.input = argv[1];
    o.spacing = argv[2];
    const fdr::GisMesh m = fdr::mesh_domain(o);
    fdr::write_mesh(m, argv[3]);
    std::printf("%zu triangles, %zu repairs, CRS '%s' -> %s\n", m.view.triangles.size(), m.repairs.size(),
                m.crs_name.c_str(), argv[3]);
    return 0;
  } catch (const fdr::Error& e) {
    std::fprintf(stderr, "ERROR %d: %s\n", e.exit_code(), e.what());
    return e.exit_code();
  }
}
