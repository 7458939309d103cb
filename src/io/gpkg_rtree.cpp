// Bulk-loaded GeoPackage R-tree spatial index (gpkg_rtree_index extension), packed with Sort-Tile-Recursive.
//
// SQLite R*tree storage (2D, no auxiliary columns), as documented in SQLite's rtree.c:
//   <rtree>_node(nodeno INTEGER PRIMARY KEY, data BLOB): node 1 is the root; every blob has the
//     table's fixed node size: [depth:int16 BE (root only)][count:int16 BE][cells...], a cell being
//     [id:int64 BE][minx maxx miny maxy: float32 BE]; id is a rowid in leaves, a child node number
//     otherwise. Boxes are rounded outwards to float.
//   <rtree>_parent(nodeno, parentnode) for every non-root node; <rtree>_rowid(rowid, nodeno) for
//     every indexed row, naming its leaf.
#include "io/gpkg_rtree.hpp"


#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>

#include "base/error.hpp"
#include "io/detail.hpp"

namespace fdr::io::detail {

namespace {

using Cell = RtreeEntry;

// The next float towards -inf / +inf from a finite non-zero float, by its bits (what
// std::nextafter gives there, without the library call: one per box side of every row).
float float_below(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  u = f > 0 ? u - 1 : u + 1;
  std::memcpy(&f, &u, 4);
  return f;
}
float float_above(float f) {
  std::uint32_t u;
  std::memcpy(&u, &f, 4);
  u = f > 0 ? u + 1 : u - 1;
  std::memcpy(&f, &u, 4);
  return f;
}

float round_down(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) > v)
    f = std::isfinite(f) && f != 0 && f != -std::numeric_limits<float>::max() ? float_below(f)
                                                                              : std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}
float round_up(double v) {
  float f = static_cast<float>(v);
  if (static_cast<double>(f) < v)
    f = std::isfinite(f) && f != 0 && f != std::numeric_limits<float>::max() ? float_above(f)
                                                                             : std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

// Order-preserving unsigned key of a double (negatives below positives).
std::uint64_t sort_key(double v) {
  std::uint64_t u;
  std::memcpy(&u, &v, 8);
  return (u >> 63) ? ~u : (u | (std::uint64_t{1} << 63));
}

// Stable LSD radix sort of [b, e) by key(cell) (8-bit digits, passes where all digits agree
// skipped). The cells move themselves between [b, e) and one buffer (24 bytes per cell extra, the
// key computed again in each pass) instead of sorting (key, index) pairs and gathering: 32 bytes
// less per cell at the writer's peak.
// `buf` is the caller's, reused from call to call (grown to n cells when smaller). Why: a fresh
// buffer per STR slice was 150 slices' worth of page faults per tree at 1 M triangles (freed
// memory goes back to the system at once in the mesh stages: base/memory.hpp).
template <class Key>
void radix_sort(std::vector<Cell>::iterator b, std::vector<Cell>::iterator e, Key key, std::vector<Cell>& buf) {
  const auto n = static_cast<std::size_t>(e - b);
  if (n < 2) return;
  Cell* src = &*b;
  if (buf.size() < n) buf.resize(n);
  Cell* dst = buf.data();
  // The digit counts of every pass in one read of the keys; a pass whose digit is the same for
  // every key moves nothing and is skipped.
  std::array<std::array<std::size_t, 257>, 8> count;
  for (auto& c : count) c.fill(0);
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint64_t k = key(src[i]);
    for (int d = 0; d < 8; ++d) ++count[d][((k >> (8 * d)) & 0xFF) + 1];
  }
  for (int d = 0; d < 8; ++d) {
    auto& c = count[d];
    if (*std::max_element(c.begin() + 1, c.end()) == n) continue;  // one digit value: nothing moves
    for (int x = 0; x < 256; ++x) c[x + 1] += c[x];
    const int shift = 8 * d;
    for (std::size_t i = 0; i < n; ++i) dst[c[(key(src[i]) >> shift) & 0xFF]++] = src[i];
    std::swap(src, dst);
  }
  if (src != &*b) std::copy(src, src + n, &*b);
}

