// GeoPackage writer through OGR: nodes, triangles, boundaries, repairs and metadata layers in one transaction.
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <limits>
#include <mutex>

#include "io/detail.hpp"
#include "io/gdal_util.hpp"
#include "io/gpkg_rtree.hpp"

namespace fdr::io::detail {

void gdal_register_once() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

namespace {

struct Writer {
  const std::string& path;
  GdalErrors& errs;

  [[noreturn]] void fail(const std::string& what) const { fail_output(path, errs.reason(what)); }


  OGRLayer* layer(GDALDataset& ds, const char* name, OGRSpatialReference* srs, OGRwkbGeometryType g) {
    // Spatial indexes are bulk-loaded at the end (gpkg_rtree.cpp), not maintained row by row.
    const char* opts[] = {"SPATIAL_INDEX=NO", nullptr};
    OGRLayer* l = ds.CreateLayer(name, g == wkbNone ? nullptr : srs, g, const_cast<char**>(opts));
    if (!l) fail(std::string("cannot create layer '") + name + "'");
    return l;
  }
  void field(OGRLayer* l, const char* name, OGRFieldType t, OGRFieldSubType st = OFSTNone) {
    OGRFieldDefn fd(name, t);
    fd.SetSubType(st);
    if (l->CreateField(&fd) != OGRERR_NONE) fail(std::string("cannot create field '") + name + "' in layer '" + l->GetName() + "'");
  }
  void create(OGRLayer* l, OGRFeature& feat) {
    if (l->CreateFeature(&feat) != OGRERR_NONE)
      fail(std::string("cannot write feature ") + std::to_string(feat.GetFID()) + " of layer '" + l->GetName() + "'");
  }
};

void set_real_or_null(OGRFeature& f, int i, double v) {
  if (std::isfinite(v)) f.SetField(i, v);
  else f.SetFieldNull(i);
}

}  // namespace

void write_gpkg(const mesh::MeshView& m, const std::string& path, const WriteOptions& o) {
  gdal_register_once();
  GdalErrors errs;
  Writer w{path, errs};
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GPKG");
  if (!drv) fail_output(path, "the GDAL GeoPackage driver is not available");

  OGRSpatialReference srs;
  OGRSpatialReference* srs_ptr = nullptr;
  if (!m.crs_wkt.empty()) {
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    if (srs.SetFromUserInput(m.crs_wkt.c_str()) != OGRERR_NONE) w.fail("the mesh CRS cannot be parsed");
  } else {
    // No CRS: use the GeoPackage's "undefined Cartesian SRS" (srs_id -1) rather than GDAL's
    // default "undefined geographic SRS" (0), since mesh coordinates are planar.
    srs.SetLocalCS("Undefined cartesian SRS");
  }
  srs_ptr = &srs;

  // Per-vertex f (from the mesh, else from the sizing field) and conformity.
  const std::size_t nv = m.vertices.size();
  std::vector<double> fv(nv, std::nan(""));
  for (std::size_t v = 0; v < nv; ++v) {
    if (!m.f.empty()) fv[v] = m.f[v];
    else if (o.f) fv[v] = (*o.f)(m.vertices[v]);
  }
  std::vector<double> nn = nearest_neighbour_distance(m);

  TempFile tf(path);  // declared before the dataset: the dataset closes first on failure
  tf.release_for_library();
  DatasetPtr ds(drv->Create(tf.path().c_str(), 0, 0, 0, GDT_Unknown, nullptr));
  if (!ds) w.fail("cannot create the GeoPackage");

  OGRLayer* ln = w.layer(*ds, "nodes", srs_ptr, wkbPoint);
  w.field(ln, "id", OFTInteger64);
  w.field(ln, "z", OFTReal);
  w.field(ln, "f", OFTReal);
  w.field(ln, "conformity", OFTReal);
  w.field(ln, "marker", OFTInteger);
  OGRLayer* lt = w.layer(*ds, "triangles", srs_ptr, wkbPolygon);
  for (const char* n : {"id", "n1", "n2", "n3"}) w.field(lt, n, OFTInteger64);
  for (const char* n : {"area", "min_angle", "R_over_f", "quality"}) w.field(lt, n, OFTReal);
  OGRLayer* lb = w.layer(*ds, "boundaries", srs_ptr, wkbLineString);
  w.field(lb, "id", OFTInteger);
  w.field(lb, "kind", OFTString);
  w.field(lb, "marker", OFTInteger);
  w.field(lb, "part", OFTInteger);
  w.field(lb, "closed", OFTInteger, OFSTBoolean);
  w.field(lb, "num_nodes", OFTInteger64);
  OGRLayer* lr = w.layer(*ds, "repairs", srs_ptr, wkbPoint);
  w.field(lr, "kind", OFTString);
  w.field(lr, "size", OFTReal);
  w.field(lr, "reason", OFTString);
  w.field(lr, "part", OFTInteger);
  OGRLayer* lm = w.layer(*ds, "metadata", nullptr, wkbNone);
  w.field(lm, "key", OFTString);
  w.field(lm, "value", OFTString);

  std::vector<RtreeEntry> node_boxes, tri_boxes, chain_boxes, repair_boxes;
  const bool index = o.gpkg_spatial_index;
  if (index) {
    node_boxes.reserve(nv);
    tri_boxes.reserve(m.triangles.size());
  }

  // One transaction for all rows: SQLite commits per statement otherwise (orders of magnitude slower).
  if (ds->StartTransaction() != OGRERR_NONE) w.fail("cannot start a transaction");

  {
    // Features and geometries are reused; only coordinates and fields change per row.
    OGRFeature feat(ln->GetLayerDefn());
    feat.SetGeometryDirectly(new OGRPoint(0, 0));
    auto* pt = static_cast<OGRPoint*>(feat.GetGeometryRef());
    for (std::size_t v = 0; v < nv; ++v) {
      Point2 p = m.world(static_cast<Index>(v));
      pt->setX(p.x);
      pt->setY(p.y);
      feat.SetFID(static_cast<GIntBig>(v + 1));
      feat.SetField(0, static_cast<GIntBig>(v + 1));
      if (m.z.empty()) feat.SetFieldNull(1);
      else set_real_or_null(feat, 1, m.z[v]);
      set_real_or_null(feat, 2, fv[v]);
      double c = std::nan("");
      if (fv[v] > 0 && std::isfinite(nn[v]) && nn[v] > 0) c = std::min(nn[v] / fv[v], fv[v] / nn[v]);
      set_real_or_null(feat, 3, c);
      feat.SetField(4, m.vertex_marker.empty() ? 0 : m.vertex_marker[v]);
      w.create(ln, feat);
      if (index) node_boxes.push_back({static_cast<std::int64_t>(v + 1), p.x, p.x, p.y, p.y});
    }
  }
  {
    OGRFeature feat(lt->GetLayerDefn());
    auto* poly = new OGRPolygon();
    auto* ring = new OGRLinearRing();
    ring->setNumPoints(4);
    poly->addRingDirectly(ring);
    feat.SetGeometryDirectly(poly);
    ring = static_cast<OGRPolygon*>(feat.GetGeometryRef())->getExteriorRing();
    for (std::size_t t = 0; t < m.triangles.size(); ++t) {
      const auto& tr = m.triangles[t];
      RtreeEntry box{static_cast<std::int64_t>(t + 1), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()};
      for (int k = 0; k < 4; ++k) {
        Point2 p = m.world(tr[k % 3]);
        ring->setPoint(k, p.x, p.y);
        box.minx = std::min(box.minx, p.x);
        box.maxx = std::max(box.maxx, p.x);
        box.miny = std::min(box.miny, p.y);
        box.maxy = std::max(box.maxy, p.y);
      }
      if (index) tri_boxes.push_back(box);
      feat.SetFID(static_cast<GIntBig>(t + 1));
      feat.SetField(0, static_cast<GIntBig>(t + 1));
      for (int k = 0; k < 3; ++k) feat.SetField(1 + k, static_cast<GIntBig>(tr[k]) + 1);
      feat.SetField(4, o.triangle_area ? (*o.triangle_area)[t] : triangle_area(m, t));
      feat.SetField(5, o.triangle_min_angle ? (*o.triangle_min_angle)[t] : triangle_min_angle_deg(m, t));
      if (o.f || o.triangle_r_over_f) {
        double r;
        if (o.triangle_r_over_f) {
          r = (*o.triangle_r_over_f)[t];
        } else {
          Point2 c;
          r = circumradius(m, t, c) / (*o.f)(c);
        }
        set_real_or_null(feat, 6, r);
        if (o.bound_B > 0) set_real_or_null(feat, 7, r / o.bound_B);
        else feat.SetFieldNull(7);
      } else {
        feat.SetFieldNull(6);
        feat.SetFieldNull(7);
      }
      w.create(lt, feat);
    }
  }
  {
    std::vector<Chain> chains = build_chains(m);
    OGRFeature feat(lb->GetLayerDefn());
    for (std::size_t i = 0; i < chains.size(); ++i) {
      const Chain& c = chains[i];
      auto* ls = new OGRLineString();
      ls->setNumPoints(static_cast<int>(c.nodes.size() + (c.closed ? 1 : 0)));
      for (std::size_t k = 0; k < c.nodes.size(); ++k) {
        Point2 p = m.world(c.nodes[k]);
        ls->setPoint(static_cast<int>(k), p.x, p.y);
      }
      if (c.closed) {
        Point2 p = m.world(c.nodes[0]);
        ls->setPoint(static_cast<int>(c.nodes.size()), p.x, p.y);
      }
      feat.SetGeometryDirectly(ls);
      feat.SetFID(static_cast<GIntBig>(i + 1));
      feat.SetField(0, static_cast<int>(i + 1));
      feat.SetField(1, kind_name(c.marker).c_str());
      feat.SetField(2, c.marker);
      feat.SetField(3, c.part);
      feat.SetField(4, c.closed ? 1 : 0);
      feat.SetField(5, static_cast<GIntBig>(c.nodes.size()));
      w.create(lb, feat);
      OGREnvelope env;
      ls->getEnvelope(&env);
      chain_boxes.push_back({static_cast<std::int64_t>(i + 1), env.MinX, env.MaxX, env.MinY, env.MaxY});
    }
  }
  {
    OGRFeature feat(lr->GetLayerDefn());
    for (std::size_t i = 0; i < o.repairs.size(); ++i) {
      const RepairRow& r = o.repairs[i];
      feat.SetGeometryDirectly(new OGRPoint(r.x, r.y));
      feat.SetFID(static_cast<GIntBig>(i + 1));
      feat.SetField(0, r.kind.c_str());
      set_real_or_null(feat, 1, r.size);
      feat.SetField(2, r.reason.c_str());
      feat.SetField(3, r.part);
      w.create(lr, feat);
      if (std::isfinite(r.x) && std::isfinite(r.y)) repair_boxes.push_back({static_cast<std::int64_t>(i + 1), r.x, r.x, r.y, r.y});
    }
  }
  {
    OGRFeature feat(lm->GetLayerDefn());
    GIntBig fid = 0;
    auto row = [&](const std::string& k, const std::string& v) {
      feat.SetFID(++fid);
      feat.SetField(0, k.c_str());
      feat.SetField(1, v.c_str());
      w.create(lm, feat);
    };
    bool has_title = false, has_b = false;
    for (const auto& [k, v] : o.metadata) {
      has_title |= k == "title";
      has_b |= k == "bound_B";
      row(k, v);
    }
    if (!has_title && !o.title.empty()) row("title", o.title);
    if (!has_b && o.bound_B > 0) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", o.bound_B);
      row("bound_B", buf);
    }
  }
  if (index) {
    build_gpkg_rtree(*ds, "nodes", std::move(node_boxes), path, errs);
    build_gpkg_rtree(*ds, "triangles", std::move(tri_boxes), path, errs);
    build_gpkg_rtree(*ds, "boundaries", std::move(chain_boxes), path, errs);
    build_gpkg_rtree(*ds, "repairs", std::move(repair_boxes), path, errs);
  }
  if (ds->CommitTransaction() != OGRERR_NONE) w.fail("cannot commit the transaction");
  GDALDataset* raw = ds.release();
  GDALClose(raw);
  if (errs.any()) w.fail("closing the GeoPackage failed");
  tf.commit();
}

}  // namespace fdr::io::detail
