// Mesh readers: SMS 2dm, ADCIRC fort.14, SCHISM hgrid.gr3/.ll, Telemac Selafin, Gmsh msh 4.1 ASCII,
// Triangle node/ele, fdrmesh GeoPackage.
#include "io/reader.hpp"

#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <numbers>
#include <cstring>
#include <fstream>
#include <map>
#include <unordered_map>

#include "base/error.hpp"
#include "io/detail.hpp"
#include "io/gdal_util.hpp"

namespace fdr::io {

namespace {

using detail::kind_from_name;

[[noreturn]] void unreadable(const std::string& path, const std::string& why) {
  throw Error(ExitCode::kInputUnreadable, path + ": " + why);
}

// Reads a text file line by line, splitting each line into whitespace-separated tokens.
class Lines {
 public:
  Lines(const std::string& path, bool commas_are_blanks = false) : path_(path), commas_(commas_are_blanks) {
    in_.open(path, std::ios::binary);
    if (!in_) unreadable(path, std::string("cannot open: ") + std::strerror(errno));
  }
  // Next line (any content); false at end of file.
  bool next() {
    if (!std::getline(in_, line_)) return false;
    ++lineno_;
    if (!line_.empty() && line_.back() == '\r') line_.pop_back();
    tokens_.clear();
    std::size_t i = 0;
    while (i < line_.size()) {
      while (i < line_.size() && blank(line_[i])) ++i;
      std::size_t j = i;
      while (j < line_.size() && !blank(line_[j])) ++j;
      if (j > i) tokens_.emplace_back(line_.data() + i, j - i);
      i = j;
    }
    return true;
  }
  // Next line with at least one token and not a '#' comment; false at end of file.
  bool next_data() {
    while (next())
      if (!tokens_.empty() && tokens_[0][0] != '#') return true;
    return false;
  }
  void require_data(const char* what) {
    if (!next_data()) fail(std::string("unexpected end of file, expected ") + what);
  }
  [[noreturn]] void fail(const std::string& why) const {
    throw Error(ExitCode::kInputMalformed, path_ + ":" + std::to_string(lineno_) + ": " + why);
  }
  const std::string& line() const { return line_; }
  std::size_t size() const { return tokens_.size(); }
  std::string_view tok(std::size_t i) const {
    if (i >= tokens_.size()) fail("expected at least " + std::to_string(i + 1) + " values");
    return tokens_[i];
  }
  long long integer(std::size_t i) const {
    std::string_view t = tok(i);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    long long v = 0;
    auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("'" + std::string(tok(i)) + "' is not an integer");
    return v;
  }
  double real(std::size_t i) const {
    std::string_view t = tok(i);
    if (!t.empty() && t[0] == '+') t.remove_prefix(1);
    double v = 0;
    auto r = std::from_chars(t.data(), t.data() + t.size(), v);
    if (r.ec == std::errc() && r.ptr == t.data() + t.size()) return v;
    // Fortran writes exponents as 1.5D+02.
    std::string s(t);
    for (char& c : s)
      if (c == 'D' || c == 'd') c = 'e';
    r = std::from_chars(s.data(), s.data() + s.size(), v);
    if (r.ec != std::errc() || r.ptr != s.data() + s.size()) fail("'" + std::string(tok(i)) + "' is not a number");
    return v;
  }
  std::size_t lineno() const { return lineno_; }
  const std::string& path() const { return path_; }

