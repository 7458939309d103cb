// fdrmesh._core: pybind11 bindings of the core API (fdr::triangulate) and the GIS API
// (fdr::mesh_domain, fdr::write_mesh); numpy arrays in and out. The Python-facing functions with
// their documentation are in fdrmesh/__init__.py.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <map>
#include <memory>
#include "api/triangulate.hpp"
#include "base/error.hpp"
#include "base/version.hpp"
#include "cli/cli.hpp"
#include "cli/option_table.hpp"
#include "pipeline/mesh_domain.hpp"
#include "python/tet_binding.hpp"

namespace py = pybind11;

namespace {

// Exception classes by exit code (fdrmesh.Error and its subclasses), created in PYBIND11_MODULE.
std::map<int, py::object>& error_classes() {
  static auto* m = new std::map<int, py::object>();
  return *m;
}

// The Python Mesh: owns the C++ result; numpy arrays are views into it (base = this object).
struct PyMesh {
  fdr::GisMesh m;
  bool gis = false;
  std::vector<std::pair<int, std::string>> log;  // (level, message) emitted while meshing
};

template <class T>
py::array view_array(const PyMesh& self, py::handle owner, const T* data, std::vector<py::ssize_t> shape,
                     std::vector<py::ssize_t> strides) {
  py::array a(py::dtype::of<T>(), std::move(shape), std::move(strides), data, owner);
  py::detail::array_proxy(a.ptr())->flags &= ~py::detail::npy_api::NPY_ARRAY_WRITEABLE_;
  return a;
}

fdr::LogFn collector(std::vector<std::pair<int, std::string>>* out) {
  return [out](fdr::LogLevel lvl, std::string_view s) { out->push_back({static_cast<int>(lvl), std::string(s)}); };
}

fdr::Pslg make_pslg(py::array_t<double, py::array::c_style | py::array::forcecast> v,
                    std::optional<py::array_t<long long, py::array::c_style | py::array::forcecast>> s,
                    std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> h,
                    std::optional<py::array_t<int, py::array::c_style | py::array::forcecast>> smark,
                    std::optional<py::array_t<int, py::array::c_style | py::array::forcecast>> vmark) {
  auto need2 = [](const py::array& a, const char* what) {
    if (a.ndim() != 2 || a.shape(1) != 2)
      throw fdr::Error(fdr::ExitCode::kUsage, std::string(what) + " must be an array of shape (n, 2)");
  };
  fdr::Pslg g;
  need2(v, "vertices");
  const auto n = static_cast<std::size_t>(v.shape(0));
  g.points.resize(n);
  for (std::size_t i = 0; i < n; ++i) g.points[i] = {v.at(i, 0), v.at(i, 1)};
  if (s && s->size()) {
    need2(*s, "segments");
    const auto m = static_cast<std::size_t>(s->shape(0));
    if (smark && static_cast<std::size_t>(smark->size()) != m)
      throw fdr::Error(fdr::ExitCode::kUsage, "segment_markers must have one value per segment");
    for (std::size_t i = 0; i < m; ++i) {
      const long long a = s->at(i, 0), b = s->at(i, 1);
      if (a < 0 || b < 0 || static_cast<std::size_t>(a) >= n || static_cast<std::size_t>(b) >= n)
        throw fdr::Error(fdr::ExitCode::kInputMalformed,
                         "segment " + std::to_string(i) + " (" + std::to_string(a) + ", " + std::to_string(b) +
                             ") refers to a vertex that does not exist (0-based, " + std::to_string(n) + " vertices)");
      fdr::pslg::Segment seg;
      seg.a = static_cast<fdr::Index>(a);
      seg.b = static_cast<fdr::Index>(b);
      seg.marker = smark ? smark->data()[i] : 0;
      g.segments.push_back(seg);
    }
  }
  if (h && h->size()) {
    need2(*h, "holes");
    for (py::ssize_t i = 0; i < h->shape(0); ++i) g.holes.push_back({h->at(i, 0), h->at(i, 1)});
  }
  if (vmark) {
    if (static_cast<std::size_t>(vmark->size()) != n)
      throw fdr::Error(fdr::ExitCode::kUsage, "vertex_markers must have one value per vertex");
    g.point_markers.assign(vmark->data(), vmark->data() + n);
  }
  return g;
}


// Exceptions: fdrmesh.Error(RuntimeError) with .exit_code; one subclass per exit code, and the
// translator of fdr::Error and std::bad_alloc to them.
void bind_errors(py::module_& mod) {
  // Exceptions: fdrmesh.Error(RuntimeError) with .exit_code; one subclass per exit code.
  py::handle base_error = PyErr_NewException("fdrmesh.Error", PyExc_RuntimeError, nullptr);
  mod.attr("Error") = base_error;
  const std::pair<int, const char*> kinds[] = {
      {1, "InternalError"}, {2, "UsageError"},  {3, "InputUnreadableError"}, {4, "InputMalformedError"},
      {5, "GeometryError"}, {6, "SpacingError"}, {7, "WorkLimitError"},      {8, "OutputError"},
      {9, "CrsError"},      {10, "CheckError"},  {11, "CancelledError"}};
  error_classes()[0] = py::reinterpret_borrow<py::object>(base_error);
  for (const auto& [code, name] : kinds) {
    py::object bases = code == 2 ? py::make_tuple(base_error, py::handle(PyExc_ValueError))
                                 : py::make_tuple(base_error);
    py::handle cls = PyErr_NewException(("fdrmesh." + std::string(name)).c_str(), bases.ptr(), nullptr);
    py::setattr(cls, "exit_code", py::int_(code));
    mod.attr(name) = cls;
    error_classes()[code] = py::reinterpret_borrow<py::object>(cls);
  }
  py::setattr(base_error, "exit_code", py::int_(1));
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const fdr::Error& e) {
      auto& cls = error_classes();
      py::object c = cls.count(e.exit_code()) ? cls[e.exit_code()] : cls[0];
      py::object exc = c(py::str(e.what()));
      exc.attr("exit_code") = e.exit_code();
      PyErr_SetObject(c.ptr(), exc.ptr());
    } catch (const std::bad_alloc&) {
      py::object c = error_classes()[7];
      py::object exc = c(py::str("out of memory; coarsen the spacing or lower max_steiner"));
      PyErr_SetObject(c.ptr(), exc.ptr());
    }
  });
}

