// The water of a global run: land polygons joined across the antimeridian and subtracted from the
// coast of the land mass holding the pole, in the stereographic plane (global_domain.hpp).
#include "gis/global_domain.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <type_traits>

#include <cpl_error.h>
#include <ogr_api.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>

#include "coast/convex.hpp"
#include "base/error.hpp"
#include "base/step_laps.hpp"
#include "gis/gdal_util.hpp"
#include "gis/global_generalise.hpp"
#include "gis/global_land.hpp"
#include "gis/vector_layers.hpp"

namespace fdr::gis {

namespace {

bool same(LonLat a, LonLat b) { return a.lon_deg == b.lon_deg && a.lat_deg == b.lat_deg; }

LonLat sphere_point(LonLat p) {
  if (p.lat_deg <= -90.0) return {0.0, -90.0};
  if (p.lat_deg >= 90.0) return {0.0, 90.0};
  if (p.lon_deg == -180.0) p.lon_deg = 180.0;
  return p;
}

std::string at(LonLat p) { return "(" + num(p.lon_deg) + ", " + num(p.lat_deg) + ")"; }

// Signed area on the sphere of a ring of the plane (counter-clockwise positive): the sum of the
// spherical triangles (projection centre, a, b), none of which comes near the centre's antipode.
double sphere_ring_area(const std::vector<Point2>& ring, const SphereStereo& proj) {
  const Point3 c = unit_vector(proj.centre());
  double a = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i)
    a += spherical_triangle_area(c, unit_vector(proj.inverse(ring[i])), unit_vector(proj.inverse(ring[(i + 1) % n])),
                                 proj.radius());
  return a;
}

struct LandRing {
  std::int64_t fid;
  std::vector<LonLat> ll;  // as read
  bool holds_pole = false;
};

// Every land polygon's exterior ring in lon/lat (WGS 84, traditional order); holes counted.
std::vector<LandRing> land_rings(LayerData& L, LonLat pole, GlobalWater& out) {
  OGRSpatialReference ll;
  ll.importFromEPSG(4326);
  ll.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  std::vector<LandRing> rings;
  for (auto& f : L.features) {
    if (!L.srs.IsSame(&ll)) {
      f.geom->assignSpatialReference(&L.srs);
      if (f.geom->transformTo(&ll) != OGRERR_NONE)
        throw Error(ExitCode::kCrsError, L.label() + ", feature FID " + std::to_string(f.fid) +
                                             ": cannot transform to WGS 84 lon/lat");
    }
    std::vector<const OGRPolygon*> ps;
    if (const OGRGeometry* bad = collect_polygons(f.geom.get(), ps))
      throw Error(ExitCode::kInvalidGeometry, L.label() + ", feature FID " + std::to_string(f.fid) + " " +
                                                  where_str(bad) + ": geometry is " + bad->getGeometryName() +
                                                  ", expected Polygon or MultiPolygon");
    for (const OGRPolygon* p : ps) {
      if (p->IsEmpty()) continue;
      ++out.land_polygons;
      out.land_holes_filled += static_cast<std::size_t>(p->getNumInteriorRings());
      LandRing r{f.fid, {}, false};
      for (const Point2& q : curve_points(p->getExteriorRing())) r.ll.push_back({q.x, q.y});
      if (r.ll.size() >= 2 && same(r.ll.front(), r.ll.back())) r.ll.pop_back();
      r.holds_pole = ring_holds_pole(r.ll, pole);
      rings.push_back(std::move(r));
    }
  }
  return rings;
}

// The ring (cleaned, densified) in the plane.
std::vector<Point2> plane_ring(const LandRing& r, const SphereStereo& proj, const std::string& label) {
  std::vector<Point2> pts;
  pts.reserve(r.ll.size());
  for (const LonLat& p : r.ll) {
    const Point2 q = proj.forward(p);
    if (!std::isfinite(q.x) || !std::isfinite(q.y) || std::max(std::fabs(q.x), std::fabs(q.y)) > 1e3 * proj.radius())
      throw Error(ExitCode::kInvalidGeometry,
                  label + ", feature FID " + std::to_string(r.fid) + ": vertex " + at(p) + " lies at the pole " +
                      at(proj.pole()) + " of the projection" +
                      (r.holds_pole ? ": the coast of the land holding the pole reaches it; give --pole inside that land"
                                    : ": only the land holding the pole may contain it"));
    pts.push_back(q);
  }
  return pts;
}

// water minus the disjoint land: land inside it becomes holes directly, land crossing its
// boundary is subtracted with GEOS, land outside it (inside the pole's land mass) is dropped.
std::unique_ptr<OGRGeometry> subtract_land(std::unique_ptr<OGRGeometry> water,
                                           std::vector<std::unique_ptr<OGRPolygon>> land, const std::string& what) {
  std::vector<std::unique_ptr<OGRPolygon>> inside;
  OGRMultiPolygon crossing;
  {
    const PreparedPtr pw(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(water.get())));
    for (auto& q : land) {
      OGRGeometryH h = OGRGeometry::ToHandle(q.get());
      if (OGRPreparedGeometryContains(pw.get(), h)) inside.push_back(std::move(q));
      else if (OGRPreparedGeometryIntersects(pw.get(), h)) crossing.addGeometry(q.get());
    }
  }
  if (!crossing.IsEmpty()) {
    water.reset(water->Difference(&crossing));
    if (!water) throw Error(ExitCode::kInvalidGeometry, what + " failed: " + CPLGetLastErrorMsg());
  }
  std::vector<const OGRPolygon*> ps;
  collect_polygons(water.get(), ps);
  std::vector<std::unique_ptr<OGRPolygon>> parts;
  std::vector<PreparedPtr> prepared;
  std::vector<OGREnvelope> envs(ps.size());
  for (std::size_t k = 0; k < ps.size(); ++k) {
    parts.emplace_back(ps[k]->clone());
    parts[k]->getEnvelope(&envs[k]);
    prepared.emplace_back(OGRCreatePreparedGeometry(OGRGeometry::ToHandle(parts[k].get())));
  }
  for (auto& q : inside) {
    OGREnvelope e;
    q->getEnvelope(&e);
    for (std::size_t k = 0; k < parts.size(); ++k)
      if (envs[k].Contains(e) && OGRPreparedGeometryContains(prepared[k].get(), OGRGeometry::ToHandle(q.get()))) {
        parts[k]->addRing(q->getExteriorRing());
        break;
      }
  }
  auto result = std::make_unique<OGRMultiPolygon>();
  for (auto& p : parts) result->addGeometryDirectly(p.release());
  return result;
}

}  // namespace

