// The 3D binding: numpy arrays and lists -> plc::Plc -> fdr::tetrahedralize -> numpy arrays.
#include "python/tet_binding.hpp"
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <cstdint>
#include <string>
#include <vector>
#include "api/tetrahedralize.hpp"
#include "base/error.hpp"
#include "cli/cli.hpp"
#include "pipeline/run3d.hpp"
#include "pipeline/terrain_run.hpp"

namespace py = pybind11;

namespace fdr::python {
namespace {

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<Point3> points3(const Doubles& a, const char* what) {
  if (a.ndim() != 2 || a.shape(1) != 3)
    throw Error(ExitCode::kUsage, std::string(what) + " must be an (n, 3) array");
  std::vector<Point3> p(static_cast<std::size_t>(a.shape(0)));
  auto r = a.unchecked<2>();
  for (py::ssize_t i = 0; i < a.shape(0); ++i) p[static_cast<std::size_t>(i)] = {r(i, 0), r(i, 1), r(i, 2)};
  return p;
}

// A facet is a sequence of vertex ids (one polygon) or a sequence of such sequences (polygons).
plc::Facet facet_of(py::handle h, std::size_t n_points, std::size_t index) {
  plc::Facet f;
  const auto seq = py::reinterpret_borrow<py::sequence>(h);
  const bool nested = py::len(seq) > 0 && py::isinstance<py::sequence>(seq[0]) && !py::isinstance<py::str>(seq[0]);
  auto polygon = [&](py::handle ph) {
    std::vector<VertexId> poly;
    for (py::handle v : py::reinterpret_borrow<py::sequence>(ph)) {
      const long long id = v.cast<long long>();
      if (id < 0 || static_cast<std::size_t>(id) >= n_points)
        throw Error(ExitCode::kInputMalformed, "facet " + std::to_string(index) + ": vertex id " + std::to_string(id) +
                                                   " out of range (0.." + std::to_string(n_points - 1) + ")");
      poly.push_back(static_cast<VertexId>(id));
    }
    f.polygons.push_back(std::move(poly));
  };
  if (nested)
    for (py::handle ph : seq) polygon(ph);
  else
    polygon(seq);
  return f;
}

template <class T>
py::array_t<T> array_of(const T* data, std::vector<py::ssize_t> shape) {
  py::array_t<T> a(shape);
  std::copy(data, data + a.size(), a.mutable_data());
  return a;
}

// The tetrahedra, their materials and the faces and edges that tile the input, as numpy arrays.
py::dict tet_arrays(const TetMesh& m) {
  const auto n = static_cast<py::ssize_t>(m.points.size()), nt = static_cast<py::ssize_t>(m.tets.size());
  const auto nf = static_cast<py::ssize_t>(m.faces.size()), ne = static_cast<py::ssize_t>(m.edges.size());
  py::dict d;
  d["points"] = array_of<double>(n ? &m.points[0].x : nullptr, {n, 3});
  d["tets"] = array_of<VertexId>(nt ? m.tets[0].data() : nullptr, {nt, 4});
  d["materials"] = array_of<std::int32_t>(m.tet_material.data(), {static_cast<py::ssize_t>(m.tet_material.size())});
  d["faces"] = array_of<VertexId>(nf ? m.faces[0].data() : nullptr, {nf, 3});
  d["face_markers"] = array_of<std::int32_t>(m.face_marker.data(), {static_cast<py::ssize_t>(m.face_marker.size())});
  d["edges"] = array_of<VertexId>(ne ? m.edges[0].data() : nullptr, {ne, 2});
  d["edge_markers"] = array_of<std::int32_t>(m.edge_marker.data(), {static_cast<py::ssize_t>(m.edge_marker.size())});
  return d;
}

// _tetrahedralize(vertices, facets, facet_markers, holes, regions, spacing_spec, grid, bound, max_vertices)
// grid = None or (nx, ny, nz, x0, y0, z0, d, values, label): a callable sampled by the Python side.
py::dict tetrahedralize(Doubles v, py::sequence facets, std::optional<std::vector<int>> markers,
                        std::optional<Doubles> holes, std::optional<Doubles> regions, const std::string& spec,
                        py::object grid, double bound, std::size_t max_vertices) {
  plc::Plc plc;
  plc.source = "vertices";
  plc.points = points3(v, "vertices");
  std::size_t k = 0;
  for (py::handle h : facets) plc.facets.push_back(facet_of(h, plc.points.size(), k++));
  if (markers) {
    if (markers->size() != plc.facets.size())
      throw Error(ExitCode::kUsage, "facet_markers has " + std::to_string(markers->size()) + " entries for " +
                                        std::to_string(plc.facets.size()) + " facets");
    for (std::size_t i = 0; i < markers->size(); ++i) plc.facets[i].marker = (*markers)[i];
  }
  if (holes) plc.holes = points3(*holes, "holes");
  if (regions) {
    if (regions->ndim() != 2 || (regions->shape(1) != 4 && regions->shape(1) != 5))
      throw Error(ExitCode::kUsage, "regions must be an (n, 4) array (x, y, z, attribute) or (n, 5) with a volume bound");
    auto r = regions->unchecked<2>();
    for (py::ssize_t i = 0; i < regions->shape(0); ++i)
      plc.regions.push_back({{r(i, 0), r(i, 1), r(i, 2)}, r(i, 3), regions->shape(1) == 5 ? r(i, 4) : -1.0});
  }
  sizing::SizingPtr3 f;
  if (!grid.is_none()) {
    auto t = grid.cast<py::tuple>();
    sizing::Grid3 g;
    g.nx = t[0].cast<std::size_t>();
    g.ny = t[1].cast<std::size_t>();
    g.nz = t[2].cast<std::size_t>();
    g.x0 = t[3].cast<double>();
    g.y0 = t[4].cast<double>();
    g.z0 = t[5].cast<double>();
    g.dx = g.dy = g.dz = t[6].cast<double>();
    auto vals = t[7].cast<Doubles>();
    g.v.assign(vals.data(), vals.data() + vals.size());
    if (g.v.size() != g.nx * g.ny * g.nz)
      throw Error(ExitCode::kInvalidSpacing, "the spacing callable returned " + std::to_string(g.v.size()) +
                                                 " values for a grid of " + std::to_string(g.nx * g.ny * g.nz));
    f = grid_spacing3(std::move(g), t[8].cast<std::string>());
  }
  TetOptions o;
  o.bound = bound;
  o.max_vertices = max_vertices;
  TetResult r;
  {
    py::gil_scoped_release nogil;
    if (f) r = fdr::tetrahedralize(plc, *f, o);
    else r = fdr::tetrahedralize(plc, spec.empty() ? default_spacing3(plc) : spec, o);
  }
  py::dict d = tet_arrays(r.mesh);
  const TetStats& s = r.stats;
  py::dict st;
  st["bound"] = s.bound;
  st["input_vertices"] = s.input_vertices;
  st["segment_splits"] = s.segment_splits;
  st["facet_splits"] = s.facet_splits;
  st["tet_splits"] = s.tet_splits;
  st["rejected"] = s.rejected;
  st["capped"] = s.capped;
  st["sliver_angle_deg"] = s.sliver_angle_deg;
  st["sliver_splits"] = s.sliver_splits;
  st["slivers_before"] = s.slivers_before;
  st["slivers_left"] = s.slivers_left;
  py::list sf;
  for (const auto& x : s.shortfalls) sf.append(py::make_tuple(py::make_tuple(x.where.x, x.where.y, x.where.z), x.what));
  st["shortfalls"] = sf;
  d["stats"] = st;
  return d;
}

// _mesh3(args): a 3D run of `fdrmesh mesh` (a terrain volume with --dem, or a 3D PLC file) with the
// command line's arguments: the tetrahedra as numpy arrays, the names of the markers and
// materials, the per-tetrahedron quality values, the report (JSON text with the layers), the files
// written and the log.
py::dict mesh3(const std::vector<std::string>& args) {
  const pipeline::Options o = cli::parse_mesh_args(args);
  std::vector<std::pair<int, std::string>> log;
  const LogFn collect = [&log](LogLevel lvl, std::string_view s) { log.push_back({static_cast<int>(lvl), std::string(s)}); };
  pipeline::Result3 r;
  {
    py::gil_scoped_release nogil;
    r = pipeline::run3d(o, {}, collect);
  }
  py::dict d = tet_arrays(r.mesh);
  d["material_names"] = r.mesh.material_names;
  d["marker_names"] = r.mesh.marker_names;
  py::dict fields;
  for (const auto& [name, v] : r.mesh.cell_fields)
    fields[py::str(name)] = array_of<double>(v.data(), {static_cast<py::ssize_t>(v.size())});
  d["cell_fields"] = fields;
  d["report_json"] = pipeline::report_json3(r);
  d["written"] = r.written;
  d["log"] = log;
  return d;
}

}  // namespace

void bind_tetrahedralize(py::module_& mod) {
  mod.def("_tetrahedralize", &tetrahedralize);
  mod.def("_mesh3", &mesh3);
  mod.def("default_spacing3", [](Doubles v) {
    plc::Plc p;
    p.points = points3(v, "vertices");
    return default_spacing3(p);
  });
}

}  // namespace fdr::python