 private:
  bool blank(char c) const { return c == ' ' || c == '\t' || (commas_ && c == ','); }
  std::string path_;
  bool commas_;
  std::ifstream in_;
  std::string line_;
  std::vector<std::string_view> tokens_;
  std::size_t lineno_ = 0;
};

// Maps file node ids to vertex indices (ids may be sparse or unordered).
struct IdMap {
  std::unordered_map<long long, Index> map;
  bool add(long long id, Index v) { return map.emplace(id, v).second; }
  Index at(const Lines& in, long long id) const {
    auto it = map.find(id);
    if (it == map.end()) in.fail("node id " + std::to_string(id) + " is not defined");
    return it->second;
  }
};

// Whole-mesh orientation: a file written clockwise is flipped so that triangles are
// counter-clockwise as MeshView requires; per-triangle order is otherwise kept. The majority of
// the triangles at most 180 units wide decides, not the total area: written in lon/lat, a
// triangle from 179.9 to -179.9 degrees is clockwise in the file's coordinates and its area
// outweighs that of all others. When every triangle is wider (a lon/lat mesh wholly across the
// antimeridian), those of a mesh within lon/lat bounds vote with their western longitudes plus
// 360. A tie falls back to the total area.
void orient_ccw(mesh::MeshView& m) {
  bool lonlat = true;
  for (const Point2& p : m.vertices) lonlat = lonlat && std::fabs(p.x) <= 180 && std::fabs(p.y) <= 90;
  auto twice_area = [](Point2 a, Point2 b, Point2 c) { return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x); };
  double total = 0;
  std::size_t ccw = 0, cw = 0, wide_ccw = 0, wide_cw = 0;
  for (const auto& t : m.triangles) {
    Point2 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
    const double d = twice_area(a, b, c);
    total += d;
    if (std::max({a.x, b.x, c.x}) - std::min({a.x, b.x, c.x}) <= 180) {
      ccw += d > 0;
      cw += d < 0;
    } else if (lonlat) {
      for (Point2* p : {&a, &b, &c})
        if (p->x < 0) p->x += 360;
      const double u = twice_area(a, b, c);
      wide_ccw += u > 0;
      wide_cw += u < 0;
    }
  }
  if (ccw + cw == 0) {
    ccw = wide_ccw;
    cw = wide_cw;
  }
  if (cw > ccw || (cw == ccw && total < 0))
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
}

void add_chain(mesh::MeshView& m, std::vector<Index> nodes, std::int32_t marker, std::int32_t part) {
  bool closed = nodes.size() > 2 && nodes.front() == nodes.back();
  if (closed) nodes.pop_back();
  detail::edges_from_chain(m, nodes, closed, marker, part);
}

// ------------------------------------------------------------------ SMS 2dm
mesh::MeshView read_2dm(const std::string& path) {
  Lines in(path);
  if (!in.next_data() || in.tok(0) != "MESH2D") in.fail("expected the MESH2D card on the first line");
  mesh::MeshView m;
  struct Node { long long id; double x, y, z; };
  struct Tri { long long n[3]; std::size_t line; };
  std::vector<Node> nodes;
  std::vector<Tri> tris;
  std::vector<std::pair<std::vector<long long>, std::size_t>> strings;  // ids, line
  std::vector<long long> cur;
  while (in.next_data()) {
    std::string_view card = in.tok(0);
    if (card == "ND") {
      nodes.push_back({in.integer(1), in.real(2), in.real(3), in.real(4)});
    } else if (card == "E3T") {
      tris.push_back({{in.integer(2), in.integer(3), in.integer(4)}, in.lineno()});
    } else if (card == "NS") {
      // Node ids continue over several NS cards; a negative id ends the string (an optional
      // name may follow it).
      for (std::size_t i = 1; i < in.size(); ++i) {
        long long id = in.integer(i);
        if (id == 0) in.fail("node id 0 in nodestring");
        cur.push_back(std::llabs(id));
        if (id < 0) {
          strings.push_back({cur, in.lineno()});
          cur.clear();
          break;
        }
      }
    } else if (card == "E2L" || card == "E3L" || card == "E4Q" || card == "E6T" || card == "E8Q" || card == "E9Q") {
      in.fail("element card " + std::string(card) + " is not a linear triangle; fdrmesh reads triangular meshes (E3T) only");
    }
    // Other cards (MESHNAME, NUM_MATERIALS_PER_ELEM, BC/model cards) do not change the mesh.
  }
  if (!cur.empty()) in.fail("the last nodestring is not terminated by a negative node id");
  IdMap ids;
  std::stable_sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a.id < b.id; });
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!ids.add(nodes[i].id, static_cast<Index>(i)))
      throw Error(ExitCode::kInputMalformed, path + ": node id " + std::to_string(nodes[i].id) + " defined twice");
    m.vertices.push_back({nodes[i].x, nodes[i].y});
    m.z.push_back(nodes[i].z);
  }
  for (const Tri& t : tris) {
    std::array<Index, 3> tri{};
    for (int k = 0; k < 3; ++k) {
      auto it = ids.map.find(t.n[k]);
      if (it == ids.map.end())
        throw Error(ExitCode::kInputMalformed, path + ":" + std::to_string(t.line) + ": node id " + std::to_string(t.n[k]) + " is not defined");
      tri[k] = it->second;
    }
    m.triangles.push_back(tri);
  }
  for (std::size_t s = 0; s < strings.size(); ++s) {
    std::vector<Index> chain;
    for (long long id : strings[s].first) {
      auto it = ids.map.find(id);
      if (it == ids.map.end())
        throw Error(ExitCode::kInputMalformed, path + ":" + std::to_string(strings[s].second) + ": nodestring node id " + std::to_string(id) + " is not defined");
      chain.push_back(it->second);
    }
    add_chain(m, chain, static_cast<std::int32_t>(mesh::EdgeKind::kOpen), static_cast<std::int32_t>(s));
  }
  return m;
}

// ------------------------------------------------------------------ ADCIRC fort.14
std::int32_t adcirc_kind(long long ibtype) {
  switch (ibtype) {
    case 1: case 11: case 21: return static_cast<std::int32_t>(mesh::EdgeKind::kIsland);
    case 4: case 24: case 5: case 25: return static_cast<std::int32_t>(mesh::EdgeKind::kBreakline);  // internal barriers
    default: return static_cast<std::int32_t>(mesh::EdgeKind::kLand);
  }
}

