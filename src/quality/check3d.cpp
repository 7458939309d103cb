// The 3D mesh checks of --check: orientation, face sharing, closed boundary, local Delaunay
// (exact), conformity to the PLC and R/f(c) <= B.
#include "quality/check3d.hpp"
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>
#include "base/error.hpp"
#include "plc/check.hpp"
#include "predicates/predicates3d.hpp"
#include "tet/tet_geometry.hpp"

namespace fdr::quality {
namespace {

using Tri = std::array<VertexId, 3>;
using Edge = std::array<VertexId, 2>;

std::string at(Point3 p) {
  std::ostringstream s;
  s.precision(17);
  s << "(" << p.x << ", " << p.y << ", " << p.z << ")";
  return s.str();
}

Tri sorted(Tri t) {
  std::sort(t.begin(), t.end());
  return t;
}

// Every face of every tetrahedron with its tetrahedron and the local index of the opposite vertex,
// sorted by the face's vertex ids.
struct FaceUse {  // 20 bytes with 32-bit ids: four per tetrahedron
  Tri key;
  Index tet;
  std::uint8_t opposite;
  bool operator<(const FaceUse& o) const { return std::tie(key, tet) < std::tie(o.key, o.tet); }
};

std::vector<FaceUse> face_uses(const tet::TetMesh& m) {
  std::vector<FaceUse> f;
  f.reserve(m.tets.size() * 4);
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    for (int k = 0; k < 4; ++k)
      f.push_back({sorted({t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]}), static_cast<Index>(i),
                   static_cast<std::uint8_t>(k)});
  }
  std::sort(f.begin(), f.end());
  return f;
}

std::vector<Tri> boundary_faces(const std::vector<FaceUse>& uses) {
  std::vector<Tri> b;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 1) b.push_back(uses[i].key);
    i = j;
  }
  return b;
}

double tri_area(Point3 a, Point3 b, Point3 c) { return 0.5 * std::sqrt(norm2(cross(b - a, c - a))); }

double bbox_diagonal(const std::vector<Point3>& pts) {
  if (pts.empty()) return 0;
  Point3 lo = pts[0], hi = pts[0];
  for (const auto& p : pts) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  return dist(lo, hi);
}

bool less3(Point3 a, Point3 b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); }

// The plane of one facet: its first triangle (exact tests) and unit normal (distances).
struct Plane {
  Point3 p0, p1, p2, n;
  std::int32_t marker = 0;
};

// Mesh vertex ids of the input points (matched by exact coordinates), or -1 when absent.
std::vector<long long> input_ids(const tet::TetMesh& m, const plc::Plc& plc) {
  std::vector<std::pair<Point3, VertexId>> byp;
  byp.reserve(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) byp.push_back({m.points[i], static_cast<VertexId>(i)});
  std::sort(byp.begin(), byp.end(), [](const auto& a, const auto& b) { return less3(a.first, b.first); });
  std::vector<long long> ids(plc.points.size(), -1);
  for (std::size_t i = 0; i < plc.points.size(); ++i) {
    auto it = std::lower_bound(byp.begin(), byp.end(), plc.points[i],
                               [](const auto& a, Point3 p) { return less3(a.first, p); });
    if (it != byp.end() && it->first == plc.points[i]) ids[i] = it->second;
  }
  return ids;
}

bool on_plane(const Plane& pl, Point3 v, bool is_input, double tol) {
  if (is_input) return predicates::orient3d(pl.p0, pl.p1, pl.p2, v) == 0;
  return std::abs(dot(v - pl.p0, pl.n)) <= tol;
}

std::optional<std::string> check_facet_areas(const tet::TetMesh& m, const plc::Plc& plc,
                                             const plc::FacetTriangulation& ft) {
  std::map<std::int32_t, std::pair<double, double>> area;  // marker -> (input, mesh)
  for (std::size_t f = 0; f < ft.triangles.size(); ++f)
    for (const auto& t : ft.triangles[f])
      area[plc.facets[f].marker].first += tri_area(plc.points[t[0]], plc.points[t[1]], plc.points[t[2]]);
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const auto& t = m.faces[i];
    area[m.face_marker[i]].second += tri_area(m.points[t[0]], m.points[t[1]], m.points[t[2]]);
  }
  for (const auto& [marker, a] : area)
    if (std::abs(a.first - a.second) > 1e-9 * std::max(a.first, a.second)) {
      std::ostringstream s;
      s.precision(17);
      s << "facets with marker " << marker << ": input area " << a.first << " but the subfacets' area " << a.second;
      return s.str();
    }
  return std::nullopt;
}