// Sorts the cells by (x, id) in place, x(c) being a double, as std::sort with that comparison
// would, in about a third of its time at 1 M cells: first distributed in place into buckets of
// x (American flag sort; the bucket is a monotone function of x, so the buckets are in order),
// then each bucket sorted. std::sort when some x is not finite.
template <class X>
void sort_by_key_then_id(std::vector<Cell>& cells, X x) {
  auto less = [&x](const Cell& a, const Cell& b) {
    const std::uint64_t ka = sort_key(x(a)), kb = sort_key(x(b));
    return ka < kb || (ka == kb && a.id < b.id);
  };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  bool nan = false;
  for (const Cell& c : cells) {
    const double v = x(c);
    nan = nan || std::isnan(v);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  const std::size_t n = cells.size();
  if (nan || !(std::isfinite(lo) && std::isfinite(hi) && hi > lo) || n < 1024) {
    std::sort(cells.begin(), cells.end(), less);
    return;
  }
  // Few enough buckets that their write heads stay in cache (65536 made every move a miss);
  // each bucket (about n / 1024 cells) is then sorted within the cache.
  const std::size_t nb = std::min<std::size_t>(1024, n / 8);
  const double scale = static_cast<double>(nb) / (hi - lo);
  if (!std::isfinite(scale)) {
    std::sort(cells.begin(), cells.end(), less);
    return;
  }
  auto bucket = [&](const Cell& c) {
    const double t = (x(c) - lo) * scale;  // monotone in x; NaN excluded above
    return t >= static_cast<double>(nb - 1) ? nb - 1 : static_cast<std::size_t>(t);
  };
  std::vector<std::size_t> next(nb + 1, 0), end(nb, 0);
  for (const Cell& c : cells) ++next[bucket(c) + 1];
  for (std::size_t b = 0; b < nb; ++b) next[b + 1] += next[b];
  for (std::size_t b = 0; b < nb; ++b) end[b] = next[b + 1];
  for (std::size_t b = 0; b < nb; ++b)
    while (next[b] < end[b]) {
      Cell c = cells[next[b]];
      for (std::size_t d = bucket(c); d != b; d = bucket(c)) std::swap(c, cells[next[d]++]);
      cells[next[b]++] = c;
    }
  std::size_t first = 0;
  for (std::size_t b = 0; b < nb; ++b) {
    std::sort(cells.begin() + static_cast<std::ptrdiff_t>(first), cells.begin() + static_cast<std::ptrdiff_t>(end[b]), less);
    first = end[b];
  }
}

// Sort-Tile-Recursive: sort by x centre into vertical slices of about sqrt(#nodes) nodes each,
// sort each slice by y centre, cut runs of `cap` cells. Nodes come out full except the last of a slice.
// The sorts are stable (equal centres keep their order), so the packing is deterministic.
// Sorts `cells` in place and returns the node sizes in order.
std::vector<std::size_t> str_pack(std::vector<Cell>& cells, std::size_t cap) {
  auto cx = [](const Cell& c) { return sort_key(0.5 * (double(c.box[0]) + double(c.box[1]))); };
  auto cy = [](const Cell& c) { return sort_key(0.5 * (double(c.box[2]) + double(c.box[3]))); };
  if (cells.size() <= cap) return {cells.size()};
  std::size_t nodes = (cells.size() + cap - 1) / cap;
  auto slices = static_cast<std::size_t>(std::ceil(std::sqrt(static_cast<double>(nodes))));
  std::size_t per_slice = slices * cap;
  // The sort of all cells sorts in place when the ids ascend (as the writer makes them): a stable
  // sort by x centre of cells in id order is the sort by (x centre, id), which needs no buffer
  // of the cells' size (25 MB at 1 M triangles, held while other writers run).
  const bool ids_ascend = std::is_sorted(cells.begin(), cells.end(), [](const Cell& a, const Cell& b) { return a.id < b.id; });
  std::vector<Cell> buf;
  if (ids_ascend && cells.size() > 65536)
    sort_by_key_then_id(cells, [](const Cell& c) { return 0.5 * (double(c.box[0]) + double(c.box[1])); });
  else
    radix_sort(cells.begin(), cells.end(), cx, buf);
  std::vector<std::size_t> out;
  out.reserve(nodes + slices);
  for (std::size_t s = 0; s < cells.size(); s += per_slice) {
    const std::size_t e = std::min(cells.size(), s + per_slice);
    radix_sort(cells.begin() + static_cast<std::ptrdiff_t>(s), cells.begin() + static_cast<std::ptrdiff_t>(e), cy, buf);
    for (std::size_t k = s; k < e; k += cap) out.push_back(std::min(cap, e - k));
  }
  return out;
}

void put_be(char* out, std::uint64_t v, int bytes) {
  for (int i = bytes - 1; i >= 0; --i) *out++ = static_cast<char>((v >> (8 * i)) & 0xFF);
}

void node_blob(std::string& b, const Cell* cells, std::size_t n, int depth, std::size_t node_size) {
  b.assign(node_size, '\0');  // zero padding to the fixed node size
  char* o = b.data();
  put_be(o, static_cast<std::uint64_t>(depth), 2);
  put_be(o + 2, n, 2);
  o += 4;
  for (const Cell* c = cells; c != cells + n; ++c, o += 24) {
    put_be(o, static_cast<std::uint64_t>(c->id), 8);
    for (int k = 0; k < 4; ++k) {
      std::uint32_t u;
      std::memcpy(&u, &c->box[k], 4);
      put_be(o + 8 + 4 * k, u, 4);
    }
  }
}

std::string quoted(const std::string& name) { return "\"" + name + "\""; }

}  // namespace

