// take_view gives exactly to_view's mesh (order, markers, parts, adjacency) and empties the triangulation.
#include <gtest/gtest.h>

#include "cdt/cdt.hpp"
#include "cdt/tests/test_inputs.hpp"
#include "refine/tests/fn_field.hpp"
#include "mesh/take_view.hpp"
#include "refine/refine.hpp"

using namespace fdr;

namespace {
void expect_same(const mesh::MeshView& a, const mesh::MeshView& b) {
  EXPECT_EQ(a.origin, b.origin);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  for (std::size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]) << i;
  EXPECT_EQ(a.triangles, b.triangles);
  ASSERT_EQ(a.edges.size(), b.edges.size());
  for (std::size_t i = 0; i < a.edges.size(); ++i) {
    EXPECT_EQ(a.edges[i].a, b.edges[i].a);
    EXPECT_EQ(a.edges[i].b, b.edges[i].b);
    EXPECT_EQ(a.edges[i].marker, b.edges[i].marker);
    EXPECT_EQ(a.edges[i].part, b.edges[i].part);
  }
  EXPECT_EQ(a.vertex_marker, b.vertex_marker);
  // The adjacency (the triangulation's twins, renumbered): the same in both, and consistent.
  EXPECT_EQ(a.neighbours, b.neighbours);
  ASSERT_EQ(b.neighbours.size(), 3 * b.triangles.size());
  std::size_t boundary = 0;
  for (std::size_t h = 0; h < b.neighbours.size(); ++h) {
    const Index g = b.neighbours[h];
    if (g == kNoId) { ++boundary; continue; }
    ASSERT_LT(g, b.neighbours.size());
    EXPECT_EQ(b.neighbours[g], h);
    EXPECT_EQ(b.triangles[h / 3][h % 3], b.triangles[g / 3][(g % 3 + 1) % 3]);
    EXPECT_EQ(b.triangles[h / 3][(h % 3 + 1) % 3], b.triangles[g / 3][g % 3]);
  }
  EXPECT_GT(boundary, 0u);
}
}  // namespace

TEST(TakeView, SameAsToViewAfterCdtAndRefinement) {
  for (unsigned seed : {3u, 17u, 42u}) {
    pslg::Pslg p = fdr::testing::random_pslg(seed, 30, 12);
    mesh::Triangulation t = cdt::build_cdt(p);
    {
      mesh::Triangulation copy = t;
      expect_same(t.to_view(), mesh::take_view(copy));
      EXPECT_EQ(copy.num_slots(), 0u);
      EXPECT_EQ(copy.num_vertices(), 0u);
    }
    fdr::testing::FnField f([](Point2 q) { return 0.3 + 0.05 * q.x; });
    refine::Refiner r(t, f, {});
    r.init();
    r.run();
    mesh::Triangulation copy = t;
    const mesh::MeshView want = t.to_view();
    ASSERT_FALSE(want.edges.empty());
    expect_same(want, mesh::take_view(copy));
  }
}

// A mesh large enough for the two-thread renumbering (65 536 triangles or more), with and
// without dead slots: the same mesh as to_view's, the corners' array handed over (no copy).
TEST(TakeView, LargeMeshSameAsToViewAndCornersHandedOver) {
  pslg::Pslg p = fdr::testing::random_pslg(7, 40, 16);
  mesh::Triangulation t = cdt::build_cdt(p);
  fdr::testing::FnField f([](Point2 q) { return 0.02 + 0.004 * std::abs(q.x); });
  refine::Refiner r(t, f, {});
  r.init();
  r.run();
  ASSERT_GE(t.num_live_triangles(), 65536u);
  for (bool with_dead : {false, true}) {
    mesh::Triangulation copy = t;
    if (with_dead) {  // a dead slot in the middle: the slot-order compaction
      const TriangleId s = static_cast<TriangleId>(copy.num_slots() / 2);
      for (int k = 0; k < 3; ++k)
        if (copy.twin(3 * s + k) != kNoId) copy.set_twin(copy.twin(3 * s + k), kNoId);
      copy.kill_triangle(s);
    }
    const mesh::MeshView want = copy.to_view();
    const std::array<Index, 3>* corners = copy.corners().data();
    const mesh::MeshView got = mesh::take_view(copy);
    expect_same(want, got);
    EXPECT_EQ(got.triangles.data(), corners) << "with_dead " << with_dead;
  }
}
