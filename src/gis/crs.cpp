// Frame implementation: CRS choice (UTM / centred TM), OGR transformations, PROJ scale factors.
#include "gis/crs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <mutex>
#include <sstream>

#include <cpl_conv.h>
#include <ogr_spatialref.h>
#include <proj.h>

#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::gis {

namespace {

struct OctDeleter {
  void operator()(OGRCoordinateTransformation* t) const { OGRCoordinateTransformation::DestroyCT(t); }
};
using OctPtr = std::unique_ptr<OGRCoordinateTransformation, OctDeleter>;

OGRSpatialReference wgs84_lonlat() {
  OGRSpatialReference s;
  s.importFromEPSG(4326);
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return s;
}

std::string fmt(double v, int prec = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", prec, v);
  return buf;
}

}  // namespace

struct Frame::Impl {
  OGRSpatialReference srs;
  OGRSpatialReference lonlat = wgs84_lonlat();
  std::string name;
  Point2 origin;
  OctPtr to_ll;    // frame -> WGS 84 lon/lat
  OctPtr from_ll;  // WGS 84 lon/lat -> frame
  PJ_CONTEXT* ctx = nullptr;
  PJ* pj_crs = nullptr;   // the projected CRS
  PJ* pj_conv = nullptr;  // its conversion as a PROJ pipeline (proj_factors on a CRS rebuilds it per call)
  PJ* pj_geog = nullptr;  // frame -> its own base geographic CRS, lon/lat degrees
  mutable std::mutex mu;  // OGR/PROJ transformation objects are not thread-safe

  ~Impl() {
    if (pj_geog) proj_destroy(pj_geog);
    if (pj_conv) proj_destroy(pj_conv);
    if (pj_crs) proj_destroy(pj_crs);
    if (ctx) proj_context_destroy(ctx);
  }
};

Frame::Frame() = default;
Frame::~Frame() = default;
Frame::Frame(const Frame&) = default;
Frame& Frame::operator=(const Frame&) = default;
Frame::Frame(Frame&&) noexcept = default;
Frame& Frame::operator=(Frame&&) noexcept = default;

bool Frame::valid() const { return impl_ != nullptr; }

static void require(const Frame& f) {
  if (!f.valid()) throw Error(ExitCode::kInternal, "gis::Frame used before choose_frame()");
}

const std::string& Frame::name() const { require(*this); return impl_->name; }

std::string Frame::wkt() const {
  require(*this);
  char* w = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  impl_->srs.exportToWkt(&w, opts);
  std::string s = w ? w : "";
  CPLFree(w);
  return s;
}

std::string Frame::projjson() const {
  require(*this);
  char* w = nullptr;
  impl_->srs.exportToPROJJSON(&w, nullptr);
  std::string s = w ? w : "";
  CPLFree(w);
  return s;
}

int Frame::epsg() const {
  require(*this);
  const char* auth = impl_->srs.GetAuthorityName(nullptr);
  const char* code = impl_->srs.GetAuthorityCode(nullptr);
  if (auth && code && std::string(auth) == "EPSG") return std::atoi(code);
  return 0;
}

const OGRSpatialReference& Frame::srs() const { require(*this); return impl_->srs; }
Point2 Frame::origin() const { require(*this); return impl_->origin; }
Box2 Frame::domain_box() const { return domain_box_; }
void Frame::set_domain_box(const Box2& b) { domain_box_ = b; }

Point2 Frame::to_local(double x, double y, const OGRSpatialReference& src) const {
  std::vector<Point2> v{{x, y}};
  to_local_batch(v, src, "point");
  return v[0];
}