std::vector<LonLat> sphere_ring(std::vector<LonLat> ring) {
  std::vector<LonLat> out;
  out.reserve(ring.size());
  for (LonLat p : ring) {
    p = sphere_point(p);
    if (!out.empty() && same(out.back(), p)) continue;
    if (out.size() >= 2 && same(out[out.size() - 2], p)) {  // a -> b -> a: b is a spike's tip
      out.pop_back();
      continue;
    }
    out.push_back(p);
  }
  // The same across the ring's start.
  for (bool changed = true; changed && out.size() >= 2;) {
    changed = false;
    const std::size_t n = out.size();
    if (same(out.front(), out.back())) {
      out.pop_back();
      changed = true;
    } else if (n >= 3 && same(out[n - 1], out[1])) {
      out.erase(out.begin(), out.begin() + 2);
      changed = true;
    } else if (n >= 3 && same(out[n - 2], out[0])) {
      out.resize(n - 2);
      changed = true;
    }
  }
  if (out.size() < 3) out.clear();
  return out;
}

bool ring_holds_pole(const std::vector<LonLat>& ring, LonLat pole) {
  if (std::fabs(pole.lat_deg) >= 90.0)
    return std::any_of(ring.begin(), ring.end(), [&](LonLat p) {
      return pole.lat_deg < 0 ? p.lat_deg <= -90.0 : p.lat_deg >= 90.0;
    });
  bool in = false;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const LonLat a = ring[i], b = ring[(i + 1) % n];
    if ((a.lat_deg > pole.lat_deg) == (b.lat_deg > pole.lat_deg)) continue;
    const double x = a.lon_deg + (pole.lat_deg - a.lat_deg) / (b.lat_deg - a.lat_deg) * (b.lon_deg - a.lon_deg);
    if (pole.lon_deg < x) in = !in;
  }
  return in;
}