RtreeEntry RtreeEntry::of(std::int64_t id, double minx, double maxx, double miny, double maxy) {
  if (id < 1 || id > 0xFFFFFFFFLL)
    throw Error(ExitCode::kInternal, "R-tree entry id " + std::to_string(id) + " outside 1 .. 2^32 - 1");
  return {static_cast<std::uint32_t>(id), {round_down(minx), round_up(maxx), round_down(miny), round_up(maxy)}};
}

std::size_t gpkg_rtree_cap(std::int64_t page_size) {
  const std::size_t cell_bytes = 8 + 4 * 4;
  const std::int64_t node = page_size - 64;
  if (node < static_cast<std::int64_t>(4 + 4 * cell_bytes)) return 0;
  return std::min<std::size_t>(51, (static_cast<std::size_t>(node) - 4) / cell_bytes);
}

RtreePlan plan_gpkg_rtree(std::vector<RtreeEntry> entries, std::size_t cap) {
  RtreePlan p;
  p.cap = cap;
  if (entries.empty() || cap < 2) return p;
  std::vector<Cell> cur = std::move(entries);
  std::int64_t next_no = 2;
  // Level by level; a level that fits in one node becomes the root (node 1).
  for (int depth = 0;; ++depth) {
    std::vector<std::size_t> sizes = str_pack(cur, cap);
    const bool root = sizes.size() == 1;
    std::vector<Cell> parents;
    parents.reserve(sizes.size());
    const Cell* grp = cur.data();
    for (const std::size_t n : sizes) {
      const std::int64_t no = root ? 1 : next_no++;
      Cell q{static_cast<std::uint32_t>(no), {grp[0].box[0], grp[0].box[1], grp[0].box[2], grp[0].box[3]}};
      for (const Cell* c = grp; c != grp + n; ++c) {
        q.box[0] = std::min(q.box[0], c->box[0]);
        q.box[1] = std::max(q.box[1], c->box[1]);
        q.box[2] = std::min(q.box[2], c->box[2]);
        q.box[3] = std::max(q.box[3], c->box[3]);
      }
      parents.push_back(q);
      grp += n;
    }
    p.levels.push_back(std::move(cur));
    p.sizes.push_back(std::move(sizes));
    if (root) break;
    cur = std::move(parents);
  }
  return p;
}

