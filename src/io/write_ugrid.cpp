// UGRID-1.0 NetCDF writer (netCDF C API): 2D mesh topology, node z, constrained edges, CF grid mapping.
#include <netcdf.h>
#include <ogr_spatialref.h>

#include <climits>
#include <cmath>
#include <cstring>

#include "io/detail.hpp"
#include "io/netcdf_util.hpp"
#include "io/gdal_util.hpp"

namespace fdr::io::detail {

namespace {

// netCDF names: letters, digits and '_', starting with a letter.
std::string nc_name(const std::string& key) {
  std::string r = "fdrmesh_";
  for (char c : key) r.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return r;
}

}  // namespace

NcCrs nc_crs(const std::string& crs_wkt, const std::string& path) {
  NcCrs c;
  if (crs_wkt.empty()) return c;
  gdal_register_once();
  GdalErrors errs;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(crs_wkt.c_str()) != OGRERR_NONE)
    fail_output(path, errs.reason("the mesh CRS cannot be parsed"));
  c.geographic = srs.IsGeographic();
  char* s = nullptr;
  if (srs.exportToWkt(&s) == OGRERR_NONE && s) c.wkt1 = s;
  CPLFree(s);
  s = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  if (srs.exportToWkt(&s, opts) == OGRERR_NONE && s) c.wkt2 = s;
  CPLFree(s);
  if (c.wkt1.empty()) c.wkt1 = crs_wkt;
  if (c.wkt2.empty()) c.wkt2 = crs_wkt;
  OGRSpatialReference probe(srs);
  const char* auth = probe.GetAuthorityName(nullptr);
  if (!(auth && std::strcmp(auth, "EPSG") == 0)) {
    probe.AutoIdentifyEPSG();
    auth = probe.GetAuthorityName(nullptr);
  }
  if (auth && std::strcmp(auth, "EPSG") == 0 && probe.GetAuthorityCode(nullptr))
    c.epsg = std::atoi(probe.GetAuthorityCode(nullptr));
  c.semi_major = srs.GetSemiMajor();
  c.semi_minor = srs.GetSemiMinor();
  c.inverse_flattening = srs.GetInvFlattening();
  if (const char* n = srs.GetName()) c.name = n;
  return c;
}

