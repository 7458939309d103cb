// `fdrmesh quality` on meshes written by `fdrmesh mesh` in every readable format: the same counts,
// the same R/f(c) maximum and the same bad-triangle count as the mesher's own report.
#include <gtest/gtest.h>
#include "cli_test_util.hpp"
#include <sys/wait.h>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fs = std::filesystem;

using fdr::cli_test::load;
using fdr::cli_test::run;
using fdr::cli_test::slurp;
using fdr::cli_test::fresh_dir;

TEST(QualityCommand, MatchesTheMeshReportForEveryFormat) {
  const fs::path dir = fresh_dir("fdrmesh_quality");
  const std::string in = std::string(FDR_TESTDATA_DIR) + "/poly/square_with_hole.poly";
  ASSERT_EQ(run("mesh " + in + " --spacing '0.2+0.05*x' -q -o " + (dir / "m.2dm").string() + " -o " +
                (dir / "m.14").string() + " -o " + (dir / "m.msh").string() + " -o " + (dir / "m.gpkg").string() +
                " -o " + (dir / "m.node").string() + " -o " + (dir / "m.gr3").string() + " -o " +
                (dir / "m.slf").string() + " --report " + (dir / "mesh.json").string()),
            0);
  ASSERT_EQ(run("mesh " + in + " --spacing '0.2+0.05*x' -q --slf-double -o " + (dir / "d.slf").string()), 0);
  const auto ref = load(dir / "mesh.json");
  for (const char* f : {"m.2dm", "m.14", "m.msh", "m.gpkg", "m.node", "m.gr3", "d.slf"}) {
    const fs::path rep = dir / (std::string(f) + ".json");
    ASSERT_EQ(run("quality " + (dir / f).string() + " --spacing '0.2+0.05*x' -q --report " + rep.string()), 0) << f;
    const auto q = load(rep);
    EXPECT_EQ(q["vertices"], ref["vertices"]) << f;
    EXPECT_EQ(q["triangles"], ref["triangles"]) << f;
    EXPECT_EQ(q["bad_triangles"], 0) << f;
    EXPECT_NEAR(q["max_R_over_f"].get<double>(), ref["max_R_over_f"].get<double>(), 1e-9) << f;
    EXPECT_NEAR(q["min_angle_deg"].get<double>(), ref["min_angle_deg"].get<double>(), 1e-9) << f;
  }
  // A stricter bound counts bad triangles.
  const fs::path strict = dir / "strict.json";
  ASSERT_EQ(run("quality " + (dir / "m.2dm").string() + " --spacing '0.2+0.05*x' --bound 0.5 -q --report " +
                strict.string()),
            0);
  EXPECT_GT(load(strict)["bad_triangles"].get<int>(), 0);
  fs::remove_all(dir);
}

// Same input, same output, bit for bit: two runs of the whole GIS pipeline write identical files.
TEST(Determinism, TwoRunsWriteIdenticalFiles) {
  const fs::path dir = fresh_dir("fdrmesh_determinism");
  const std::string t = FDR_TESTDATA_DIR;
  for (const char* run_name : {"a", "b"}) {
    const fs::path o = dir / run_name;
    fs::create_directories(o);
    ASSERT_EQ(run("mesh " + t + "/chesapeake/chesapeake_mouth_water.geojson --open-boundary " + t +
                  "/chesapeake/chesapeake_mouth_open_boundary.geojson --raster " + t +
                  "/chesapeake/chesapeake_mouth_etopo5.tif --min-angle 20 -q -o " + (o / "m.2dm").string() + " -o " +
                  (o / "m.14").string() + " -o " + (o / "m.msh").string() + " -o " + (o / "m.node").string() +
                  " -o " + (o / "m.gr3").string() + " -o " + (o / "m.ll").string() + " -o " + (o / "m.slf").string()),
              0);
  }
  for (const char* f : {"m.2dm", "m.14", "m.msh", "m.node", "m.ele", "m.gr3", "m.ll", "m.slf", "m.cli"}) {
    const std::string a = slurp(dir / "a" / f), b = slurp(dir / "b" / f);
    EXPECT_GT(a.size(), 1000u) << f;
    EXPECT_TRUE(a == b) << f << " differs between two runs";
  }
  fs::remove_all(dir);
}

