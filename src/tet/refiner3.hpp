// The state of Functional Delaunay Refinement in 3D on a PLC and its steps: the conforming
// Delaunay tetrahedralization (rules 1 and 2: encroached subsegments and subfacets), the regions
// (materials, outside), and the B-bad tetrahedra (rule 3). tetrahedralize() runs them in order;
// tests reach the steps and the tetrahedralization here.
#pragma once
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>
#include "base/large_array.hpp"
#include "plc/plc.hpp"
#include "plc/triangulate_facets.hpp"
#include "sizing/spacing3d.hpp"
#include "tet/boundary.hpp"
#include "tet/delaunay3.hpp"
#include "tet/refine3d.hpp"
#include "tet/slivers.hpp"
#include "tet/tetrahedralize.hpp"

namespace fdr::tet {

// Where a subsegment ab is split: the midpoint, or, when exactly one end is an apex (an input
// vertex where input segments meet), the point at a power-of-two distance from it nearest to the
// midpoint (concentric shells: splits near a small angle stay on spheres around its apex, so they
// stop encroaching each other's pieces).
Point3 segment_split_point(Point3 a, Point3 b, bool a_apex, bool b_apex);

// The centre of the circle through a, b, c in their plane: double precision relative to a, or
// constructed exactly for a triangle too close to collinear for it; a point with NaN coordinates
// when a, b, c are exactly collinear (no such circle), which no caller may insert.
Point3 triangle_circumcentre(Point3 a, Point3 b, Point3 c);

// Tetrahedron region codes besides indices into Plc::regions.
inline constexpr std::int32_t kOutsideRegion = -2;  // beyond the outer surface or in a volume hole
inline constexpr std::int32_t kDefaultRegion = -1;  // inside, in no region of the PLC
inline constexpr std::int32_t kUnknownRegion = -3;

class Refiner3 {
 public:
  // Inserts the PLC's vertices; `ft` is its checked facet triangulation.
  Refiner3(const plc::Plc& plc, const plc::FacetTriangulation& ft, const sizing::SizingField3& f,
           const TetOptions& options);

  // Rules 1 and 2 until no subsegment or subfacet is encroached or missing (or the cap).
  void conform();
  // Every tetrahedron's region by a flood fill across faces that are not subfacets.
  void flood_regions();
  // Rule 3 (with rules 1 and 2 first) until no tetrahedron in the domain is bad (or the cap).
  void refine();
  // Adds a shortfall for every tetrahedron of the domain still bad (the first few).
  void list_shortfalls();
  // After rule 3: slivers (smallest dihedral under options.sliver_angle_deg) split by a point near
  // the circumcentre, rule 3 and the boundary rules applied as it goes (slivers.cpp).
  void remove_slivers();

  // The first subsegment that is not an edge, or live subfacet that is not a face, of the
  // tetrahedralization, named with its corners; empty when the whole boundary is there.
  std::string missing_boundary() const;

  // The regions of `tets` (live or not, repeats allowed) flooded again from their neighbours'
  // across faces that are not subfacets, as at the end of a conform() episode that split the
  // boundary; tetrahedra that enter the domain are offered to rule 3.
  void relabel_regions(const std::vector<TetId>& tets);
  // How many region labels a fresh flood would change, or empty (the FDR_DEBUG_TET aid's check).
  std::string stale_regions();
  // The first subfacet that the segment from tetrahedron t (finite) to `centre` (strictly inside
  // t's circumsphere: its circumcentre, say) crosses, when `centre` encroaches it or would destroy
  // it; UINT32_MAX when there is none (or the walk cannot tell, e.g. at a degenerate crossing).
  std::uint32_t subfacet_toward(TetId t, Point3 centre) const;

  bool segment_encroached(VertexId a, VertexId b);
  bool subfacet_encroached(std::uint32_t t);
  // Whether tetrahedron t (finite, in the domain) is bad: R / f(c) > B, radius-edge above 2, or
  // its region's volume bound exceeded. *out gets its entry for the queue.
  bool tet_bad(TetId t, BadTet* out) const;
  std::int32_t region(TetId t) const { return t < region_.size() ? region_[t] : kUnknownRegion; }
  std::int32_t material(TetId t) const;

  const Delaunay3& dt() const { return dt_; }
  const Boundary& boundary() const { return *bd_; }
  const TetStats& stats() const { return stats_; }
  // No subsegment or subfacet is left queued after the last conform() episode.
  bool conforming() const { return seg_queue_.empty() && facet_queue_.empty(); }
  // Whether some conform() episode stopped at its cap on stalled or fruitless splits.
  bool gave_up() const { return gave_up_; }
  TetStats& stats() { return stats_; }
  double bound() const { return bound_; }
  const sizing::SizingField3& spacing() const { return f_; }
  const plc::Plc& plc() const { return plc_; }

