// Several outputs of one mesh written concurrently (see write_many.hpp).
#include "io/write_many.hpp"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <mutex>

#include "base/error.hpp"
#include "base/parallel.hpp"
#include "io/boundaries.hpp"
#include "io/detail.hpp"

namespace fdr::io {

namespace {
// Files a write_mesh call creates: the path, plus the .ele beside a .node.
std::vector<std::string> files_of(const std::string& path, Format f) {
  if (f != Format::kNode) return {path};
  std::string base = path;
  const std::string ext = detail::lower_extension(path);
  if (ext == ".node" || ext == ".ele") base = path.substr(0, path.size() - ext.size());
  return {base + ".node", base + ".ele"};
}
// 0 for the writers that cost most per triangle (SQLite, netCDF, XML), 1 for the text formats.
int cost_rank(Format f) {
  switch (f) {
    case Format::kGpkg:
    case Format::kUgrid:
    case Format::kDflowfm:
    case Format::kVtu:
      return 0;
    default:
      return 1;
  }
}
}  // namespace

void write_meshes(const mesh::MeshView& mesh, const std::vector<std::string>& paths, const std::vector<Format>& formats,
                  const WriteOptions& options, unsigned threads) {
  const std::size_t n = paths.size();
  if (formats.size() != n) throw Error(ExitCode::kInternal, "write_meshes: one format per path expected");
  // Outputs that carry boundary lists share one extraction instead of one each.
  std::size_t with_boundaries = 0;
  for (Format f : formats) with_boundaries += carries_boundaries(f) ? 1 : 0;
  BoundaryCache cache;
  WriteOptions shared;
  const WriteOptions* opts = &options;
  if (with_boundaries >= 2 && !options.boundary_cache) {
    shared = options;
    shared.boundary_cache = &cache;
    opts = &shared;
  }
  std::vector<std::exception_ptr> errors(n);
  std::vector<char> done(n, 0);
  // The costliest outputs start first (a GeoPackage takes as long as several text files), so
  // the last file to finish is a cheap one; which thread writes a file changes nothing in it.
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return cost_rank(formats[a]) < cost_rank(formats[b]); });
  // One chunk per file, claimed in `order`; each file's outcome goes to its own slot. Database
  // outputs wait until every file is written (below).
  parallel_chunks(
      n,
      [&](std::size_t k, unsigned) {
        const std::size_t i = order[k];
        if (formats[i] == Format::kPostgis) return;
        try {
          if (formats[i] == Format::kUgrid) {
            // The netCDF library is not thread-safe: one UGRID file at a time.
            static std::mutex netcdf;
            std::lock_guard<std::mutex> lock(netcdf);
            write_mesh(mesh, paths[i], formats[i], *opts);
          } else {
            write_mesh(mesh, paths[i], formats[i], *opts);
          }
          done[i] = 1;
        } catch (...) {
          errors[i] = std::current_exception();
        }
      },
      std::max(1u, threads));
  // Database outputs last, one at a time, and only once every file is written: a committed
  // transaction cannot be taken back when a file fails, a file can be removed when one fails.
  const bool files_ok = std::none_of(errors.begin(), errors.end(), [](const auto& e) { return e != nullptr; });
  for (std::size_t i = 0; i < n && files_ok; ++i) {
    if (formats[i] != Format::kPostgis) continue;
    try {
      write_mesh(mesh, paths[i], formats[i], *opts);
      done[i] = 1;
    } catch (...) {
      errors[i] = std::current_exception();
      break;
    }
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!errors[i]) continue;
    for (std::size_t j = 0; j < n; ++j)
      if (done[j] && formats[j] != Format::kPostgis)
        for (const auto& p : files_of(paths[j], formats[j])) std::remove(p.c_str());
    std::rethrow_exception(errors[i]);
  }
}

}  // namespace fdr::io