namespace {

// The rtree virtual table; returns its node size (bytes of a node blob).
std::size_t create_rtree_table(SqliteDb& db, const std::string& table, const std::string& rt) {
  db.exec("CREATE VIRTUAL TABLE " + quoted(rt) + " USING rtree(id, minx, maxx, miny, maxy)");
  const auto node_size =
      static_cast<std::size_t>(db.query_int("SELECT length(data) FROM " + quoted(rt + "_node") + " WHERE nodeno = 1"));
  if (node_size < 4 + 4 * (8 + 4 * 4)) fail_output(db.path(), "cannot read the R-tree node size of table '" + table + "'");
  return node_size;
}

std::size_t cap_of(std::size_t node_size) { return (node_size - 4) / (8 + 4 * 4); }

// Node numbers as plan_gpkg_rtree gives them: the root 1, then 2, 3, ... level by level from
// the leaves. Calls node(no, depth, first cell, cell count, is_root) in creation order.
template <class Fn>
void for_each_node(const RtreePlan& plan, Fn node) {
  std::int64_t next_no = 2;
  for (std::size_t depth = 0; depth < plan.levels.size(); ++depth) {
    const bool root = plan.sizes[depth].size() == 1;
    std::size_t first = 0;
    for (const std::size_t n : plan.sizes[depth]) {
      node(root ? 1 : next_no++, depth, first, n, root);
      first += n;
    }
  }
}

// The leaf of every row id (0 for ids not indexed); 4 bytes each (6 MB less at 1.6 M rows: the
// writer's arrays add to the process's peak).
std::vector<std::uint32_t> leaves_of(const RtreePlan& plan) {
  std::vector<std::uint32_t> leaf_of;
  std::int64_t max_id = 0;
  for (const Cell& c : plan.levels[0]) max_id = std::max<std::int64_t>(max_id, c.id);
  leaf_of.assign(static_cast<std::size_t>(max_id) + 1, 0);
  for_each_node(plan, [&](std::int64_t no, std::size_t depth, std::size_t first, std::size_t n, bool) {
    if (depth == 0)
      for (std::size_t c = first; c < first + n; ++c)
        leaf_of[static_cast<std::size_t>(plan.levels[0][c].id)] = static_cast<std::uint32_t>(no);
  });
  return leaf_of;
}

// Maintenance triggers of the GeoPackage 1.2 "gpkg_rtree_index" extension (spec, Annex F.3) and
// its gpkg_extensions row.
void add_triggers(SqliteDb& db, const std::string& t, const std::string& g, const std::string& fid, const std::string& rt) {
  auto sql = [&](const std::string& s) { db.exec(s); };
  const std::string T = quoted(t), C = quoted(g), I = quoted(fid), R = quoted(rt);
  const std::string values = "VALUES (NEW." + I + ", ST_MinX(NEW." + C + "), ST_MaxX(NEW." + C + "), ST_MinY(NEW." + C +
                             "), ST_MaxY(NEW." + C + "))";
  sql("CREATE TRIGGER " + quoted(rt + "_insert") + " AFTER INSERT ON " + T + " WHEN (new." + C +
      " NOT NULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN INSERT OR REPLACE INTO " + R + " " + values + "; END");
  sql("CREATE TRIGGER " + quoted(rt + "_update1") + " AFTER UPDATE OF " + C + " ON " + T + " WHEN OLD." + I + " = NEW." + I +
      " AND (NEW." + C + " NOTNULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN INSERT OR REPLACE INTO " + R + " " + values + "; END");
  sql("CREATE TRIGGER " + quoted(rt + "_update2") + " AFTER UPDATE OF " + C + " ON " + T + " WHEN OLD." + I + " = NEW." + I +
      " AND (NEW." + C + " ISNULL OR ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R + " WHERE id = OLD." + I + "; END");
  sql("CREATE TRIGGER " + quoted(rt + "_update3") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I +
      " AND (NEW." + C + " NOTNULL AND NOT ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R + " WHERE id = OLD." + I +
      "; INSERT OR REPLACE INTO " + R + " " + values + "; END");
  sql("CREATE TRIGGER " + quoted(rt + "_update4") + " AFTER UPDATE ON " + T + " WHEN OLD." + I + " != NEW." + I +
      " AND (NEW." + C + " ISNULL OR ST_IsEmpty(NEW." + C + ")) BEGIN DELETE FROM " + R + " WHERE id IN (OLD." + I +
      ", NEW." + I + "); END");
  sql("CREATE TRIGGER " + quoted(rt + "_delete") + " AFTER DELETE ON " + T + " WHEN old." + C +
      " NOT NULL BEGIN DELETE FROM " + R + " WHERE id = OLD." + I + "; END");

  sql("CREATE TABLE IF NOT EXISTS gpkg_extensions (table_name TEXT, column_name TEXT, extension_name TEXT NOT NULL, "
      "definition TEXT NOT NULL, scope TEXT NOT NULL, CONSTRAINT ge_tce UNIQUE (table_name, column_name, extension_name))");
  sql("INSERT INTO gpkg_extensions (table_name, column_name, extension_name, definition, scope) VALUES ('" + t + "', '" + g +
      "', 'gpkg_rtree_index', 'http://www.geopackage.org/spec120/#extension_rtree', 'write-only')");
}

}  // namespace

void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                      std::vector<RtreeEntry> entries) {
  RtreePlan p;
  p.levels.push_back(std::move(entries));  // not yet packed: build_gpkg_rtree packs it for the table's cap
  build_gpkg_rtree(db, table, geom_col, fid_col, std::move(p));
}

