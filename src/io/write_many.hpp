// Several outputs of one mesh written concurrently (one thread per file, at most max_threads()).
#pragma once
#include <string>
#include <vector>
#include "base/threads.hpp"
#include "io/writer.hpp"

namespace fdr::io {

// Threads fdrmesh may use (FDR_THREADS, else min(2, hardware threads)); see base/threads.hpp.
using fdr::max_threads;

// Writes mesh to every paths[i] in formats[i] like write_mesh, up to `threads` files at a time.
// All or nothing: if any output fails, every output written by this call is removed again and
// the error of the first failing output (in the order given) is rethrown. The writers must not
// evaluate a sizing field concurrently unless it is thread-safe: with threads > 1 give the
// per-triangle values (WriteOptions::triangle_*) and a mesh with MeshView::f, and leave
// WriteOptions::f null.
// Whether the writer of f writes the mesh's boundary lists (extracted once per write_meshes call,
// in one array read per half-edge when the mesh has the mesher's adjacency, MeshView::neighbours;
// without it, by grouping the half-edges, which takes large temporary arrays).
// Inline: the pipeline core asks it without linking the writers (they live in the GIS module).
inline bool carries_boundaries(Format f) {
  switch (f) {
    case Format::k2dm:
    case Format::kFort14:
    case Format::kGr3:
    case Format::kLl:
    case Format::kSelafin:
    case Format::kDflowfm:
      return true;
    default:
      return false;
  }
}

void write_meshes(const mesh::MeshView& mesh, const std::vector<std::string>& paths, const std::vector<Format>& formats,
                  const WriteOptions& options, unsigned threads);

}  // namespace fdr::io
