// The option table and its JSON rendering (--json-usage), consumed by the QGIS plugin.
#include "cli/option_table.hpp"
#include <nlohmann/json.hpp>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <sstream>
#include "base/error.hpp"
#include "base/version.hpp"
#include "pipeline/output_formats.hpp"

namespace fdr::cli {

namespace {
using MeshOptions = pipeline::Options;
using QualityOptions = pipeline::QualityOptions;

double parse_number(const std::string& key, const std::string& s) {
  char* end = nullptr;
  const double x = std::strtod(s.c_str(), &end);
  if (end == s.c_str() || *end != '\0' || !std::isfinite(x))
    throw Error(ExitCode::kUsage, "--" + key + ": '" + s + "' is not a number");
  return x;
}

template <class M> struct Member;
template <class C, class T> struct Member<T C::*> {
  using Class = C;
  using Type = T;
};
template <class C> C& target(Request& r) {
  if constexpr (std::is_same_v<C, MeshOptions>) return r.mesh;
  else return r.quality;
}

// The typed binding of a field: its type decides how the values are read.
//   std::string: the last value; std::vector<std::string>: every value (repeatable options);
//   bool: true when the flag is given; double / std::optional<double>: the last value, a number.
template <auto M>
void field(Request& r, const std::string& key, const std::vector<std::string>& v) {
  using T = typename Member<decltype(M)>::Type;
  T& f = target<typename Member<decltype(M)>::Class>(r).*M;
  if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    if (!v.empty()) f = v;
  } else {
    if (v.empty()) return;
    if constexpr (std::is_same_v<T, std::string>) f = v.back();
    else if constexpr (std::is_same_v<T, bool>) f = true;
    else f = parse_number(key, v.back());  // double, std::optional<double>
  }
}

// A comma-separated list of exactly N numbers, or a usage error that shows the expected form.
template <std::size_t N>
std::array<double, N> parse_number_list(const std::string& key, const std::string& text, const std::string& form) {
  std::array<double, N> out{};
  std::stringstream ss(text);
  std::string tok;
  std::size_t k = 0;
  while (std::getline(ss, tok, ',')) {
    char* end = nullptr;
    if (k >= N) throw Error(ExitCode::kUsage, key + " takes " + form);
    out[k] = std::strtod(tok.c_str(), &end);
    if (end == tok.c_str() || *end) throw Error(ExitCode::kUsage, key + ": '" + tok + "' is not a number");
    ++k;
  }
  if (k != N) throw Error(ExitCode::kUsage, key + " takes " + form);
  return out;
}

void set_extent(Request& r, const std::string&, const std::vector<std::string>& v) {
  if (v.empty() || v.back().empty()) return;
  const std::array<double, 4> box = parse_number_list<4>("--extent", v.back(), "XMIN,YMIN,XMAX,YMAX");
  if (!(box[0] < box[2]) || !(box[1] < box[3]))
    throw Error(ExitCode::kUsage, "--extent takes XMIN,YMIN,XMAX,YMAX with XMIN < XMAX and YMIN < YMAX");
  r.mesh.extent = box;
}

void set_pole(Request& r, const std::string&, const std::vector<std::string>& v) {
  if (v.empty() || v.back().empty()) return;
  const std::array<double, 2> p = parse_number_list<2>("--pole", v.back(), "LON,LAT");
  if (!(p[0] >= -180 && p[0] <= 180) || !(p[1] >= -90 && p[1] <= 90))
    throw Error(ExitCode::kUsage, "--pole takes LON,LAT in degrees (-180..180, -90..90)");
  r.mesh.pole = p;
}

void set_min_angle(Request& r, const std::string& key, const std::vector<std::string>& v) {
  if (v.empty()) return;  // automatic: 30 for GIS inputs, 0 for .poly (pipeline::plan_run)
  r.mesh.min_angle_deg = parse_number(key, v.back());
  if (r.mesh.min_angle_deg < 0) throw Error(ExitCode::kUsage, "--min-angle must be in [0, 60)");
}

void set_smooth(Request& r, const std::string& key, const std::vector<std::string>& v) {
  if (v.empty()) return;  // automatic: 4 for GIS inputs, 0 for .poly
  const double sm = parse_number(key, v.back());
  if (!(sm >= 0 && sm <= 100) || sm != std::floor(sm)) throw Error(ExitCode::kUsage, "--smooth must be an integer in [0, 100]");
  r.mesh.smooth_passes = static_cast<int>(sm);
}

void set_frontal(Request& r, const std::string& key, const std::vector<std::string>& v) {
  if (v.empty()) return;  // automatic: 0.75 for GIS inputs, 0 for .poly (pipeline::plan_run)
  const double k = parse_number(key, v.back());
  if (!(k >= 0 && k < 1)) throw Error(ExitCode::kUsage, "--frontal must be in [0, 1)");
  r.mesh.frontal_radius = k;
}

void set_bound(Request& r, const std::string& key, const std::vector<std::string>& v) {
  if (v.empty()) return;  // 2D: 1; 3D: the 3D default (tet::TetOptions)
  r.mesh.bound = parse_number(key, v.back());
  r.mesh.bound_given = true;
}

void set_max_steiner(Request& r, const std::string& key, const std::vector<std::string>& v) {
  if (v.empty()) return;
  const double ms = parse_number(key, v.back());
  if (!(ms >= 1) || ms != std::floor(ms)) throw Error(ExitCode::kUsage, "--max-steiner must be a positive integer");
  r.mesh.max_steiner = static_cast<std::uint64_t>(ms);
}
}  // namespace