void build_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                      RtreePlan plan) {
  const std::string rt = "rtree_" + table + "_" + geom_col;
  const std::size_t node_size = create_rtree_table(db, table, rt);
  const std::size_t cap = cap_of(node_size);
  if (plan.cap != cap) {  // not packed, or packed for another node size
    std::vector<Cell> entries;
    if (!plan.levels.empty()) entries = std::move(plan.levels[0]);
    plan = plan_gpkg_rtree(std::move(entries), cap);
  }

  if (!plan.levels.empty()) {
    db.exec("DELETE FROM " + quoted(rt + "_node"));
    // Leaf links are written in rowid order: appending to a B-tree is much cheaper than
    // inserting in the STR order.
    BatchInsert parent_rows(db, rt + "_parent", {"nodeno", "parentnode"}, 256);
    BatchInsert node_rows(db, rt + "_node", {"nodeno", "data"}, 16);
    std::string blob;
    for_each_node(plan, [&](std::int64_t no, std::size_t depth, std::size_t first, std::size_t n, bool root) {
      const Cell* grp = plan.levels[depth].data() + first;
      if (depth > 0)
        for (const Cell* c = grp; c != grp + n; ++c) {
          parent_rows.add_int(static_cast<std::int64_t>(c->id)).add_int(no);
          parent_rows.end_row();
        }
      node_blob(blob, grp, n, root ? static_cast<int>(depth) : 0, node_size);
      node_rows.add_int(no).add_blob(blob.data(), blob.size());
      node_rows.end_row();
    });
    // Made only now: the plan may have been made while other writers held memory.
    const std::vector<std::uint32_t> leaf_of = leaves_of(plan);
    // Dense ids 1..n (nodes, triangles) are appended without naming the rowid (SQLite then
    // takes previous + 1 without searching the B-tree); sparse ids name it.
    bool dense = true;
    for (std::size_t id = 1; id < leaf_of.size() && dense; ++id) dense = leaf_of[id] != 0;
    BatchInsert rowid_rows(db, rt + "_rowid", dense ? std::vector<std::string>{"nodeno"}
                                                    : std::vector<std::string>{"rowid", "nodeno"}, 512);
    for (std::size_t id = 1; id < leaf_of.size(); ++id) {
      if (!leaf_of[id]) continue;
      if (!dense) rowid_rows.add_int(static_cast<std::int64_t>(id));
      rowid_rows.add_int(leaf_of[id]);
      rowid_rows.end_row();
    }
    rowid_rows.finish();
    parent_rows.finish();
    node_rows.finish();
  }
  add_triggers(db, table, geom_col, fid_col, rt);
}

