// The faces of an arrangement of lines, cluster by cluster: what the differences by faces
// (geometry_ops.hpp) polygonize.
#pragma once
#include <vector>

#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Lines in clusters: two lines are in one cluster when boxes of their segments meet (so lines of
// different clusters never meet). Clusters in the order of their first line; each lists its
// lines in increasing order.
std::vector<std::vector<int>> line_clusters(const OGRMultiLineString& lines);

// The bounded faces of the arrangement of `lines`, each a polygon with its holes, in the order
// of the clusters (line_clusters) and, within a cluster, as GEOS polygonizes it. Each cluster is
// noded and polygonized on its own (in parallel, the same result for any thread count); a face
// of one cluster that holds other clusters gets their faces cut out (the holes a polygonization
// of the whole would give it). False when GEOS fails on some cluster.
bool arrangement_faces(const OGRMultiLineString& lines, OwnedPolygons& faces);

}  // namespace fdr::coast
