// Mesh writers: format selection, and the text formats (SMS 2dm, Gmsh msh 4.1, Triangle node/ele, VTU, ADCIRC fort.14);
// msh and VTU also on the sphere (Earth-centred x, y, z) for global meshes.
#include "io/writer.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <sstream>

#include "base/error.hpp"
#include "io/detail.hpp"
#include "io/write_postgis.hpp"

namespace fdr::io {

using detail::Chain;
using detail::TempFile;
using detail::TextOut;

namespace {

std::string one_line(const std::string& s) {
  std::string r = s;
  for (char& c : r)
    if (c == '\n' || c == '\r') c = ' ';
  return r;
}

double z_of(const mesh::MeshView& m, std::size_t v) { return m.z.empty() ? 0.0 : m.z[v]; }

// ------------------------------------------------------------------ SMS 2dm
// Cards: MESH2D, MESHNAME, NUM_MATERIALS_PER_ELEM, E3T id n1 n2 n3 matid, ND id x y z (1-based),
// NS nodestrings (open-boundary chains, at most 10 ids per card, last id negated).
void write_2dm(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  TempFile tf(path);
  TextOut out(tf.stream(), path);
  std::string title = one_line(o.title.empty() ? "fdrmesh" : o.title);
  std::replace(title.begin(), title.end(), '"', '\'');
  out.str("MESH2D").nl();
  out.str("MESHNAME \"").str(title).str("\"").nl();
  out.str("NUM_MATERIALS_PER_ELEM 1").nl();
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tr = m.triangles[t];
    out.str("E3T ").num(static_cast<std::uint64_t>(t + 1));
    for (Index v : tr) out.sp().num(static_cast<std::uint64_t>(v) + 1);
    out.str(" 1").nl();
  }
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    Point2 w = m.world(static_cast<Index>(v));
    out.str("ND ").num(static_cast<std::uint64_t>(v + 1)).sp().num(w.x).sp().num(w.y).sp().num(z_of(m, v)).nl();
  }
  // One nodestring per boundary run (open runs first, then land and island runs; see
  // detail::model_boundary_lists); closed runs are split in two, as SMS does not allow a
  // nodestring that starts and ends on the same node.
  for (const auto& ns : detail::model_boundary_lists(m, path, detail::BoundaryFlavor::k2dm, o.boundary_cache).all()) {
    const std::vector<Index>& ids = ns.nodes;
    for (std::size_t i = 0; i < ids.size(); ++i) {
      if (i % 10 == 0) out.str(i ? "\nNS" : "NS");
      auto id = static_cast<std::int64_t>(ids[i]) + 1;
      out.sp().num(i + 1 == ids.size() ? -id : id);
    }
    out.nl();
  }
  out.flush();
  tf.commit();
}

// ------------------------------------------------------------------ Gmsh msh 4.1 ASCII
// One physical group per boundary kind (dimension 1, tag = marker; markers <= 0 get 1000 - marker)
// and "domain" (dimension 2, tag kDomainTag); one curve entity per boundary chain, one surface.
constexpr int kDomainTag = 10;
int physical_tag(std::int32_t marker) { return marker > 0 ? marker : 1000 - marker; }

// One scalar per node as a $NodeData section (time step 0): the elevation of a mesh whose third
// coordinate is taken by the sphere.
void write_msh_node_data(const std::vector<double>& values, const char* name, TextOut& out) {
  out.str("$NodeData\n1\n\"").str(name).str("\"\n1\n0\n3\n0\n1\n").num(static_cast<std::uint64_t>(values.size())).nl();
  for (std::size_t v = 0; v < values.size(); ++v) out.num(static_cast<std::uint64_t>(v + 1)).sp().num(values[v]).nl();
  out.str("$EndNodeData\n");
}