void Frame::to_local_batch(std::vector<Point2>& xy, const OGRSpatialReference& src,
                           const std::string& what) const {
  require(*this);
  if (xy.empty()) return;
  OGRSpatialReference s(src);
  s.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const Point2 o = impl_->origin;
  if (s.IsSame(&impl_->srs)) {
    for (auto& p : xy) p = p - o;
    return;
  }
  OctPtr ct(OGRCreateCoordinateTransformation(&s, &impl_->srs));
  if (!ct) throw Error(ExitCode::kCrsError, what + ": no transformation from its CRS to " + impl_->name);
  std::vector<double> x(xy.size()), y(xy.size());
  for (std::size_t i = 0; i < xy.size(); ++i) { x[i] = xy[i].x; y[i] = xy[i].y; }
  std::vector<int> ok(xy.size(), 0);
  ct->Transform(static_cast<int>(xy.size()), x.data(), y.data(), nullptr, ok.data());
  for (std::size_t i = 0; i < xy.size(); ++i) {
    if (!ok[i] || !std::isfinite(x[i]) || !std::isfinite(y[i]))
      throw Error(ExitCode::kCrsError, what + ": cannot transform (" + fmt(xy[i].x, 9) + ", " +
                                           fmt(xy[i].y, 9) + ") to " + impl_->name);
    xy[i] = Point2{x[i], y[i]} - o;
  }
}

Point2 Frame::lonlat_to_local(LonLat ll) const {
  require(*this);
  double x = ll.lon_deg, y = ll.lat_deg;
  std::lock_guard<std::mutex> lock(impl_->mu);
  if (!impl_->from_ll->Transform(1, &x, &y))
    throw Error(ExitCode::kCrsError, "cannot project (" + fmt(ll.lon_deg) + ", " + fmt(ll.lat_deg) +
                                         ") to " + impl_->name);
  return Point2{x, y} - impl_->origin;
}

LonLat Frame::to_lonlat(Point2 local) const {
  require(*this);
  Point2 w = to_world(local);
  double x = w.x, y = w.y;
  std::lock_guard<std::mutex> lock(impl_->mu);
  if (!impl_->to_ll->Transform(1, &x, &y)) return {std::nan(""), std::nan("")};
  return {x, y};
}

double Frame::scale_factor(Point2 local) const {
  require(*this);
  const Point2 w = to_world(local);
  std::lock_guard<std::mutex> lock(impl_->mu);
  // proj_factors() wants longitude/latitude (radians) of the projected CRS's own base CRS.
  PJ_COORD c = proj_coord(w.x, w.y, 0, 0);
  PJ_COORD g = proj_trans(impl_->pj_geog, PJ_FWD, c);
  if (!std::isfinite(g.lp.lam) || !std::isfinite(g.lp.phi)) return std::nan("");
  PJ_COORD lp = proj_coord(proj_torad(g.lp.lam), proj_torad(g.lp.phi), 0, 0);
  PJ* P = impl_->pj_conv ? impl_->pj_conv : impl_->pj_crs;
  PJ_FACTORS f = proj_factors(P, lp);
  if (proj_errno(P) != 0) {
    proj_errno_reset(P);
    return std::nan("");
  }
  if (f.angular_distortion < 1e-12) return f.meridional_scale;  // conformal: h == k
  return std::sqrt(f.areal_scale);
}

namespace {

std::shared_ptr<Frame::Impl> make_impl(const OGRSpatialReference& srs_in, const std::string& what) {
  auto impl = std::make_shared<Frame::Impl>();
  impl->srs = srs_in;
  impl->srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!impl->srs.IsProjected())
    throw Error(ExitCode::kCrsError, what + ": the working CRS must be projected (metres), got '" +
                                         std::string(impl->srs.GetName() ? impl->srs.GetName() : "?") + "'");
  const double unit = impl->srs.GetLinearUnits(nullptr);
  if (std::abs(unit - 1.0) > 1e-12)
    throw Error(ExitCode::kCrsError, what + ": the working CRS must use metres (its unit is " +
                                         fmt(unit, 6) + " m)");
  std::string name = impl->srs.GetName() ? impl->srs.GetName() : "projected CRS";
  const char* auth = impl->srs.GetAuthorityName(nullptr);
  const char* code = impl->srs.GetAuthorityCode(nullptr);
  if (auth && code) name += std::string(" (") + auth + ":" + code + ")";
  impl->name = name;
  impl->to_ll.reset(OGRCreateCoordinateTransformation(&impl->srs, &impl->lonlat));
  impl->from_ll.reset(OGRCreateCoordinateTransformation(&impl->lonlat, &impl->srs));
  if (!impl->to_ll || !impl->from_ll)
    throw Error(ExitCode::kCrsError, what + ": no transformation between WGS 84 and " + name);

