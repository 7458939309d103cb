// The MDAL dynamic driver "FDRMESH_ADCIRC": the plain C functions MDAL looks up by name in every
// library of the folder named by MDAL_DRIVER_PATH (MDAL's external-driver interface). Meshes are
// read whole at open, kept under an id that is never reused, and freed at close. No exception
// crosses into MDAL: a file that cannot be read opens as id -1, which QGIS shows as an invalid layer.
#include <algorithm>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "adcirc_grid.hpp"

#define FDR_MDAL_EXPORT extern "C" __attribute__((visibility("default")))

namespace {

std::mutex g_mutex;
std::map<int, std::shared_ptr<const fdr_mdal::Grid>> g_grids;
int g_next_id = 0;

// The grid under `id`, or null. Shared ownership: a call in progress keeps the grid alive even if
// another thread closes it meanwhile.
std::shared_ptr<const fdr_mdal::Grid> grid(int id) {
  std::lock_guard<std::mutex> lock(g_mutex);
  auto it = g_grids.find(id);
  return it == g_grids.end() ? nullptr : it->second;
}

// The one dataset group: the file's depth column on the vertices (positive down).
constexpr const char* kDepthGroup = "depth";

bool valid_dataset(const fdr_mdal::Grid* g, int group, int dataset) { return g && group == 0 && dataset == 0; }

}  // namespace

FDR_MDAL_EXPORT const char* MDAL_DRIVER_driverName() { return "FDRMESH_ADCIRC"; }
FDR_MDAL_EXPORT const char* MDAL_DRIVER_driverLongName() { return "ADCIRC fort.14 / SCHISM hgrid (fdrmesh)"; }
FDR_MDAL_EXPORT const char* MDAL_DRIVER_filters() { return "*.14;;*.grd;;*.gr3;;*.ll"; }
FDR_MDAL_EXPORT int MDAL_DRIVER_capabilities() { return 1; }  // read mesh
FDR_MDAL_EXPORT int MDAL_DRIVER_maxVertexPerFace() { return 4; }

FDR_MDAL_EXPORT bool MDAL_DRIVER_canReadMesh(const char* uri) {
  try {
    return uri && fdr_mdal::looks_like_grid(uri);
  } catch (...) {
    return false;
  }
}

FDR_MDAL_EXPORT int MDAL_DRIVER_openMesh(const char* uri, const char* /*name*/) {
  try {
    if (!uri) return -1;
    auto g = std::make_shared<fdr_mdal::Grid>();
    if (!fdr_mdal::read_grid(uri, *g).empty()) return -1;
    std::lock_guard<std::mutex> lock(g_mutex);
    const int id = g_next_id++;
    g_grids.emplace(id, std::move(g));
    return id;
  } catch (...) {
    return -1;
  }
}

FDR_MDAL_EXPORT void MDAL_DRIVER_closeMesh(int id) {
  std::lock_guard<std::mutex> lock(g_mutex);
  g_grids.erase(id);
}

FDR_MDAL_EXPORT int MDAL_DRIVER_M_vertexCount(int id) {
  auto g = grid(id);
  return g ? g->vertex_count() : -1;
}

FDR_MDAL_EXPORT int MDAL_DRIVER_M_faceCount(int id) {
  auto g = grid(id);
  return g ? g->face_count() : -1;
}

FDR_MDAL_EXPORT int MDAL_DRIVER_M_edgeCount(int id) { return grid(id) ? 0 : -1; }

FDR_MDAL_EXPORT void MDAL_DRIVER_M_extent(int id, double* xmin, double* xmax, double* ymin, double* ymax) {
  auto g = grid(id);
  if (!g || !xmin || !xmax || !ymin || !ymax) return;
  *xmin = g->xmin;
  *xmax = g->xmax;
  *ymin = g->ymin;
  *ymax = g->ymax;
}

FDR_MDAL_EXPORT const char* MDAL_DRIVER_M_projection(int id) {
  auto g = grid(id);
  return g ? g->crs.c_str() : "";  // lives while the mesh is open; MDAL copies it right after the open
}

// Vertices from `start`: x, y, z (bed elevation) each; returns how many were written.
FDR_MDAL_EXPORT int MDAL_DRIVER_M_vertices(int id, int start, int count, double* buffer) {
  auto g = grid(id);
  if (!g || !buffer || start < 0 || count < 0) return -1;
  if (start >= g->vertex_count()) return 0;
  const int n = std::min(count, g->vertex_count() - start);
  std::copy_n(g->xyz.data() + 3 * static_cast<std::size_t>(start), 3 * static_cast<std::size_t>(n), buffer);
  return n;
}

