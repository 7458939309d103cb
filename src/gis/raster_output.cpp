// Raster output: sizing::Grid -> Float32 GeoTIFF in the frame's CRS, written atomically.
#include "gis/raster_output.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <unistd.h>

#include <gdal_priv.h>

#include "base/error.hpp"
#include "gis/gdal_util.hpp"

namespace fdr::gis {

void write_grid_geotiff(const sizing::Grid& g, const Frame& frame, const std::string& path) {
  ensure_gdal_registered();
  if (g.nx == 0 || g.ny == 0 || g.v.size() != g.nx * g.ny)
    throw Error(ExitCode::kInternal, path + ": grid to write is empty or inconsistent");
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!drv) throw Error(ExitCode::kOutputError, path + ": GDAL has no GTiff driver");
  const std::string tmp = path + ".tmp" + std::to_string(::getpid()) + ".tif";
  GdalQuiet quiet;
  CPLErrorReset();
  {
    char** opts = nullptr;
    opts = CSLSetNameValue(opts, "COMPRESS", "DEFLATE");
    opts = CSLSetNameValue(opts, "TILED", "YES");
    DatasetPtr ds(drv->Create(tmp.c_str(), static_cast<int>(g.nx), static_cast<int>(g.ny), 1, GDT_Float32, opts));
    CSLDestroy(opts);
    if (!ds) throw Error(ExitCode::kOutputError, path + ": cannot create: " + CPLGetLastErrorMsg());
    const Point2 o = frame.origin();
    double gt[6] = {o.x + g.x0, g.dx, 0, o.y + g.y0 + static_cast<double>(g.ny) * g.dy, 0, -g.dy};
    ds->SetGeoTransform(gt);
    ds->SetSpatialRef(&frame.srs());
    GDALRasterBand* b = ds->GetRasterBand(1);
    b->SetNoDataValue(std::numeric_limits<double>::quiet_NaN());
    std::vector<float> row(g.nx);
    CPLErr err = CE_None;
    // GeoTIFF rows run north to south; Grid row 0 is the southern one.
    for (std::size_t r = 0; r < g.ny && err == CE_None; ++r) {
      const std::size_t j = g.ny - 1 - r;
      for (std::size_t i = 0; i < g.nx; ++i) row[i] = static_cast<float>(g.at(i, j));
      err = b->RasterIO(GF_Write, 0, static_cast<int>(r), static_cast<int>(g.nx), 1, row.data(),
                        static_cast<int>(g.nx), 1, GDT_Float32, 0, 0);
    }
    if (err == CE_None) ds->FlushCache();
    if (err != CE_None) {
      std::string msg = CPLGetLastErrorMsg();
      ds.reset();
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Error(ExitCode::kOutputError, path + ": write failed: " + msg);
    }
    CPLErrorReset();
    ds.reset();  // GDALClose writes the remaining blocks
    if (CPLGetLastErrorType() >= CE_Failure) {
      std::error_code ec;
      std::filesystem::remove(tmp, ec);
      throw Error(ExitCode::kOutputError, path + ": closing failed: " + CPLGetLastErrorMsg());
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw Error(ExitCode::kOutputError, path + ": cannot rename the temporary file: " + ec.message());
  }
}

}  // namespace fdr::gis