void write_msh(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  std::vector<Chain> chains = detail::build_chains(m);
  std::set<std::int32_t> markers;
  for (const Chain& c : chains) markers.insert(c.marker);
  double zmin = 0, zmax = 0;
  if (!m.z.empty()) {
    zmin = std::numeric_limits<double>::infinity();
    zmax = -zmin;
    for (double z : m.z)
      if (std::isfinite(z)) zmin = std::min(zmin, z), zmax = std::max(zmax, z);
    if (zmin > zmax) zmin = zmax = 0;
  }
  // A node's coordinates: plane x, y and the elevation, or Earth-centred x, y, z on the sphere.
  const std::vector<Point3>* sphere = o.sphere_xyz;
  auto node_xyz = [&](Index v) {
    if (sphere) return (*sphere)[v];
    const Point2 w = m.world(v);
    return Point3{w.x, w.y, z_of(m, v)};
  };
  auto box_of = [&](const std::vector<Index>& ids, TextOut& out) {
    Box3 b;
    for (Index v : ids) b.add(node_xyz(v));
    if (b.empty()) b.add({0, 0, 0});
    if (!sphere) b.lo.z = zmin, b.hi.z = zmax;
    out.num(b.lo.x).sp().num(b.lo.y).sp().num(b.lo.z).sp().num(b.hi.x).sp().num(b.hi.y).sp().num(b.hi.z);
  };

  TempFile tf(path);
  TextOut out(tf.stream(), path);
  out.str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  if (!o.title.empty() || sphere) {
    out.str("$Comments\n");
    if (!o.title.empty()) out.str(one_line(o.title)).nl();
    if (sphere) out.str(detail::kMshSphereComment).sp().num(o.sphere_radius).nl();
    out.str("$EndComments\n");
  }
  out.str("$PhysicalNames\n").num(static_cast<std::uint64_t>(markers.size() + 1)).nl();
  for (std::int32_t mk : markers)
    out.str("1 ").num(physical_tag(mk)).str(" \"").str(detail::kind_name(mk)).str("\"").nl();
  out.str("2 ").num(kDomainTag).str(" \"domain\"").nl();
  out.str("$EndPhysicalNames\n");

  out.str("$Entities\n0 ").num(static_cast<std::uint64_t>(chains.size())).str(" 1 0\n");
  for (std::size_t i = 0; i < chains.size(); ++i) {
    out.num(static_cast<std::uint64_t>(i + 1)).sp();
    box_of(chains[i].nodes, out);
    out.str(" 1 ").num(physical_tag(chains[i].marker)).str(" 0").nl();
  }
  {
    std::vector<Index> all(m.vertices.size());
    for (std::size_t v = 0; v < all.size(); ++v) all[v] = static_cast<Index>(v);
    out.str("1 ");
    box_of(all, out);
    out.str(" 1 ").num(kDomainTag).str(" 0").nl();
  }
  out.str("$EndEntities\n");

  // All nodes are classified on the surface entity (one block).
  const auto nv = static_cast<std::uint64_t>(m.vertices.size());
  out.str("$Nodes\n");
  if (nv == 0) {
    out.str("0 0 0 0\n");
  } else {
    out.str("1 ").num(nv).str(" 1 ").num(nv).nl();
    out.str("2 1 0 ").num(nv).nl();
    for (std::uint64_t v = 1; v <= nv; ++v) out.num(v).nl();
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      const Point3 p = node_xyz(static_cast<Index>(v));
      out.num(p.x).sp().num(p.y).sp().num(p.z).nl();
    }
  }
  out.str("$EndNodes\n");

  std::uint64_t nelem = m.triangles.size();
  std::uint64_t nblocks = m.triangles.empty() ? 0 : 1;
  for (const Chain& c : chains) {
    nelem += c.closed ? c.nodes.size() : c.nodes.size() - 1;
    ++nblocks;
  }
  out.str("$Elements\n").num(nblocks).sp().num(nelem).sp().num(nelem ? 1u : 0u).sp().num(nelem).nl();
  std::uint64_t tag = 0;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& c = chains[i];
    std::size_t k = c.nodes.size();
    std::size_t ne = c.closed ? k : k - 1;
    out.str("1 ").num(static_cast<std::uint64_t>(i + 1)).str(" 1 ").num(static_cast<std::uint64_t>(ne)).nl();
    for (std::size_t s = 0; s < ne; ++s)
      out.num(++tag).sp().num(static_cast<std::uint64_t>(c.nodes[s]) + 1).sp()
          .num(static_cast<std::uint64_t>(c.nodes[(s + 1) % k]) + 1).nl();
  }
  if (!m.triangles.empty()) {
    out.str("2 1 2 ").num(static_cast<std::uint64_t>(m.triangles.size())).nl();
    for (const auto& tr : m.triangles) {
      out.num(++tag);
      for (Index v : tr) out.sp().num(static_cast<std::uint64_t>(v) + 1);
      out.nl();
    }
  }
  out.str("$EndElements\n");
  if (sphere && !m.z.empty()) write_msh_node_data(m.z, "z", out);
  out.flush();
  tf.commit();
}