std::size_t densify_lonlat(std::vector<LonLat>& ring, double step) {
  if (!(step > 0) || ring.size() < 2) return 0;
  std::vector<LonLat> out;
  out.reserve(ring.size());
  std::size_t added = 0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const LonLat a = ring[i];
    LonLat b = ring[(i + 1) % n];
    out.push_back(a);
    // An edge across the antimeridian (179.9 -> -179.9) is the short way round, not 359.8 degrees.
    if (b.lon_deg - a.lon_deg > 180.0) b.lon_deg -= 360.0;
    if (a.lon_deg - b.lon_deg > 180.0) b.lon_deg += 360.0;
    const double span = std::max(std::fabs(b.lon_deg - a.lon_deg), std::fabs(b.lat_deg - a.lat_deg));
    if (!(span > step)) continue;
    const int k = static_cast<int>(std::min(std::ceil(span / step), 1e5));
    for (int j = 1; j < k; ++j) {
      const double t = static_cast<double>(j) / k;
      double lon = a.lon_deg + (b.lon_deg - a.lon_deg) * t;
      if (lon > 180.0) lon -= 360.0;
      if (lon < -180.0) lon += 360.0;
      out.push_back({lon, a.lat_deg + (b.lat_deg - a.lat_deg) * t});
    }
    added += static_cast<std::size_t>(k - 1);
  }
  ring = std::move(out);
  return added;
}

namespace {

// The land holding the pole: the largest (most vertices) of the rings that hold it.
std::size_t pole_ring(const std::vector<LandRing>& rings) {
  std::size_t pole = rings.size();
  for (std::size_t i = 0; i < rings.size(); ++i)
    if (rings[i].holds_pole && (pole == rings.size() || rings[i].ll.size() > rings[pole].ll.size())) pole = i;
  return pole;
}

// The sphere minus the land `rings` (cleaned and densified, rings[pole] the outer coast) in the
// plane, as polygons (outer counter-clockwise, holes clockwise); its area on the sphere.
std::vector<std::vector<std::vector<Point2>>> water_polygons(const std::vector<LandRing>& rings, std::size_t pole,
                                                             const SphereStereo& proj, const std::string& label,
                                                             double& area, StepLaps& lap) {
  std::vector<std::unique_ptr<OGRPolygon>> others;
  std::vector<Point2> coast;
  for (std::size_t i = 0; i < rings.size(); ++i) {
    std::vector<Point2> pr = plane_ring(rings[i], proj, label);
    if (i == pole) {
      coast = std::move(pr);
      continue;
    }
    const OGRPolygon poly = plane_polygon(pr);
    std::unique_ptr<OGRGeometry> v = valid_copy(poly, label + ", feature FID " + std::to_string(rings[i].fid));
    std::vector<const OGRPolygon*> ps;
    collect_polygons(v.get(), ps);
    for (const OGRPolygon* p : ps) others.emplace_back(p->clone());
  }
  lap("rings");
  const std::int64_t fid = rings[pole].fid;
  if (coast.size() < 3)
    throw Error(ExitCode::kInvalidGeometry,
                label + ", feature FID " + std::to_string(fid) + ": the land holding the pole has no coast left on the sphere");
  const std::string what = label + ": the sphere minus land";
  std::unique_ptr<OGRGeometry> water =
      valid_copy(plane_polygon(coast), what + " (outer coast, FID " + std::to_string(fid) + ")");
  std::vector<std::unique_ptr<OGRPolygon>> pieces = disjoint_land(std::move(others), label);
  lap("union");
  water = subtract_land(std::move(water), std::move(pieces), what);
  lap("difference");
  std::vector<const OGRPolygon*> ps;
  collect_polygons(water.get(), ps);
  if (ps.empty()) throw Error(ExitCode::kInvalidGeometry, label + ": the land covers the whole sphere");
  std::vector<std::vector<std::vector<Point2>>> out;
  area = 0;
  for (const OGRPolygon* p : ps) {
    out.emplace_back();
    for (const OGRLinearRing* r : *p) {
      std::vector<Point2> pts = curve_points(r);
      if (pts.size() >= 2 && pts.front() == pts.back()) pts.pop_back();
      if (pts.size() < 3) continue;
      const bool hole = !out.back().empty();
      const double a = std::fabs(sphere_ring_area(pts, proj));
      area += hole ? -a : a;
      if ((coast::signed_area(pts) > 0) == hole) std::reverse(pts.begin(), pts.end());  // outer CCW, holes CW
      out.back().push_back(std::move(pts));
    }
    if (out.back().empty()) out.pop_back();
  }
  lap("rings out");
  return out;
}

// The land generalised in ground metres (global_generalise.hpp) as rings of the pole's feature
// (the ring holding the pole) or of no feature.
std::vector<LandRing> generalised_rings(const std::vector<LandRing>& rings, std::size_t pole, const SphereStereo& proj,
                                        const coast::Options& o, double step, GlobalWater& out) {
  std::vector<std::vector<LonLat>> ll;
  ll.reserve(rings.size());
  for (const LandRing& r : rings) ll.push_back(r.ll);
  GeneralisedLand g = generalise_land(ll, proj.pole(), o, step);
  out.groups = g.groups;
  out.batches = g.batches;
  out.max_batch_scale = g.max_scale;
  out.features = std::move(g.result);
  std::vector<LandRing> res;
  for (std::size_t k = 0; k < g.rings.size(); ++k) {
    LandRing r{g.holds_pole[k] ? rings[pole].fid : -1, sphere_ring(std::move(g.rings[k])), g.holds_pole[k] != 0};
    if (r.ll.size() >= 3) res.push_back(std::move(r));
  }
  return res;
}

}  // namespace

