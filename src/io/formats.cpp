// Output formats: the table the option table publishes, format from a file name or --of, and the
// Telemac boundary codes. No GDAL/SQLite/netCDF here: the CLI links this part of io without the
// writers (pipeline's plan is made before the GIS module is loaded, see pipeline/gis_backend.hpp).
#include <algorithm>
#include <cctype>
#include <sstream>

#include "base/error.hpp"
#include "io/writer.hpp"

namespace fdr::io {
namespace {
std::string lower(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}
std::string base_name(const std::string& path) {  // as detail::file_name
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}
std::string lower_ext(const std::string& path) {  // as detail::lower_extension (with the dot)
  const std::string n = base_name(path);
  const auto dot = n.find_last_of('.');
  if (dot == std::string::npos || dot == 0) return "";
  return lower(n.substr(dot));
}
}  // namespace

const std::vector<FormatInfo>& format_infos() {
  static const std::vector<FormatInfo> t = {
      {Format::kGpkg, "GPKG", ".gpkg", "GeoPackage (nodes, triangles, boundaries, repairs)",
       "z positive up; boundaries as lines with kind; CRS"},
      {Format::k2dm, "2DM", ".2dm", "SMS 2DM mesh",
       "z positive up; nodestrings: open, then land and island boundaries; no CRS"},
      {Format::kFort14, "FORT14", ".14 .grd fort.14", "ADCIRC fort.14 mesh",
       "depth positive down; open (elevation) and land boundaries, IBTYPE 0 mainland / 1 island; no CRS"},
      {Format::kGr3, "GR3", ".gr3", "SCHISM hgrid.gr3",
       "depth positive down; open, land (0) and island (1) boundaries; no CRS (working CRS coordinates)"},
      {Format::kLl, "LL", ".ll", "SCHISM hgrid.ll (lon/lat)",
       "hgrid.gr3 with EPSG:4326 lon/lat nodes; depth positive down; same boundaries"},
      {Format::kSelafin, "SELAFIN", ".slf", "Telemac Selafin geometry + .cli",
       "BOTTOM = bed elevation positive up; IPOBO and NAME.cli boundary codes; no CRS (I_ORIG/J_ORIG offset)"},
      {Format::kDflowfm, "DFLOWFM", "_net.nc", "Delft3D FM UGRID net file",
       "node z positive up; every edge, edge type open/closed boundary; EPSG CRS"},
      {Format::kUgrid, "UGRID", ".nc", "UGRID netCDF mesh",
       "z positive up; constrained edges with kind; CRS"},
      {Format::kMsh, "MSH", ".msh", "Gmsh 4.1 mesh",
       "z positive up; boundary physical groups; no CRS; --global: x, y, z on the sphere, z as node data"},
      {Format::kNode, "NODE", ".node .ele", "Triangle node/ele", "z, f attributes; vertex markers; no CRS"},
      {Format::kVtu, "VTU", ".vtu", "VTK unstructured grid",
       "z, f point data; no boundaries; no CRS; --global: x, y, z on the sphere"},
      {Format::kPostgis, "POSTGRESQL", "PG:", "PostGIS tables (nodes, triangles, boundaries, repairs, metadata)",
       "the GeoPackage's layers as tables <prefix>nodes ... in one transaction; CRS as SRID"},
  };
  return t;
}

const char* format_name(Format f) {
  for (const auto& i : format_infos())
    if (i.format == f) return i.name;
  return "?";
}

namespace {
std::string known_list() {
  std::string s;
  for (const auto& i : format_infos()) {
    if (!s.empty()) s += ", ";
    s += std::string(i.name) + " (" + i.extensions + ")";
  }
  return s;
}
}  // namespace

Format format_from_path(const std::string& path, const std::string& of_override) {
  if (!of_override.empty()) {
    std::string up = of_override;
    for (char& c : up) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    for (const auto& i : format_infos())
      if (up == i.name) return i.format;
    throw Error(ExitCode::kUsage, "unknown output format '" + of_override + "'; known formats: " + known_list());
  }
  // A GDAL PostgreSQL connection string ("PG:dbname=... "), not a file name.
  if (path.size() >= 3 && lower(path.substr(0, 3)) == "pg:") return Format::kPostgis;
  std::string name = lower(base_name(path));
  if (name == "fort.14") return Format::kFort14;
  if (name.size() > 7 && name.compare(name.size() - 7, 7, "_net.nc") == 0) return Format::kDflowfm;
  std::string ext = lower_ext(path);
  if (ext == ".gpkg") return Format::kGpkg;
  if (ext == ".2dm") return Format::k2dm;
  if (ext == ".msh") return Format::kMsh;
  if (ext == ".node" || ext == ".ele") return Format::kNode;
  if (ext == ".vtu") return Format::kVtu;
  if (ext == ".14" || ext == ".grd") return Format::kFort14;
  if (ext == ".nc") return Format::kUgrid;
  if (ext == ".slf") return Format::kSelafin;
  if (ext == ".gr3") return Format::kGr3;
  if (ext == ".ll") return Format::kLl;
  throw Error(ExitCode::kUsage, "cannot tell the output format of '" + path +
                                    "' from its extension; use --of with one of: " + known_list());
}

std::array<int, 3> parse_telemac_codes(const std::string& text) {
  std::array<int, 3> c{};
  std::string t = text;
  for (char& ch : t)
    if (ch == ',' || ch == ';') ch = ' ';
  std::istringstream in(t);
  std::string extra;
  int k = 0;
  for (; k < 3 && (in >> c[k]); ++k) {
  }
  bool ok = k == 3 && !(in >> extra);
  for (int v : c) ok = ok && v >= 0 && v <= 6;
  if (!ok)
    throw Error(ExitCode::kUsage, "--telemac-open '" + text +
                                      "': give three Telemac codes LIHBOR,LIUBOR,LIVBOR in 0..6, e.g. 5,4,4 "
                                      "(prescribed elevation) or 4,5,5 (prescribed velocity)");
  return c;
}


}  // namespace fdr::io
