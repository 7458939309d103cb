// tetio_convert: a test tool. Reads a TetGen mesh (BASE.node/.ele[/.face]) or, with --cube, makes
// the six-tetrahedron unit cube, and writes it to each OUT by extension (.vtu raw appended,
// .b64.vtu base64, .msh, .node TetGen). With --plc IN OUT.poly, reads any 3D input (read_plc) and
// writes it as a .poly. Exit code: the fdr::Error's, 0 on success.
#include <cstdio>
#include <string>
#include "base/error.hpp"
#include "tetio/read_plc.hpp"
#include "tetio/read_tetgen.hpp"
#include "tetio/write_poly.hpp"
#include "tetio/write_tets.hpp"
#include "tetio/tests/cube_mesh.hpp"

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: tetio_convert (IN.ele | --cube) OUT... | tetio_convert --plc IN OUT.poly\n");
    return 2;
  }
  try {
    const std::string in = argv[1];
    if (in == "--plc" && argc == 4) {
      fdr::tetio::write_poly(argv[3], fdr::tetio::read_plc(argv[2]));
      return 0;
    }
    const fdr::tet::TetMesh m = in == "--cube" ? fdr::tetio::testing::cube_mesh() : fdr::tetio::read_tetgen_mesh(in);
    for (int i = 2; i < argc; ++i) {
      const std::string out = argv[i];
      if (out.size() > 8 && out.substr(out.size() - 8) == ".b64.vtu") {
        fdr::tetio::write_vtu(out, m, fdr::tetio::VtuEncoding::kBase64);
      } else {
        fdr::tetio::write_tets(out, m);
      }
    }
  } catch (const fdr::Error& e) {
    std::fprintf(stderr, "tetio_convert: %s\n", e.what());
    return e.exit_code();
  }
  return 0;
}