GlobalWater global_water(const LayerRef& land, const std::string& s_srs, const SphereStereo& proj, double step,
                         const coast::Options* generalise) {
  StepLaps lap(debug::Aid::kFilter, "global water");
  LayerData L = read_layer(land, s_srs, "--land");
  lap("read");
  GlobalWater out;
  out.file = L.file;
  out.layer = L.layer;
  std::vector<LandRing> rings = land_rings(L, proj.pole(), out);
  if (pole_ring(rings) == rings.size())
    throw Error(ExitCode::kInvalidGeometry, L.label() + ": no land polygon holds the pole " + at(proj.pole()) +
                                                " of the projection; give --pole LON,LAT inside the land that bounds "
                                                "the ocean (Antarctica)");
  // Every ring as the sphere sees it, with points along its long lon/lat edges.
  std::vector<LandRing> clean;
  for (LandRing& r : rings) {
    if (std::any_of(r.ll.begin(), r.ll.end(), [](LonLat p) { return std::fabs(p.lon_deg) == 180.0; }))
      ++out.antimeridian_rings;
    r.ll = sphere_ring(std::move(r.ll));
    if (r.ll.size() < 3) continue;
    out.densify_points += densify_lonlat(r.ll, step);
    clean.push_back(std::move(r));
  }
  const std::size_t pole = pole_ring(clean);
  if (pole == clean.size())
    throw Error(ExitCode::kInvalidGeometry, L.label() + ": the land holding the pole " + at(proj.pole()) +
                                                " has no coast left on the sphere");
  out.pole_fid = clean[pole].fid;
  GdalQuiet quiet;
  out.polygons = water_polygons(clean, pole, proj, L.label(), out.water_area_m2, lap);
  if (!generalise) return out;
  std::vector<LandRing> gen = generalised_rings(clean, pole, proj, *generalise, step, out);
  lap("generalise");
  const std::size_t gpole = pole_ring(gen);
  if (gpole == gen.size())
    throw Error(ExitCode::kInvalidGeometry, L.label() + ": the generalised land holding the pole " + at(proj.pole()) +
                                                " has no coast left");
  out.input_polygons = std::move(out.polygons);
  out.input_area_m2 = out.water_area_m2;
  out.polygons = water_polygons(gen, gpole, proj, L.label() + " (generalised)", out.water_area_m2, lap);
  out.features.input_pieces = out.input_polygons.size();
  out.features.output_pieces = out.polygons.size();
  for (auto& rep : out.features.repairs) rep.where = proj.forward({rep.where.x, rep.where.y});
  return out;
}

}  // namespace fdr::gis
