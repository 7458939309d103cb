// The option table and its JSON rendering (--json-usage), consumed by the QGIS plugin.
#include "cli/option_table.hpp"
#include <nlohmann/json.hpp>
#include "base/error.hpp"
#include "base/version.hpp"

namespace fdr::cli {

const std::vector<OptSpec>& option_table() {
  static const std::vector<OptSpec> t = {
      // mesh: input
      {"mesh", "input", "input", "vector_in", "INPUT", "", "Input",
       "Domain: Triangle .poly/.node file, or any OGR vector source with water polygons (islands as holes); "
       "not needed with --land and --extent",
       false, false, {}, true},
      {"mesh", "--layer", "layer", "string", "NAME", "", "Input", "Layer of INPUT to read (default: the first)"},
      {"mesh", "--where", "where", "string", "SQL", "", "Input", "OGR attribute filter on INPUT features"},
      {"mesh", "--land", "land", "vector_in", "FILE", "", "Input", "Land polygons subtracted from --extent (instead of water polygons)"},
      {"mesh", "--extent", "extent", "bbox", "XMIN,YMIN,XMAX,YMAX", "", "Input", "Box (lon/lat degrees) from which --land is subtracted"},
      {"mesh", "--breaklines", "breaklines", "vector_in", "FILE", "", "Input", "Lines kept as mesh edges (rivers, levees, channels); clipped to the domain"},
      {"mesh", "--points", "points", "vector_in", "FILE", "", "Input", "Fixed vertices (points inside the domain)"},
      {"mesh", "--open-boundary", "open-boundary", "vector_in", "FILE", "", "Input", "Lines marking the open-ocean parts of the boundary"},
      {"mesh", "--breaklines-layer", "breaklines-layer", "string", "NAME", "", "Input", "Layer of --breaklines to read (default: the first)"},
      {"mesh", "--points-layer", "points-layer", "string", "NAME", "", "Input", "Layer of --points to read (default: the first)"},
      {"mesh", "--open-boundary-layer", "open-boundary-layer", "string", "NAME", "", "Input", "Layer of --open-boundary to read (default: the first)"},
      {"mesh", "--s_srs", "s_srs", "crs", "SRS", "", "Input", "CRS of input layers that carry none"},
      // mesh: CRS
      {"mesh", "--t_srs", "t_srs", "crs", "SRS", "auto: UTM zone, or a centred transverse Mercator for wide domains", "CRS", "Projected CRS to mesh in (EPSG:n, PROJ string or WKT)"},
      {"mesh", "--output-crs", "output-crs", "crs", "SRS", "", "CRS", "Write node coordinates in this CRS (same topology), e.g. EPSG:4326"},
      // mesh: spacing
      {"mesh", "--spacing", "spacing", "expr", "EXPR|PRESET", "bbox diagonal / 20 (.poly)", "Spacing",
       "Spacing f(x,y): a number, paper-f1, paper-f2, K*paper-f1, or an expression in x, y (+ - * / ^ abs sin cos tan sqrt exp log min max)"},
      {"mesh", "--raster", "raster", "raster_in", "FILE", "", "Spacing", "Bathymetry/DEM raster (any GDAL format; elevation positive up)"},
      {"mesh", "--size-raster", "size-raster", "raster_in", "FILE", "", "Spacing", "Explicit size raster (metres)"},
      {"mesh", "--hmin", "hmin", "float", "M", "", "Spacing", "Smallest element size (metres)"},
      {"mesh", "--hmax", "hmax", "float", "M", "", "Spacing", "Largest element size (metres)"},
      {"mesh", "--dist-grade", "dist-grade", "float", "G", "", "Spacing", "Distance-to-shore rule h = hmin + G * distance"},
      {"mesh", "--slope-rule", "slope-rule", "float", "SLP", "", "Spacing", "Bathymetric slope rule h = (2 pi / SLP) depth / |grad depth|"},
      {"mesh", "--wavelength-rule", "wavelength-rule", "float", "WL", "", "Spacing", "Wavelength rule h = T sqrt(g depth) / WL"},
      {"mesh", "--wave-period", "wave-period", "float", "S", "44712 (M2)", "Spacing", "Wave period T for --wavelength-rule (seconds)"},
      {"mesh", "--vertical-tol", "vertical-tol", "float", "M", "", "Spacing", "Terrain rule h = sqrt(8 tol / |curvature|): TIN within tol metres of the DEM"},
      {"mesh", "--gradation", "gradation", "float", "ALPHA", "0.15", "Spacing", "Gradient limit |grad f| <= ALPHA applied to raster spacing"},
      {"mesh", "--cell-size", "cell-size", "float", "M", "raster resolution", "Spacing", "Cell size of the spacing grid (metres)"},
      {"mesh", "--write-spacing", "write-spacing", "file_out", "FILE.tif", "", "Spacing", "Write the final spacing f as GeoTIFF"},
      // mesh: repair
      {"mesh", "--snap", "snap", "float", "M", "1e-6 of the domain size", "Repair", "Merge vertices closer than this (metres)"},
      {"mesh", "--min-island", "min-island", "float", "FACTOR", "0", "Repair", "Drop islands with area < FACTOR * f^2"},
      {"mesh", "--strict", "strict", "flag", "", "", "Repair",
       "Refuse crossing, overlapping, duplicate or zero-length constraints in a .poly/.node INPUT (exit 5 naming the first) instead of resolving them"},
      {"mesh", "--convex-hull", "convex-hull", "flag", "", "", "Input",
       "The convex hull of all vertices bounds the domain (.poly/.node INPUT; like Triangle -c): point sets and dangling breaklines mesh"},
      {"mesh", "--simplify", "simplify", "float", "FACTOR", "", "Repair", "Thin boundary vertices closer than FACTOR * f (shape kept within f/10)"},
      // mesh: refinement
      {"mesh", "--bound", "bound", "float", "B", "1", "Refinement", "Quality bound: a triangle is bad when R/f(c) > B (need alpha*B < 1)"},
      {"mesh", "--min-angle", "min-angle", "float", "DEG", "0 (off)", "Refinement", "Extra minimum-angle bound combined with FDR (like Triangle -q)"},
      {"mesh", "--max-steiner", "max-steiner", "int", "N", "20000000", "Refinement", "Cap on inserted Steiner points; reaching it is an error (exit 7)"},
      {"mesh", "--check", "check", "flag", "", "", "Refinement", "Verify the mesh invariants (exit 10 if one fails)"},
      // mesh: output
      {"mesh", "-o,--output", "output", "file_out", "FILE", "", "Output",
       "Output mesh; format from the extension (.gpkg .2dm .14/.grd .msh .nc .node .vtu); repeatable", true},
      {"mesh", "--of", "of", "choice", "FORMAT", "", "Output", "Output format override",
       false, false, {"GPKG", "2DM", "FORT14", "MSH", "UGRID", "NODE", "VTU"}},
      {"mesh", "--report", "report", "file_out", "FILE.json", "", "Output", "Write the quality report as JSON"},
      {"mesh", "-q,--quiet", "quiet", "flag", "", "", "Output", "No progress and no report on stdout"},
      // quality
      {"quality", "mesh", "mesh", "mesh_in", "MESH", "", "Input", "Mesh to judge (.2dm, fort.14/.grd, .msh, .node, fdrmesh .gpkg)",
       false, true, {}, true},
      {"quality", "--spacing", "spacing", "expr", "EXPR|PRESET", "", "Spacing", "Spacing f(x,y) in the mesh's coordinates"},
      {"quality", "--raster", "raster", "raster_in", "FILE", "", "Spacing", "Spacing from a size raster in the mesh's CRS (metres)"},
      {"quality", "--bound", "bound", "float", "B", "1", "Quality", "Bound B for counting bad triangles (R/f(c) > B)"},
      {"quality", "--report", "report", "file_out", "FILE.json", "", "Output", "Write the report as JSON"},
      {"quality", "-q,--quiet", "quiet", "flag", "", "", "Output", "No report on stdout"},
  };
  return t;
}

std::string json_usage() {
  using nlohmann::ordered_json;
  ordered_json j;
  j["program"] = "fdrmesh";
  j["version"] = kVersion;
  ordered_json cmds = ordered_json::array();
  for (const char* c : {"mesh", "quality"}) {
    ordered_json cmd;
    cmd["name"] = c;
    cmd["summary"] = std::string(c) == "mesh" ? "Mesh a domain by Functional Delaunay Refinement"
                                              : "Report the quality of an existing mesh against a spacing function";
    ordered_json opts = ordered_json::array();
    for (const auto& o : option_table()) {
      if (o.command != c) continue;
      ordered_json e;
      e["key"] = o.key;
      std::string names = o.names;
      ordered_json nm = ordered_json::array();
      for (std::size_t p = 0; p <= names.size();) {
        const auto q = names.find(',', p);
        nm.push_back(names.substr(p, q == std::string::npos ? std::string::npos : q - p));
        if (q == std::string::npos) break;
        p = q + 1;
      }
      e["names"] = nm;
      e["type"] = o.type;
      e["metavar"] = o.metavar;
      e["default"] = o.def;
      e["group"] = o.group;
      e["help"] = o.help;
      e["repeat"] = o.repeat;
      e["required"] = o.required;
      e["positional"] = o.positional;
      if (!o.choices.empty()) e["choices"] = o.choices;
      opts.push_back(e);
    }
    cmd["options"] = opts;
    cmds.push_back(cmd);
  }
  j["commands"] = cmds;
  ordered_json codes = ordered_json::object();
  for (int c = 0; c <= 11; ++c) codes[std::to_string(c)] = exit_code_name(static_cast<ExitCode>(c));
  j["exit_codes"] = codes;
  j["progress"] = "GDAL style on stderr: 0...10...20...30...40...50...60...70...80...90...100 - done.";
  j["errors"] = "one line on stderr: 'ERROR <exit code>: <message>'";
  return j.dump(2);
}

}  // namespace fdr::cli
