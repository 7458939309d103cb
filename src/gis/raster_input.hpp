// Raster input: any GDAL raster (band 1) warped into the working frame as a sizing::Grid.
#pragma once
#include <string>
#include <vector>
#include "base/types.hpp"
#include "gis/crs.hpp"
#include "sizing/grid.hpp"

namespace fdr::gis {

// Warps band 1 of `path` (bilinear, GDAL warper) into the frame's CRS on a regular grid of
// cell_m x cell_m cells that covers local_bbox with one extra cell on each side. Nodata and
// cells outside the raster become NaN; the band's scale/offset are applied.
// Errors: unreadable / no band / no CRS -> kInputUnreadable (kCrsError for the CRS);
// the raster does not cover the domain -> kInvalidSpacing naming the uncovered places (lon/lat);
// nodata everywhere over the box -> kInvalidSpacing; more than 16M cells -> kWorkLimit.
// Coverage is checked on `must_cover` (local points, e.g. the PSLG's vertices) when given, else on
// the outline of local_bbox (its corners are named). Pass the domain's vertices when the raster is
// cut to the domain's lon/lat box: the bbox of the projected domain reaches beyond that box.
sizing::Grid read_raster_to_frame(const std::string& path, const Frame& frame, Box2 local_bbox, double cell_m,
                                  const std::vector<Point2>* must_cover = nullptr);

// Band 1 of `path` on its own grid and CRS (no reprojection), shifted so that local = world -
// origin: for a size raster already in the mesh's CRS. Rotated or south-up rasters are resampled
// north-up (bilinear) through a warped VRT first. Nodata -> NaN; scale/offset applied.
// Errors: unreadable -> kInputUnreadable; nodata everywhere -> kInvalidSpacing; > 16M cells -> kWorkLimit.
sizing::Grid read_raster_native(const std::string& path, Point2 origin);

// Bilinear samples of g at nodes (cell-centre interpolation, clamped at the grid edge). Where the
// interpolation touches a NaN cell the value of the nearest valid cell (Euclidean, cell centres)
// is used instead; *n_filled_from_nearest counts those nodes. Throws kInvalidSpacing when the grid
// has no valid cell at all.
std::vector<double> sample_depths(const sizing::Grid& g, const std::vector<Point2>& nodes,
                                  int* n_filled_from_nearest = nullptr);

// Default cell size (metres) for read_raster_to_frame: the raster's native resolution in metres at
// the box centre, enlarged when needed so that the grid has at most max_cells cells.
double grid_cell_size_hint(const std::string& path, const Frame& frame, Box2 local_bbox,
                           double max_cells = 4e6);

}  // namespace fdr::gis
