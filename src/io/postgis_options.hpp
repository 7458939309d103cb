// What a PostGIS output needs beyond the mesh (io::WriteOptions::postgis; no GDAL here).
#pragma once
#include <string>

namespace fdr::io {

struct PostgisOptions {
  // The tables are <prefix>nodes, <prefix>triangles, <prefix>boundaries, <prefix>repairs and
  // <prefix>metadata, so several meshes live side by side in one schema.
  std::string prefix = "mesh_";
  // Schema of the tables; empty: the first of the connection string's `schemas=` list, else
  // the database's current schema (usually `public`).
  std::string schema;
  // Replace the tables of an existing mesh with the same prefix (within the same transaction);
  // false: refuse with kOutputError and leave them.
  bool overwrite = false;
  // Test hooks: fail as a broken connection would, so the tests can see that nothing is left.
  // fail_after_layer: once the rows of that many tables (1..5, in the order nodes, triangles,
  // boundaries, repairs, metadata) are in; < 0: off. fail_at: at a named step, "staging" (the
  // staging schema made), "rows:<table>", "indexes:<table>" (<table> without the prefix), or
  // "commit" (everything in place, before the last commit); "": off.
  int fail_after_layer = -1;
  std::string fail_at{};
};

}  // namespace fdr::io