// Faces from `start` while both buffers have room: offsets[i] is where face i's node indices end
// in `nodes` (counted from this call's first face); returns how many faces were written.
FDR_MDAL_EXPORT int MDAL_DRIVER_M_faces(int id, int start, int count, int* offsets, int nodes_len, int* nodes) {
  auto g = grid(id);
  if (!g || !offsets || !nodes || start < 0 || count < 0 || nodes_len < 0) return -1;
  if (start >= g->face_count()) return 0;
  const int base = start == 0 ? 0 : g->face_end[static_cast<std::size_t>(start) - 1];
  int written = 0;
  for (int f = start; f < g->face_count() && written < count; ++f, ++written) {
    const int end = g->face_end[static_cast<std::size_t>(f)];
    if (end - base > nodes_len) break;
    offsets[written] = end - base;
  }
  const int used = written == 0 ? 0 : offsets[written - 1];
  std::copy_n(g->face_nodes.data() + base, used, nodes);
  return written;
}

FDR_MDAL_EXPORT int MDAL_DRIVER_M_edges(int id, int, int, int*, int*) { return grid(id) ? 0 : -1; }

FDR_MDAL_EXPORT int MDAL_DRIVER_M_datasetGroupCount(int id) { return grid(id) ? 1 : 0; }

FDR_MDAL_EXPORT const char* MDAL_DRIVER_G_groupName(int id, int group) {
  return grid(id) && group == 0 ? kDepthGroup : "";
}

FDR_MDAL_EXPORT const char* MDAL_DRIVER_G_referenceTime(int, int) { return ""; }

FDR_MDAL_EXPORT int MDAL_DRIVER_G_metadataCount(int, int) { return 0; }
FDR_MDAL_EXPORT const char* MDAL_DRIVER_G_metadataKey(int, int, int) { return ""; }
FDR_MDAL_EXPORT const char* MDAL_DRIVER_G_metadataValue(int, int, int) { return ""; }

// One scalar dataset on the vertices (data location 1).
FDR_MDAL_EXPORT bool MDAL_DRIVER_G_datasetsDescription(int id, int group, bool* is_scalar, int* location, int* count) {
  if (!grid(id) || group != 0 || !is_scalar || !location || !count) return false;
  *is_scalar = true;
  *location = 1;
  *count = 1;
  return true;
}

FDR_MDAL_EXPORT double MDAL_DRIVER_D_time(int id, int group, int dataset, bool* ok) {
  auto g = grid(id);
  if (ok) *ok = valid_dataset(g.get(), group, dataset);
  return 0.0;
}

FDR_MDAL_EXPORT int MDAL_DRIVER_D_data(int id, int group, int dataset, int start, int count, double* buffer) {
  auto g = grid(id);
  if (!valid_dataset(g.get(), group, dataset) || !buffer || start < 0 || count < 0 || start >= g->vertex_count())
    return 0;
  const int n = std::min(count, g->vertex_count() - start);
  std::copy_n(g->depth.data() + start, n, buffer);
  return n;
}

FDR_MDAL_EXPORT bool MDAL_DRIVER_D_hasActiveFlagCapability(int, int, int) { return false; }
FDR_MDAL_EXPORT int MDAL_DRIVER_D_activeFlags(int, int, int, int, int, int*) { return 0; }

// No volumes (3D stacked meshes): the 3D entry points of newer MDAL versions report none.
FDR_MDAL_EXPORT int MDAL_DRIVER_D_maximumVerticalLevelCount(int, int, int) { return 0; }
FDR_MDAL_EXPORT int MDAL_DRIVER_D_volumeCount(int, int, int) { return 0; }
FDR_MDAL_EXPORT int MDAL_DRIVER_D_verticalLevelCountData(int, int, int, int, int, int*) { return 0; }
FDR_MDAL_EXPORT int MDAL_DRIVER_D_verticalLevelData(int, int, int, int, int, double*) { return 0; }
FDR_MDAL_EXPORT int MDAL_DRIVER_D_faceToVolumeData(int, int, int, int, int, int*) { return 0; }

FDR_MDAL_EXPORT void MDAL_DRIVER_D_unload(int, int, int) {}