  impl->ctx = proj_context_create();
  char* wkt = nullptr;
  const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
  impl->srs.exportToWkt(&wkt, opts);
  impl->pj_crs = proj_create(impl->ctx, wkt ? wkt : "");
  CPLFree(wkt);
  if (!impl->pj_crs) throw Error(ExitCode::kCrsError, what + ": PROJ cannot read " + name);
  PJ* geog = proj_crs_get_geodetic_crs(impl->ctx, impl->pj_crs);
  PJ* op = geog ? proj_create_crs_to_crs_from_pj(impl->ctx, impl->pj_crs, geog, nullptr, nullptr) : nullptr;
  if (geog) proj_destroy(geog);
  if (op) {
    impl->pj_geog = proj_normalize_for_visualization(impl->ctx, op);  // lon, lat in degrees
    proj_destroy(op);
  }
  if (!impl->pj_geog) throw Error(ExitCode::kCrsError, what + ": PROJ cannot invert " + name);
  // The projection alone (geographic -> projected on the base ellipsoid) for proj_factors().
  if (const char* ps = proj_as_proj_string(impl->ctx, impl->pj_crs, PJ_PROJ_5, nullptr)) {
    std::string p = ps;
    const auto t = p.find(" +type=crs");
    if (t != std::string::npos) p.erase(t, 10);
    impl->pj_conv = proj_create(impl->ctx, p.c_str());
    if (impl->pj_conv && proj_get_type(impl->pj_conv) != PJ_TYPE_CONVERSION &&
        proj_get_type(impl->pj_conv) != PJ_TYPE_OTHER_COORDINATE_OPERATION) {
      proj_destroy(impl->pj_conv);
      impl->pj_conv = nullptr;
    }
  }
  return impl;
}

// A round-number origin near c: rounding step 10^(floor(log10(diameter)) - 1), within [1, 1000] m.
Point2 round_origin(Point2 c, double diameter) {
  double step = std::pow(10.0, std::floor(std::log10(std::max(diameter, 1.0))) - 1.0);
  step = std::clamp(step, 1.0, 1000.0);
  return {std::round(c.x / step) * step, std::round(c.y / step) * step};
}

}  // namespace

Frame Frame::from_crs(const std::string& crs, Point2 origin) {
  OGRSpatialReference srs;
  GdalQuiet quiet;  // our ERROR 9 line, not GDAL's own
  if (srs.SetFromUserInput(crs.c_str()) != OGRERR_NONE)
    throw Error(ExitCode::kCrsError, "--t_srs '" + crs + "': unknown CRS");
  Frame f;
  f.impl_ = make_impl(srs, "--t_srs '" + crs + "'");
  f.impl_->origin = origin;
  return f;
}