// ------------------------------------------------------------------ Triangle .node / .ele
// .node: "<n> 2 <#attributes> 1" then "<id> <x> <y> [z] [f] <marker>" (1-based); the attribute
// names are given in a comment line. Markers: MeshView::vertex_marker when present, else the
// largest marker of the constrained edges at the vertex (0 for interior vertices).
void write_node_ele(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  std::string base = path;
  std::string ext = detail::lower_extension(path);
  if (ext == ".node" || ext == ".ele") base = path.substr(0, path.size() - ext.size());
  std::vector<std::int32_t> marker = m.vertex_marker;
  if (marker.empty()) {
    marker.assign(m.vertices.size(), 0);
    for (const auto& e : m.edges) {
      marker[e.a] = std::max(marker[e.a], e.marker);
      marker[e.b] = std::max(marker[e.b], e.marker);
    }
  }
  TempFile node_tf(base + ".node");
  TempFile ele_tf(base + ".ele");
  {
    TextOut out(node_tf.stream(), node_tf.target());
    int nattr = (m.z.empty() ? 0 : 1) + (m.f.empty() ? 0 : 1);
    out.num(static_cast<std::uint64_t>(m.vertices.size())).str(" 2 ").num(nattr).str(" 1").nl();
    out.str("# fdrmesh attributes:");
    if (!m.z.empty()) out.str(" z");
    if (!m.f.empty()) out.str(" f");
    out.nl();
    for (std::size_t v = 0; v < m.vertices.size(); ++v) {
      Point2 w = m.world(static_cast<Index>(v));
      out.num(static_cast<std::uint64_t>(v + 1)).sp().num(w.x).sp().num(w.y);
      if (!m.z.empty()) out.sp().num(m.z[v]);
      if (!m.f.empty()) out.sp().num(m.f[v]);
      out.sp().num(static_cast<std::int64_t>(marker[v])).nl();
    }
    out.flush();
    node_tf.close_stream();
  }
  {
    TextOut out(ele_tf.stream(), ele_tf.target());
    out.num(static_cast<std::uint64_t>(m.triangles.size())).str(" 3 0").nl();
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      out.num(static_cast<std::uint64_t>(t + 1));
      for (Index v : m.triangles[t]) out.sp().num(static_cast<std::uint64_t>(v) + 1);
      out.nl();
    }
    out.flush();
    ele_tf.close_stream();
  }
  detail::commit_all({&node_tf, &ele_tf});
}

// ------------------------------------------------------------------ VTK XML unstructured grid
// Longitude and latitude (degrees) of Earth-centred points, as point data: a globe's points are
// x, y, z, and users colour or threshold by lon/lat.
template <class ArrayFn>
void write_vtu_lonlat(const std::vector<Point3>& xyz, ArrayFn& array) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  std::vector<double> lon(xyz.size()), lat(xyz.size());
  for (std::size_t v = 0; v < xyz.size(); ++v) {
    const Point3 p = xyz[v];
    lon[v] = std::atan2(p.y, p.x) * kDeg;
    lat[v] = std::atan2(p.z, std::hypot(p.x, p.y)) * kDeg;
  }
  array("lon", lon);
  array("lat", lat);
}