// `schism`: hgrid.gr3/.ll, where depth is always positive down and island boundaries (type 1)
// are closed without repeating their first node.
mesh::MeshView read_fort14(const std::string& path, const ReadOptions& o, bool schism = false) {
  Lines in(path, true);
  if (!in.next()) in.fail("empty file, expected the grid title line");
  in.require_data("NE NP");
  long long ne = in.integer(0), np = in.integer(1);
  if (ne < 0 || np < 0) in.fail("negative element or node count");
  mesh::MeshView m;
  IdMap ids;
  m.vertices.reserve(static_cast<std::size_t>(np));
  m.z.reserve(static_cast<std::size_t>(np));
  for (long long i = 0; i < np; ++i) {
    in.require_data("a node line 'JN X Y DP'");
    if (!ids.add(in.integer(0), static_cast<Index>(i))) in.fail("node id " + std::string(in.tok(0)) + " defined twice");
    m.vertices.push_back({in.real(1), in.real(2)});
    double dp = in.real(3);
    m.z.push_back(o.fort14_depth_positive_down || schism ? -dp : dp);
  }
  m.triangles.reserve(static_cast<std::size_t>(ne));
  for (long long i = 0; i < ne; ++i) {
    in.require_data("an element line 'JE 3 N1 N2 N3'");
    if (in.integer(1) != 3) in.fail("element with " + std::string(in.tok(1)) + " nodes; only triangles (3) are valid");
    m.triangles.push_back({ids.at(in, in.integer(2)), ids.at(in, in.integer(3)), ids.at(in, in.integer(4))});
  }
  std::int32_t part = 0;
  if (in.next_data()) {  // boundary information is optional
    long long nope = in.integer(0);
    in.require_data("NETA");
    for (long long k = 0; k < nope; ++k) {
      in.require_data("NVDLL");
      long long n = in.integer(0);
      std::vector<Index> chain;
      for (long long j = 0; j < n; ++j) {
        in.require_data("an open boundary node id");
        chain.push_back(ids.at(in, in.integer(0)));
      }
      add_chain(m, chain, static_cast<std::int32_t>(mesh::EdgeKind::kOpen), part++);
    }
    if (in.next_data()) {
      long long nbou = in.integer(0);
      in.require_data("NVEL");
      for (long long k = 0; k < nbou; ++k) {
        in.require_data("NVELL IBTYPE");
        long long n = in.integer(0), ibtype = in.integer(1);
        std::vector<Index> chain;
        for (long long j = 0; j < n; ++j) {
          in.require_data("a land boundary node id");
          chain.push_back(ids.at(in, in.integer(0)));
        }
        if (schism && ibtype == 1 && chain.size() > 2 && chain.front() != chain.back()) chain.push_back(chain.front());
        add_chain(m, chain, adcirc_kind(ibtype), part++);
      }
    }
  }
  return m;
}

// ------------------------------------------------------------------ Gmsh msh 4.1 ASCII
// A $NodeData section after its header line: its name (the first string tag, unquoted) and one
// scalar per vertex (through the node tags; 0 where the section gives none).
void read_msh_node_data(Lines& in, const IdMap& ids, std::size_t nv, std::string& name, std::vector<double>& values) {
  in.require_data("number of string tags");
  const long long ns = in.integer(0);
  for (long long i = 0; i < ns; ++i) {
    in.require_data("a string tag");
    if (i > 0) continue;
    name = in.line();
    std::erase_if(name, [](char c) { return c == '"' || c == ' ' || c == '\t'; });
  }
  in.require_data("number of real tags");
  for (long long i = 0, nr = in.integer(0); i < nr; ++i) in.require_data("a real tag");
  in.require_data("number of integer tags");
  std::vector<long long> ints(static_cast<std::size_t>(std::max(0LL, in.integer(0))));
  for (auto& v : ints) {
    in.require_data("an integer tag");
    v = in.integer(0);
  }
  if (ints.size() < 3) in.fail("$NodeData needs the time step, component and node counts");
  if (ints[1] != 1) in.fail("$NodeData with " + std::to_string(ints[1]) + " components; fdrmesh reads scalars");
  values.assign(nv, 0.0);
  for (long long i = 0; i < ints[2]; ++i) {
    in.require_data("a node value");
    values[ids.at(in, in.integer(0))] = in.real(1);
  }
  in.require_data("$EndNodeData");
  if (in.tok(0) != "$EndNodeData") in.fail("expected $EndNodeData");
}

