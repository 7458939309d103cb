// Helpers for the pipeline tests: temp folders, mesh area, parity area of a PSLG, rasters.
#pragma once
#include <gdal_priv.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "mesh/mesh_view.hpp"
#include "pipeline/gis_stage.hpp"
#include "pslg/pslg.hpp"

namespace fdr::pipeline::testing_util {

// A fresh folder under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  explicit TempDir(const std::string& tag) {
    std::string tmpl = (std::filesystem::temp_directory_path() / ("fdr_pipe_" + tag + "_XXXXXX")).string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  std::string file(const std::string& name) const { return path_ + "/" + name; }
  // Names of every file in the folder (recursively, relative paths).
  std::set<std::string> list() const {
    std::set<std::string> s;
    for (const auto& e : std::filesystem::recursive_directory_iterator(path_))
      s.insert(std::filesystem::relative(e.path(), path_).string());
    return s;
  }

 private:
  std::string path_;
};

// Sum of signed triangle areas (Neumaier-compensated), in the mesh's frame.
inline double mesh_area(const mesh::MeshView& m) {
  double sum = 0, c = 0;
  for (const auto& t : m.triangles) {
    const Point2 a = m.vertices[t[0]], b = m.vertices[t[1]], d = m.vertices[t[2]];
    const double x = 0.5 * ((b.x - a.x) * (d.y - a.y) - (b.y - a.y) * (d.x - a.x));
    const double s = sum + x;
    c += std::fabs(sum) >= std::fabs(x) ? (sum - s) + x : (x - s) + sum;
    sum = s;
  }
  return sum + c;
}

// Area of the region enclosed by the PSLG's boundary segments by the even-odd rule, computed
// independently of the triangulator: in each vertical slab between consecutive vertex
// x-coordinates no two segments cross (the PSLG is clean), so sorting the segments by their y
// at the slab's middle and pairing them (1st-2nd, 3rd-4th, ...) gives the inside intervals;
// each pair bounds a trapezoid of area dx * (difference of the mid-slab y values).
inline double parity_area(const pslg::Pslg& g) {
  struct Seg {
    Point2 p, q;  // p.x < q.x
  };
  std::vector<Seg> segs;
  std::vector<double> xs;
  for (const auto& s : g.segments) {
    if (!s.is_boundary()) continue;
    Point2 p = g.points[s.a], q = g.points[s.b];
    if (p.x == q.x) continue;  // vertical: no area in any slab
    if (q.x < p.x) std::swap(p, q);
    segs.push_back({p, q});
    xs.push_back(p.x);
    xs.push_back(q.x);
  }
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  std::sort(segs.begin(), segs.end(), [](const Seg& a, const Seg& b) { return a.p.x < b.p.x; });
  std::vector<Seg> active;
  std::vector<double> ys;
  std::size_t next = 0;
  double area = 0;
  for (std::size_t k = 0; k + 1 < xs.size(); ++k) {
    const double x0 = xs[k], x1 = xs[k + 1], xm = 0.5 * (x0 + x1);
    while (next < segs.size() && segs[next].p.x <= x0) active.push_back(segs[next++]);
    active.erase(std::remove_if(active.begin(), active.end(), [&](const Seg& s) { return s.q.x <= x0; }), active.end());
    ys.clear();
    for (const Seg& s : active) ys.push_back(s.p.y + (s.q.y - s.p.y) * ((xm - s.p.x) / (s.q.x - s.p.x)));
    if (ys.size() % 2) throw std::runtime_error("parity_area: odd number of boundary segments over a slab");
    std::sort(ys.begin(), ys.end());
    double w = 0;
    for (std::size_t i = 0; i + 1 < ys.size(); i += 2) w += ys[i + 1] - ys[i];
    area += w * (x1 - x0);
  }
  return area;
}

// A numeric metadata value of a prepared GIS input (throws if missing).
inline double metadata_double(const PreparedInput& in, const std::string& key) {
  for (const auto& [k, v] : in.metadata)
    if (k == key) return std::stod(v);
  throw std::runtime_error("metadata key missing: " + key);
}

// A GeoTIFF in EPSG:4326 whose every cell is nodata (-9999).
inline void write_nodata_raster(const std::string& path, double west, double south, double cell, int nx, int ny) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = drv->Create(path.c_str(), nx, ny, 1, GDT_Float32, nullptr);
  double gt[6] = {west, cell, 0, south + cell * ny, 0, -cell};
  ds->SetGeoTransform(gt);
  OGRSpatialReference srs;
  srs.importFromEPSG(4326);
  ds->SetSpatialRef(&srs);
  GDALRasterBand* b = ds->GetRasterBand(1);
  b->SetNoDataValue(-9999);
  std::vector<float> v(static_cast<std::size_t>(nx) * ny, -9999.0f);
  if (b->RasterIO(GF_Write, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0) != CE_None)
    throw std::runtime_error("write_nodata_raster failed");
  GDALClose(ds);
}

}  // namespace fdr::pipeline::testing_util
