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
  // Test hook: after this many tables are written (1..5), fail as a broken connection would,
  // so the tests can see the transaction roll back. < 0: off.
  int fail_after_layer = -1;
};

}  // namespace fdr::io