void write_vtu(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  TempFile tf(path);
  TextOut out(tf.stream(), path);
  out.str("<?xml version=\"1.0\"?>\n");
  if (!o.title.empty()) {
    std::string t = one_line(o.title);
    // "--" may not appear inside an XML comment.
    for (std::size_t p; (p = t.find("--")) != std::string::npos;) t.replace(p, 2, "- -");
    out.str("<!-- ").str(t).str(" -->\n");
  }
  out.str("<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n");
  const std::vector<Point3>* sphere = o.sphere_xyz;
  out.str("<UnstructuredGrid>\n");
  if (sphere) {  // the radius the points lie on, for readers that want lon/lat back
    out.str("<FieldData>\n<DataArray type=\"Float64\" Name=\"sphere_radius_m\" NumberOfTuples=\"1\" format=\"ascii\">\n")
        .num(o.sphere_radius).str("\n</DataArray>\n</FieldData>\n");
  }
  out.str("<Piece NumberOfPoints=\"").num(static_cast<std::uint64_t>(m.vertices.size()))
      .str("\" NumberOfCells=\"").num(static_cast<std::uint64_t>(m.triangles.size())).str("\">\n");
  auto array = [&](const char* name, const std::vector<double>& v) {
    out.str("<DataArray type=\"Float64\" Name=\"").str(name).str("\" format=\"ascii\">\n");
    for (double x : v) out.num(x).nl();
    out.str("</DataArray>\n");
  };
  out.str("<PointData>\n");
  if (!m.z.empty()) array("z", m.z);
  if (!m.f.empty()) array("f", m.f);
  if (sphere) write_vtu_lonlat(*sphere, array);
  out.str("</PointData>\n<CellData>\n");
  {
    std::vector<double> ang(m.triangles.size());
    for (std::size_t t = 0; t < ang.size(); ++t)
      ang[t] = o.triangle_min_angle ? (*o.triangle_min_angle)[t] : detail::triangle_min_angle_deg(m, t);
    array("min_angle", ang);
    if (o.f || o.triangle_r_over_f) {
      std::vector<double> r(m.triangles.size());
      for (std::size_t t = 0; t < r.size(); ++t) {
        if (o.triangle_r_over_f) { r[t] = (*o.triangle_r_over_f)[t]; continue; }
        Point2 c;
        double R = detail::circumradius(m, t, c);
        r[t] = R / (*o.f)(c);
      }
      array("R_over_f", r);
    }
  }
  out.str("</CellData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n");
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    if (sphere) {
      const Point3 p = (*sphere)[v];
      out.num(p.x).sp().num(p.y).sp().num(p.z).nl();
      continue;
    }
    Point2 w = m.world(static_cast<Index>(v));
    out.num(w.x).sp().num(w.y).str(" 0").nl();
  }
  out.str("</DataArray>\n</Points>\n<Cells>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
  for (const auto& tr : m.triangles)
    out.num(static_cast<std::uint64_t>(tr[0])).sp().num(static_cast<std::uint64_t>(tr[1])).sp()
        .num(static_cast<std::uint64_t>(tr[2])).nl();
  out.str("</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
  for (std::size_t t = 0; t < m.triangles.size(); ++t) out.num(static_cast<std::uint64_t>(3 * (t + 1))).nl();
  out.str("</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
  for (std::size_t t = 0; t < m.triangles.size(); ++t) out.str("5\n");
  out.str("</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n");
  out.flush();
  tf.commit();
}

}  // namespace

void write_mesh(const mesh::MeshView& mesh, const std::string& path, Format format, const WriteOptions& options) {
  // A database, not a file; it names itself without its password in every message.
  if (format == Format::kPostgis) return detail::write_postgis(mesh, path, options);
  detail::validate_for_output(mesh, path);
  if (options.sphere_xyz && options.sphere_xyz->size() != mesh.vertices.size())
    detail::fail_output(path, "invalid mesh: " + std::to_string(options.sphere_xyz->size()) +
                                  " points on the sphere for " + std::to_string(mesh.vertices.size()) + " vertices");
  // Writers throw kOutputError themselves; anything else (out of memory, a sizing field that
  // throws) is reported as an output error too, after the temp file has been removed.
  try {
    switch (format) {
      case Format::kGpkg: detail::write_gpkg(mesh, path, options); return;
      case Format::k2dm: write_2dm(mesh, path, options); return;
      case Format::kMsh: write_msh(mesh, path, options); return;
      case Format::kNode: write_node_ele(mesh, path, options); return;
      case Format::kVtu: write_vtu(mesh, path, options); return;
      case Format::kFort14: detail::write_adcirc(mesh, path, options, detail::BoundaryFlavor::kFort14); return;
      case Format::kUgrid: detail::write_ugrid(mesh, path, options); return;
      case Format::kGr3: detail::write_adcirc(mesh, path, options, detail::BoundaryFlavor::kGr3); return;
      case Format::kLl: detail::write_adcirc(mesh, path, options, detail::BoundaryFlavor::kLl); return;
      case Format::kSelafin: detail::write_selafin(mesh, path, options); return;
      case Format::kDflowfm: detail::write_dflowfm_net(mesh, path, options); return;
      case Format::kPostgis: break;  // written above
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    detail::fail_output(path, e.what());
  }
  throw Error(ExitCode::kInternal, "write_mesh: bad format value");
}

}  // namespace fdr::io