namespace {
// The output formats as the writers publish them (pipeline::output_formats): -o help and --of choices.
std::string output_help() {
  std::string s = "Output mesh; format from the extension (";
  bool first = true;
  for (const auto& f : pipeline::output_formats()) {
    s += std::string(first ? "" : " ") + f.extensions;
    first = false;
  }
  return s + "); repeatable; .slf also writes NAME.cli; 3D inputs: .vtu, .msh, .node (TetGen .node/.ele/.face)";
}
std::vector<std::string> output_choices() {
  std::vector<std::string> c;
  for (const auto& f : pipeline::output_formats()) c.push_back(f.name);
  return c;
}
}  // namespace

const std::vector<OptSpec>& option_table() {
  static const std::vector<OptSpec> t = {
      // mesh: input
      {"mesh", "input", "input", field<&MeshOptions::input>, "vector_in", "INPUT", "", "Input",
       "Domain: Triangle .poly/.node file, or any OGR vector source with water polygons (islands as holes), "
       "a PostGIS table or view among them (\"PG:dbname=... \" with --layer schema.table); "
       "not needed with --land and --extent; a TetGen .poly/.node whose dimension line says 3, .smesh, .off, .stl or "
       ".ply runs the 3D mesher (docs/3d.md)",
       false, false, {}, true},
      {"mesh", "--layer", "layer", field<&MeshOptions::layer>, "string", "NAME", "", "Input", "Layer of INPUT to read (default: the first)"},
      {"mesh", "--where", "where", field<&MeshOptions::where>, "string", "SQL", "", "Input", "OGR attribute filter on INPUT features"},
      {"mesh", "--land", "land", field<&MeshOptions::land>, "vector_in", "FILE", "", "Input", "Land polygons subtracted from --extent (instead of water polygons)"},
      {"mesh", "--global", "global", field<&MeshOptions::global>, "flag", "", "", "Input", "Mesh the whole ocean: the sphere minus --land (no --extent), in a stereographic plane whose pole lies inside Antarctica; outputs in lon/lat (docs/global.md)"},
      {"mesh", "--pole", "pole", set_pole, "string", "LON,LAT", "0,-90", "Input", "--global: the point sent to infinity by the stereographic projection, inside the land polygon that bounds the ocean"},
      {"mesh", "--extent", "extent", set_extent, "bbox", "XMIN,YMIN,XMAX,YMAX", "", "Input", "Box (lon/lat degrees) from which --land is subtracted"},
      {"mesh", "--breaklines", "breaklines", field<&MeshOptions::breaklines>, "vector_in", "FILE", "", "Input", "Lines kept as mesh edges (rivers, levees, channels); clipped to the domain"},
      {"mesh", "--points", "points", field<&MeshOptions::points>, "vector_in", "FILE", "", "Input", "Fixed vertices (points inside the domain)"},
      {"mesh", "--open-boundary", "open-boundary", field<&MeshOptions::open_boundary>, "vector_in", "FILE", "", "Input", "Lines marking the open-ocean parts of the boundary"},
      {"mesh", "--breaklines-layer", "breaklines-layer", field<&MeshOptions::breaklines_layer>, "string", "NAME", "", "Input", "Layer of --breaklines to read (default: the first)"},
      {"mesh", "--points-layer", "points-layer", field<&MeshOptions::points_layer>, "string", "NAME", "", "Input", "Layer of --points to read (default: the first)"},
      {"mesh", "--open-boundary-layer", "open-boundary-layer", field<&MeshOptions::open_boundary_layer>, "string", "NAME", "", "Input", "Layer of --open-boundary to read (default: the first)"},
      {"mesh", "--s_srs", "s_srs", field<&MeshOptions::s_srs>, "crs", "SRS", "", "Input", "CRS of input layers that carry none"},
      {"mesh", "--densify", "densify", field<&MeshOptions::densify_deg>, "float", "DEG", "0 (chords, as GDAL)", "Input", "Lon/lat layers: segments longer than DEG degrees follow their lon/lat line (a box side its parallel) instead of the chord"},
      // mesh: CRS
      {"mesh", "--t_srs", "t_srs", field<&MeshOptions::t_srs>, "crs", "SRS", "auto: UTM zone, or a centred transverse Mercator for wide domains", "CRS", "Projected CRS to mesh in (EPSG:n, PROJ string or WKT)"},
      {"mesh", "--output-crs", "output-crs", field<&MeshOptions::output_crs>, "crs", "SRS", "", "CRS", "Write node coordinates in this CRS (same topology), e.g. EPSG:4326"},
      // mesh: spacing
      {"mesh", "--spacing", "spacing", field<&MeshOptions::spacing>, "expr", "EXPR|PRESET", "bbox diagonal / 20 (.poly)", "Spacing",
       "Spacing f(x,y): a number, paper-f1, paper-f2, K*paper-f1, or an expression in x, y (+ - * / ^ abs sin cos tan sqrt exp log min max); "
       "3D inputs: the same in x, y, z"},
      {"mesh", "--raster", "raster", field<&MeshOptions::raster>, "raster_in", "FILE", "", "Spacing", "Bathymetry/DEM raster (any GDAL format; elevation positive up)"},
      {"mesh", "--size-raster", "size-raster", field<&MeshOptions::size_raster>, "raster_in", "FILE", "", "Spacing", "Explicit size raster (metres)"},
      {"mesh", "--hmin", "hmin", field<&MeshOptions::hmin>, "float", "M", "", "Spacing", "Smallest element size (metres)"},
      {"mesh", "--hmax", "hmax", field<&MeshOptions::hmax>, "float", "M", "", "Spacing", "Largest element size (metres)"},
      {"mesh", "--dist-grade", "dist-grade", field<&MeshOptions::dist_grade>, "float", "G", "", "Spacing", "Distance-to-shore rule h = hmin + G * distance"},
      {"mesh", "--slope-rule", "slope-rule", field<&MeshOptions::slope_rule>, "float", "SLP", "", "Spacing", "Bathymetric slope rule h = (2 pi / SLP) depth / |grad depth|"},
      {"mesh", "--wavelength-rule", "wavelength-rule", field<&MeshOptions::wavelength_rule>, "float", "WL", "", "Spacing", "Wavelength rule h = T sqrt(g depth) / WL"},
      {"mesh", "--wave-period", "wave-period", field<&MeshOptions::wave_period_s>, "float", "S", "44712 (M2)", "Spacing", "Wave period T for --wavelength-rule (seconds)"},
      {"mesh", "--vertical-tol", "vertical-tol", field<&MeshOptions::vertical_tol>, "float", "M", "", "Spacing", "Terrain rule h = sqrt(8 tol / |curvature|): TIN within tol metres of the DEM"},
      // mesh: terrain volumes
      {"mesh", "--dem", "dem", field<&MeshOptions::dem>, "raster_in", "FILE", "", "Terrain",
       "DEM raster: the top of a terrain volume (a tetrahedral mesh of INPUT's polygon down to --base); also the raster of "
       "the 2D terrain TIN (--vertical-tol, --hmin, --hmax); outputs .vtu, .msh, .node (docs/terrain3d.md)"},
      {"mesh", "--base", "base", field<&MeshOptions::base>, "string", "Z|FILE", "", "Terrain",
       "Base of the terrain volume: an elevation in metres (e.g. -500) or a raster; must lie below the DEM"},
      {"mesh", "--horizon", "horizon", field<&MeshOptions::horizons>, "raster_in", "FILE", "", "Terrain",
       "Horizon raster (elevation), an internal surface between layers; repeatable, from the top down; clamped "
       "between the surface above and the base (layers pinch out there); named after the file",
       true},
      {"mesh", "--depth-grade", "depth-grade", field<&MeshOptions::depth_grade>, "float", "G", "0.25", "Terrain",
       "Terrain volumes: the spacing grows by G metres per metre of depth below the DEM (h = h2D + G depth)"},
      {"mesh", "--min-thickness", "min-thickness", field<&MeshOptions::min_thickness>, "float", "M", "0.15*hmin, at least --vertical-tol", "Terrain",
       "Terrain volumes: where a layer is thinner than M metres at a TIN vertex its horizon moves onto the surface above "
       "(or the base): the layer collapses there instead of ending in a thin wedge (0: keep every layer, collapsing "
       "only where surfaces cross)"},
      {"mesh", "--wells", "wells", field<&MeshOptions::wells>, "vector_in", "FILE", "", "Terrain",
       "Terrain volumes: wells as vertical segments refined around (points with fields top/bottom elevations or "
       "depth_from/depth_to depths below the DEM, or LineString Z); docs/terrain3d.md"},
      {"mesh", "--wells-layer", "wells-layer", field<&MeshOptions::wells_layer>, "string", "NAME", "", "Terrain",
       "Layer of --wells to read (default: the first)"},
      {"mesh", "--well-spacing", "well-spacing", field<&MeshOptions::well_spacing>, "float", "M", "--hmin", "Terrain",
       "Terrain volumes: the spacing along the wells is at most M metres (graded away by --gradation)"},
      {"mesh", "--gradation", "gradation", field<&MeshOptions::gradation>, "float", "ALPHA", "0.15", "Spacing", "Gradient limit |grad f| <= ALPHA applied to raster spacing"},
      {"mesh", "--cell-size", "cell-size", field<&MeshOptions::cell_size>, "float", "M", "max(hmin, sqrt(box area / 4e6))", "Spacing", "Cell size of the spacing grid (metres)"},
      {"mesh", "--write-spacing", "write-spacing", field<&MeshOptions::write_spacing>, "file_out", "FILE.tif", "", "Spacing", "Write the final spacing f as GeoTIFF"},
      // mesh: repair
      {"mesh", "--snap", "snap", field<&MeshOptions::snap>, "float", "M", "1e-6 of the domain size", "Repair", "Merge vertices closer than this (metres)"},
      {"mesh", "--min-island", "min-island", field<&MeshOptions::min_island_factor>, "float", "FACTOR", "0.3 (0 with --keep-coast)", "Repair", "Remove islands with area < FACTOR * hmin^2 (listed in repairs)"},
      {"mesh", "--close-width", "close-width", field<&MeshOptions::close_width>, "float", "M", "0.15*hmin (0 with --keep-coast)", "Repair", "Close dead-end water (inlets, gaps, slivers) and remove land thinner than M metres (spits, thin islands near other land); tips of land stay unless other land is within 0.5 hmin of their end (listed in repairs; 0: keep)"},
      {"mesh", "--widen-width", "widen-width", field<&MeshOptions::widen_width>, "float", "M", "0.65*hmin (0 with --keep-coast)", "Repair", "Widen water narrower than M metres (and at least --close-width wide) to about M by moving its banks into the land, unless that would join two water bodies (listed in repairs; 0: keep)"},
      {"mesh", "--min-feature", "min-feature", field<&MeshOptions::min_feature>, "float", "M", "hmin/10", "Repair", "Keep channels joining water bodies down to M metres wide; narrower ones are closed (listed)"},
      {"mesh", "--coast-tol", "coast-tol", field<&MeshOptions::coast_tol>, "float", "FACTOR", "0.35", "Repair", "Resample boundaries to f keeping the shape within FACTOR * f"},
      {"mesh", "--keep-coast", "keep-coast", field<&MeshOptions::keep_coast>, "flag", "", "", "Repair", "Keep every input boundary vertex and close nothing (no resampling)"},
      {"mesh", "--channel-elements", "channel-elements", field<&MeshOptions::channel_elements>, "float", "N", "2", "Spacing", "Channel rule: spacing at most width / N in narrow water (N elements across; 0: off)"},
      {"mesh", "--min-depth", "min-depth", field<&MeshOptions::min_depth_m>, "float", "M", "1", "Output", "Depth clamp (metres) for the gravity-wave time step in the report"},
      {"mesh", "--strict", "strict", field<&MeshOptions::strict>, "flag", "", "", "Repair",
       "Refuse crossing, overlapping, duplicate or zero-length constraints in a .poly/.node INPUT (exit 5 naming the first) instead of resolving them"},
      {"mesh", "--convex-hull", "convex-hull", field<&MeshOptions::convex_hull>, "flag", "", "", "Input",
       "The convex hull of all vertices bounds the domain (.poly/.node INPUT; like Triangle -c): point sets and dangling breaklines mesh"},
      {"mesh", "--simplify", "simplify", field<&MeshOptions::simplify>, "float", "FACTOR", "", "Repair", "Thin boundary vertices closer than FACTOR * f (shape kept within f/10)"},
      // mesh: refinement
      {"mesh", "--bound", "bound", set_bound, "float", "B", "1 (2D), the 3D default keeping radius-edge <= 2 (3D)", "Refinement", "Quality bound: a triangle (tetrahedron) is bad when R/f(c) > B (need alpha*B < 1)"},
      {"mesh", "--min-angle", "min-angle", set_min_angle, "float", "DEG", "30 for GIS inputs, 0 for .poly", "Refinement", "Extra minimum-angle bound combined with FDR (like Triangle -q; GIS inputs: above 20 deg it gives way where a split would cut a boundary segment under f/2); 0 turns it off"},
      {"mesh", "--smooth", "smooth", set_smooth, "int", "N", "4 for GIS inputs, 0 for .poly", "Refinement", "Quality smoothing sweeps after refinement (moves kept only if exact checks pass; 0: off)"},
      {"mesh", "--frontal", "frontal", set_frontal, "float", "K", "0.75 for GIS inputs, 0 for .poly", "Refinement", "Frontal point placement: a bad triangle next to accepted ones is split where the new triangle's circumradius is K*B*f (0 < K < 1), if no vertex is nearer than B*f there; 0: circumcentres only"},
      {"mesh", "--no-sliver-removal", "no-sliver-removal", field<&MeshOptions::no_sliver_removal>, "flag", "", "", "Refinement",
       "3D: keep the slivers refinement leaves (by default tetrahedra with a dihedral angle under --sliver-angle are "
       "split by a point near their circumcentre that makes no new sliver; R/f <= B and Delaunay kept)"},
      {"mesh", "--sliver-angle", "sliver-angle", field<&MeshOptions::sliver_angle_deg>, "float", "DEG", "15", "Refinement",
       "3D: a tetrahedron whose smallest dihedral angle is under DEG is a sliver to remove (0 < DEG <= 30)"},
      {"mesh", "--max-steiner", "max-steiner", set_max_steiner, "int", "N", "20000000", "Refinement", "Cap on inserted Steiner points; reaching it is an error (exit 7)"},
      {"mesh", "--check", "check", field<&MeshOptions::check>, "flag", "", "", "Refinement", "Verify the mesh invariants (exit 10 if one fails); 3D: valid, Delaunay and conforming tetrahedralization "
       "with R/f(c) <= B, checked exactly before anything is written"},
      // mesh: output
      {"mesh", "-o,--output", "output", field<&MeshOptions::outputs>, "file_out", "FILE", "", "Output", output_help(), true},
      {"mesh", "--of", "of", field<&MeshOptions::of>, "choice", "FORMAT", "", "Output", "Output format override",
       false, false, output_choices()},
      {"mesh", "--slf-double", "slf-double", field<&MeshOptions::slf_double>, "flag", "", "", "Output", "Write Selafin (.slf) in double precision (SERAFIND)"},
      {"mesh", "--telemac-open", "telemac-open", field<&MeshOptions::telemac_open>, "string", "L,U,V", "5,4,4", "Output",
       "Telemac .cli codes LIHBOR,LIUBOR,LIVBOR of open-boundary nodes (5,4,4 prescribed elevation; 4,5,5 prescribed velocity)"},
      {"mesh", "--pg-prefix", "pg-prefix", field<&MeshOptions::pg_prefix>, "string", "PREFIX", "mesh_", "Output",
       "PostGIS output (-o PG:...): prefix of the tables PREFIXnodes, PREFIXtriangles, PREFIXboundaries, PREFIXrepairs, PREFIXmetadata"},
      {"mesh", "--pg-schema", "pg-schema", field<&MeshOptions::pg_schema>, "string", "SCHEMA", "the connection's schemas=, else the current schema", "Output",
       "PostGIS output: schema of the tables"},
      {"mesh", "--overwrite", "overwrite", field<&MeshOptions::pg_overwrite>, "flag", "", "", "Output",
       "PostGIS output: replace an existing mesh with the same table prefix (in the same transaction); files are always replaced"},
      {"mesh", "--report", "report", field<&MeshOptions::report_json>, "file_out", "FILE.json", "", "Output", "Write the quality report as JSON"},
      {"mesh", "-q,--quiet", "quiet", field<&MeshOptions::quiet>, "flag", "", "", "Output", "No progress and no report on stdout"},
      // quality
      {"quality", "mesh", "mesh", field<&QualityOptions::mesh>, "mesh_in", "MESH", "", "Input", "Mesh to judge (.2dm, fort.14/.grd, .gr3/.ll, .slf, .msh, .node, fdrmesh .gpkg)",
       false, true, {}, true},
      {"quality", "--spacing", "spacing", field<&QualityOptions::spacing>, "expr", "EXPR|PRESET", "", "Spacing", "Spacing f(x,y) in the mesh's coordinates"},
      {"quality", "--raster", "raster", field<&QualityOptions::raster>, "raster_in", "FILE", "", "Spacing", "Spacing from a size raster in the mesh's CRS (metres)"},
      {"quality", "--bound", "bound", field<&QualityOptions::bound>, "float", "B", "1", "Quality", "Bound B for counting bad triangles (R/f(c) > B)"},
      {"quality", "--report", "report", field<&QualityOptions::report_json>, "file_out", "FILE.json", "", "Output", "Write the report as JSON"},
      {"quality", "-q,--quiet", "quiet", field<&QualityOptions::quiet>, "flag", "", "", "Output", "No report on stdout"},
  };
  return t;
}