Frame choose_frame(const std::vector<LonLat>& sample, const std::string& t_srs) {
  if (sample.empty()) throw Error(ExitCode::kInvalidGeometry, "cannot choose a working CRS: the domain has no points");
  double lon_min = 1e300, lon_max = -1e300, lat_min = 1e300, lat_max = -1e300;
  for (const auto& p : sample) {
    lon_min = std::min(lon_min, p.lon_deg); lon_max = std::max(lon_max, p.lon_deg);
    lat_min = std::min(lat_min, p.lat_deg); lat_max = std::max(lat_max, p.lat_deg);
  }
  bool shifted = false;
  // A domain straddling the antimeridian looks > 180 degrees wide in -180..180: measure it in 0..360.
  if (lon_max - lon_min > 180.0) {
    double a = 1e300, b = -1e300;
    for (const auto& p : sample) {
      const double l = p.lon_deg < 0 ? p.lon_deg + 360.0 : p.lon_deg;
      a = std::min(a, l); b = std::max(b, l);
    }
    if (b - a < lon_max - lon_min) { lon_min = a; lon_max = b; shifted = true; }
  }
  double lon_c = 0.5 * (lon_min + lon_max);
  if (shifted && lon_c > 180.0) lon_c -= 360.0;
  const double lat_c = 0.5 * (lat_min + lat_max);
  const double width = lon_max - lon_min;

  OGRSpatialReference srs;
  std::string what;
  if (!t_srs.empty()) {
    GdalQuiet quiet;  // our ERROR 9 line, not GDAL's own
    if (srs.SetFromUserInput(t_srs.c_str()) != OGRERR_NONE)
      throw Error(ExitCode::kCrsError, "--t_srs '" + t_srs + "': unknown CRS");
    what = "--t_srs '" + t_srs + "'";
  } else if (width <= 6.0 && std::max(std::abs(lat_min), std::abs(lat_max)) < 84.0) {
    const int zone = std::clamp(static_cast<int>(std::floor((lon_c + 180.0) / 6.0)) + 1, 1, 60);
    srs.importFromEPSG((lat_c >= 0 ? 32600 : 32700) + zone);
    what = "UTM zone " + std::to_string(zone);
  } else {
    if (width > 120.0)
      throw Error(ExitCode::kCrsError, "the domain spans " + fmt(width, 1) +
                                           " degrees of longitude: too wide for an automatic projected CRS; give --t_srs");
    const double lon0 = std::round(lon_c * 100.0) / 100.0, lat0 = std::round(lat_c * 100.0) / 100.0;
    const std::string p = "+proj=tmerc +lat_0=" + fmt(lat0, 2) + " +lon_0=" + fmt(lon0, 2) +
                          " +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs +type=crs";
    srs.importFromProj4(p.c_str());
    srs.SetProjCS(("Transverse Mercator centred at " + fmt(lon0, 2) + ", " + fmt(lat0, 2)).c_str());
    what = p;
  }
  Frame f;
  f.impl_ = make_impl(srs, what);
  // The origin: the centre of the projected sample, rounded.
  Box2 world;
  for (const auto& p : sample) {
    double x = p.lon_deg, y = p.lat_deg;
    if (f.impl_->from_ll->Transform(1, &x, &y) && std::isfinite(x) && std::isfinite(y)) world.add({x, y});
  }
  if (world.empty())
    throw Error(ExitCode::kCrsError, "no domain point can be projected to " + f.impl_->name);
  const double diam = std::hypot(world.width(), world.height());
  f.impl_->origin = round_origin(world.center(), diam);
  f.domain_box_ = Box2{world.lo - f.impl_->origin, world.hi - f.impl_->origin};
  return f;
}