 private:
  // Queued pieces; `forced` ones are split without a test (a rejected point encroached them).
  struct QueuedSegment {
    VertexId a, b;
    bool forced = false;
  };
  struct QueuedFacet {
    std::uint32_t tri;
    std::array<VertexId, 3> v;
    bool forced = false;
  };
  bool capped();
  // One entry of the boundary queues taken and acted on; *last gets the piece's middle when split.
  void conform_step(Point3* last);
  void split_segment(VertexId a, VertexId b);
  void split_subfacet(std::uint32_t t);
  void try_split_tet(const BadTet& b);
  // A rule-3 split given up for the boundary pieces queued from these positions on: they are
  // split (and b offered again) unless only b's shape is bad next to an acute angle.
  void reject_for_boundary(const BadTet& b, std::size_t segs_before, std::size_t facets_before);
  // Encroached (or, for subfacets, destroyed) subsegments and subfacets if p were inserted with
  // conflict region `cavity`; returns whether any.
  bool find_encroached(Point3 p, const std::vector<TetId>& cavity, bool facets);
  // After the insertion of v that made `created`: queues the subsegments and subfacets it may
  // have destroyed or changed the neighbourhood of.
  void enqueue_changed(VertexId v, const std::vector<TetId>& created);
  void after_insert(VertexId v, const std::vector<TetId>& created);
  // Queues every subsegment and subfacet (a sweep per refinement pass).
  void enqueue_all();
  void enqueue_at(VertexId u);
  void assign_regions(const std::vector<TetId>& created);
  void flood(TetId start, std::int32_t code, std::vector<std::uint32_t>& mark, std::uint32_t stamp);
  void offer(TetId t);
  // Whether the queue entries from these positions on lie near a small angle: a piece of a facet
  // of an acute pair whose diametral or equatorial ball reaches the other facet's plane.
  bool near_small_angle(std::size_t segs_from, std::size_t facets_from) const;
  // Whether the ball (centre c, radius r) on facet f reaches the plane of a facet paired with f in
  // acute_.
  bool near_acute_partner(std::uint32_t f, Point3 c, double r) const;
  bool face_is_subfacet(TetId t, int i) const;
  // The sliver phase's steps (slivers.cpp).
  double tet_dihedral_cos(TetId t) const;
  void offer_sliver(TetId t);
  void try_split_sliver(const SliverTet& s);
  void yield_for_sliver(const SliverTet& s, Point3 centre);
  void list_slivers();
  void note_shortfall(Point3 where, const std::string& what);

  const plc::Plc& plc_;
  const plc::FacetTriangulation& ft_;
  const sizing::SizingField3& f_;
  TetOptions options_;
  double bound_ = 1;
  std::size_t cap_ = 0;
  Delaunay3 dt_;
  std::vector<VertexId> vid_;          // PLC point -> vertex
  std::vector<std::uint8_t> apex_;     // per vertex: an input vertex where input segments meet
  // Facet pairs meeting at a small dihedral angle (below 60 degrees) along a segment (f < g), sorted: a vertex of
  // one does not encroach the other's subfacets (missing ones are still split), which stops the
  // cascade of splits between two facets at a small angle.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> acute_;
  struct FacetPlane {
    Point3 p, n;  // a point of the facet and the plane's unit normal
  };
  std::vector<FacetPlane> acute_planes_;  // per acute_ entry: its first facet's plane, then its second's
  bool acute_pair(std::uint32_t f, std::uint32_t g) const;
  void find_acute_facet_pairs();
  std::unique_ptr<Boundary> bd_;
  std::deque<QueuedSegment> seg_queue_;
  std::deque<QueuedFacet> facet_queue_;
  std::vector<std::uint8_t> facet_queued_;  // per subfacet slot
  bool regions_live_ = false;               // rule 3: regions kept up to date at every insertion
  LargeArray<std::int32_t> region_;         // per tetrahedron slot, room for the slots reserved
  std::unique_ptr<BadTetQueue> bad_;
  std::unique_ptr<SliverState> slivers_;  // during the sliver phase only: offer() queues slivers too
  std::vector<TetId> created_;  // the tetrahedra the last rule-3 split made
  std::vector<TetId> episode_tets_;  // made since the last relabel_regions (slots may repeat)
  bool episode_split_ = false;       // a boundary piece was split since then
  std::vector<std::uint32_t> tmark_;  // per tetrahedron slot: == tstamp_ when in the cavity at hand
  std::uint32_t tstamp_ = 0;
  std::vector<VertexId> around_;  // the vertices of the tetrahedra an insertion made
  std::vector<VertexId> ring_;    // scratch: the vertices around a subsegment
  std::vector<std::uint32_t> vmark_;
  std::uint32_t vstamp_ = 0;
  std::size_t stalls_ = 0;     // splits of the current conform() episode that made no vertex
  bool gave_up_ = false;       // an episode ended at its stall or progress cap
  bool check_boundary_ = false;  // the FDR_DEBUG_TET aid: missing_boundary() after every episode
  std::size_t regions_checked_at_ = 0;  // the aid's vertex count at its last stale_regions()
  TetStats stats_;
};

}  // namespace fdr::tet