// read_poly(path): the .poly file as numpy arrays (world coordinates).
py::tuple read_poly(const std::string& path) {
  fdr::Pslg g;
  {
    py::gil_scoped_release nogil;
    g = fdr::read_pslg(path);
  }
  const auto n = static_cast<py::ssize_t>(g.points.size()), m = static_cast<py::ssize_t>(g.segments.size()),
             h = static_cast<py::ssize_t>(g.holes.size());
  py::array_t<double> v({n, py::ssize_t(2)}), hs({h, py::ssize_t(2)});
  py::array_t<long long> s({m, py::ssize_t(2)});
  py::array_t<int> smark(m), vmark(n);
  auto vv = v.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const fdr::Point2 w = g.origin + g.points[i];
    vv(i, 0) = w.x;
    vv(i, 1) = w.y;
    vmark.mutable_at(i) = g.point_markers.empty() ? 0 : g.point_markers[i];
  }
  auto ss = s.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < m; ++i) {
    ss(i, 0) = g.segments[i].a;
    ss(i, 1) = g.segments[i].b;
    smark.mutable_at(i) = g.segments[i].marker;
  }
  auto hh = hs.mutable_unchecked<2>();
  for (py::ssize_t i = 0; i < h; ++i) {
    const fdr::Point2 w = g.origin + g.holes[i];
    hh(i, 0) = w.x;
    hh(i, 1) = w.y;
  }
  return py::make_tuple(v, s, hs, vmark, smark, g.point_markers.empty());
}

// The spacing grid the Python side sampled: None, or (nx, ny, x0, y0, dx, dy, values, label).
std::optional<fdr::sizing::Grid> spacing_grid(py::object grid, std::string* label) {
  if (grid.is_none()) return std::nullopt;
  fdr::sizing::Grid gr;
  auto t = grid.cast<py::tuple>();
  gr.nx = t[0].cast<std::size_t>();
  gr.ny = t[1].cast<std::size_t>();
  gr.x0 = t[2].cast<double>();
  gr.y0 = t[3].cast<double>();
  gr.dx = t[4].cast<double>();
  gr.dy = t[5].cast<double>();
  auto vals = t[6].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  if (static_cast<std::size_t>(vals.size()) != gr.nx * gr.ny)
    throw fdr::Error(fdr::ExitCode::kInvalidSpacing, "the spacing callable returned " + std::to_string(vals.size()) +
                                                         " values for a grid of " + std::to_string(gr.nx * gr.ny));
  gr.v.assign(vals.data(), vals.data() + vals.size());
  *label = t[7].cast<std::string>();
  return gr;
}

