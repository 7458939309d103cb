// FDR benchmark: f = k * paper-f1 on [0,10]^2, B = 1; fdrmesh's refiner beside CGAL's Delaunay_mesher_2 (same R/f(c) criterion) and Gmsh (background size field).
// Prints per tool: refine seconds, whole-process wall seconds, peak RSS of the process (VmHWM / ru_maxrss, not an
// increase), bytes/triangle, triangles per unit of the integral of 1/f^2 over the domain, min angle, vertices.
// The "fdrmesh" row is the refiner in-process (CDT + FDR); "fdrmesh-cli" is the real command line
// (fdrmesh mesh square10.poly --spacing K*paper-f1, no output files: read, CDT, refine, report), run as a child.
// Usage in kUsage below.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>
#include <chrono>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <nlohmann/json.hpp>
#include "base/error.hpp"
#include "chains.hpp"
#include "child.hpp"
#include "cdt/cdt.hpp"
#include "refine/refine.hpp"
#include "sizing/fields.hpp"

namespace {
using Clock = std::chrono::steady_clock;
double secs(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

// A "Vm...:" field of /proc/self/status in kB (0 if unavailable).
long proc_status_kb(const char* key) {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  long kb = 0;
  const std::size_t n = std::strlen(key);
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, key, n) == 0) kb = std::atol(line + n);
  std::fclose(f);
  return kb;
}
long vm_hwm_kb() { return proc_status_kb("VmHWM:"); }

double min_angle_of(double ax, double ay, double bx, double by, double cx, double cy) {
  auto ang = [](double px, double py, double qx, double qy, double rx, double ry) {
    double ux = qx - px, uy = qy - py, vx = rx - px, vy = ry - py;
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
  };
  return std::min({ang(ax, ay, bx, by, cx, cy), ang(bx, by, cx, cy, ax, ay), ang(cx, cy, ax, ay, bx, by)});
}

// Whole-process wall clock and VmHWM of a forked measurement child, from its own start.
Clock::time_point g_child_start;

// Integral of 1/f^2 over [0,10]^2 for f = k * ((|x-5| + |y-5|) * 0.1 + 0.1): by symmetry
// 4 * 100 / k^2 * int_0^5 int_0^5 (u + v + 1)^-2 du dv = 400 (2 ln 6 - ln 11) / k^2.
double integral_inv_f2(double k) { return 400.0 * (2.0 * std::log(6.0) - std::log(11.0)) / (k * k); }

struct Row {
  std::string tool; double k; double seconds; std::size_t tris, verts; double rss_mb, min_angle; std::string note;
  double whole_s = 0;  // whole process wall clock (0: not measured)
};

void print(const Row& r) {
  std::printf("%-11s k=%-7g refine %7.3f s  whole %7.3f s (%5.2fx)  %10zu tri  %6.3f tri/int(1/f^2)  %10.0f tri/s  "
              "peak %8.1f MiB  %6.1f B/tri  min angle %5.2f  %9zu vertices\n",
              r.tool.c_str(), r.k, r.seconds, r.whole_s, r.seconds > 0 ? r.whole_s / r.seconds : 0.0, r.tris,
              r.tris / integral_inv_f2(r.k), r.tris / r.seconds, r.rss_mb, r.rss_mb * 1048576.0 / r.tris, r.min_angle,
              r.verts);
  if (!r.note.empty()) std::printf("  note: %s\n", r.note.c_str());
  std::fflush(stdout);
}

Row run_fdr(double k) {
  using namespace fdr;
  pslg::Pslg p;
  p.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  sizing::PaperF1Field f(k);
  auto t0 = Clock::now();
  auto T = cdt::build_cdt(p);
  refine::Refiner r(T, f, {});
  r.reserve(refine::estimate_triangles(T, f, 1.0));
  r.init();
  r.run();
  auto t1 = Clock::now();
  double amin = 180;
  for (TriangleId t = 0; t < T.num_slots(); ++t) {
    if (T.dead(t)) continue;
    const Point2 a = T.point(T.corner(t, 0)), b = T.point(T.corner(t, 1)), c = T.point(T.corner(t, 2));
    amin = std::min(amin, min_angle_of(a.x, a.y, b.x, b.y, c.x, c.y));
  }
  Row row{"fdrmesh", k, secs(t0, t1), T.num_live_triangles(), T.num_vertices() - 3, vm_hwm_kb() / 1024.0, amin, {}};
  row.note = "in-process CDT + refine (bench process peak)";
  return row;
}

