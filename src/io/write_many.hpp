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
void write_meshes(const mesh::MeshView& mesh, const std::vector<std::string>& paths, const std::vector<Format>& formats,
                  const WriteOptions& options, unsigned threads);

}  // namespace fdr::io