// _triangulate(vertices, segments, holes, segment_markers, vertex_markers, spacing_spec, grid,
//              bound, min_angle, max_steiner, convex_hull, check, smooth)
// grid = None or (nx, ny, x0, y0, dx, dy, values, label): a spacing sampled by the Python side.
std::shared_ptr<PyMesh> triangulate(py::array_t<double, py::array::c_style | py::array::forcecast> v,
                                    std::optional<py::array_t<long long, py::array::c_style | py::array::forcecast>> s,
                                    std::optional<py::array_t<double, py::array::c_style | py::array::forcecast>> h,
                                    std::optional<py::array_t<int, py::array::c_style | py::array::forcecast>> smark,
                                    std::optional<py::array_t<int, py::array::c_style | py::array::forcecast>> vmark,
                                    const std::string& spec, py::object grid, double bound, double min_angle,
                                    std::uint64_t max_steiner, bool convex_hull, bool check, int smooth) {
  auto out = std::make_shared<PyMesh>();
  fdr::Pslg g = make_pslg(v, s, h, smark, vmark);
  std::string label;
  std::optional<fdr::sizing::Grid> gr = spacing_grid(grid, &label);
  fdr::TriangulateOptions o;
  o.bound = bound;
  o.min_angle_deg = min_angle;
  o.max_steiner = max_steiner;
  o.convex_hull = convex_hull;
  o.check = check;
  o.smooth_passes = smooth;
  o.source = "vertices";
  o.log = collector(&out->log);
  {
    py::gil_scoped_release nogil;
    fdr::SizingPtr f = gr ? fdr::grid_spacing(std::move(*gr), label) : fdr::make_spacing(spec);
    static_cast<fdr::Mesh&>(out->m) = fdr::triangulate(g, std::move(f), o);
  }
  return out;
}

// _mesh(args): a GIS run with the arguments of `fdrmesh mesh`.
std::shared_ptr<PyMesh> mesh_gis(const std::vector<std::string>& args) {
  auto out = std::make_shared<PyMesh>();
  out->gis = true;
  fdr::DomainOptions o = fdr::cli::parse_mesh_args(args);
  {
    py::gil_scoped_release nogil;
    out->m = fdr::mesh_domain(o, {}, collector(&out->log));
  }
  return out;
}

// The `mesh` options of the CLI option table: (key, type, repeat, positional, names).
py::list mesh_options() {
  py::list l;
  for (const auto& o : fdr::cli::option_table())
    if (o.command == "mesh") l.append(py::make_tuple(o.key, o.type, o.repeat, o.positional, o.names));
  return l;
}

// The Mesh's numpy arrays: read-only views into the C++ result.
void bind_mesh_arrays(py::class_<PyMesh, std::shared_ptr<PyMesh>>& c) {
  c.def_property_readonly("origin", [](const PyMesh& s) { return py::make_tuple(s.m.view.origin.x, s.m.view.origin.y); })
      .def_property_readonly("local_vertices", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto n = static_cast<py::ssize_t>(s.m.view.vertices.size());
        return view_array<double>(s, self, n ? &s.m.view.vertices[0].x : nullptr, {n, 2},
                                  {static_cast<py::ssize_t>(sizeof(fdr::Point2)), sizeof(double)});
      })
      .def_property_readonly("triangles", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto t = static_cast<py::ssize_t>(s.m.view.triangles.size());
        return view_array<fdr::Index>(s, self, t ? s.m.view.triangles[0].data() : nullptr, {t, 3},
                                      {static_cast<py::ssize_t>(3 * sizeof(fdr::Index)), sizeof(fdr::Index)});
      })
      .def_property_readonly("segments", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto e = static_cast<py::ssize_t>(s.m.view.edges.size());
        return view_array<fdr::Index>(s, self, e ? &s.m.view.edges[0].a : nullptr, {e, 2},
                                      {static_cast<py::ssize_t>(sizeof(fdr::mesh::MeshEdge)), sizeof(fdr::Index)});
      })
      .def_property_readonly("segment_markers", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto e = static_cast<py::ssize_t>(s.m.view.edges.size());
        return view_array<std::int32_t>(s, self, e ? &s.m.view.edges[0].marker : nullptr, {e},
                                        {static_cast<py::ssize_t>(sizeof(fdr::mesh::MeshEdge))});
      })
      .def_property_readonly("segment_parts", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto e = static_cast<py::ssize_t>(s.m.view.edges.size());
        return view_array<std::int32_t>(s, self, e ? &s.m.view.edges[0].part : nullptr, {e},
                                        {static_cast<py::ssize_t>(sizeof(fdr::mesh::MeshEdge))});
      })
      .def_property_readonly("vertex_markers", [](py::object self) {
        const PyMesh& s = self.cast<const PyMesh&>();
        const auto n = static_cast<py::ssize_t>(s.m.view.vertex_marker.size());
        return view_array<std::int32_t>(s, self, n ? s.m.view.vertex_marker.data() : nullptr, {n},
                                        {static_cast<py::ssize_t>(sizeof(std::int32_t))});
      })
      .def_property_readonly("_z", [](py::object self) -> py::object {
        const PyMesh& s = self.cast<const PyMesh&>();
        if (s.m.view.z.empty()) return py::none();
        const auto n = static_cast<py::ssize_t>(s.m.view.z.size());
        return view_array<double>(s, self, s.m.view.z.data(), {n}, {static_cast<py::ssize_t>(sizeof(double))});
      })
      .def_property_readonly("spacing", [](py::object self) -> py::object {
        const PyMesh& s = self.cast<const PyMesh&>();
        if (s.m.view.f.empty()) return py::none();
        const auto n = static_cast<py::ssize_t>(s.m.view.f.size());
        return view_array<double>(s, self, s.m.view.f.data(), {n}, {static_cast<py::ssize_t>(sizeof(double))});
      });
}

