// gis_backend(): the GIS table when the program links the GIS library, else that library loaded
// on first use (gis_backend.hpp).
#include "pipeline/gis_backend.hpp"
#include <dlfcn.h>
#include <unistd.h>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include "base/debug.hpp"
#include "base/error.hpp"

// Weak: null unless the program links the GIS library (or fdr_pipeline itself).
extern "C" const fdr::pipeline::GisBackend* fdr_gis_backend_table() __attribute__((weak));

namespace fdr::pipeline {
namespace {

#ifndef FDR_GIS_MODULE_NAME
#define FDR_GIS_MODULE_NAME "fdrmesh_gis.so"
#endif

// The folder of the running program (symbolic links resolved), "" if unknown.
std::string exe_dir() {
  std::string buf(4096, '\0');
  const ssize_t n = ::readlink("/proc/self/exe", buf.data(), buf.size() - 1);
  if (n <= 0) return "";
  buf.resize(static_cast<std::size_t>(n));
  const auto slash = buf.find_last_of('/');
  return slash == std::string::npos ? std::string() : buf.substr(0, slash);
}

// Where the module is looked for, in order: $FDRMESH_GIS_MODULE; beside the program as installed
// (<bindir>/<relative path to libdir>/fdrmesh/, which is also where the build tree puts it); the
// configured install prefix.
std::vector<std::string> candidates() {
  std::vector<std::string> c;
  if (const char* e = debug::value(debug::Aid::kGisModule); e && *e) {
    c.emplace_back(e);
    return c;
  }
#ifdef FDR_GIS_MODULE_RELDIR
  if (const std::string d = exe_dir(); !d.empty()) {
    const std::string p = d + "/" FDR_GIS_MODULE_RELDIR "/" FDR_GIS_MODULE_NAME;
    char real[PATH_MAX];
    c.push_back(::realpath(p.c_str(), real) ? std::string(real) : p);  // without "bin/../"
  }
#endif
#ifdef FDR_GIS_MODULE_INSTALL_DIR
  c.emplace_back(FDR_GIS_MODULE_INSTALL_DIR "/" FDR_GIS_MODULE_NAME);
#endif
  return c;
}

const GisBackend* load_module() {
  std::string why;
  for (const auto& path : candidates()) {
    if (::access(path.c_str(), F_OK) != 0) {
      why += "\n  " + path + ": not found";
      continue;
    }
    void* h = ::dlopen(path.c_str(), RTLD_LAZY | RTLD_LOCAL);
    if (!h) {
      const char* e = ::dlerror();
      why += "\n  " + path + ": " + (e ? e : "cannot be loaded");
      continue;
    }
    using Fn = const GisBackend* (*)();
    auto fn = reinterpret_cast<Fn>(::dlsym(h, "fdr_gis_backend_table"));
    const GisBackend* b = fn ? fn() : nullptr;
    if (!b || std::strcmp(b->version, kVersion) != 0) {
      why += "\n  " + path + ": from another version of fdrmesh";
      ::dlclose(h);
      continue;
    }
    return b;  // never closed: its code (spacing fields, writers) is used until exit
  }
  throw Error(ExitCode::kInternal,
              "this run needs the GIS module " FDR_GIS_MODULE_NAME
              " (GDAL, PROJ, netCDF, SQLite: GIS inputs, output meshes, `fdrmesh quality`), but it could not be "
              "loaded:" + why + "\n  (reinstall fdrmesh, or set FDRMESH_GIS_MODULE to the module's path)");
}

std::mutex g_mutex;
const GisBackend* g_table = nullptr;

}  // namespace

const GisBackend& gis_backend() {
  std::lock_guard<std::mutex> lock(g_mutex);
  if (!g_table) g_table = fdr_gis_backend_table ? fdr_gis_backend_table() : load_module();
  return *g_table;
}

bool gis_backend_loaded() {
  std::lock_guard<std::mutex> lock(g_mutex);
  return g_table != nullptr || fdr_gis_backend_table != nullptr;
}

}  // namespace fdr::pipeline