void write_ugrid(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  Nc nc{path};
  const std::size_t nv = m.vertices.size(), nt = m.triangles.size(), ne = m.edges.size();
  // Ids fit in NC_INT unless the mesh has more than 2^31-1 nodes.
  const bool wide = nv > static_cast<std::size_t>(INT_MAX);
  const nc_type id_type = wide ? NC_INT64 : NC_INT;

  const NcCrs crs = nc_crs(m.crs_wkt, path);
  const bool geographic = crs.geographic;
  const std::string& wkt1 = crs.wkt1;
  const std::string& wkt2 = crs.wkt2;
  const int epsg = crs.epsg;

  TempFile tf(path);
  tf.release_for_library();
  NcFile f;
  nc.check(nc_create(tf.path().c_str(), NC_NETCDF4 | NC_NOCLOBBER, &f.id), "create");
  const int id = f.id;

  // Dimensions (a zero length would mean "unlimited" in netCDF, which is what an empty mesh needs).
  int d_node, d_face, d_edge = -1, d_three, d_two;
  nc.check(nc_def_dim(id, "nmesh2d_node", nv, &d_node), "dimension nmesh2d_node");
  nc.check(nc_def_dim(id, "nmesh2d_face", nt, &d_face), "dimension nmesh2d_face");
  nc.check(nc_def_dim(id, "max_nmesh2d_face_nodes", 3, &d_three), "dimension max_nmesh2d_face_nodes");
  nc.check(nc_def_dim(id, "Two", 2, &d_two), "dimension Two");
  if (ne) nc.check(nc_def_dim(id, "nmesh2d_edge", ne, &d_edge), "dimension nmesh2d_edge");

  nc.text(id, NC_GLOBAL, "Conventions", "CF-1.8 UGRID-1.0");
  nc.text(id, NC_GLOBAL, "title", o.title.empty() ? "fdrmesh mesh" : o.title);
  nc.text(id, NC_GLOBAL, "source", "fdrmesh");
  for (const auto& [k, v] : o.metadata) nc.text(id, NC_GLOBAL, nc_name(k).c_str(), v);

  int v_mesh;
  nc.check(nc_def_var(id, "mesh2d", NC_INT, 0, nullptr, &v_mesh), "variable mesh2d");
  nc.text(id, v_mesh, "cf_role", "mesh_topology");
  nc.text(id, v_mesh, "long_name", "Topology data of 2D mesh");
  nc.integer(id, v_mesh, "topology_dimension", 2);
  nc.text(id, v_mesh, "node_coordinates", "mesh2d_node_x mesh2d_node_y");
  nc.text(id, v_mesh, "face_node_connectivity", "mesh2d_face_nodes");
  nc.text(id, v_mesh, "node_dimension", "nmesh2d_node");
  nc.text(id, v_mesh, "face_dimension", "nmesh2d_face");
  nc.text(id, v_mesh, "max_face_nodes_dimension", "max_nmesh2d_face_nodes");
  if (ne) {
    nc.text(id, v_mesh, "edge_node_connectivity", "mesh2d_edge_nodes");
    nc.text(id, v_mesh, "edge_dimension", "nmesh2d_edge");
  }

  int v_crs = -1;
  if (!m.crs_wkt.empty()) {
    nc.check(nc_def_var(id, "crs", NC_INT, 0, nullptr, &v_crs), "variable crs");
    if (geographic) nc.text(id, v_crs, "grid_mapping_name", "latitude_longitude");
    nc.text(id, v_crs, "crs_wkt", wkt2);
    nc.text(id, v_crs, "spatial_ref", wkt1);
    nc.text(id, v_crs, "wkt", wkt1);
    if (epsg > 0) {
      nc.integer(id, v_crs, "epsg", epsg);
      nc.text(id, v_crs, "EPSG_code", "EPSG:" + std::to_string(epsg));
    }
  }
  auto on_mesh = [&](int var, const char* location) {
    nc.text(id, var, "mesh", "mesh2d");
    nc.text(id, var, "location", location);
    if (v_crs >= 0) nc.text(id, var, "grid_mapping", "crs");
  };

  int v_x, v_y;
  nc.check(nc_def_var(id, "mesh2d_node_x", NC_DOUBLE, 1, &d_node, &v_x), "variable mesh2d_node_x");
  nc.check(nc_def_var(id, "mesh2d_node_y", NC_DOUBLE, 1, &d_node, &v_y), "variable mesh2d_node_y");
  nc.text(id, v_x, "standard_name", geographic ? "longitude" : "projection_x_coordinate");
  nc.text(id, v_y, "standard_name", geographic ? "latitude" : "projection_y_coordinate");
  nc.text(id, v_x, "long_name", "x-coordinate of mesh nodes");
  nc.text(id, v_y, "long_name", "y-coordinate of mesh nodes");
  nc.text(id, v_x, "units", geographic ? "degrees_east" : "m");
  nc.text(id, v_y, "units", geographic ? "degrees_north" : "m");
  on_mesh(v_x, "node");
  on_mesh(v_y, "node");

  int face_dims[2] = {d_face, d_three};
  int v_faces;
  nc.check(nc_def_var(id, "mesh2d_face_nodes", id_type, 2, face_dims, &v_faces), "variable mesh2d_face_nodes");
  nc.text(id, v_faces, "cf_role", "face_node_connectivity");
  nc.text(id, v_faces, "long_name", "Vertex nodes of mesh faces (counterclockwise)");
  nc.integer(id, v_faces, "start_index", 0);
  if (!wide) {
    int fill = -1;
    nc.check(nc_put_att_int(id, v_faces, "_FillValue", NC_INT, 1, &fill), "_FillValue");
  } else {
    long long fill = -1;
    nc.check(nc_put_att_longlong(id, v_faces, "_FillValue", NC_INT64, 1, &fill), "_FillValue");
  }

  int v_edges = -1, v_kind = -1, v_part = -1;
  if (ne) {
    int edge_dims[2] = {d_edge, d_two};
    nc.check(nc_def_var(id, "mesh2d_edge_nodes", id_type, 2, edge_dims, &v_edges), "variable mesh2d_edge_nodes");
    nc.text(id, v_edges, "cf_role", "edge_node_connectivity");
    nc.text(id, v_edges, "long_name", "Nodes of the constrained (boundary and breakline) edges");
    nc.integer(id, v_edges, "start_index", 0);
    nc.check(nc_def_var(id, "mesh2d_edge_kind", NC_INT, 1, &d_edge, &v_kind), "variable mesh2d_edge_kind");
    nc.text(id, v_kind, "long_name", "kind of constrained edge");
    int flags[5] = {0, 1, 2, 3, 4};
    nc.check(nc_put_att_int(id, v_kind, "flag_values", NC_INT, 5, flags), "flag_values");
    nc.text(id, v_kind, "flag_meanings", "none land island open breakline");
    on_mesh(v_kind, "edge");
    nc.check(nc_def_var(id, "mesh2d_edge_part", NC_INT, 1, &d_edge, &v_part), "variable mesh2d_edge_part");
    nc.text(id, v_part, "long_name", "input ring or line id of the constrained edge");
    on_mesh(v_part, "edge");
  }

  auto node_var = [&](const char* name, const char* long_name, const char* std_name) {
    int v;
    nc.check(nc_def_var(id, name, NC_DOUBLE, 1, &d_node, &v), name);
    if (std_name) nc.text(id, v, "standard_name", std_name);
    nc.text(id, v, "long_name", long_name);
    nc.text(id, v, "units", "m");
    nc.text(id, v, "coordinates", "mesh2d_node_x mesh2d_node_y");
    on_mesh(v, "node");
    return v;
  };
  int v_z = -1, v_f = -1;
  if (!m.z.empty()) {
    v_z = node_var("mesh2d_node_z", "elevation of mesh nodes (positive up)", "altitude");
    nc.text(id, v_z, "positive", "up");
  }
  if (!m.f.empty()) v_f = node_var("mesh2d_node_f", "target spacing f at mesh nodes", nullptr);

  auto face_var = [&](const char* name, const char* long_name, const char* units) {
    int v;
    nc.check(nc_def_var(id, name, NC_DOUBLE, 1, &d_face, &v), name);
    nc.text(id, v, "long_name", long_name);
    nc.text(id, v, "units", units);
    on_mesh(v, "face");
    return v;
  };
  int v_angle = face_var("mesh2d_face_min_angle", "smallest angle of the triangle", "degree");
  int v_ratio = (o.f || o.triangle_r_over_f) ? face_var("mesh2d_face_R_over_f", "circumradius over spacing f at the circumcentre", "1") : -1;

  nc.check(nc_enddef(id), "enddef");

  // Data.
  if (nv) {
    std::vector<double> x(nv), y(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      Point2 p = m.world(static_cast<Index>(v));
      x[v] = p.x;
      y[v] = p.y;
    }
    nc.check(nc_put_var_double(id, v_x, x.data()), "write mesh2d_node_x");
    nc.check(nc_put_var_double(id, v_y, y.data()), "write mesh2d_node_y");
    if (v_z >= 0) nc.check(nc_put_var_double(id, v_z, m.z.data()), "write mesh2d_node_z");
    if (v_f >= 0) nc.check(nc_put_var_double(id, v_f, m.f.data()), "write mesh2d_node_f");
  }
  // Writes an id table of `rows` x `cols` through the chosen integer width.
  auto put_ids = [&](int var, std::size_t rows, std::size_t cols, auto get, const char* what) {
    std::size_t start[2] = {0, 0}, count[2] = {rows, cols};
    if (wide) {
      std::vector<long long> buf(rows * cols);
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < cols; ++c) buf[r * cols + c] = static_cast<long long>(get(r, c));
      nc.check(nc_put_vara_longlong(id, var, start, count, buf.data()), what);
    } else {
      std::vector<int> buf(rows * cols);
      for (std::size_t r = 0; r < rows; ++r)
        for (std::size_t c = 0; c < cols; ++c) buf[r * cols + c] = static_cast<int>(get(r, c));
      nc.check(nc_put_vara_int(id, var, start, count, buf.data()), what);
    }
  };
  if (nt) {
    put_ids(v_faces, nt, 3, [&](std::size_t r, std::size_t c) { return m.triangles[r][c]; }, "write mesh2d_face_nodes");
    std::vector<double> ang(nt);
    for (std::size_t t = 0; t < nt; ++t)
      ang[t] = o.triangle_min_angle ? (*o.triangle_min_angle)[t] : triangle_min_angle_deg(m, t);
    nc.check(nc_put_var_double(id, v_angle, ang.data()), "write mesh2d_face_min_angle");
    if (v_ratio >= 0) {
      for (std::size_t t = 0; t < nt; ++t) {
        if (o.triangle_r_over_f) { ang[t] = (*o.triangle_r_over_f)[t]; continue; }
        Point2 c;
        double r = circumradius(m, t, c);
        ang[t] = r / (*o.f)(c);
      }
      nc.check(nc_put_var_double(id, v_ratio, ang.data()), "write mesh2d_face_R_over_f");
    }
  }
  if (ne) {
    put_ids(v_edges, ne, 2, [&](std::size_t r, std::size_t c) { return c == 0 ? m.edges[r].a : m.edges[r].b; },
            "write mesh2d_edge_nodes");
    std::vector<int> kind(ne), part(ne);
    for (std::size_t e = 0; e < ne; ++e) {
      kind[e] = m.edges[e].marker;
      part[e] = m.edges[e].part;
    }
    nc.check(nc_put_var_int(id, v_kind, kind.data()), "write mesh2d_edge_kind");
    nc.check(nc_put_var_int(id, v_part, part.data()), "write mesh2d_edge_part");
  }
  int status = nc_close(id);
  f.id = -1;
  nc.check(status, "close");
  tf.commit();
}

}  // namespace fdr::io::detail