std::optional<std::string> check_subfacet_planes(const tet::TetMesh& m, const plc::Plc& plc,
                                                 const plc::FacetTriangulation& ft, const std::vector<long long>& ids) {
  std::vector<Plane> planes;
  for (std::size_t f = 0; f < ft.triangles.size(); ++f) {
    if (ft.triangles[f].empty()) continue;
    const auto& t = ft.triangles[f][0];
    Plane p{plc.points[t[0]], plc.points[t[1]], plc.points[t[2]], {}, plc.facets[f].marker};
    const Point3 n = cross(p.p1 - p.p0, p.p2 - p.p0);
    p.n = (1.0 / std::sqrt(norm2(n))) * n;
    planes.push_back(p);
  }
  std::vector<char> is_input(m.points.size(), 0);
  for (long long id : ids)
    if (id >= 0) is_input[static_cast<std::size_t>(id)] = 1;
  const double tol = 1e-9 * bbox_diagonal(plc.points);
  // The plane that held the previous subfacet is tried first: subfacets come facet by facet, so
  // the scan over every plane is the exception.
  std::size_t last = 0;
  for (std::size_t i = 0; i < m.faces.size(); ++i) {
    const auto& t = m.faces[i];
    auto holds = [&](const Plane& pl) {
      if (pl.marker != m.face_marker[i]) return false;
      for (VertexId v : t)
        if (!on_plane(pl, m.points[v], is_input[v], tol)) return false;
      return true;
    };
    bool found = last < planes.size() && holds(planes[last]);
    for (std::size_t k = 0; !found && k < planes.size(); ++k)
      if (holds(planes[k])) {
        found = true;
        last = k;
      }
    if (!found)
      return "subfacet " + std::to_string(i) + " " + at(m.points[t[0]]) + " " + at(m.points[t[1]]) + " " +
             at(m.points[t[2]]) + " lies in no facet with marker " + std::to_string(m.face_marker[i]);
  }
  return std::nullopt;
}

std::optional<std::string> check_boundary_is_subfacets(const tet::TetMesh& m, const std::vector<FaceUse>& uses) {
  std::vector<Tri> sub;
  sub.reserve(m.faces.size());
  for (const auto& f : m.faces) sub.push_back(sorted(f));
  std::sort(sub.begin(), sub.end());
  for (const Tri& b : boundary_faces(uses))
    if (!std::binary_search(sub.begin(), sub.end(), b))
      return "boundary face " + at(m.points[b[0]]) + " " + at(m.points[b[1]]) + " " + at(m.points[b[2]]) +
             " is no subfacet of the PLC";
  return std::nullopt;
}

// Walks from a to b along mesh edges whose ends lie on the segment, each step the neighbour
// farthest along it (within the segment).
std::optional<std::string> check_segments(const tet::TetMesh& m, const plc::Plc& plc, const plc::FacetTriangulation& ft,
                                          const std::vector<long long>& ids) {
  std::vector<Edge> edges;
  static constexpr int kPairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (const auto& t : m.tets)
    for (const auto& p : kPairs) {
      edges.push_back({t[p[0]], t[p[1]]});
      edges.push_back({t[p[1]], t[p[0]]});
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const double tol = 1e-9 * bbox_diagonal(plc.points);
  for (const auto& s : ft.subsegments) {
    const Point3 pa = plc.points[s.a], pb = plc.points[s.b];
    const std::string name = "segment " + at(pa) + " - " + at(pb);
    if (ids[s.a] < 0 || ids[s.b] < 0) return name + ": an end is not a mesh vertex";
    const Point3 d = pb - pa;
    const double len2 = norm2(d);
    auto along = [&](Point3 p) { return dot(p - pa, d) / len2; };
    VertexId cur = static_cast<VertexId>(ids[s.a]);
    const VertexId end = static_cast<VertexId>(ids[s.b]);
    while (cur != end) {
      const double t0 = along(m.points[cur]);
      VertexId next = cur;
      double best = t0;
      for (auto it = std::lower_bound(edges.begin(), edges.end(), Edge{cur, 0}); it != edges.end() && (*it)[0] == cur; ++it) {
        const Point3 q = m.points[(*it)[1]];
        const double t = along(q);
        if (t <= best || t > 1) continue;
        const Point3 foot = pa + t * d;
        if ((*it)[1] != end && dist(q, foot) > tol) continue;
        best = t;
        next = (*it)[1];
      }
      if (next == cur) return name + ": no mesh edge continues it from " + at(m.points[cur]);
      cur = next;
    }
  }
  return std::nullopt;
}

std::optional<std::string> faces_closed(const tet::TetMesh& m, const std::vector<FaceUse>& uses) {
  for (std::size_t i = 0; i + 2 < uses.size(); ++i)
    if (uses[i].key == uses[i + 2].key)
      return "face " + at(m.points[uses[i].key[0]]) + " " + at(m.points[uses[i].key[1]]) + " " +
             at(m.points[uses[i].key[2]]) + " is shared by more than two tetrahedra";
  std::vector<Edge> be;
  for (const Tri& b : boundary_faces(uses))
    for (int k = 0; k < 3; ++k) be.push_back({std::min(b[k], b[(k + 1) % 3]), std::max(b[k], b[(k + 1) % 3])});
  std::sort(be.begin(), be.end());
  for (std::size_t i = 0; i < be.size();) {
    std::size_t j = i;
    while (j < be.size() && be[j] == be[i]) ++j;
    if ((j - i) % 2)
      return "the boundary is not closed at edge " + at(m.points[be[i][0]]) + " - " + at(m.points[be[i][1]]);
    i = j;
  }
  return std::nullopt;
}

std::optional<std::string> delaunay(const tet::TetMesh& m, const std::vector<FaceUse>& uses) {
  for (std::size_t i = 0; i + 1 < uses.size(); ++i) {
    if (uses[i].key != uses[i + 1].key) continue;
    const auto& t = m.tets[uses[i].tet];
    const Point3 e = m.points[m.tets[uses[i + 1].tet][uses[i + 1].opposite]];
    if (predicates::insphere(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]], e) > 0)
      return "tetrahedron " + std::to_string(uses[i].tet) + " at " + at(m.points[t[0]]) +
             " is not Delaunay: its neighbour's vertex " + at(e) + " lies inside its circumsphere";
  }
  return std::nullopt;
}