// The thread count (FDR_THREADS: concurrent writers, report, distance to shore) never changes
// what is written.
TEST(Determinism, ThreadCountDoesNotChangeFiles) {
  const fs::path dir = fresh_dir("fdrmesh_threads");
  const std::string t = FDR_TESTDATA_DIR;
  for (const char* threads : {"1", "2", "3"}) {
    const fs::path o = dir / threads;
    fs::create_directories(o);
    const std::string cmd = std::string("FDR_THREADS=") + threads + " " + FDR_BINARY + " mesh " + t +
                            "/chesapeake/chesapeake_mouth_water.geojson --open-boundary " + t +
                            "/chesapeake/chesapeake_mouth_open_boundary.geojson --raster " + t +
                            "/chesapeake/chesapeake_mouth_etopo5.tif --dist-grade 0.05 -q -o " + (o / "m.2dm").string() +
                            " -o " + (o / "m.14").string() + " -o " + (o / "m.msh").string() + " -o " +
                            (o / "m.node").string() + " -o " + (o / "m.vtu").string() + " -o " + (o / "m.gpkg").string() + " --report " +
                            (o / "r.json").string() + " > /dev/null 2>&1";
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << cmd;
  }
  for (const char* f : {"m.2dm", "m.14", "m.msh", "m.node", "m.ele", "m.vtu"}) {
    const std::string a = slurp(dir / "1" / f);
    EXPECT_GT(a.size(), 1000u) << f;
    EXPECT_TRUE(a == slurp(dir / "2" / f)) << f << " differs between 1 and 2 threads";
    EXPECT_TRUE(a == slurp(dir / "3" / f)) << f << " differs between 1 and 3 threads";
  }
  EXPECT_GT(fs::file_size(dir / "2" / "m.gpkg"), 10000u);
  // The report (measured with the nearest neighbours on a second thread) has the same values;
  // only its timings and memory figures may differ.
  auto values = [&](const char* threads) {
    auto j = load(dir / threads / "r.json");
    j.erase("timings_s");
    j.erase("run");
    j.erase("peak_rss_mb");
    return j;
  };
  const auto r1 = values("1");
  EXPECT_TRUE(r1.contains("conformity"));
  EXPECT_EQ(r1, values("2"));
  EXPECT_EQ(r1, values("3"));
  fs::remove_all(dir);
}

// `-q` without --report and without an output that stores the report: nobody reads the quality
// report, so it is not measured (no "report" stage), and every file is the same as when it is
// (the .node file's f attribute, which the report fills, included; the boundary lists, which
// read the mesher's adjacency). A .poly run and a GIS run.
TEST(QuietRuns, UnreadReportIsNotMeasuredAndTheFilesAreTheSame) {
  const fs::path dir = fresh_dir("fdrmesh_unread_report");
  const std::string t = FDR_TESTDATA_DIR;
  auto capture = [](const std::string& cmd) {  // stdout and stderr of a command
    std::string out;
    if (FILE* p = popen((cmd + " 2>&1").c_str(), "r")) {
      char buf[4096];
      for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
      pclose(p);
    }
    return out;
  };
  struct Case {
    const char* name;
    std::string input;
    std::vector<const char*> files;  // written (the -o list is the first of each pair's stem)
  };
  const std::vector<Case> cases = {
      {"poly", t + "/poly/square_with_hole.poly --spacing '0.2+0.05*x'", {"m.2dm", "m.14", "m.msh", "m.node", "m.gr3", "m.slf"}},
      {"gis", t + "/chesapeake/chesapeake_mouth_water.geojson --open-boundary " + t +
                  "/chesapeake/chesapeake_mouth_open_boundary.geojson --raster " + t +
                  "/chesapeake/chesapeake_mouth_etopo5.tif --hmin 300 --hmax 5000",
       {"m.2dm", "m.14", "m.node", "m.gr3", "m.ll", "m.slf"}}};
  for (const Case& c : cases) {
    std::string stages[2];
    for (int with_report = 0; with_report < 2; ++with_report) {
      const fs::path o = dir / c.name / (with_report ? "with" : "without");
      fs::create_directories(o);
      std::string cmd = std::string("FDR_DEBUG_STAGES=1 ") + FDR_BINARY + " mesh " + c.input + " -q";
      for (const char* f : c.files) cmd += " -o " + (o / f).string();
      if (with_report) cmd += " --report " + (o / "r.json").string();
      const fs::path err = o / "stderr.txt";
      cmd += " > /dev/null 2> " + err.string();
      const int st = std::system(cmd.c_str());
      ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << cmd;
      stages[with_report] = slurp(err);
    }
    EXPECT_EQ(stages[0].find("stage report"), std::string::npos) << c.name << ": " << stages[0];
    EXPECT_NE(stages[1].find("stage report"), std::string::npos) << c.name << ": " << stages[1];
    std::vector<std::string> files(c.files.begin(), c.files.end());
    files.push_back("m.ele");
    if (std::find(files.begin(), files.end(), "m.slf") != files.end()) files.push_back("m.cli");
    for (const std::string& f : files) {
      const std::string a = slurp(dir / c.name / "without" / f);
      EXPECT_GT(a.size(), 100u) << c.name << " " << f;
      EXPECT_TRUE(a == slurp(dir / c.name / "with" / f)) << c.name << " " << f << " differs without the report";
    }
    const std::string node = slurp(dir / c.name / "without" / "m.node");
    const std::string header = node.substr(0, node.find('\n', node.find('\n') + 1));
    EXPECT_NE(header.find("attributes:"), std::string::npos) << header;
    EXPECT_NE(header.find(" f"), std::string::npos) << header;
  }
  // Printed (no -q) or stored by an output (GPKG): measured.
  const std::string base = std::string("FDR_DEBUG_STAGES=1 ") + FDR_BINARY + " mesh " + t + "/poly/square_with_hole.poly --spacing 0.3";
  std::string out = capture(base + " -o " + (dir / "p.2dm").string());
  EXPECT_NE(out.find("stage report"), std::string::npos) << out;
  EXPECT_NE(out.find("Mesh quality"), std::string::npos) << out;
  out = capture(base + " -q -o " + (dir / "p.gpkg").string());
  EXPECT_NE(out.find("stage report"), std::string::npos) << out;
  fs::remove_all(dir);
}