void bind_options(const std::string& command, const std::map<std::string, std::vector<std::string>>& values,
                  Request& request) {
  static const std::vector<std::string> none;
  for (const auto& o : option_table()) {
    if (o.command != command) continue;
    const auto it = values.find(o.key);
    o.bind(request, o.key, it == values.end() ? none : it->second);
  }
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
  // Output formats (-o by extension, --of by name) with what each file carries.
  ordered_json fmts = ordered_json::array();
  for (const auto& f : pipeline::output_formats()) {
    ordered_json e;
    e["name"] = f.name;
    ordered_json ext = ordered_json::array();
    std::string x = f.extensions;
    for (std::size_t p = 0; p < x.size();) {
      const auto q = x.find(' ', p);
      ext.push_back(x.substr(p, q == std::string::npos ? std::string::npos : q - p));
      if (q == std::string::npos) break;
      p = q + 1;
    }
    e["extensions"] = ext;
    e["label"] = f.label;
    e["carries"] = f.carries;
    fmts.push_back(e);
  }
  j["output_formats"] = fmts;
  ordered_json codes = ordered_json::object();
  for (int c = 0; c <= 11; ++c) codes[std::to_string(c)] = exit_code_name(static_cast<ExitCode>(c));
  j["exit_codes"] = codes;
  j["progress"] = "GDAL style on stderr: 0...10...20...30...40...50...60...70...80...90...100 - done.";
  j["errors"] = "one line on stderr: 'ERROR <exit code>: <message>'";
  return j.dump(2);
}

}  // namespace fdr::cli
