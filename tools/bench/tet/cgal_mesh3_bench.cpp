// CGAL Mesh_3 on a closed polyhedral surface (.off) with a constant size H, for the 3D benchmark:
// cell_radius_edge_ratio = 2 and cell_size = H (B * f with B = 1, f = H), sharp edges protected.
// Prints "tetrahedra N" for the driver; the driver measures the whole process.
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
  return 0;
}