// An msh written on the sphere: x, y, z (vertices and z) back to lon/lat degrees, and the
// elevation from its $NodeData "z" (0 without it).
void msh_sphere_to_lonlat(mesh::MeshView& m, std::vector<double> elevation) {
  constexpr double kDeg = 180.0 / std::numbers::pi;
  for (std::size_t v = 0; v < m.vertices.size(); ++v) {
    const double x = m.vertices[v].x, y = m.vertices[v].y, z = m.z[v];
    m.vertices[v] = {std::atan2(y, x) * kDeg, std::atan2(z, std::hypot(x, y)) * kDeg};
  }
  if (elevation.size() != m.vertices.size()) elevation.assign(m.vertices.size(), 0.0);
  m.z = std::move(elevation);
}

mesh::MeshView read_msh(const std::string& path) {
  Lines in(path);
  mesh::MeshView m;
  std::map<std::pair<int, int>, std::string> phys_names;   // (dim, tag) -> name
  std::map<int, int> curve_phys;                           // curve entity -> first physical tag
  IdMap ids;
  bool have_format = false;
  bool on_sphere = false;               // written on the sphere (kMshSphereComment)
  std::vector<double> elevation;        // its $NodeData "z"
  auto expect_end = [&](const char* section) {
    in.require_data(section);
    if (in.tok(0) != section) in.fail(std::string("expected ") + section);
  };
  while (in.next_data()) {
    std::string_view sec = in.tok(0);
    if (sec == "$MeshFormat") {
      in.require_data("version line");
      std::string_view ver = in.tok(0);
      if (ver.substr(0, 2) != "4.") in.fail("msh version " + std::string(ver) + "; fdrmesh reads msh 4.1");
      if (in.integer(1) != 0) in.fail("binary msh file; fdrmesh reads ASCII msh 4.1 (save with Binary=0)");
      expect_end("$EndMeshFormat");
      have_format = true;
    } else if (sec == "$PhysicalNames") {
      in.require_data("number of physical names");
      long long n = in.integer(0);
      for (long long i = 0; i < n; ++i) {
        in.require_data("a physical name");
        std::string name;
        auto q1 = in.line().find('"'), q2 = in.line().rfind('"');
        if (q1 == std::string::npos || q2 <= q1) in.fail("physical name is not quoted");
        name = in.line().substr(q1 + 1, q2 - q1 - 1);
        phys_names[{static_cast<int>(in.integer(0)), static_cast<int>(in.integer(1))}] = name;
      }
      expect_end("$EndPhysicalNames");
    } else if (sec == "$Entities") {
      in.require_data("entity counts");
      long long cnt[4] = {in.integer(0), in.integer(1), in.integer(2), in.integer(3)};
      for (int dim = 0; dim < 4; ++dim) {
        for (long long i = 0; i < cnt[dim]; ++i) {
          in.require_data("an entity line");
          // point: tag x y z nphys ...; others: tag 6 box values nphys ...
          std::size_t at = dim == 0 ? 4 : 7;
          long long nphys = in.integer(at);
          if (dim == 1 && nphys > 0) curve_phys[static_cast<int>(in.integer(0))] = static_cast<int>(in.integer(at + 1));
        }
      }
      expect_end("$EndEntities");
    } else if (sec == "$Nodes") {
      if (!have_format) in.fail("$Nodes before $MeshFormat");
      in.require_data("node counts");
      long long blocks = in.integer(0), total = in.integer(1);
      m.vertices.reserve(static_cast<std::size_t>(std::max(0LL, total)));
      for (long long b = 0; b < blocks; ++b) {
        in.require_data("a node block header");
        bool parametric = in.integer(2) != 0;
        long long n = in.integer(3);
        std::vector<long long> tags(static_cast<std::size_t>(n));
        for (auto& t : tags) {
          in.require_data("a node tag");
          t = in.integer(0);
        }
        for (long long i = 0; i < n; ++i) {
          in.require_data("node coordinates");
          if (!ids.add(tags[i], static_cast<Index>(m.vertices.size()))) in.fail("node tag " + std::to_string(tags[i]) + " defined twice");
          m.vertices.push_back({in.real(0), in.real(1)});
          m.z.push_back(in.real(2));
          (void)parametric;  // parametric coordinates follow x y z on the same line; not needed
        }
      }
      expect_end("$EndNodes");
    } else if (sec == "$Elements") {
      in.require_data("element counts");
      long long blocks = in.integer(0);
      for (long long b = 0; b < blocks; ++b) {
        in.require_data("an element block header");
        int dim = static_cast<int>(in.integer(0)), tag = static_cast<int>(in.integer(1));
        long long type = in.integer(2), n = in.integer(3);
        if (type != 1 && type != 2 && type != 15)
          in.fail("element type " + std::to_string(type) + "; fdrmesh reads linear triangles (2), lines (1) and points (15)");
        std::int32_t marker = 0;
        if (type == 1) {
          auto it = curve_phys.find(tag);
          if (it != curve_phys.end()) {
            auto nm = phys_names.find({1, it->second});
            if (nm == phys_names.end() || !kind_from_name(nm->second, marker)) marker = it->second;
          }
        }
        (void)dim;
        for (long long i = 0; i < n; ++i) {
          in.require_data("an element line");
          if (type == 2) m.triangles.push_back({ids.at(in, in.integer(1)), ids.at(in, in.integer(2)), ids.at(in, in.integer(3))});
          if (type == 1) m.edges.push_back({ids.at(in, in.integer(1)), ids.at(in, in.integer(2)), marker, tag});
        }
      }
      expect_end("$EndElements");
    } else if (sec == "$NodeData" && on_sphere) {
      std::string name;
      std::vector<double> values;
      read_msh_node_data(in, ids, m.vertices.size(), name, values);
      if (name == "z") elevation = std::move(values);
    } else if (sec.size() > 1 && sec[0] == '$') {
      // Unknown section ($Comments, $NodeData, ...): skip to its end; a comment may say the nodes
      // are on the sphere.
      const std::string section(sec);  // sec views the current line, which next() replaces
      const std::string end = "$End" + section.substr(1);
      for (;;) {
        if (!in.next()) in.fail("unexpected end of file inside section " + section);
        if (!in.line().empty() && in.line().rfind(end, 0) == 0) break;
        if (section == "$Comments" && in.line().rfind(detail::kMshSphereComment, 0) == 0) on_sphere = true;
      }
    } else {
      in.fail("expected a $Section line");
    }
  }
  if (!have_format) in.fail("no $MeshFormat section; not a Gmsh msh file");
  if (on_sphere) msh_sphere_to_lonlat(m, std::move(elevation));
  return m;
}

