// GeoPackage spatial index through SQL (see gpkg_index.hpp).
#include "io/gpkg_index.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "io/detail.hpp"

namespace fdr::io::detail {

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
  {
    const std::vector<std::uint32_t> order = rtree_insert_order(n, box);
    BatchInsert ins(db, rt, {"id", "minx", "maxx", "miny", "maxy"}, 64);
    IndexBox b{};
    for (const std::uint32_t i : order) {
      box(i, b);
      ins.add_int(static_cast<std::int64_t>(i) + 1).add_real(b.minx).add_real(b.maxx).add_real(b.miny).add_real(b.maxy);
      ins.end_row();
    }
    ins.finish();
  }
  add_triggers(db, table, geom_col, rt);
}

}  // namespace fdr::io::detail