// CGAL's mesher with an R/f(c) criterion: a face is bad when circumradius / f(circumcenter) > B.
// CGAL refines the bad face of SMALLEST Quality first, so Quality = B f(c) / R: the largest R/f(c)
// is refined first, the paper's order (Quality = R/(B f) ran the opposite order).
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

struct RfCriteria {
  double k, B;
  using Quality = double;
  struct Is_bad {
    double k, B;
    CGAL::Mesh_2::Face_badness operator()(const Quality q) const {
      return q < 1 ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
    CGAL::Mesh_2::Face_badness operator()(CDT::Face_handle fh, Quality& q) const {
      const auto& a = fh->vertex(0)->point(); const auto& b = fh->vertex(1)->point(); const auto& c = fh->vertex(2)->point();
      const auto cc = CGAL::circumcenter(a, b, c);
      const double r = std::sqrt(CGAL::squared_distance(cc, a));
      const double f = k * ((std::fabs(cc.x() - 5) + std::fabs(cc.y() - 5)) * 0.1 + 0.1);
      q = (B * f) / r;
      return q < 1 ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
  };
  Is_bad is_bad_object() const { return {k, B}; }
};

Row run_cgal(double k) {
  CDT cdt;
  auto v0 = cdt.insert(K::Point_2(0, 0)), v1 = cdt.insert(K::Point_2(10, 0));
  auto v2 = cdt.insert(K::Point_2(10, 10)), v3 = cdt.insert(K::Point_2(0, 10));
  cdt.insert_constraint(v0, v1); cdt.insert_constraint(v1, v2);
  cdt.insert_constraint(v2, v3); cdt.insert_constraint(v3, v0);
  auto t0 = Clock::now();
  CGAL::Delaunay_mesher_2<CDT, RfCriteria> mesher(cdt, RfCriteria{k, 1.0});
  mesher.refine_mesh();
  auto t1 = Clock::now();
  std::size_t n = 0;
  double amin = 180;
  for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    ++n;
    const auto& a = f->vertex(0)->point(); const auto& b = f->vertex(1)->point(); const auto& c = f->vertex(2)->point();
    amin = std::min(amin, min_angle_of(a.x(), a.y(), b.x(), b.y(), c.x(), c.y()));
  }
  Row r{"cgal", k, secs(t0, t1), n, cdt.number_of_vertices(), vm_hwm_kb() / 1024.0, amin, {}};
  r.note = "CGAL Delaunay_mesher_2, largest R/f(c) first (bench process peak)";
  return r;
}

// ---- Gmsh peer: the same square and size law as a .geo with a MathEval background field, run as a child process.

// Gmsh sizes are target edge lengths h. An equilateral triangle with circumradius f has edge sqrt(3) f, but a
// Delaunay refiner stops as soon as R <= B f, so its triangles are smaller than the bound, while Gmsh aims at
// edges ~ h. h = factor * B * f with these factors gives Gmsh fdrmesh's triangle count: calibrated at k = 0.08
// and k = 0.025 from h = sqrt(3) B f, which gave 0.617x (Algorithm 5) and 0.556x (Algorithm 6) of fdrmesh's
// count at both k, hence sqrt(3) * sqrt(0.617) = 1.36 and sqrt(3) * sqrt(0.556) = 1.29.
constexpr double kGmshDelaunayFactor = 1.36;
constexpr double kGmshFrontalFactor = 1.29;

// factor <= 0 means the calibrated per-algorithm factor.
struct GmshOptions { double factor = 0; double min_k = 0.025; std::string binary = "gmsh"; };

double gmsh_factor(const GmshOptions& g, int algorithm) {
  if (g.factor > 0) return g.factor;
  return algorithm == 5 ? kGmshDelaunayFactor : kGmshFrontalFactor;
}

// Writes the .geo for one run: the square, the background field h(x,y) = factor * B * k * f1, and the options
// that make the field the only size source (no sizes from points, curvature or boundary extension).
void write_geo(const std::string& path, double k, double factor, int algorithm) {
  std::ofstream o(path);
  if (!o) throw fdr::Error(fdr::ExitCode::kOutputError, "bench_fdr: cannot write " + path);
  char f[256];
  std::snprintf(f, sizeof f, "%.17g*%.17g*((Fabs(x-5)+Fabs(y-5))*0.1+0.1)", factor, k);
  o << "Point(1) = {0, 0, 0}; Point(2) = {10, 0, 0}; Point(3) = {10, 10, 0}; Point(4) = {0, 10, 0};\n"
       "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
       "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
       "Field[1] = MathEval; Field[1].F = \"" << f << "\";\n"
       "Background Field = 1;\n"
       "Mesh.MeshSizeExtendFromBoundary = 0; Mesh.MeshSizeFromPoints = 0; Mesh.MeshSizeFromCurvature = 0;\n"
       "Mesh.Algorithm = " << algorithm << "; Mesh.MshFileVersion = 4.1; Mesh.Binary = 0;\n";
  if (!o) throw fdr::Error(fdr::ExitCode::kOutputError, "bench_fdr: cannot write " + path);
}

struct MshStats { std::size_t tris = 0, verts = 0; double min_angle = 180; };

// Reads the ASCII .msh 4.1 sections $Nodes and $Elements: node coordinates by tag, then every 3-node triangle
// (element type 2) for the count and the minimum angle.
MshStats read_msh41(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw fdr::Error(fdr::ExitCode::kInputUnreadable, "bench_fdr: cannot open Gmsh output " + path);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const char* p = text.c_str();
  auto bad = [&](const char* what) {
    return fdr::Error(fdr::ExitCode::kInputMalformed,
                      std::string("bench_fdr: ") + path + " (byte " + std::to_string(p - text.c_str()) + "): " + what);
  };
  auto num = [&]() {
    char* e;
    const double v = std::strtod(p, &e);
    if (e == p) throw bad("number expected");
    p = e;
    return v;
  };
  auto uint = [&]() {
    char* e;
    const unsigned long long v = std::strtoull(p, &e, 10);
    if (e == p) throw bad("integer expected");
    p = e;
    return static_cast<std::size_t>(v);
  };
  auto seek = [&](const char* tag) {
    const char* q = std::strstr(p, tag);
    if (!q) throw bad((std::string("section ") + tag + " missing").c_str());
    p = q + std::strlen(tag);
  };
  seek("$MeshFormat");
  if (num() < 4.1 - 1e-9) throw bad("not a .msh 4.1 file");
  MshStats st;
  seek("$Nodes");
  std::size_t blocks = uint(), n_nodes = uint();
  uint();
  const std::size_t max_tag = uint();
  st.verts = n_nodes;
  std::vector<double> xy(2 * (max_tag + 1), std::nan(""));
  std::vector<std::size_t> tags;
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t dim = uint();
    uint();
    const std::size_t parametric = uint(), n = uint();
    tags.resize(n);
    for (auto& t : tags) {
      t = uint();
      if (t > max_tag) throw bad("node tag above maxNodeTag");
    }
    for (std::size_t t : tags) {
      xy[2 * t] = num();
      xy[2 * t + 1] = num();
      num();
      // Parametric nodes carry dim extra coordinates (u, or u v).
      for (std::size_t d = 0; parametric && d < dim; ++d) num();
    }
  }
  seek("$Elements");
  blocks = uint();
  uint(); uint(); uint();
  for (std::size_t b = 0; b < blocks; ++b) {
    uint(); uint();
    const std::size_t type = uint(), n = uint();
    // Nodes per element for the types a 2D linear mesh contains: 15 point, 1 line, 2 triangle, 3 quadrangle.
    std::size_t nn = 0;
    switch (type) {
      case 15: nn = 1; break;
      case 1: nn = 2; break;
      case 2: nn = 3; break;
      case 3: nn = 4; break;
      default: throw bad(("unexpected element type " + std::to_string(type)).c_str());
    }
    std::size_t v[4];
    for (std::size_t e = 0; e < n; ++e) {
      uint();
      for (std::size_t j = 0; j < nn; ++j) {
        v[j] = uint();
        if (v[j] > max_tag || std::isnan(xy[2 * v[j]])) throw bad("element refers to an unknown node");
      }
      if (type != 2) continue;
      ++st.tris;
      st.min_angle = std::min(st.min_angle, min_angle_of(xy[2 * v[0]], xy[2 * v[0] + 1], xy[2 * v[1]], xy[2 * v[1] + 1],
                                                         xy[2 * v[2]], xy[2 * v[2] + 1]));
    }
  }
  return st;
}