// ------------------------------------------------------------------ Triangle .node / .ele
mesh::MeshView read_node_ele(const std::string& path) {
  std::string ext = detail::lower_extension(path);
  std::string base = path.substr(0, path.size() - ext.size());
  mesh::MeshView m;
  IdMap ids;
  {
    Lines in(base + ".node");
    in.require_data("the .node header");
    long long n = in.integer(0), dim = in.integer(1);
    long long nattr = in.size() > 2 ? in.integer(2) : 0;
    long long nbm = in.size() > 3 ? in.integer(3) : 0;
    if (dim != 2) in.fail("dimension " + std::to_string(dim) + "; Triangle files are 2D");
    int z_attr = nattr > 0 ? 0 : -1, f_attr = -1;
    // fdrmesh names its attributes in a comment line right after the header; without it the
    // first attribute is taken as z.
    bool pending = false;  // the line in hand is already the first vertex
    if (in.next() && in.line().rfind("# fdrmesh attributes:", 0) == 0) {
      z_attr = -1;
      for (std::size_t i = 3; i < in.size(); ++i) {
        if (in.tok(i) == "z") z_attr = static_cast<int>(i - 3);
        if (in.tok(i) == "f") f_attr = static_cast<int>(i - 3);
      }
    } else {
      pending = in.size() > 0 && in.tok(0)[0] != '#';
    }
    for (long long i = 0; i < n; ++i) {
      if (!pending) in.require_data("a vertex line");
      pending = false;
      long long id = in.integer(0);
      if (!ids.add(id, static_cast<Index>(m.vertices.size()))) in.fail("vertex " + std::to_string(id) + " defined twice");
      m.vertices.push_back({in.real(1), in.real(2)});
      if (z_attr >= 0) m.z.push_back(in.real(3 + z_attr));
      if (f_attr >= 0) m.f.push_back(in.real(3 + f_attr));
      if (nbm > 0) m.vertex_marker.push_back(static_cast<std::int32_t>(in.integer(3 + nattr)));
    }
  }
  {
    Lines in(base + ".ele");
    in.require_data("the .ele header");
    long long n = in.integer(0), npt = in.integer(1);
    if (npt != 3) in.fail(std::to_string(npt) + " nodes per triangle; fdrmesh reads linear (3-node) triangles");
    m.triangles.reserve(static_cast<std::size_t>(std::max(0LL, n)));
    for (long long i = 0; i < n; ++i) {
      in.require_data("a triangle line");
      m.triangles.push_back({ids.at(in, in.integer(1)), ids.at(in, in.integer(2)), ids.at(in, in.integer(3))});
    }
  }
  return m;
}

// ------------------------------------------------------------------ fdrmesh GeoPackage
struct CoordKey {
  double x, y;
  bool operator==(const CoordKey& o) const { return x == o.x && y == o.y; }
};
struct CoordHash {
  std::size_t operator()(const CoordKey& k) const {
    std::uint64_t a, b;
    std::memcpy(&a, &k.x, 8);
    std::memcpy(&b, &k.y, 8);
    return std::hash<std::uint64_t>()(a * 0x9E3779B97F4A7C15ull ^ b);
  }
};

