// fdr::mesh_domain (the GIS API) is pipeline::run; fdr::write_mesh writes what -o writes.
#include <gtest/gtest.h>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include "base/error.hpp"
#include "pipeline/mesh_domain.hpp"

namespace {
const std::string kT = FDR_TESTDATA_DIR;

std::string slurp(const std::string& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(MeshDomain, SameAsPipelineRunAndWritesLikeTheCli) {
  const auto dir = std::filesystem::temp_directory_path() / "fdr_mesh_domain_test";
  std::filesystem::create_directories(dir);
  fdr::DomainOptions o;
  o.input = kT + "/chesapeake/chesapeake_mouth.gpkg";
  o.layer = "water";
  o.open_boundary = o.input;
  o.open_boundary_layer = "open_boundary";
  o.raster = kT + "/chesapeake/chesapeake_mouth_etopo5.tif";
  o.outputs = {(dir / "run.2dm").string()};
  const fdr::GisMesh g = fdr::mesh_domain(o);
  const fdr::pipeline::Result r = fdr::pipeline::run(o, nullptr, [](fdr::LogLevel, std::string_view) {});
  EXPECT_EQ(g.view.triangles, r.mesh.triangles);
  EXPECT_EQ(g.view.z, r.mesh.z);
  EXPECT_FALSE(g.view.crs_wkt.empty());
  EXPECT_EQ(g.repairs.size(), r.repairs);
  EXPECT_EQ(g.written, std::vector<std::string>{(dir / "run.2dm").string()});
  // write_mesh after the run writes the same 2DM as the run itself.
  fdr::write_mesh(g, (dir / "api.2dm").string());
  EXPECT_EQ(slurp((dir / "api.2dm").string()), slurp((dir / "run.2dm").string()));
  std::filesystem::remove_all(dir);
}

TEST(MeshDomain, OutputCrsMeshIsWrittenDuringTheRun) {
  fdr::DomainOptions o;
  o.input = kT + "/poly/square10.poly";
  o.spacing = "1";
  fdr::GisMesh g = fdr::mesh_domain(o);
  g.output_crs = "EPSG:4326";
  try {
    fdr::write_mesh(g, "never.2dm");
    FAIL();
  } catch (const fdr::Error& e) {
    EXPECT_EQ(e.exit_code(), 2);
  }
}
}  // namespace