// Gmsh's own "Done meshing 2D (Wall X s" figure: meshing time without start-up, .geo parsing and .msh writing.
std::optional<double> gmsh_mesh2d_wall(const std::string& log) {
  std::ifstream in(log);
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find("Done meshing 2D (Wall ");
    if (at != std::string::npos) return std::atof(line.c_str() + at + 22);
  }
  return std::nullopt;
}

struct GmshResult { Row row; double raw_mb = 0; std::optional<double> mesh2d; };

// One Gmsh run in a fresh scratch directory (removed afterwards unless Gmsh failed, so its log can be read).
GmshResult run_gmsh_once(const GmshOptions& g, double k, int algorithm, const char* label, double factor) {
  char dir_tmpl[] = "/tmp/bench_fdr_gmsh.XXXXXX";
  if (!mkdtemp(dir_tmpl)) throw fdr::Error(fdr::ExitCode::kOutputError, "bench_fdr: mkdtemp in /tmp failed");
  const std::string dir = dir_tmpl, geo = dir + "/square.geo", msh = dir + "/square.msh", log = dir + "/gmsh.log";
  write_geo(geo, k, factor, algorithm);
  ChildRun c;
  try {
    c = spawn_and_wait({g.binary, geo, "-2", "-nt", "1", "-o", msh}, log);
  } catch (const fdr::Error&) {
    std::remove(geo.c_str()); std::remove(log.c_str()); rmdir(dir.c_str());  // nothing ran: nothing to inspect
    throw;
  }
  if (!WIFEXITED(c.status) || WEXITSTATUS(c.status) != 0)
    throw fdr::Error(fdr::ExitCode::kInternal, "bench_fdr: " + g.binary + " failed on " + geo + " (status " +
                                                   std::to_string(c.status) + "), see " + log);
  const MshStats m = read_msh41(msh);
  const auto mesh2d = gmsh_mesh2d_wall(log);
  std::remove(geo.c_str()); std::remove(msh.c_str()); std::remove(log.c_str()); rmdir(dir.c_str());
  return {{label, k, c.wall, m.tris, m.verts, c.maxrss_mb, m.min_angle, {}}, c.maxrss_mb, mesh2d};
}