mesh::MeshView read_gpkg(const std::string& path) {
  detail::gdal_register_once();
  detail::GdalErrors errs;
  const char* drivers[] = {"GPKG", nullptr};
  detail::DatasetPtr ds(static_cast<GDALDataset*>(
      GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, drivers, nullptr, nullptr)));
  if (!ds) unreadable(path, errs.reason("cannot open as a GeoPackage"));
  auto malformed = [&](const std::string& why) { throw Error(ExitCode::kInputMalformed, path + ": " + why); };
  auto need = [&](const char* name) {
    OGRLayer* l = ds->GetLayerByName(name);
    if (!l) malformed(std::string("layer '") + name + "' not found (not a mesh written by fdrmesh?)");
    return l;
  };
  OGRLayer* ln = need("nodes");
  OGRLayer* lt = need("triangles");
  OGRLayer* lb = ds->GetLayerByName("boundaries");
  mesh::MeshView m;
  // srs_id <= 0 are the GeoPackage's "undefined" systems: no CRS.
  long long srs_id = 0;
  if (OGRLayer* q = ds->ExecuteSQL("SELECT srs_id FROM gpkg_contents WHERE table_name = 'nodes'", nullptr, nullptr)) {
    if (std::unique_ptr<OGRFeature> row{q->GetNextFeature()}) srs_id = row->GetFieldAsInteger64(0);
    ds->ReleaseResultSet(q);
  }
  const OGRSpatialReference* srs = srs_id > 0 ? ln->GetSpatialRef() : nullptr;
  if (srs) {
    char* s = nullptr;
    const char* opts[] = {"FORMAT=WKT2_2019", nullptr};
    if (srs->exportToWkt(&s, opts) == OGRERR_NONE && s) m.crs_wkt = s;
    CPLFree(s);
  }

  const OGRFeatureDefn* dn = ln->GetLayerDefn();
  int i_id = dn->GetFieldIndex("id"), i_z = dn->GetFieldIndex("z"), i_f = dn->GetFieldIndex("f"),
      i_mk = dn->GetFieldIndex("marker");
  if (i_id < 0) malformed("layer 'nodes' has no field 'id'");
  struct Node { long long id; double x, y, z, f; int marker; };
  std::vector<Node> nodes;
  bool all_z = i_z >= 0, all_f = i_f >= 0;
  ln->ResetReading();
  for (auto& feat : *ln) {
    const OGRGeometry* g = feat->GetGeometryRef();
    if (!g || wkbFlatten(g->getGeometryType()) != wkbPoint)
      malformed("layer 'nodes' feature " + std::to_string(feat->GetFID()) + ": geometry is not a point");
    auto* p = g->toPoint();
    Node n{feat->GetFieldAsInteger64(i_id), p->getX(), p->getY(), 0, 0, 0};
    if (i_z >= 0 && feat->IsFieldSetAndNotNull(i_z)) n.z = feat->GetFieldAsDouble(i_z);
    else all_z = false;
    if (i_f >= 0 && feat->IsFieldSetAndNotNull(i_f)) n.f = feat->GetFieldAsDouble(i_f);
    else all_f = false;
    if (i_mk >= 0) n.marker = feat->GetFieldAsInteger(i_mk);
    nodes.push_back(n);
  }
  std::stable_sort(nodes.begin(), nodes.end(), [](const Node& a, const Node& b) { return a.id < b.id; });
  std::unordered_map<long long, Index> ids;
  std::unordered_map<CoordKey, Index, CoordHash> at_xy;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    if (!ids.emplace(nodes[i].id, static_cast<Index>(i)).second)
      malformed("layer 'nodes': id " + std::to_string(nodes[i].id) + " appears twice");
    at_xy.emplace(CoordKey{nodes[i].x, nodes[i].y}, static_cast<Index>(i));
    m.vertices.push_back({nodes[i].x, nodes[i].y});
    if (all_z) m.z.push_back(nodes[i].z);
    if (all_f) m.f.push_back(nodes[i].f);
    if (i_mk >= 0) m.vertex_marker.push_back(nodes[i].marker);
  }
  auto by_xy = [&](const char* layer, GIntBig fid, double x, double y) {
    auto it = at_xy.find({x, y});
    if (it == at_xy.end()) {
      char buf[128];
      std::snprintf(buf, sizeof buf, "(%.17g, %.17g)", x, y);
      malformed(std::string("layer '") + layer + "' feature " + std::to_string(fid) + ": vertex " + buf + " is not a mesh node");
    }
    return it->second;
  };

  const OGRFeatureDefn* dt = lt->GetLayerDefn();
  int i_n[3] = {dt->GetFieldIndex("n1"), dt->GetFieldIndex("n2"), dt->GetFieldIndex("n3")};
  bool by_id = i_n[0] >= 0 && i_n[1] >= 0 && i_n[2] >= 0;
  lt->ResetReading();
  for (auto& feat : *lt) {
    std::array<Index, 3> tri{};
    if (by_id) {
      for (int k = 0; k < 3; ++k) {
        long long id = feat->GetFieldAsInteger64(i_n[k]);
        auto it = ids.find(id);
        if (it == ids.end())
          malformed("layer 'triangles' feature " + std::to_string(feat->GetFID()) + ": node id " + std::to_string(id) + " not in layer 'nodes'");
        tri[k] = it->second;
      }
    } else {
      // Without node id fields, the polygon's ring vertices are matched to nodes exactly.
      const OGRGeometry* g = feat->GetGeometryRef();
      const OGRLinearRing* ring = nullptr;
      if (g && wkbFlatten(g->getGeometryType()) == wkbPolygon) ring = g->toPolygon()->getExteriorRing();
      if (!ring || ring->getNumPoints() != 4)
        malformed("layer 'triangles' feature " + std::to_string(feat->GetFID()) + ": geometry is not a triangle polygon");
      for (int k = 0; k < 3; ++k) tri[k] = by_xy("triangles", feat->GetFID(), ring->getX(k), ring->getY(k));
    }
    m.triangles.push_back(tri);
  }

  if (lb) {
    const OGRFeatureDefn* db = lb->GetLayerDefn();
    int i_kind = db->GetFieldIndex("kind"), i_marker = db->GetFieldIndex("marker"), i_part = db->GetFieldIndex("part");
    lb->ResetReading();
    for (auto& feat : *lb) {
      const OGRGeometry* g = feat->GetGeometryRef();
      if (!g || wkbFlatten(g->getGeometryType()) != wkbLineString)
        malformed("layer 'boundaries' feature " + std::to_string(feat->GetFID()) + ": geometry is not a line string");
      const OGRLineString* ls = g->toLineString();
      std::int32_t marker = 0;
      if (i_kind < 0 || !kind_from_name(feat->GetFieldAsString(i_kind), marker))
        marker = i_marker >= 0 ? feat->GetFieldAsInteger(i_marker) : 0;
      std::int32_t part = i_part >= 0 ? feat->GetFieldAsInteger(i_part) : static_cast<std::int32_t>(feat->GetFID());
      std::vector<Index> chain;
      for (int k = 0; k < ls->getNumPoints(); ++k) chain.push_back(by_xy("boundaries", feat->GetFID(), ls->getX(k), ls->getY(k)));
      add_chain(m, chain, marker, part);
    }
  }
  return m;
}

