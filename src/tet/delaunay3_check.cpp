// Delaunay3: the exact checks of the structure and of the Delaunay property, and the output mesh.
#include <algorithm>
#include <sstream>
#include "predicates/predicates3d.hpp"
#include "tet/delaunay3.hpp"

namespace fdr::tet {
namespace {
bool fail(std::string* why, const std::string& msg) {
  if (why) *why = msg;
  return false;
}
std::string tet_name(TetId t, const std::array<VertexId, 4>& v) {
  std::ostringstream os;
  os << "tetrahedron " << t << " (" << v[0] << ", " << v[1] << ", " << v[2] << ", ";
  if (v[3] == kInfinite) os << "infinite)";
  else os << v[3] << ")";
  return os.str();
}
std::array<VertexId, 3> sorted_face(const std::array<VertexId, 4>& v, int i) {
  std::array<VertexId, 3> f{};
  for (int m = 0, k = 0; m < 4; ++m)
    if (m != i) f[k++] = v[m];
  std::sort(f.begin(), f.end());
  return f;
}
}  // namespace

bool Delaunay3::is_delaunay(std::string* why) const {
  for (TetId t = 0; t < cells_.size(); ++t) {
    if (!alive(t)) continue;
    for (int i = 0; i < 4; ++i) {
      const TetId n = neighbour(t, i);
      const VertexId q = cells_[n].v[mirror_index(t, i)];
      // The infinite vertex across a hull face: nothing to compare (its ghost checks the face).
      if (q == kInfinite) continue;
      if (conflict(t, pts_[q])) {
        std::ostringstream os;
        os << "vertex " << q << " (" << pts_[q].x << ", " << pts_[q].y << ", " << pts_[q].z << ") lies inside the "
           << (is_ghost(t) ? "hull side of " : "circumsphere of ") << tet_name(t, cells_[t].v);
        return fail(why, os.str());
      }
    }
  }
  return true;
}

bool Delaunay3::check_valid(std::string* why) const {
  if (dim_ < 3) {
    if (!cells_.empty() || finite_ != 0) return fail(why, "tetrahedra exist below dimension 3");
    return true;
  }
  std::size_t finite = 0;
  for (TetId t = 0; t < cells_.size(); ++t) {
    if (!alive(t)) continue;
    const auto& v = cells_[t].v;
    for (int m = 0; m < 4; ++m) {
      if (v[m] == kInfinite ? m != 3 : v[m] >= pts_.size())
        return fail(why, tet_name(t, v) + ": bad vertex at position " + std::to_string(m));
      for (int k = 0; k < m; ++k)
        if (v[k] == v[m]) return fail(why, tet_name(t, v) + ": repeated vertex");
    }
    if (!is_ghost(t)) {
      ++finite;
      if (predicates::orient3d(pts_[v[0]], pts_[v[1]], pts_[v[2]], pts_[v[3]]) <= 0)
        return fail(why, tet_name(t, v) + " is not positively oriented");
    } else {
      // The finite neighbour's fourth vertex lies strictly inside the hull face's plane.
      const auto& f = cells_[neighbour(t, 3)].v;
      if (cells_[neighbour(t, 3)].v[3] == kInfinite)
        return fail(why, tet_name(t, v) + ": a ghost across its hull face");
      const VertexId q = f[mirror_index(t, 3)];
      if (predicates::orient3d(pts_[v[0]], pts_[v[1]], pts_[v[2]], pts_[q]) >= 0)
        return fail(why, tet_name(t, v) + ": hull face turned inward");
    }
    for (int i = 0; i < 4; ++i) {
      const TetId n = neighbour(t, i);
      const int j = mirror_index(t, i);
      if (n >= cells_.size() || !alive(n)) return fail(why, tet_name(t, v) + ": dead neighbour");
      if (neighbour(n, j) != t || mirror_index(n, j) != i)
        return fail(why, tet_name(t, v) + ": neighbour " + std::to_string(i) + " does not point back");
      if (sorted_face(v, i) != sorted_face(cells_[n].v, j))
        return fail(why, tet_name(t, v) + ": face " + std::to_string(i) + " differs from its neighbour's");
    }
  }
  if (finite != finite_) return fail(why, "finite tetrahedron count is off");
  for (VertexId u = 0; u < pts_.size(); ++u) {
    const TetId t = vtet_[u];
    if (t >= cells_.size() || !alive(t) || std::find(cells_[t].v.begin(), cells_[t].v.end(), u) == cells_[t].v.end())
      return fail(why, "vertex " + std::to_string(u) + " has no tetrahedron holding it");
  }
  return true;
}

TetMesh Delaunay3::to_mesh() const {
  TetMesh m;
  m.points.assign(pts_.begin(), pts_.end());
  m.tets.reserve(finite_);
  for_each_finite_tet([&](TetId t) { m.tets.push_back(cells_[t].v); });
  m.tet_material.assign(m.tets.size(), 0);
  return m;
}

std::size_t Delaunay3::bytes() const {
  return pts_.capacity() * sizeof(Point3) + (vtet_.capacity() + vlocal_.capacity()) * sizeof(Index) +
         cells_.capacity() * sizeof(Cell) + edge_dense_.capacity() * sizeof(DenseSlot) +
         in_cavity_.capacity() + free_.capacity() * sizeof(TetId) + cavity_.capacity() * sizeof(TetId) +
         ball_.capacity() * sizeof(NewCell) + ball_ids_.capacity() * sizeof(TetId) +
         edge_table_.capacity() * sizeof(EdgeSlot) + edge_used_.capacity() * sizeof(std::size_t);
}

}  // namespace fdr::tet
