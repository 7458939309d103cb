// GeoPackage spatial index through SQL (see gpkg_index.hpp).
//
// The tables behind SQLite's rtree module (2D, no auxiliary columns), as its rtree.c documents
// them:
//   <rtree>_node(nodeno INTEGER PRIMARY KEY, data BLOB): node 1 is the root; every blob has the
//     table's node size: [depth: int16 BE, root only, else 0][count: int16 BE][cells], a cell
//     being [id: int64 BE][minx maxx miny maxy: float32 BE], id a row id in leaves and a child
//     node number above; boxes are rounded outwards to float.
//   <rtree>_parent(nodeno, parentnode) for every node but the root; <rtree>_rowid(rowid, nodeno)
//     for every indexed row, naming its leaf.
#include "io/gpkg_index.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include "io/detail.hpp"

namespace fdr::io::detail {

using Cell = RtreeCell;

std::uint32_t hilbert_key(std::uint32_t x, std::uint32_t y) {
  x &= 0xFFFF;
  y &= 0xFFFF;
  std::uint32_t d = 0;
  for (std::uint32_t s = 1u << 15; s > 0; s >>= 1) {
    const std::uint32_t rx = (x & s) ? 1 : 0, ry = (y & s) ? 1 : 0;
    d += s * s * ((3 * rx) ^ ry);
    // Turn the quadrant just entered into the curve's standard orientation for the next level.
    if (ry == 0) {
      if (rx == 1) {
        x ^= 0xFFFF;
        y ^= 0xFFFF;
      }
      std::swap(x, y);
    }
  }
  return d;
}

std::vector<std::uint32_t> rtree_insert_order(std::size_t n, const BoxOf& box) {
  if (n > std::numeric_limits<std::uint32_t>::max())
    throw Error(ExitCode::kInternal, "R-tree of more than 2^32 rows");
  // The grid spans the box centres; a degenerate extent puts every centre in one cell.
  double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  double hi[2] = {-lo[0], -lo[1]};
  IndexBox b{};
  std::size_t count = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!box(i, b)) continue;
    ++count;
    const double c[2] = {0.5 * (b.minx + b.maxx), 0.5 * (b.miny + b.maxy)};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
  }
  double scale[2];
  for (int k = 0; k < 2; ++k) {
    scale[k] = hi[k] > lo[k] ? 65535.0 / (hi[k] - lo[k]) : 0.0;
    if (!std::isfinite(scale[k])) scale[k] = 0.0;
  }
  auto cell = [&](double v, int k) -> std::uint32_t {
    const double t = (v - lo[k]) * scale[k];
    return t >= 0 && t <= 65535.0 ? static_cast<std::uint32_t>(t) : 0;  // NaN centres: cell 0
  };
  // Key in the high half, row in the low: sorting the pairs orders by key, then by row.
  std::vector<std::uint64_t> keyed;
  keyed.reserve(count);
  for (std::size_t i = 0; i < n; ++i) {
    if (!box(i, b)) continue;
    const std::uint32_t key = hilbert_key(cell(0.5 * (b.minx + b.maxx), 0), cell(0.5 * (b.miny + b.maxy), 1));
    keyed.push_back(std::uint64_t{key} << 32 | i);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint32_t> order(keyed.size());
  for (std::size_t k = 0; k < keyed.size(); ++k) order[k] = static_cast<std::uint32_t>(keyed[k]);
  return order;
}

namespace {

std::string quoted(const std::string& name) { return "\"" + name + "\""; }

// The float at or below v, and at or above v: the rounding SQLite's rtree applies to boxes.
float float_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float float_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

void put_be(char* out, std::uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) *out++ = static_cast<char>((v >> (8 * i)) & 0xFF);
}

void node_blob(std::string& b, const Cell* cells, std::size_t n, int depth, std::size_t node_size) {
  b.assign(node_size, '\0');
  char* o = b.data();
  put_be(o, static_cast<std::uint64_t>(depth), 2);
  put_be(o + 2, n, 2);
  o += 4;
  for (const Cell* c = cells; c != cells + n; ++c, o += 24) {
    put_be(o, c->id, 8);
    for (int k = 0; k < 4; ++k) {
      std::uint32_t u;
      std::memcpy(&u, &c->box[k], 4);
      put_be(o + 8 + 4 * k, u, 4);
    }
  }
}

}  // namespace