// ------------------------------------------------------------------ Telemac Selafin
// Fortran sequential records (big-endian as Telemac writes them; little-endian files are
// accepted too): see write_selafin in write_models.cpp for the layout. Coordinates get the
// IPARAM(3)/(4) origin added; z is the first time step of BOTTOM (or FOND), else 0.
mesh::MeshView read_selafin(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) unreadable(path, std::string("cannot open: ") + std::strerror(errno));
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0, std::ios::beg);
  bool swap = true;  // file big-endian on a little-endian machine
  auto bad = [&](const std::string& why) -> void {
    throw Error(ExitCode::kInputMalformed, path + ": byte " + std::to_string(static_cast<long long>(in.tellg())) + ": " + why);
  };
  auto u32 = [&]() {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) bad("unexpected end of file");
    return swap ? (std::uint32_t{b[0]} << 24 | std::uint32_t{b[1]} << 16 | std::uint32_t{b[2]} << 8 | b[3])
                : (std::uint32_t{b[3]} << 24 | std::uint32_t{b[2]} << 16 | std::uint32_t{b[1]} << 8 | b[0]);
  };
  auto u64 = [&]() {
    std::uint64_t hi = u32(), lo = u32();
    return swap ? (hi << 32 | lo) : (lo << 32 | hi);
  };
  {
    std::uint32_t first = u32();
    if (first != 80) {
      swap = !swap;
      in.seekg(0);
      if (u32() != 80) bad("not a Selafin file (the first record is not the 80-character title)");
    }
    in.seekg(0);
  }
  // Reads one record's length marker, checks it against `want` when want > 0.
  auto open_rec = [&](std::uint64_t want) {
    const std::uint64_t n = u32();
    if (want && n != want) bad("record of " + std::to_string(n) + " bytes, expected " + std::to_string(want));
    if (n > size) bad("record length beyond the end of the file");
    return n;
  };
  auto close_rec = [&](std::uint64_t n) {
    if (u32() != n) bad("record end marker does not match its start");
  };
  open_rec(80);
  std::string title(80, ' ');
  if (!in.read(title.data(), 80)) bad("unexpected end of file");
  close_rec(80);
  const std::string kind = title.substr(72, 8);
  const bool dbl = kind == "SERAFIND";
  if (!dbl && kind.rfind("SERAFIN", 0) != 0 && kind != "        ") bad("unknown Selafin type '" + kind + "'");
  open_rec(8);
  const std::uint32_t nbv1 = u32(), nbv2 = u32();
  close_rec(8);
  if (nbv1 > 100000 || nbv2 > 100000) bad("implausible number of variables");
  int bottom = -1;
  for (std::uint32_t i = 0; i < nbv1 + nbv2; ++i) {
    open_rec(32);
    std::string name(32, ' ');
    if (!in.read(name.data(), 32)) bad("unexpected end of file");
    close_rec(32);
    std::string n16 = name.substr(0, 16);
    while (!n16.empty() && n16.back() == ' ') n16.pop_back();
    if (bottom < 0 && (n16 == "BOTTOM" || n16 == "FOND")) bottom = static_cast<int>(i);
  }
  open_rec(40);
  std::int32_t ip[10];
  for (auto& v : ip) v = static_cast<std::int32_t>(u32());
  close_rec(40);
  if (ip[6] > 1) bad("3D Selafin files (IPARAM(7) = " + std::to_string(ip[6]) + " planes) are not meshes fdrmesh reads");
  if (ip[7] != 0 || ip[8] != 0) bad("a partition of a parallel run (IPARAM(8..9) set): merge the partitions into one Selafin file first");
  if (ip[9] == 1) {
    open_rec(24);
    for (int k = 0; k < 6; ++k) u32();
    close_rec(24);
  }
  open_rec(16);
  const std::uint32_t nelem = u32(), npoin = u32(), ndp = u32();
  u32();
  close_rec(16);
  if (ndp != 3) bad("elements with " + std::to_string(ndp) + " nodes; only triangles (3) are read");
  if (static_cast<std::uint64_t>(nelem) * 12 > size || static_cast<std::uint64_t>(npoin) * 8 > size)
    bad("element or node count larger than the file");
  mesh::MeshView m;
  m.triangles.resize(nelem);
  open_rec(12ull * nelem);
  for (auto& t : m.triangles)
    for (auto& v : t) {
      const std::uint32_t id = u32();
      if (id < 1 || id > npoin) bad("IKLE references node " + std::to_string(id) + " of " + std::to_string(npoin));
      v = static_cast<Index>(id - 1);
    }
  close_rec(12ull * nelem);
  open_rec(4ull * npoin);
  for (std::uint32_t i = 0; i < npoin; ++i) u32();  // IPOBO
  close_rec(4ull * npoin);
  const std::uint64_t rs = dbl ? 8 : 4;
  auto real = [&]() {
    if (dbl) {
      std::uint64_t u = u64();
      double d;
      std::memcpy(&d, &u, 8);
      return d;
    }
    std::uint32_t u = u32();
    float f;
    std::memcpy(&f, &u, 4);
    return static_cast<double>(f);
  };
  std::vector<double> x(npoin), y(npoin);
  open_rec(rs * npoin);
  for (auto& v : x) v = real() + ip[2];
  close_rec(rs * npoin);
  open_rec(rs * npoin);
  for (auto& v : y) v = real() + ip[3];
  close_rec(rs * npoin);
  m.vertices.resize(npoin);
  for (std::uint32_t i = 0; i < npoin; ++i) m.vertices[i] = {x[i], y[i]};
  m.z.assign(npoin, 0.0);
  if (bottom >= 0 && static_cast<std::uint64_t>(in.tellg()) < size) {
    open_rec(rs);
    real();  // time
    close_rec(rs);
    for (int i = 0; i <= bottom; ++i) {
      open_rec(rs * npoin);
      for (std::uint32_t k = 0; k < npoin; ++k) {
        const double v = real();
        if (i == bottom) m.z[k] = v;
      }
      close_rec(rs * npoin);
    }
  }
  return m;
}

}  // namespace