// Peak RSS of Gmsh meshing the same square with h from 0.45 to 5 (a few hundred triangles): its start-up footprint,
// subtracted from each run's ru_maxrss so "peak" means memory added by meshing, as in the fdrmesh/CGAL rows.
double gmsh_baseline_mb(const GmshOptions& g) {
  const GmshResult r = run_gmsh_once(g, 1.0, 5, "baseline", 5.0 / (0.1 * 1.0 * 11.0));
  return r.raw_mb;
}

Row run_gmsh(const GmshOptions& g, double k, int algorithm, const char* label, double baseline_mb) {
  GmshResult r = run_gmsh_once(g, k, algorithm, label, gmsh_factor(g, algorithm));
  r.row.rss_mb = r.raw_mb;
  r.row.whole_s = r.row.seconds;
  if (r.mesh2d) r.row.seconds = *r.mesh2d;
  char note[256];
  std::snprintf(note, sizeof note, "%s: refine = Gmsh's own 2D meshing wall, whole = the gmsh process (start-up %.1f MiB, "
                "includes .msh write)", label, baseline_mb);
  r.row.note = note;
  return r.row;
}

// The real command line on the square, no output files: whole-process wall clock and ru_maxrss of
// the fdrmesh child; refine seconds, counts and min angle from its JSON report.
Row run_fdr_cli(double k, const std::string& binary) {
  char dir_tmpl[] = "/tmp/bench_fdr_cli.XXXXXX";
  if (!mkdtemp(dir_tmpl)) throw fdr::Error(fdr::ExitCode::kOutputError, "bench_fdr: mkdtemp in /tmp failed");
  const std::string dir = dir_tmpl, json = dir + "/report.json", log = dir + "/log.txt";
  char spacing[64];
  const auto end = std::to_chars(spacing, spacing + 40, k).ptr;  // shortest text that reads back as k
  std::snprintf(end, 24, "*paper-f1");
  const ChildRun c = spawn_and_wait({binary, "mesh", std::string(FDR_TESTDATA_DIR) + "/poly/square10.poly", "--spacing",
                                     spacing, "-q", "--report", json}, log);
  if (!WIFEXITED(c.status) || WEXITSTATUS(c.status) != 0)
    throw fdr::Error(fdr::ExitCode::kInternal, "bench_fdr: " + binary + " failed (status " + std::to_string(c.status) +
                                                   "), see " + log);
  std::ifstream in(json);
  const auto j = nlohmann::json::parse(in);
  Row r{"fdrmesh-cli", k, j["timings_s"]["refine"].get<double>(), j["triangles"].get<std::size_t>(),
        j["vertices"].get<std::size_t>(), c.maxrss_mb, j["min_angle_deg"].get<double>(), {}};
  r.whole_s = c.wall;
  char note[200];
  std::snprintf(note, sizeof note, "fdrmesh mesh square10.poly --spacing %s -q (read, CDT, refine, report; no output); "
                "cdt %.3f s", spacing, j["timings_s"]["cdt"].get<double>());
  r.note = note;
  std::remove(json.c_str()); std::remove(log.c_str()); rmdir(dir.c_str());
  return r;
}

