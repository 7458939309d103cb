#!/usr/bin/python3
"""Writes the terrain-volume test rasters of this folder (run from anywhere; GDAL and numpy).

- lux_h1.tif, lux_h2.tif: two synthetic horizons on the grid of ../luxembourg/elev.tif (EPSG:4326):
  h1 = 50 + 80 sin(2 pi (lon - 5.74) / 0.4) m, below the DEM (at least 141 m) and above h2 everywhere;
  h2 = -150 + 200 (lat - 49.8) m, a tilted plane.
- synthetic_dem.tif: 24 x 24 cells of 100 m in EPSG:32632 (UTM 32N) from (500000, 5500000) north-up,
  z = 300 + 40 sin(x / 500 m) cos(y / 700 m) + 0.02 x (x, y from the lower-left corner).
- synthetic_h1.tif: the same grid, z = 150 + 0.1 (x - 1200) m: meets the DEM nowhere.
- synthetic_pinch.tif: the same grid, z = 200 + 0.1 x m: above the DEM in the east (pinches out).
- synthetic_high.tif: the same grid, z = 1000 m everywhere: above the DEM.
- synthetic_nocrs.tif: synthetic_h1 without a CRS.
- synthetic_nodata.tif: the same grid, every cell nodata.
- synthetic_domain.geojson: a polygon inside the synthetic grid (EPSG:32632).
"""
import json
import os
import numpy as np
from osgeo import gdal, osr

gdal.UseExceptions()
HERE = os.path.dirname(os.path.abspath(__file__))


def write(name, z, gt, epsg, nodata=None):
    ds = gdal.GetDriverByName("GTiff").Create(os.path.join(HERE, name), z.shape[1], z.shape[0], 1, gdal.GDT_Float32,
                                              options=["COMPRESS=DEFLATE"])
    ds.SetGeoTransform(gt)
    if epsg:
        srs = osr.SpatialReference()
        srs.ImportFromEPSG(epsg)
        ds.SetProjection(srs.ExportToWkt())
    band = ds.GetRasterBand(1)
    if nodata is not None:
        band.SetNoDataValue(nodata)
    band.WriteArray(z.astype(np.float32))
    ds = None


def luxembourg():
    src = gdal.Open(os.path.join(HERE, "..", "luxembourg", "elev.tif"))
    gt = src.GetGeoTransform()
    nx, ny = src.RasterXSize, src.RasterYSize
    lon = gt[0] + (np.arange(nx) + 0.5) * gt[1]
    lat = gt[3] + (np.arange(ny) + 0.5) * gt[5]
    LON, LAT = np.meshgrid(lon, lat)
    write("lux_h1.tif", 50 + 80 * np.sin(2 * np.pi * (LON - 5.74) / 0.4), gt, 4326)
    write("lux_h2.tif", -150 + 200 * (LAT - 49.8), gt, 4326)


def synthetic():
    n, cell, x0, y0 = 24, 100.0, 500000.0, 5500000.0
    gt = (x0, cell, 0, y0 + n * cell, 0, -cell)
    x = (np.arange(n) + 0.5) * cell
    y = (n - np.arange(n) - 0.5) * cell  # row 0 is the northern one
    X, Y = np.meshgrid(x, y)
    write("synthetic_dem.tif", 300 + 40 * np.sin(X / 500) * np.cos(Y / 700) + 0.02 * X, gt, 32632)
    write("synthetic_h1.tif", 150 + 0.1 * (X - 1200), gt, 32632)
    write("synthetic_pinch.tif", 200 + 0.1 * X, gt, 32632)
    write("synthetic_high.tif", np.full_like(X, 1000.0), gt, 32632)
    write("synthetic_nocrs.tif", 150 + 0.1 * (X - 1200), gt, None)
    write("synthetic_nodata.tif", np.full_like(X, -9999.0), gt, 32632, nodata=-9999.0)
    ring = [[x0 + 300, y0 + 300], [x0 + 2100, y0 + 400], [x0 + 2000, y0 + 2100], [x0 + 900, y0 + 1800],
            [x0 + 400, y0 + 2000], [x0 + 300, y0 + 300]]
    doc = {"type": "FeatureCollection", "crs": {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}},
           "features": [{"type": "Feature", "properties": {"id": 0},
                         "geometry": {"type": "Polygon", "coordinates": [ring]}}]}
    with open(os.path.join(HERE, "synthetic_domain.geojson"), "w") as f:
        json.dump(doc, f)
        f.write("\n")


if __name__ == "__main__":
    luxembourg()
    synthetic()
