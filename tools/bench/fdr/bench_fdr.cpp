// FDR benchmark: f = k * paper-f1 on [0,10]^2, B = 1; fdrmesh's refiner side by side with CGAL's
// Delaunay_mesher_2 driven by the same R/f(c) criterion. Prints refine seconds, triangles/s,
// peak RSS, bytes/triangle, min angle and vertex count. Usage: bench_fdr [k ...] [--no-cgal]
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include "cdt/cdt.hpp"
#include "refine/refine.hpp"
#include "sizing/fields.hpp"

namespace {
using Clock = std::chrono::steady_clock;
double secs(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); }

long vm_hwm_kb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atol(line + 6);
  std::fclose(f);
  return kb;
}
long vm_rss_kb() {
  FILE* f = std::fopen("/proc/self/status", "r");
  if (!f) return 0;
  char line[256];
  long kb = 0;
  while (std::fgets(line, sizeof line, f))
    if (std::strncmp(line, "VmRSS:", 6) == 0) kb = std::atol(line + 6);
  std::fclose(f);
  return kb;
}

double min_angle_of(double ax, double ay, double bx, double by, double cx, double cy) {
  auto ang = [](double px, double py, double qx, double qy, double rx, double ry) {
    double ux = qx - px, uy = qy - py, vx = rx - px, vy = ry - py;
    return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * 180.0 / M_PI;
  };
  return std::min({ang(ax, ay, bx, by, cx, cy), ang(bx, by, cx, cy, ax, ay), ang(cx, cy, ax, ay, bx, by)});
}

struct Row { std::string tool; double k; double seconds; std::size_t tris, verts; double rss_mb, min_angle; };

void print(const Row& r) {
  std::printf("%-10s k=%-8g refine %8.3f s  %12zu tri  %10.0f tri/s  peak %8.1f MB  %6.1f B/tri  min angle %5.2f  %10zu vertices\n",
              r.tool.c_str(), r.k, r.seconds, r.tris, r.tris / r.seconds, r.rss_mb, r.rss_mb * 1048576.0 / r.tris,
              r.min_angle, r.verts);
  std::fflush(stdout);
}

Row run_fdr(double k) {
  using namespace fdr;
  pslg::Pslg p;
  p.points = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
  for (Index i = 0; i < 4; ++i) p.segments.push_back({i, (i + 1) % 4, 1, 0});
  sizing::PaperF1Field f(k);
  const long base = vm_rss_kb();
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
    const auto& a = T.pts[T.tv[3 * t]]; const auto& b = T.pts[T.tv[3 * t + 1]]; const auto& c = T.pts[T.tv[3 * t + 2]];
    amin = std::min(amin, min_angle_of(a.x, a.y, b.x, b.y, c.x, c.y));
  }
  return {"fdrmesh", k, secs(t0, t1), T.num_live_triangles(), T.pts.size() - 3, (vm_hwm_kb() - base) / 1024.0, amin};
}

// CGAL's mesher with an R/f(c) criterion: a face is bad when circumradius / f(circumcenter) > B.
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
      return q > 1 ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
    CGAL::Mesh_2::Face_badness operator()(CDT::Face_handle fh, Quality& q) const {
      const auto& a = fh->vertex(0)->point(); const auto& b = fh->vertex(1)->point(); const auto& c = fh->vertex(2)->point();
      const auto cc = CGAL::circumcenter(a, b, c);
      const double r = std::sqrt(CGAL::squared_distance(cc, a));
      const double f = k * ((std::fabs(cc.x() - 5) + std::fabs(cc.y() - 5)) * 0.1 + 0.1);
      q = r / (B * f);
      return q > 1 ? CGAL::Mesh_2::BAD : CGAL::Mesh_2::NOT_BAD;
    }
  };
  Is_bad is_bad_object() const { return {k, B}; }
};

Row run_cgal(double k) {
  const long base = vm_rss_kb();
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
  return {"cgal", k, secs(t0, t1), n, cdt.number_of_vertices(), (vm_hwm_kb() - base) / 1024.0, amin};
}

// Runs `fn` in a child process so each measurement has its own peak RSS.
template <class Fn>
void isolated(Fn fn) {
  std::fflush(stdout);
  const pid_t pid = fork();
  if (pid == 0) {
    print(fn());
    std::fflush(stdout);
    _exit(0);
  }
  int st = 0;
  waitpid(pid, &st, 0);
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<double> ks;
  bool cgal = true;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--no-cgal") == 0) cgal = false;
    else ks.push_back(std::atof(argv[i]));
  }
  if (ks.empty()) ks = {0.08, 0.025, 0.0125};
  std::printf("FDR benchmark: f = k * paper-f1 on [0,10]^2, B = 1 (one core)\n");
  for (double k : ks) {
    isolated([k] { return run_fdr(k); });
    if (cgal) isolated([k] { return run_cgal(k); });
  }
  return 0;
}