// Runs `fn` in a child process so each measurement has its own peak RSS. Errors in the child are printed there;
// returns the child's exit code (0 on success) so one failing peer does not hide the others' rows.
template <class Fn>
int isolated(Fn fn) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    g_child_start = Clock::now();
    int code = 0;
    try {
      Row r = fn();
      if (r.whole_s == 0) r.whole_s = secs(g_child_start, Clock::now());
      print(r);
    } catch (const fdr::Error& e) {
      std::fprintf(stderr, "%s\n", e.what());
      code = e.exit_code();
    }
    std::fflush(stdout);
    std::fflush(stderr);
    _exit(code);
  }
  int st = 0;
  waitpid(pid, &st, 0);
  return WIFEXITED(st) ? WEXITSTATUS(st) : static_cast<int>(fdr::ExitCode::kInternal);
}

constexpr const char* kUsage =
    "usage: bench_fdr [k ...] [--no-cgal] [--no-gmsh] [--only fdr|cgal|gmsh] [--gmsh-min-k K] [--gmsh-factor F]\n"
    "                 [--gmsh-bin PATH] [--fdrmesh-bin PATH] [--no-cli]\n"
    "  k             size scale, f = k * f1 (default 0.08 0.025 0.0125)\n"
    "  --no-cgal     skip CGAL's Delaunay_mesher_2\n"
    "  --no-gmsh     skip Gmsh (Algorithm 5 'gmsh-del' and 6 'gmsh-front')\n"
    "  --only T      run only fdrmesh, CGAL or Gmsh\n"
    "  --gmsh-min-k  run Gmsh only for k >= K (default 0.025; Gmsh needs ~40 s per million triangles)\n"
    "  --gmsh-factor Gmsh edge length h = F * B * f for both algorithms (default 1.36 Delaunay, 1.29 Frontal,\n"
    "                calibrated so Gmsh makes as many triangles as fdrmesh)\n"
    "  --gmsh-bin    Gmsh executable (default gmsh from PATH)\n"
    "  --fdrmesh-bin fdrmesh executable for the fdrmesh-cli row (default: the one built with this bench)\n"
    "  --no-cli      skip the fdrmesh-cli row (whole command-line process)\n"
    "  --chains N    instead: the chain benchmark (chains.hpp) with about N vertices per case (fdrmesh's CDT,\n"
    "                CGAL's CDT unless --no-cgal, the command line unless --no-cli)\n";

double parse_number(const char* opt, const char* text) {
  char* e;
  const double v = std::strtod(text, &e);
  if (e == text || *e != '\0' || !std::isfinite(v) || v <= 0)
    throw fdr::Error(fdr::ExitCode::kUsage, std::string("bench_fdr: ") + opt + " needs a positive number, got '" +
                                                text + "'\n" + kUsage);
  return v;
}

