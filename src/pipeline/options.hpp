// Options of one fdrmesh run (filled by the CLI, the QGIS plugin through the CLI, or C++ callers).
#pragma once
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace fdr::pipeline {

struct Options {
  // Input: a Triangle .poly/.node file, or any OGR vector source (water polygons).
  std::string input;
  std::string layer, where;              // OGR layer and attribute filter of the domain
  std::string land;                      // land polygons subtracted from --extent
  std::optional<std::array<double, 4>> extent;  // xmin,ymin,xmax,ymax (lon/lat)
  // Global run: the sphere minus --land, meshed in the stereographic plane whose point at
  // infinity is `pole` (lon, lat; default the south pole, inside Antarctica); outputs in lon/lat.
  bool global = false;
  std::optional<std::array<double, 2>> pole;
  std::string breaklines, points, open_boundary;
  // Layers of those sources (default: the first layer of each file).
  std::string breaklines_layer, points_layer, open_boundary_layer;
  std::string s_srs, t_srs, output_crs;

  // Outputs.
  std::vector<std::string> outputs;      // format from the extension, or `of`
  std::string of;
  std::string report_json;
  std::string write_spacing;             // GeoTIFF of the final f (GIS runs)
  bool slf_double = false;               // Selafin in double precision (SERAFIND)
  std::string telemac_open;              // LIHBOR,LIUBOR,LIVBOR of open nodes in the .cli ("" = 5,4,4)
  bool overwrite = true;
  // PostGIS output (-o "PG:..."): table name prefix, schema ("" = the connection's schemas=,
  // else the current schema), and whether an existing mesh with that prefix may be replaced.
  std::string pg_prefix = "mesh_";
  std::string pg_schema;
  bool pg_overwrite = false;

  // Spacing.
  std::string spacing;                   // expression / preset / constant (world coordinates)
  std::string raster;                    // bathymetry / DEM
  std::string size_raster;               // explicit size raster (metres)
  std::optional<double> hmin, hmax;      // metres
  std::optional<double> dist_grade;      // h = hmin + g * distance to shore
  std::optional<double> slope_rule;      // OceanMesh2D slp: h = (2 pi / slp) depth / |grad depth|
  std::optional<double> wavelength_rule; // wl: h = T sqrt(g depth) / wl
  double wave_period_s = 44712.0;        // M2 tide, 12.42 h
  std::optional<double> vertical_tol;    // terrain: h = sqrt(8 tol / |kappa|)
  double gradation = 0.15;               // alpha for gradient limiting (GIS runs)
  // Terrain volumes (a 3D run from GIS layers): the DEM as the top surface (also the 2D run's
  // raster), the base (an elevation in metres, or a raster), horizon rasters from the top down,
  // and the growth of the spacing per metre of depth below the top.
  std::string dem;
  std::string base;
  std::vector<std::string> horizons;
  std::optional<double> depth_grade;
  std::optional<double> min_thickness;   // thinner layers collapse locally (default: terrain::default_min_thickness)
  // Wells (an OGR source of points with a depth range, or 3D lines): vertical segments in the
  // volume with the spacing at most well_spacing along them (default: hmin).
  std::string wells, wells_layer;
  std::optional<double> well_spacing;
  std::optional<double> cell_size;       // sizing grid cell (metres); default from the raster
  // Model-ready coast (GIS runs; coast/generalise.hpp, pslg/resample.hpp).
  bool keep_coast = false;               // keep every input vertex, close nothing (as before 0.2)
  double coast_tol = 0.35;               // resampling tolerance, fraction of the local f
  std::optional<double> close_width;     // dead-end water narrower than this is closed (default 0.15 hmin)
  std::optional<double> widen_width;     // narrower water is widened to about this (default 0.65 hmin)
  std::optional<double> min_feature;     // connections narrower than this are closed (default hmin/10)
  std::optional<double> min_island_factor;  // islands with area < factor * hmin^2 removed (default 0.1)
  double min_depth_m = 1.0;              // depth clamp for the gravity-wave time step in the report
  double channel_elements = 2.0;         // channel rule: elements across narrow water (0: off)
  std::optional<double> simplify;        // thin boundary vertices closer than factor * f
  std::optional<double> snap;            // snap distance (metres)
  double densify_deg = 0;                // lon/lat segments longer than this follow their line (0: chords)
  // .poly/.node input: refuse conflicting constraints (exit 5 naming the first) instead of
  // resolving them (pslg::resolve).
  bool strict = false;
  // .poly/.node input: the convex hull of all vertices bounds the domain (Triangle -c).
  bool convex_hull = false;

  // Refinement.
  double bound = 1.0;                    // B (2D; a 3D run without --bound takes the 3D default)
  bool bound_given = false;              // --bound was given
  double min_angle_deg = -1.0;           // < 0: automatic (30 for GIS inputs, 0 for .poly/.node)
  int smooth_passes = -1;                // quality smoothing sweeps; < 0: automatic (4 GIS, 0 .poly)
  double frontal_radius = -1.0;          // frontal placement radius (fraction of B f); 0: off; < 0: automatic
  std::uint64_t max_steiner = 20'000'000;
  // 3D: sliver removal after refinement (on unless --no-sliver-removal) and its threshold on the
  // smallest dihedral angle (unset: tet::TetOptions' default).
  bool no_sliver_removal = false;
  std::optional<double> sliver_angle_deg;
  bool check = false;
  bool quiet = false;
  // The command line's runs: with `quiet`, no --report and no output that stores the report (GPKG,
  // VTU, UGRID, D-Flow FM net file), nobody reads the quality report, so it is not measured
  // (Result::report then holds the counts, the run's figures and the timings only). Library and
  // Python callers keep it false: they read Result::report.
  bool report_only_if_read = false;

  std::string command_line;              // for provenance (metadata)
};

}  // namespace fdr::pipeline
