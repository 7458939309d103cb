// Small PLCs for the plc tests: boxes, stacked layers, internal facets, tilted facets.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>
#include "plc/plc.hpp"

namespace fdr::plc::samples {

inline VertexId add_point(Plc& p, Point3 q) {
  p.points.push_back(q);
  return static_cast<VertexId>(p.points.size() - 1);
}

inline void add_facet(Plc& p, std::vector<std::vector<VertexId>> polygons, std::int32_t marker = 0,
                      std::vector<Point3> holes = {}) {
  p.facets.push_back({std::move(polygons), std::move(holes), marker});
}

// The eight corners of [x0, x1] x [y0, y1] x [z0, z1] (index bit 0: x, bit 1: y, bit 2: z).
inline std::vector<VertexId> add_box_corners(Plc& p, Point3 lo, Point3 hi) {
  std::vector<VertexId> c;
  for (int k = 0; k < 8; ++k)
    c.push_back(add_point(p, {k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z}));
  return c;
}

// The six faces of a box given its corners; `skip` leaves one face out (-1: none).
inline void add_box_faces(Plc& p, const std::vector<VertexId>& c, std::int32_t marker = 0, int skip = -1) {
  const int faces[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (int f = 0; f < 6; ++f)
    if (f != skip) add_facet(p, {{c[faces[f][0]], c[faces[f][1]], c[faces[f][2]], c[faces[f][3]]}}, marker + f);
}

// The parallelepiped o + s e1 + t e2 + u e3, s, t, u in [0, 1]: six tilted facets (dyadic edge
// vectors, so every facet is exactly planar).
inline Plc parallelepiped(Point3 o, Point3 e1, Point3 e2, Point3 e3) {
  Plc p;
  p.source = "tilted.poly";
  std::vector<VertexId> c;
  for (int k = 0; k < 8; ++k) c.push_back(add_point(p, o + (k & 1 ? 1.0 : 0.0) * e1 + (k & 2 ? 1.0 : 0.0) * e2 +
                                                          (k & 4 ? 1.0 : 0.0) * e3));
  add_box_faces(p, c);
  return p;
}

// A prism over the triangle (0,0), (1,0), (cos a, sin a) in z in [0, 1]: two side facets meet
// at the dihedral angle a along the z axis.
inline Plc wedge_prism(double angle_deg) {
  Plc p;
  p.source = "wedge.poly";
  const double a = angle_deg * 3.14159265358979323846 / 180;
  std::vector<VertexId> lo, hi;
  for (Point3 q : {Point3{0, 0, 0}, Point3{1, 0, 0}, Point3{std::cos(a), std::sin(a), 0}}) {
    lo.push_back(add_point(p, q));
    hi.push_back(add_point(p, {q.x, q.y, 1}));
  }
  add_facet(p, {lo}, 1);
  add_facet(p, {hi}, 2);
  for (std::size_t i = 0; i < 3; ++i) add_facet(p, {{lo[i], lo[(i + 1) % 3], hi[(i + 1) % 3], hi[i]}}, 3);
  return p;
}

inline Plc unit_cube() {
  Plc p;
  p.source = "cube.poly";
  add_box_faces(p, add_box_corners(p, {0, 0, 0}, {1, 1, 1}));
  return p;
}

// `layers` boxes [0,2] x [0,1] x [k, k+1] stacked in z, each sharing its top facet with the next;
// region point k in the middle of layer k.
inline Plc stacked_layers(int layers) {
  Plc p;
  p.source = "layers.poly";
  std::vector<std::vector<VertexId>> ring(static_cast<std::size_t>(layers) + 1);
  for (int k = 0; k <= layers; ++k)
    for (Point3 q : {Point3{0, 0, 0}, Point3{2, 0, 0}, Point3{2, 1, 0}, Point3{0, 1, 0}})
      ring[static_cast<std::size_t>(k)].push_back(add_point(p, {q.x, q.y, static_cast<double>(k)}));
  for (int k = 0; k <= layers; ++k)
    add_facet(p, {ring[static_cast<std::size_t>(k)]}, k == 0 ? 1 : k == layers ? 2 : 10 + k);
  for (int k = 0; k < layers; ++k) {
    const auto& a = ring[static_cast<std::size_t>(k)];
    const auto& b = ring[static_cast<std::size_t>(k) + 1];
    for (std::size_t i = 0; i < 4; ++i) add_facet(p, {{a[i], a[(i + 1) % 4], b[(i + 1) % 4], b[i]}}, 3);
    p.regions.push_back({{1.0, 0.5, k + 0.5}, static_cast<double>(k + 1), -1});
  }
  return p;
}

// The box [0,4] x [0,4] x [0,4] with a floating internal square at z = 2 ([1,3]^2) and a wall
// x = 2, y in [0.5, 3.5], z in [0, 1] standing on the bottom facet (its foot is a segment of
// the bottom facet).
inline Plc box_with_internal_facets() {
  Plc p;
  p.source = "internal.poly";
  const auto c = add_box_corners(p, {0, 0, 0}, {4, 4, 4});
  const VertexId f0 = add_point(p, {2, 0.5, 0}), f1 = add_point(p, {2, 3.5, 0});
  const VertexId w0 = add_point(p, {2, 0.5, 1}), w1 = add_point(p, {2, 3.5, 1});
  const VertexId s0 = add_point(p, {1, 1, 2}), s1 = add_point(p, {3, 1, 2}), s2 = add_point(p, {3, 3, 2}),
                 s3 = add_point(p, {1, 3, 2});
  add_facet(p, {{c[0], c[2], c[3], c[1]}, {f0, f1}}, 1);  // bottom with the wall's foot
  add_facet(p, {{c[4], c[5], c[7], c[6]}}, 2);
  add_facet(p, {{c[0], c[1], c[5], c[4]}}, 3);
  add_facet(p, {{c[2], c[6], c[7], c[3]}}, 3);
  add_facet(p, {{c[0], c[4], c[6], c[2]}}, 3);
  add_facet(p, {{c[1], c[3], c[7], c[5]}}, 3);
  add_facet(p, {{s0, s1, s2, s3}}, 7);
  add_facet(p, {{f0, f1, w1, w0}}, 8);
  p.regions.push_back({{0.5, 0.5, 0.5}, 1, -1});
  return p;
}

// The box [0,4]^3 with a square tunnel [1,3]^2 through it along z: top and bottom facets with a
// hole, four walls inside (a surface of genus one).
inline Plc box_with_tunnel() {
  Plc p;
  p.source = "tunnel.poly";
  const auto o = add_box_corners(p, {0, 0, 0}, {4, 4, 4});
  const auto t = add_box_corners(p, {1, 1, 0}, {3, 3, 4});
  add_facet(p, {{o[0], o[1], o[3], o[2]}, {t[0], t[1], t[3], t[2]}}, 1, {{2, 2, 0}});
  add_facet(p, {{o[4], o[5], o[7], o[6]}, {t[4], t[5], t[7], t[6]}}, 2, {{2, 2, 4}});
  const int sides[4][4] = {{0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : sides) add_facet(p, {{o[q[0]], o[q[1]], o[q[2]], o[q[3]]}}, 3);
  for (const auto& q : sides) add_facet(p, {{t[q[0]], t[q[1]], t[q[2]], t[q[3]]}}, 4);
  return p;
}

}  // namespace fdr::plc::samples