int run(int argc, char** argv) {
  std::vector<double> ks;
  std::size_t chains = 0;
  bool fdr_on = true, cgal = true, gmsh = true;
  std::string fdr_binary = FDR_BINARY;
  GmshOptions g;
  auto value = [&](int& i) -> const char* {
    if (i + 1 >= argc)
      throw fdr::Error(fdr::ExitCode::kUsage, std::string("bench_fdr: ") + argv[i] + " needs a value\n" + kUsage);
    return argv[++i];
  };
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--no-cgal") cgal = false;
    else if (a == "--no-gmsh") gmsh = false;
    else if (a == "--only") {
      const std::string t = value(i);
      if (t != "fdr" && t != "cgal" && t != "gmsh")
        throw fdr::Error(fdr::ExitCode::kUsage, "bench_fdr: --only takes fdr, cgal or gmsh, got '" + t + "'\n" + kUsage);
      fdr_on = t == "fdr"; cgal = t == "cgal"; gmsh = t == "gmsh";
    } else if (a == "--gmsh-min-k") g.min_k = parse_number("--gmsh-min-k", value(i));
    else if (a == "--gmsh-factor") g.factor = parse_number("--gmsh-factor", value(i));
    else if (a == "--gmsh-bin") g.binary = value(i);
    else if (a == "--fdrmesh-bin") fdr_binary = value(i);
    else if (a == "--no-cli") fdr_binary.clear();
    else if (a == "--chains") chains = static_cast<std::size_t>(parse_number("--chains", value(i)));
    else if (a == "-h" || a == "--help") { std::printf("%s", kUsage); return 0; }
    else if (!a.empty() && a[0] == '-' && !(a.size() > 1 && (std::isdigit(static_cast<unsigned char>(a[1])) || a[1] == '.')))
      throw fdr::Error(fdr::ExitCode::kUsage, "bench_fdr: unknown option " + a + "\n" + kUsage);
    else ks.push_back(parse_number("k", argv[i]));
  }
  if (chains > 0) return run_chains(chains, fdr_binary, cgal);
  if (ks.empty()) ks = {0.08, 0.025, 0.0125};
  std::printf("FDR benchmark: f = k * paper-f1 on [0,10]^2, B = 1; refine = meshing time, whole = the measured process\n"
              "  from start to exit, peak = its VmHWM (ru_maxrss), tri/int(1/f^2) = triangles per unit of int 1/f^2 dA\n");
  double gmsh_base = 0;
  if (gmsh && std::any_of(ks.begin(), ks.end(), [&](double k) { return k >= g.min_k; })) {
    gmsh_base = gmsh_baseline_mb(g);
    std::printf("  note: Gmsh (%s -2 -nt 1), edge length h = factor*B*f with factor %.3g (gmsh-del, Algorithm 5) and %.3g "
                "(gmsh-front, Algorithm 6)%s; start-up peak %.1f MB; refine s = wall clock of the gmsh child\n",
                g.binary.c_str(), gmsh_factor(g, 5), gmsh_factor(g, 6),
                g.factor > 0 ? " from --gmsh-factor" : ", calibrated to fdrmesh's triangle count", gmsh_base);
  }
  int code = 0;
  auto keep_first = [&code](int c) { if (code == 0) code = c; };
  for (double k : ks) {
    if (fdr_on) keep_first(isolated([k] { return run_fdr(k); }));
    if (fdr_on && !fdr_binary.empty()) keep_first(isolated([k, &fdr_binary] { return run_fdr_cli(k, fdr_binary); }));
    if (cgal) keep_first(isolated([k] { return run_cgal(k); }));
    if (gmsh && k < g.min_k) {
      std::printf("  note: gmsh skipped at k=%g (< --gmsh-min-k %g: Gmsh needs ~40 s per million triangles)\n", k, g.min_k);
    } else if (gmsh) {
      keep_first(isolated([&g, k, gmsh_base] { return run_gmsh(g, k, 5, "gmsh-del", gmsh_base); }));
      keep_first(isolated([&g, k, gmsh_base] { return run_gmsh(g, k, 6, "gmsh-front", gmsh_base); }));
    }
  }
  return code;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const fdr::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return e.exit_code();
  }
}