PackedRtree pack_rtree(std::size_t n, const BoxOf& box, std::size_t cap) {
  PackedRtree t;
  t.cap = cap;
  const std::vector<std::uint32_t> order = rtree_insert_order(n, box);
  if (order.empty() || cap < 2) return t;
  std::vector<Cell> cur;
  cur.reserve(order.size());
  IndexBox b{};
  for (const std::uint32_t i : order) {
    box(i, b);
    cur.push_back({i + 1, {float_down(b.minx), float_up(b.maxx), float_down(b.miny), float_up(b.maxy)}});
  }
  // Level by level: consecutive runs of `cap` cells make a node, whose cell one level up is
  // numbered in creation order from 2 (node 1, the root, is the level that fits in one node).
  std::uint32_t next_no = 2;
  while (cur.size() > cap) {
    std::vector<Cell> up;
    up.reserve((cur.size() + cap - 1) / cap);
    for (std::size_t first = 0; first < cur.size(); first += cap) {
      const std::size_t last = std::min(cur.size(), first + cap);
      Cell q{next_no++, {cur[first].box[0], cur[first].box[1], cur[first].box[2], cur[first].box[3]}};
      for (std::size_t k = first + 1; k < last; ++k) {
        q.box[0] = std::min(q.box[0], cur[k].box[0]), q.box[1] = std::max(q.box[1], cur[k].box[1]);
        q.box[2] = std::min(q.box[2], cur[k].box[2]), q.box[3] = std::max(q.box[3], cur[k].box[3]);
      }
      up.push_back(q);
    }
    t.levels.push_back(std::move(cur));
    cur = std::move(up);
  }
  t.levels.push_back(std::move(cur));
  return t;
}