mesh::MeshView read_mesh(const std::string& path, const ReadOptions& options) {
  struct stat st {};
  std::string ext = detail::lower_extension(path);
  std::string name = detail::to_lower(detail::file_name(path));
  std::string probe = path;
  if (ext == ".node" || ext == ".ele") probe = path.substr(0, path.size() - ext.size()) + ".node";
  if (::stat(probe.c_str(), &st) != 0) unreadable(probe, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(st.st_mode)) unreadable(probe, "is a directory");
  mesh::MeshView m;
  if (ext == ".2dm") m = read_2dm(path);
  else if (name == "fort.14" || ext == ".14" || ext == ".grd") m = read_fort14(path, options);
  else if (ext == ".msh") m = read_msh(path);
  else if (ext == ".node" || ext == ".ele") m = read_node_ele(path);
  else if (ext == ".gpkg") m = read_gpkg(path);
  else if (ext == ".gr3" || ext == ".ll") m = read_fort14(path, options, true);
  else if (ext == ".slf") m = read_selafin(path);
  else
    unreadable(path, "cannot read meshes of this type; readable: .2dm, fort.14 (.14, .grd), .gr3/.ll (SCHISM), "
                     ".slf (Selafin), .msh (4.1 ASCII), .node/.ele, .gpkg (written by fdrmesh)");
  orient_ccw(m);
  return m;
}

}  // namespace fdr::io