std::optional<std::string> conforming(const tet::TetMesh& m, const plc::Plc& plc, const std::vector<FaceUse>& uses) {
  if (plc.facets.empty()) return std::nullopt;
  const plc::FacetTriangulation ft = plc::check_and_triangulate(plc, {.closed = true});
  const std::vector<long long> ids = input_ids(m, plc);
  for (std::size_t i = 0; i < ids.size(); ++i)
    if (ids[i] < 0) return "input vertex " + std::to_string(i) + " " + at(plc.points[i]) + " is not a mesh vertex";
  if (auto e = check_facet_areas(m, plc, ft)) return e;
  if (auto e = check_subfacet_planes(m, plc, ft, ids)) return e;
  if (auto e = check_boundary_is_subfacets(m, uses)) return e;
  return check_segments(m, plc, ft, ids);
}

}  // namespace

std::optional<std::string> check_orientation(const tet::TetMesh& m) {
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    for (VertexId v : t)
      if (v >= m.points.size()) return "tetrahedron " + std::to_string(i) + ": vertex id " + std::to_string(v) + " out of range";
    if (predicates::orient3d(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]) <= 0)
      return "tetrahedron " + std::to_string(i) + " at " + at(m.points[t[0]]) + " has no positive volume";
  }
  return std::nullopt;
}

std::optional<std::string> check_faces_closed(const tet::TetMesh& m) { return faces_closed(m, face_uses(m)); }

std::optional<std::string> check_delaunay(const tet::TetMesh& m) { return delaunay(m, face_uses(m)); }

std::optional<std::string> check_conforming(const tet::TetMesh& m, const plc::Plc& plc) {
  return conforming(m, plc, face_uses(m));
}

std::optional<std::string> check_r_over_f(const tet::TetMesh& m, const sizing::SizingField3& f, double B) {
  for (std::size_t i = 0; i < m.tets.size(); ++i) {
    const auto& t = m.tets[i];
    const tet::Sphere s = tet::circumsphere(m.points[t[0]], m.points[t[1]], m.points[t[2]], m.points[t[3]]);
    const double rf = s.radius / f(s.centre);
    if (!(rf <= B * (1 + 1e-9))) {
      std::ostringstream o;
      o.precision(6);
      o << "tetrahedron " << i << " with circumcentre " << at(s.centre) << " has R/f(c) = " << rf << " > B = " << B;
      return o.str();
    }
  }
  return std::nullopt;
}

void check_tets(const tet::TetMesh& m, const plc::Plc& plc, const sizing::SizingField3& f, double B) {
  const std::string src = plc.source.empty() ? std::string("mesh") : plc.source;
  if (auto e = check_orientation(m)) throw Error(ExitCode::kCheckFailed, src + ": check: " + *e);
  const std::vector<FaceUse> uses = face_uses(m);  // sorted once for the three face checks
  if (auto e = faces_closed(m, uses)) throw Error(ExitCode::kCheckFailed, src + ": check: " + *e);
  if (auto e = delaunay(m, uses)) throw Error(ExitCode::kCheckFailed, src + ": check: " + *e);
  if (auto e = conforming(m, plc, uses)) throw Error(ExitCode::kCheckFailed, src + ": check: " + *e);
  if (auto e = check_r_over_f(m, f, B)) throw Error(ExitCode::kCheckFailed, src + ": check: " + *e);
}

}  // namespace fdr::quality
