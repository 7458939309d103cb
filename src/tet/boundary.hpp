// The PLC's boundary as refinement keeps it: subsegments (pieces of the input segments and facet
// edges) and subfacets (each facet's 2D Delaunay triangulation in its own plane, with the
// subsegments as constraints), in the vertex ids of the Delaunay tetrahedralization. Points split
// into a facet are rounded off a tilted plane, so a facet is kept as its own triangulation and
// never recovered from the tetrahedra; every decision uses exact predicates on the stored doubles.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <unordered_map>
#include <vector>
#include "plc/plc.hpp"
#include "plc/triangulate_facets.hpp"
#include "tet/delaunay3.hpp"

namespace fdr::tet {

struct SubfacetTri {
  std::array<VertexId, 3> v{};  // counter-clockwise seen from the side of the frame's normal
  std::uint32_t facet = 0;
  bool alive = true;
};

// Where a walk in a facet toward a point ended: in triangle `tri`, or stopped at subsegment `seg`
// (the point lies beyond it, outside the part of the facet reached from the start).
struct FacetLocation {
  std::uint32_t tri = UINT32_MAX;
  std::array<VertexId, 2> seg{kNoId, kNoId};
};

class Boundary {
 public:
  // `vid` maps the PLC's point ids to the tetrahedralization's vertex ids.
  Boundary(const Delaunay3& dt, const plc::Plc& plc, const plc::FacetTriangulation& ft,
           std::span<const VertexId> vid);

  // --- subsegments (a < b not required: every query orders them)
  bool is_subsegment(VertexId a, VertexId b) const;
  // The input subsegment (index in FacetTriangulation::subsegments) that ab is a piece of.
  std::uint32_t segment_origin(VertexId a, VertexId b) const;
  // The other ends of the subsegments at v.
  const std::vector<VertexId>& segment_neighbours(VertexId v) const;
  // Replaces ab by av and vb, and inserts v into every facet that has ab on its boundary (v must
  // be a vertex of the tetrahedralization lying on ab up to rounding).
  void split_segment(VertexId a, VertexId b, VertexId v);
  std::size_t num_subsegments() const { return segs_.size(); }
  template <class Fn>
  void for_each_subsegment(Fn&& fn) const {
    for (const auto& [k, o] : segs_) fn(k.a, k.b, o);
  }

  // --- subfacets
  // The subfacet with corners a, b, c in any order, or UINT32_MAX.
  std::uint32_t subfacet(VertexId a, VertexId b, VertexId c) const;
  const SubfacetTri& tri(std::uint32_t i) const { return tris_[i]; }
  std::size_t tri_slots() const { return tris_.size(); }
  // The live subfacets at v.
  const std::vector<std::uint32_t>& subfacets_at(VertexId v) const;
  // Whether v lies on facet f (is a corner of one of its subfacets).
  bool on_facet(VertexId v, std::uint32_t f) const;
  // A walk in tri's facet from tri toward p (in the facet's projection).
  FacetLocation locate_in_facet(std::uint32_t tri, Point3 p) const;
  // Inserts vertex v (inside triangle `seed` or on its boundary, up to rounding) into seed's facet
  // by Bowyer-Watson in the facet's plane, not across subsegments.
  void insert_in_facet(std::uint32_t seed, VertexId v);
  // Insertions whose cavity in a facet reached kMaxFacetCavity triangles and stopped growing there
  // (the facet's triangulation is valid but not Delaunay around the point; the caller reports it).
  std::size_t capped_cavities() const { return capped_cavities_; }
  static constexpr std::size_t kMaxFacetCavity = 4096;
  int facet_marker(std::uint32_t f) const { return plc_.facets[f].marker; }
  const plc::FacetFrame& frame(std::uint32_t f) const { return ft_.frames[f]; }
  const plc::Subsegment& origin(std::uint32_t o) const { return ft_.subsegments[o]; }

 private:
  struct SegKey {  // a < b
    VertexId a, b;
    bool operator==(const SegKey&) const = default;
  };
  struct SegHash {
    std::size_t operator()(const SegKey& k) const;
  };
  struct DirKey {  // directed edge ab of a triangle of facet f
    std::uint32_t f;
    VertexId a, b;
    bool operator==(const DirKey&) const = default;
  };
  struct DirHash {
    std::size_t operator()(const DirKey& k) const;
  };
  static SegKey seg_key(VertexId a, VertexId b);
  void grow(VertexId v);
  void add_segment(VertexId a, VertexId b, std::uint32_t origin);
  void remove_segment(VertexId a, VertexId b);
  std::uint32_t add_tri(std::array<VertexId, 3> v, std::uint32_t f);
  void kill_tri(std::uint32_t t);
  std::uint32_t across(std::uint32_t f, VertexId a, VertexId b) const;  // the triangle with edge b a
  int orient_in_facet(std::uint32_t f, VertexId a, VertexId b, Point3 p) const;
  bool in_circle(std::uint32_t t, Point3 p) const;
  bool in_cavity(std::uint32_t t) const;
  void insert_with_cavity(std::vector<std::uint32_t> cavity, std::size_t forced, VertexId v,
                          std::array<VertexId, 2> split_edge);

  const Delaunay3& dt_;
  const plc::Plc& plc_;
  const plc::FacetTriangulation& ft_;
  std::unordered_map<SegKey, std::uint32_t, SegHash> segs_;  // subsegment -> origin
  std::vector<std::vector<VertexId>> seg_nbrs_;
  std::vector<SubfacetTri> tris_;
  std::vector<std::uint32_t> free_tris_;
  std::unordered_map<DirKey, std::uint32_t, DirHash> dir_;
  std::vector<std::vector<std::uint32_t>> vtris_;
  std::vector<std::uint32_t> cav_mark_;  // per triangle slot: == cav_stamp_ while in the cavity at hand
  std::uint32_t cav_stamp_ = 0;
  std::size_t capped_cavities_ = 0;
};

}  // namespace fdr::tet
