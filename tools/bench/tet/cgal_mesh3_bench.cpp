// CGAL Mesh_3 on a closed polyhedral surface (.off) with a constant size H, for the 3D benchmark:
// cell_radius_edge_ratio = 2 and cell_size = H (B * f with B = 1, f = H), sharp edges protected.
// Prints "tetrahedra N" and the dihedral angles ("dihedral min D under5 N under10 N under15 N":
// the smallest angle and the cells whose smallest angle is under 5, 10, 15 degrees) for the
// drivers; the driver measures the whole process.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polyhedron = CGAL::Mesh_polyhedron_3<K>::type;
using Domain = CGAL::Polyhedral_mesh_domain_with_features_3<K>;
using Tr = CGAL::Mesh_triangulation_3<Domain, CGAL::Default, CGAL::Sequential_tag>::type;
using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr, Domain::Corner_index, Domain::Curve_index>;
using Criteria = CGAL::Mesh_criteria_3<Tr>;

// The smallest of a tetrahedron's six dihedral angles in degrees: pi minus the largest angle
// between two outward face normals.
double min_dihedral_deg(const K::Point_3* p) {
  K::Vector_3 n[4];
  for (int i = 0; i < 4; ++i) {
    const K::Point_3 &a = p[(i + 1) % 4], &b = p[(i + 2) % 4], &c = p[(i + 3) % 4];
    K::Vector_3 v = CGAL::cross_product(b - a, c - a);
    if (v * (p[i] - a) > 0) v = -v;
    n[i] = v / std::sqrt(v.squared_length());
  }
  double worst = -1;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) worst = std::max(worst, -(n[i] * n[j]));
  return std::acos(std::clamp(worst, -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
}

int usage() {
  std::cerr << "usage: cgal_mesh3_bench SURFACE.off H [plain|optimise]\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) return usage();
  const std::string path = argv[1];
  const double h = std::strtod(argv[2], nullptr);
  const std::string mode = argc > 3 ? argv[3] : "plain";
  if (!(h > 0) || (mode != "plain" && mode != "optimise")) return usage();
  // Facets of a PLC carry no consistent orientation, so the soup is oriented before it becomes a surface.
  namespace pmp = CGAL::Polygon_mesh_processing;
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(path, points, polygons) || polygons.empty()) {
    std::cerr << "cgal_mesh3_bench: " << path << ": not a readable .off surface\n";
    return 3;
  }
  pmp::orient_polygon_soup(points, polygons);
  Polyhedron poly;
  pmp::polygon_soup_to_polygon_mesh(points, polygons, poly);
  if (!CGAL::is_closed(poly)) {
    std::cerr << "cgal_mesh3_bench: " << path << ": the surface is not closed\n";
    return 3;
  }
  pmp::orient_to_bound_a_volume(poly);
  Domain domain(poly);
  domain.detect_features();
  namespace p = CGAL::parameters;
  // Flat facets make facet_distance moot; a quarter of H keeps it from ever being the binding bound.
  const Criteria criteria(p::edge_size = h, p::facet_angle = 25, p::facet_size = h, p::facet_distance = h / 4,
                          p::cell_radius_edge_ratio = 2, p::cell_size = h);
  C3t3 c3t3;
  if (mode == "plain")
    c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, p::no_perturb(), p::no_exude());
  else
    c3t3 = CGAL::make_mesh_3<C3t3>(domain, criteria, p::perturb(), p::exude());
  std::cout << "tetrahedra " << c3t3.number_of_cells_in_complex() << "\n";
  double lo = 180;
  std::size_t under[3] = {0, 0, 0};
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    K::Point_3 p[4];
    for (int i = 0; i < 4; ++i) p[i] = c3t3.triangulation().point(c, i).point();
    const double d = min_dihedral_deg(p);
    lo = std::min(lo, d);
    for (int k = 0; k < 3; ++k) under[k] += d < 5.0 * (k + 1);
  }
  std::cout << "dihedral min " << lo << " under5 " << under[0] << " under10 " << under[1] << " under15 " << under[2] << "\n";
  return 0;
}