RtreeRows create_gpkg_rtree(SqliteDb& db, const std::string& table, const std::string& geom_col, const std::string& fid_col,
                            bool filled) {
  RtreeRows r;
  r.name = "rtree_" + table + "_" + geom_col;
  r.node_size = create_rtree_table(db, table, r.name);
  // Its empty root goes when the plan will bring every node (an empty table keeps it).
  if (filled) db.exec("DELETE FROM " + quoted(r.name + "_node"));
  r.root_node = db.root_page(r.name + "_node");
  r.root_parent = db.root_page(r.name + "_parent");
  r.root_rowid = db.root_page(r.name + "_rowid");
  add_triggers(db, table, geom_col, fid_col, r.name);
  return r;
}

void RtreeRows::set_plan(RtreePlan p, const std::string& path) {
  const std::size_t cap = cap_of(node_size);
  if (p.cap != cap) {
    std::vector<Cell> entries;
    if (!p.levels.empty()) entries = std::move(p.levels[0]);
    p = plan_gpkg_rtree(std::move(entries), cap);
  }
  plan = std::move(p);
  nodes.clear();
  parent_of.clear();
  leaf_of.clear();
  if (plan.levels.empty()) return;
  leaf_of = leaves_of(plan);
  for (std::size_t id = 1; id < leaf_of.size(); ++id)
    if (leaf_of[id] == 0) fail_output(path, "internal: R-tree ids of " + name + " are not 1..n");
  std::size_t count = 0;
  for (const auto& sz : plan.sizes) count += sz.size();
  nodes.assign(count, {});
  parent_of.assign(count + 1, 0);
  for_each_node(plan, [&](std::int64_t no, std::size_t depth, std::size_t first, std::size_t n, bool) {
    nodes[static_cast<std::size_t>(no - 1)] = {static_cast<std::uint32_t>(depth), first, n};
    if (depth > 0)
      for (std::size_t c = first; c < first + n; ++c)
        parent_of[static_cast<std::size_t>(plan.levels[depth][c].id)] = no;
  });
}

void RtreeRows::add_tables(std::vector<BulkTable>& out) const {
  if (nodes.empty()) return;
  // _node(nodeno INTEGER PRIMARY KEY, data): the rowid column is stored as NULL in the record.
  out.push_back({name + "_node", root_node, nodes.size(), true, [this](std::size_t i, Record& r) {
                   thread_local std::string blob;
                   const NodeRef& n = nodes[i];
                   node_blob(blob, plan.levels[n.depth].data() + n.first, n.count, i == 0 ? static_cast<int>(n.depth) : 0,
                             node_size);
                   r.clear(static_cast<std::int64_t>(i + 1));
                   r.add_null().add_blob(blob.data(), blob.size());
                 }});
  // _parent(nodeno INTEGER PRIMARY KEY, parentnode): every node but the root (2, 3, ...).
  out.push_back({name + "_parent", root_parent, nodes.size() - 1, true, [this](std::size_t i, Record& r) {
                   r.clear(static_cast<std::int64_t>(i + 2));
                   r.add_null().add_int(parent_of[i + 2]);
                 }});
  // _rowid(rowid INTEGER PRIMARY KEY, nodeno).
  out.push_back({name + "_rowid", root_rowid, leaf_of.size() - 1, true, [this](std::size_t i, Record& r) {
                   r.clear(static_cast<std::int64_t>(i + 1));
                   r.add_null().add_int(leaf_of[i + 1]);
                 }});
}

}  // namespace fdr::io::detail