// The Mesh's CRS, report, repairs, log and write().
void bind_mesh_results(py::class_<PyMesh, std::shared_ptr<PyMesh>>& c) {
  c.def_property_readonly("crs_wkt", [](const PyMesh& s) -> py::object {
        if (s.m.view.crs_wkt.empty()) return py::none();
        return py::str(s.m.view.crs_wkt);
      })
      .def_property_readonly("crs_name", [](const PyMesh& s) { return s.m.crs_name; })
      .def_property_readonly("is_gis", [](const PyMesh& s) { return s.gis; })
      .def_property_readonly("_report_json", [](const PyMesh& s) { return fdr::report_json(s.m.report); })
      .def_property_readonly("repairs", [](const PyMesh& s) {
        py::list l;
        for (const auto& r : s.m.repairs) {
          py::dict d;
          d["kind"] = r.kind;
          d["x"] = r.x;
          d["y"] = r.y;
          d["size"] = r.size;
          d["reason"] = r.reason;
          d["part"] = r.part;
          l.append(d);
        }
        return l;
      })
      .def_property_readonly("written", [](const PyMesh& s) { return s.m.written; })
      .def_property_readonly("log", [](const PyMesh& s) { return s.log; })
      .def_property_readonly("segment_kinds", [](const PyMesh& s) {
        py::list l;
        for (const auto& e : s.m.view.edges) l.append(fdr::edge_kind_name(static_cast<fdr::EdgeKind>(e.marker)));
        return l;
      })
      .def("write", [](const PyMesh& s, const std::string& path, const std::string& format) {
        py::gil_scoped_release nogil;
        if (s.gis) fdr::write_mesh(s.m, path, format);
        else fdr::write_mesh(static_cast<const fdr::Mesh&>(s.m), path, format);
      }, py::arg("path"), py::arg("format") = "");
}

}  // namespace

PYBIND11_MODULE(_core, mod) {
  mod.doc() = "fdrmesh core bindings (use the fdrmesh package)";
  mod.attr("__version__") = fdr::kVersion;
  bind_errors(mod);
  mod.def("read_poly", &read_poly);
  mod.def("default_spacing", [](py::array_t<double, py::array::c_style | py::array::forcecast> v) {
    return fdr::default_spacing_spec(make_pslg(v, std::nullopt, std::nullopt, std::nullopt, std::nullopt));
  });
  mod.def("_triangulate", &triangulate);
  fdr::python::bind_tetrahedralize(mod);
  mod.def("_mesh", &mesh_gis);
  mod.def("_mesh_options", &mesh_options);
  py::class_<PyMesh, std::shared_ptr<PyMesh>> mesh(mod, "Mesh", "A finished mesh (see fdrmesh.Mesh)");
  bind_mesh_arrays(mesh);
  bind_mesh_results(mesh);
}
