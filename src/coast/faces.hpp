// The faces of an arrangement of lines, cluster by cluster: what the differences by faces
// (geometry_ops.hpp) polygonize.
#pragma once
#include <memory>
#include <vector>

#include "coast/geometry_ops.hpp"

namespace fdr::coast {

// Lines in clusters: two lines are in one cluster when boxes of their segments meet (so lines of
// different clusters never meet). Clusters in the order of their first line; each lists its
// lines in increasing order.
std::vector<std::vector<int>> line_clusters(const OGRMultiLineString& lines);

// The lines of a cluster (indices in `members`) cut at every vertex that occurs more than once,
// when no two of their segments cross, overlap or touch other than at a common vertex (exact,
// pslg::find_contacts) and no segment occurs twice: then they are already noded, and GEOS's
// noding of them (an overlay) is not needed. Null otherwise. Why: most clusters of the
// differences by faces are runs of two rings that meet only at the vertices where they part.
std::unique_ptr<OGRMultiLineString> noded_as_given(const OGRMultiLineString& lines, const std::vector<int>& members);

// The bounded faces of the arrangement of `lines`, each a polygon with its holes, in the order
// of the clusters (line_clusters) and, within a cluster, as GEOS polygonizes it. Each cluster is
// noded and polygonized on its own (in parallel, the same result for any thread count); a face
// of one cluster that holds other clusters gets their faces cut out (the holes a polygonization
// of the whole would give it). False when GEOS fails on some cluster.
bool arrangement_faces(const OGRMultiLineString& lines, OwnedPolygons& faces);

// A point strictly inside face f, away from its slivers: the middle of the widest span of the
// horizontal lines midway between the most distant consecutive vertex heights (16 of them) that
// is strictly inside. Why not GEOS's point on surface: its one scan line may meet the face only
// in a sliver along two nearly collinear segments, whose points lie within rounding of the
// segments the face was noded from (or, thinner than rounding, it falls back to a vertex on the
// boundary), and such a point says nothing of the side the face lies on. {0, 0} (and false)
// when no span is strictly inside.
bool face_point(const OGRPolygon& f, Point2& p);

}  // namespace fdr::coast
