// Issue 11 report, from what the CLI writes: `fdrmesh mesh` on the bundled Chesapeake example
// writes "model_ready" (every key present, values consistent) and a theory table whose per-bound
// `holds` agrees with bound vs measured; `fdrmesh quality` on the written mesh gives the same
// mesh-only figures (no input coast, so no coast deviation).
#include <gtest/gtest.h>
#include "cli_test_util.hpp"
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;

using fdr::cli_test::load;
using fdr::cli_test::run;

TEST(ModelReadyCli, ChesapeakeReportAndQualityCommand) {
  const fs::path dir = fs::temp_directory_path() / ("fdrmesh_model_ready_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string t = std::string(FDR_TESTDATA_DIR) + "/chesapeake/";
  ASSERT_EQ(run("mesh " + t + "chesapeake_mouth.gpkg --layer water --open-boundary " + t +
                "chesapeake_mouth.gpkg --open-boundary-layer open_boundary --raster " + t +
                "chesapeake_mouth_etopo5.tif -q -o " + (dir / "c.2dm").string() + " --report " +
                (dir / "c.json").string()),
            0);
  const auto j = load(dir / "c.json");
  ASSERT_TRUE(j.contains("model_ready"));
  const auto& mr = j["model_ready"];
  for (const char* k : {"hmin_m", "edges", "shortest_edge_m", "shortest_edge_over_hmin", "shortest_edge_at",
                        "edges_below_half_hmin_pct", "edges_below_tenth_hmin_pct", "triangles_below_20_deg_pct",
                        "triangles_below_30_deg_pct", "mean_quality", "min_quality", "pieces", "coast_deviation",
                        "time_step", "area", "features_removed", "coast_figures"})
    EXPECT_TRUE(mr.contains(k)) << k;
  const double hmin = mr["hmin_m"].get<double>();
  EXPECT_GT(hmin, 0);
  EXPECT_NEAR(mr["shortest_edge_over_hmin"].get<double>(), mr["shortest_edge_m"].get<double>() / hmin, 1e-12);
  EXPECT_GT(mr["mean_quality"].get<double>(), 0.5);
  EXPECT_LE(mr["mean_quality"].get<double>(), 1.0);
  EXPECT_GE(mr["pieces"]["mesh"].get<int>(), 1);
  EXPECT_GE(mr["pieces"]["input"].get<int>(), 1);
  for (const char* dir_name : {"input_to_mesh", "mesh_to_input"}) {
    const auto& d = mr["coast_deviation"][dir_name];
    ASSERT_TRUE(d.is_object()) << dir_name;
    EXPECT_GE(d["max_m"].get<double>(), d["p99_m"].get<double>()) << dir_name;
    EXPECT_NEAR(d["p99_over_hmin"].get<double>(), d["p99_m"].get<double>() / hmin, 1e-12) << dir_name;
    EXPECT_GT(d["samples"].get<int>(), 100) << dir_name;
  }
  // A raster was given: depths, hence a time step at a wet triangle.
  ASSERT_TRUE(mr["time_step"].is_object());
  const auto& ts = mr["time_step"];
  EXPECT_NEAR(ts["dt_s"].get<double>(),
              ts["h_m"].get<double>() / std::sqrt(9.81 * ts["depth_m"].get<double>()), 1e-9);
  EXPECT_GE(ts["depth_m"].get<double>(), 1.0);  // --min-depth default
  EXPECT_NEAR(mr["area"]["mesh_m2"].get<double>(), j["area"].get<double>(), 1e-6 * j["area"].get<double>());
  EXPECT_TRUE(mr["features_removed"].contains("islands"));

  // Theory table: every bound carries {bound, measured, holds}, holds = the relation, and valid
  // is true exactly when every counted bound holds.
  const auto& g = j["guarantees"];
  ASSERT_TRUE(g["applicable"].get<bool>());
  int rows = 0;
  bool all = true;
  for (auto it = g.begin(); it != g.end(); ++it) {
    if (!it.value().is_object()) continue;
    ++rows;
    const auto& c = it.value();
    const double b = c["bound"].get<double>(), m = c["measured"].get<double>();
    const bool holds = c["relation"] == "<=" ? m <= b : m >= b;
    EXPECT_EQ(c["holds"].get<bool>(), holds) << it.key();
    if (c["counts_for_valid"].get<bool>()) all = all && holds;
  }
  EXPECT_EQ(rows, 6);
  EXPECT_EQ(g["valid"].get<bool>(), all);
  EXPECT_TRUE(g["fdr_R_over_f_max"]["holds"].get<bool>());  // the refiner's invariant
  // beta from the conforming mesh's D (paper, Section 4): the table holds on a real coast (issue
  // 11), with D measured where the input is finer than f and beta = min(beta_B, beta_D).
  ASSERT_TRUE(g["conforming_D"].is_number());
  const double D = g["conforming_D"].get<double>();
  EXPECT_GT(D, 0.0);
  EXPECT_EQ(g["conforming_D_at"].size(), 2u);
  EXPECT_NEAR(g["beta"].get<double>(), std::min(g["beta_B"].get<double>(), g["beta_D"].get<double>()), 1e-12);
  EXPECT_TRUE(g["valid"].get<bool>());
  EXPECT_TRUE(g["theorem_4_4_nn_over_f_min"]["holds"].get<bool>());
  EXPECT_TRUE(g["theorem_4_3_R_over_l_max"]["holds"].get<bool>());

  // `fdrmesh quality` on the written 2DM: mesh-only figures agree with the mesher's.
  ASSERT_EQ(run("quality " + (dir / "c.2dm").string() + " -q --report " + (dir / "q.json").string()), 0);
  const auto q = load(dir / "q.json")["model_ready"];
  EXPECT_EQ(q["edges"], mr["edges"]);
  EXPECT_EQ(q["pieces"]["mesh"], mr["pieces"]["mesh"]);
  EXPECT_TRUE(q["pieces"]["input"].is_null());
  EXPECT_TRUE(q["hmin_m"].is_null());
  EXPECT_TRUE(q["coast_deviation"]["input_to_mesh"].is_null());
  EXPECT_EQ(q["triangles_below_30_deg"], mr["triangles_below_30_deg"]);
  EXPECT_NEAR(q["shortest_edge_m"].get<double>(), mr["shortest_edge_m"].get<double>(), 1e-6);
  EXPECT_NEAR(q["mean_quality"].get<double>(), mr["mean_quality"].get<double>(), 1e-9);
  ASSERT_TRUE(q["time_step"].is_object());  // 2DM keeps z
  EXPECT_NEAR(q["time_step"]["dt_s"].get<double>(), ts["dt_s"].get<double>(), 1e-6 * ts["dt_s"].get<double>());
  fs::remove_all(dir);
}

// From what the CLI writes: the 12 districts of lux.shp are meshed as one domain,
// so the coast deviation is measured against their union's boundary (their shared borders are no
// coast) and stays within hmin/2; the DEM lies above sea level everywhere, so the report gives
// no gravity-wave time step (every depth would be the 1 m clamp) and says why.
TEST(ModelReadyCli, LuxembourgDistrictsMeasuredAsOneLandDomain) {
  const fs::path dir = fdr::cli_test::fresh_dir("fdrmesh_model_ready_lux");
  const std::string t = std::string(FDR_TESTDATA_DIR) + "/luxembourg/";
  const std::string cmd = std::string(FDR_BINARY) + " mesh " + t + "lux.shp --raster " + t + "elev.tif -o " +
                          (dir / "lux.gpkg").string() + " --report " + (dir / "lux.json").string() + " > " +
                          (dir / "report.txt").string() + " 2> /dev/null";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << cmd;
  const auto mr = load(dir / "lux.json")["model_ready"];
  EXPECT_EQ(mr["coast_figures"]["input_polygons"], 12);
  EXPECT_EQ(mr["coast_figures"]["input_polygons_united"], 1);
  const auto& dev = mr["coast_deviation"];
  EXPECT_NE(dev["measured_against"].get<std::string>().find("united input domain (12 polygons united into 1)"),
            std::string::npos);
  // Both ways within hmin/2 at the 99th percentile and within one hmin at most (the shared
  // borders, kilometres inside the country, have no counterpart in the mesh).
  for (const char* d : {"input_to_mesh", "mesh_to_input"}) {
    EXPECT_LE(dev[d]["p99_over_hmin"].get<double>(), 0.5) << d;
    EXPECT_LE(dev[d]["max_over_hmin"].get<double>(), 1.0) << d;
  }
  EXPECT_TRUE(mr["time_step"].is_null());
  EXPECT_NE(mr["time_step_omitted"].get<std::string>().find("no vertex below sea level"), std::string::npos);
  const std::string text = fdr::cli_test::slurp(dir / "report.txt");
  EXPECT_NE(text.find("coast measured against        : boundary of the united input domain"), std::string::npos)
      << text;
  EXPECT_NE(text.find("time step h/sqrt(g depth)     : n/a: no vertex below sea level (land-only mesh)"),
            std::string::npos)
      << text;
  const std::string block = text.substr(std::min(text.find("Model readiness"), text.size()));
  EXPECT_EQ(block.find("depth 1 m"), std::string::npos) << block;
  EXPECT_EQ(block.find("narrow water"), std::string::npos) << block;  // worded for a land domain
  EXPECT_NE(block.find("narrow domain parts widened"), std::string::npos) << block;
  fs::remove_all(dir);
}