namespace {

// The rows of the rtree's node, parent and rowid tables for a packed tree (the table's empty
// root replaced). Every table is written in increasing key order, so SQLite appends each row.
void write_rtree_tables(SqliteDb& db, const std::string& rt, const PackedRtree& t, std::size_t node_size) {
  db.exec("DELETE FROM " + quoted(rt + "_node"));
  const std::size_t depth = t.levels.size() - 1, cap = t.cap;
  // Number of the first node of each level below the root (the root is 1).
  std::vector<std::uint32_t> base(t.levels.size(), 1);
  std::uint32_t next_no = 2;
  for (std::size_t l = 0; l < depth; ++l) {
    base[l] = next_no;
    next_no += static_cast<std::uint32_t>((t.levels[l].size() + cap - 1) / cap);
  }
  {
    BatchInsert nodes(db, rt + "_node", {"nodeno", "data"}, 16);
    std::string blob;
    node_blob(blob, t.levels[depth].data(), t.levels[depth].size(), static_cast<int>(depth), node_size);
    nodes.add_int(1).add_blob(blob.data(), blob.size());
    nodes.end_row();
    for (std::size_t l = 0; l < depth; ++l)
      for (std::size_t first = 0, j = 0; first < t.levels[l].size(); first += cap, ++j) {
        node_blob(blob, t.levels[l].data() + first, std::min(cap, t.levels[l].size() - first), 0, node_size);
        nodes.add_int(base[l] + static_cast<std::int64_t>(j)).add_blob(blob.data(), blob.size());
        nodes.end_row();
      }
    nodes.finish();
  }
  {
    BatchInsert parents(db, rt + "_parent", {"nodeno", "parentnode"}, 256);
    for (std::size_t l = 0; l < depth; ++l)
      for (std::size_t j = 0; j * cap < t.levels[l].size(); ++j) {
        parents.add_int(base[l] + static_cast<std::int64_t>(j)).add_int(base[l + 1] + static_cast<std::int64_t>(j / cap));
        parents.end_row();
      }
    parents.finish();
  }
  // Each row's leaf, then the rows in id order.
  const std::vector<Cell>& leaves = t.levels[0];
  std::uint32_t max_id = 0;
  for (const Cell& c : leaves) max_id = std::max(max_id, c.id);
  std::vector<std::uint32_t> leaf_of(static_cast<std::size_t>(max_id) + 1, 0);
  for (std::size_t k = 0; k < leaves.size(); ++k) leaf_of[leaves[k].id] = depth == 0 ? 1 : base[0] + static_cast<std::uint32_t>(k / cap);
  BatchInsert rowids(db, rt + "_rowid", {"rowid", "nodeno"}, 256);
  for (std::size_t id = 1; id < leaf_of.size(); ++id)
    if (leaf_of[id]) {
      rowids.add_int(static_cast<std::int64_t>(id)).add_int(leaf_of[id]);
      rowids.end_row();
    }
  rowids.finish();
}

// The maintenance triggers of the GeoPackage 1.2 gpkg_rtree_index extension (spec, Annex F.3)
// and its gpkg_extensions row.
void add_triggers(SqliteDb& db, const std::string& t, const std::string& g, const std::string& rt) {
  const std::string T = quoted(t), C = quoted(g), I = quoted("fid"), R = quoted(rt);
  const std::string values = "VALUES (NEW." + I + ", ST_MinX(NEW." + C + "), ST_MaxX(NEW." + C + "), ST_MinY(NEW." + C +
                             "), ST_MaxY(NEW." + C + "))";
  db.exec("CREATE TRIGGER " + quoted(rt + "_insert") + " AFTER INSERT ON " + T + " WHEN (new." + C +
          " NOT NULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN INSERT OR REPLACE INTO " + R + " " + values + "; END");
  db.exec("CREATE TRIGGER " + quoted(rt + "_update1") + " AFTER UPDATE OF " + C + " ON " + T + " WHEN OLD." + I +
          " = NEW." + I + " AND (NEW." + C + " NOTNULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN INSERT OR REPLACE INTO " +
          R + " " + values + "; END");
  db.exec("CREATE TRIGGER " + quoted(rt + "_update2") + " AFTER UPDATE OF " + C + " ON " + T + " WHEN OLD." + I +
          " = NEW." + I + " AND (NEW." + C + " ISNULL OR ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R +
          " WHERE id = OLD." + I + "; END");
  db.exec("CREATE TRIGGER " + quoted(rt + "_update3") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I +
          " AND (NEW." + C + " NOTNULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R + " WHERE id = OLD." +
          I + "; INSERT OR REPLACE INTO " + R + " " + values + "; END");
  db.exec("CREATE TRIGGER " + quoted(rt + "_update4") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I +
          " AND (NEW." + C + " ISNULL OR ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R + " WHERE id IN (OLD." + I +
          ", NEW." + I + "); END");
  db.exec("CREATE TRIGGER " + quoted(rt + "_delete") + " AFTER DELETE ON " + T + " WHEN old." + C +
          " NOT NULL BEGIN DELETE FROM " + R + " WHERE id = OLD." + I + "; END");
  db.exec("INSERT INTO gpkg_extensions (table_name, column_name, extension_name, definition, scope) VALUES ('" + t +
          "', '" + g + "', 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', 'write-only')");
}

}  // namespace

void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, std::size_t n,
                      const BoxOf& box) {
  const std::string rt = "rtree_" + table + "_" + geom_col;
  db.exec("CREATE VIRTUAL TABLE " + quoted(rt) + " USING rtree(id, minx, maxx, miny, maxy)");
  // The node size SQLite chose for this page size, read from the empty root it made.
  const auto node_size =
      static_cast<std::size_t>(db.query_int("SELECT length(data) FROM " + quoted(rt + "_node") + " WHERE nodeno = 1"));
  if (node_size < 4 + 4 * 24) fail_output(db.path(), "cannot read the R-tree node size of table '" + table + "'");
  const PackedRtree t = pack_rtree(n, box, (node_size - 4) / 24);
  if (!t.levels.empty()) write_rtree_tables(db, rt, t, node_size);
  add_triggers(db, table, geom_col, rt);
}

}  // namespace fdr::io::detail