namespace {

// f_ground(p) * k(p), k bilinear on a precomputed regular grid (clamped outside it).
class GroundToGridField final : public sizing::SizingField {
 public:
  GroundToGridField(sizing::SizingPtr f, Box2 box, int n, std::vector<double> k, double max_dev, std::string frame)
      : f_(std::move(f)), box_(box), n_(n), k_(std::move(k)), max_dev_(max_dev), frame_(std::move(frame)) {
    // k is bilinear on cells of the node grid (constant beyond it): on a cell its gradient is
    // bounded by the cell's edge differences; |grad(f k)| <= L_f max k + max f L_k.
    const double dx = box_.width() / (n_ - 1), dy = box_.height() / (n_ - 1);
    double l2 = 0;
    for (int j = 0; j + 1 < n_; ++j)
      for (int i = 0; i + 1 < n_; ++i) {
        auto K = [&](int a, int b) { return k_[static_cast<std::size_t>(b) * n_ + a]; };
        const double ax = std::max(std::abs(K(i + 1, j) - K(i, j)), std::abs(K(i + 1, j + 1) - K(i, j + 1))) / dx;
        const double ay = std::max(std::abs(K(i, j + 1) - K(i, j)), std::abs(K(i + 1, j + 1) - K(i + 1, j))) / dy;
        l2 = std::max(l2, ax * ax + ay * ay);
      }
    const double kmax = *std::max_element(k_.begin(), k_.end());
    const double lf = f_->lipschitz(), uf = f_->upper_bound();
    lipschitz_ = lf >= 0 && std::isfinite(uf) ? lf * kmax + uf * std::sqrt(l2) : -1.0;
    upper_ = uf * kmax;
  }
  double operator()(Point2 p) const override { return (*f_)(p) * k_at(p); }
  double lipschitz() const override { return lipschitz_; }
  double upper_bound() const override { return upper_; }
  bool thread_safe() const override { return f_->thread_safe(); }
  std::string describe() const override {
    return f_->describe() + " * k (point scale factor of " + frame_ + ", max |k-1| = " + fmt(max_dev_, 6) + ")";
  }
  double k_at(Point2 p) const {
    const double u = std::clamp((p.x - box_.lo.x) / box_.width() * (n_ - 1), 0.0, double(n_ - 1));
    const double v = std::clamp((p.y - box_.lo.y) / box_.height() * (n_ - 1), 0.0, double(n_ - 1));
    const int i = std::min(static_cast<int>(u), n_ - 2), j = std::min(static_cast<int>(v), n_ - 2);
    const double s = u - i, t = v - j;
    auto K = [&](int a, int b) { return k_[static_cast<std::size_t>(b) * n_ + a]; };
    return (1 - t) * ((1 - s) * K(i, j) + s * K(i + 1, j)) + t * ((1 - s) * K(i, j + 1) + s * K(i + 1, j + 1));
  }

 private:
  sizing::SizingPtr f_;
  Box2 box_;
  int n_;
  std::vector<double> k_;
  double max_dev_;
  std::string frame_;
  double lipschitz_ = -1, upper_ = 0;
};

}  // namespace

sizing::SizingPtr ground_to_grid(sizing::SizingPtr f_ground, const Frame& frame, double* max_dev) {
  return ground_to_grid(std::move(f_ground), frame, frame.domain_box(), max_dev);
}

sizing::SizingPtr ground_to_grid(sizing::SizingPtr f_ground, const Frame& frame, const Box2& local_box,
                                 double* max_dev_out) {
  if (local_box.empty()) throw Error(ExitCode::kInternal, "ground_to_grid: empty domain box");
  Box2 box = local_box;
  const double mx = std::max(0.05 * box.width(), 1.0), my = std::max(0.05 * box.height(), 1.0);
  box.lo = box.lo - Point2{mx, my};
  box.hi = box.hi + Point2{mx, my};
  // k varies like (distance from the central line / R)^2: 65 x 65 nodes make the bilinear
  // interpolation error far below the 1e-3 threshold for any domain we accept.
  const int n = 65;
  std::vector<double> k(static_cast<std::size_t>(n) * n);
  double max_dev = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Point2 p{box.lo.x + box.width() * i / (n - 1), box.lo.y + box.height() * j / (n - 1)};
      const double kk = frame.scale_factor(p);
      if (!std::isfinite(kk) || kk <= 0) {
        const LonLat ll = frame.to_lonlat(p);
        throw Error(ExitCode::kCrsError, frame.name() + ": scale factor undefined at (" + fmt(ll.lon_deg) + ", " +
                                             fmt(ll.lat_deg) + "); the domain is outside the projection's valid area");
      }
      k[static_cast<std::size_t>(j) * n + i] = kk;
      max_dev = std::max(max_dev, std::abs(kk - 1.0));
    }
  if (max_dev_out) *max_dev_out = max_dev;
  if (max_dev <= 1e-3) return f_ground;
  return std::make_shared<GroundToGridField>(std::move(f_ground), box, n, std::move(k), max_dev, frame.name());
}

}  // namespace fdr::gis
