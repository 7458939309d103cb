// The faces of an arrangement of lines cluster by cluster (faces.hpp), and the differences by
// faces built on them, against GEOS's overlay.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "coast/faces.hpp"
#include "coast/geometry_ops.hpp"

namespace fdr::coast {
namespace {

// A closed line around the box [x0, x1] x [y0, y1].
std::unique_ptr<OGRLineString> square_line(double x0, double y0, double x1, double y1) {
  auto l = std::make_unique<OGRLineString>();
  l->addPoint(x0, y0);
  l->addPoint(x1, y0);
  l->addPoint(x1, y1);
  l->addPoint(x0, y1);
  l->addPoint(x0, y0);
  return l;
}

OGRLinearRing square_ring(double x0, double y0, double x1, double y1) {
  return closed_ring({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

std::vector<double> areas(const OwnedPolygons& fs) {
  std::vector<double> a;
  for (const auto& f : fs) a.push_back(f->get_Area());
  std::sort(a.begin(), a.end());
  return a;
}

TEST(CoastFaces, LinesWhoseSegmentsMeetShareACluster) {
  OGRMultiLineString ml;
  ml.addGeometryDirectly(square_line(0, 0, 2, 2).release());
  ml.addGeometryDirectly(square_line(100, 0, 101, 1).release());  // far from the others
  ml.addGeometryDirectly(square_line(1, 1, 3, 3).release());      // crosses the first
  const auto c = line_clusters(ml);
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0], (std::vector<int>{0, 2}));
  EXPECT_EQ(c[1], (std::vector<int>{1}));
}

TEST(CoastFaces, LinesInsideALargeBoxButFarFromItsSegmentsAreAClusterOfTheirOwn) {
  OGRMultiLineString ml;
  ml.addGeometryDirectly(square_line(0, 0, 10, 10).release());
  ml.addGeometryDirectly(square_line(4, 4, 6, 6).release());
  EXPECT_EQ(line_clusters(ml).size(), 2u);
}

TEST(CoastFaces, CrossingSquaresGiveThreeFaces) {
  OGRMultiLineString ml;
  ml.addGeometryDirectly(square_line(0, 0, 2, 2).release());
  ml.addGeometryDirectly(square_line(1, 1, 3, 3).release());
  OwnedPolygons fs;
  ASSERT_TRUE(arrangement_faces(ml, fs));
  EXPECT_EQ(areas(fs), (std::vector<double>{1, 3, 3}));
}

TEST(CoastFaces, AFaceHoldingAnotherClusterHasItsFacesCutOut) {
  OGRMultiLineString ml;
  ml.addGeometryDirectly(square_line(0, 0, 10, 10).release());
  ml.addGeometryDirectly(square_line(4, 4, 6, 6).release());
  ml.addGeometryDirectly(square_line(4.5, 4.5, 5.5, 5.5).release());  // inside the inner one
  ml.addGeometryDirectly(square_line(20, 0, 21, 1).release());        // beside, outside
  OwnedPolygons fs;
  ASSERT_TRUE(arrangement_faces(ml, fs));
  EXPECT_EQ(areas(fs), (std::vector<double>{1, 1, 3, 96}));
}

// a - b where the lines of a's hole lie inside a face bounded by b's hole: the face gets the
// inner square cut out, as GEOS's overlay of the whole says.
TEST(CoastFaces, DifferenceByFacesWithNestedClustersIsTheOverlays) {
  OGRPolygon a, b;
  OGRLinearRing ao = square_ring(0, 0, 10, 10), ah = square_ring(4, 4, 6, 6);
  OGRLinearRing bo = square_ring(0, 0, 10, 10), bh = square_ring(1, 1, 9, 9);
  a.addRing(&ao);
  a.addRing(&ah);
  b.addRing(&bo);
  b.addRing(&bh);
  const GeomPtr by_faces = difference_by_faces(&a, &b, "test");
  const GeomPtr overlay = difference_by_faces(&a, &b, "test", true);
  EXPECT_DOUBLE_EQ(area_of(by_faces.get()), 60);
  EXPECT_DOUBLE_EQ(area_of(overlay.get()), 60);
  const GeomPtr sym(by_faces->SymDifference(overlay.get()));
  EXPECT_NEAR(area_of(sym.get()), 0, 1e-9);
}

// A face of a coast's arrangement: a bay with a spike along two nearly collinear segments, so
// thin that GEOS's scan line through the middle of its box meets it in no span, and its point
// on surface falls back to the first vertex.
OGRPolygon spiked_face() {
  OGRPolygon f;
  OGRLinearRing r = closed_ring({
      {423288.2322880651, 55610.28779539912},
      {422810.59785908746, 55563.62257593457},
      {422939.33355941, 55200.1775631316},
      {422387.58488023694, 55571.74337637212},
      {422368.2550620238, 55744.37672426345},
      {423683.6654340916, 56954.080355301136},
      {422444.9027394827, 55814.86497317913},
      {422428.0213509335, 55792.040742217},
      {422420.83255466295, 55764.57716621998},
      {422424.36633174896, 55736.40911307693},
      {422438.11637718644, 55711.57238525643},
      {422460.11264118046, 55693.62548667566},
      {422466.94713755825, 55691.48471386433},
      {422487.2035897547, 55685.13977493706},
      {422534.02049380756, 55679.82006024124},
      {422540.885179817, 55677.55907672326},
      {422546.2793739892, 55672.748813767175},
      {422579.12904779724, 55628.399776058446},
      {422603.0746327392, 55607.42271671216},
      {422633.5641986437, 55598.26769470339},
      {422665.10459323815, 55602.584124461726},
      {422692.0133417114, 55619.59433647192},
      {422709.6304580134, 55636.93797488097},
      {422881.7164949629, 55742.64566184459},
      {422897.4907917775, 55747.94531774526},
      {422996.2304266451, 55757.59224948092},
      {423010.08154610306, 55756.33066778579},
      {423173.16880696896, 55709.60130015179},
      {423179.1522688794, 55706.58238138104},
      {423183.6069475508, 55701.575233998185},
      {423216.56710657454, 55646.44602032797},
      {423235.22286476236, 55625.47657726},
      {423260.28101749637, 55612.83364098309}
});
  f.addRing(&r);
  return f;
}

TEST(CoastFacePoint, IsStrictlyInsideWhereThePointOnSurfaceIsOnTheBoundary) {
  const OGRPolygon f = spiked_face();
  const Prepared pf(&f);
  const Point2 q = inside_point(&f);
  const OGRPoint on(q.x, q.y);
  ASSERT_FALSE(pf.contains(&on));  // the premise: GEOS's point is on the boundary
  Point2 p;
  ASSERT_TRUE(face_point(f, p));
  const OGRPoint in(p.x, p.y);
  EXPECT_TRUE(pf.contains(&in));
}

// A face of GEOS's noding of a coast's arrangement: a cut corner, and a sliver along two nearly
// collinear segments to their computed crossing, where GEOS's point on surface lies (within
// rounding of the segments, so on either side of the input's).
TEST(CoastFacePoint, LiesInTheWidestPartNotInASliver) {
  OGRPolygon f;
  OGRLinearRing r = closed_ring({
      {199856.69428446327, -135278.90279929907},
      {198793.63574211334, -136469.3515836767},
      {198793.63574211337, -136469.35158367665},
      {199810.96036755925, -135330.11718083525},
      {199825.25651476398, -135306.46117373958},
      {199830.0129783078, -135279.23320005136},
      {199824.58373616057, -135252.13135829996},
      {199809.7061870223, -135228.83661579766}});
  f.addRing(&r);
  const Point2 q = inside_point(&f);
  ASSERT_LT(q.x, 199800);  // the premise: GEOS's point is in the sliver
  Point2 p;
  ASSERT_TRUE(face_point(f, p));
  EXPECT_GT(p.x, 199810);
  EXPECT_GT(p.y, -135331);
  EXPECT_LT(p.y, -135228);
}

// a - b with b far away is a: its one face is kept only when the point that classifies it lies
// inside it.
TEST(CoastFaces, DifferenceByFacesKeepsAFaceWhosePointOnSurfaceIsOnItsBoundary) {
  const OGRPolygon a = spiked_face();
  OGRPolygon b;
  OGRLinearRing br = square_ring(0, 0, 10, 10);
  b.addRing(&br);
  const GeomPtr by_faces = difference_by_faces(&a, &b, "test");
  EXPECT_NEAR(area_of(by_faces.get()), a.get_Area(), 1e-6);
}

}  // namespace
}  // namespace fdr::coast

namespace fdr::coast {
namespace {

std::unique_ptr<OGRLineString> polyline(const std::vector<Point2>& pts) {
  auto l = std::make_unique<OGRLineString>();
  for (const Point2& p : pts) l->addPoint(p.x, p.y);
  return l;
}

TEST(CoastNodedAsGiven, LinesMeetingAtVerticesAreCutThereAndKept) {
  OGRMultiLineString ml;
  // A closed square and a path from its corner (2, 0) through (2, 2), a vertex of the third line.
  ml.addGeometryDirectly(polyline({{0, 0}, {2, 0}, {2, -2}, {0, -2}, {0, 0}}).release());
  ml.addGeometryDirectly(polyline({{2, 0}, {2, 2}, {4, 2}}).release());
  ml.addGeometryDirectly(polyline({{0, 2}, {2, 2}, {2, 4}}).release());
  auto noded = noded_as_given(ml, {0, 1, 2});
  ASSERT_TRUE(noded);
  // The square cut at (2, 0) (used by the second line), the second and third lines at (2, 2).
  EXPECT_EQ(noded->getNumGeometries(), 6);
}

TEST(CoastNodedAsGiven, CrossingTouchingOrRepeatedSegmentsNeedGeosNoding) {
  OGRMultiLineString cross;
  cross.addGeometryDirectly(polyline({{0, 0}, {2, 2}}).release());
  cross.addGeometryDirectly(polyline({{0, 2}, {2, 0}}).release());
  EXPECT_FALSE(noded_as_given(cross, {0, 1}));
  OGRMultiLineString touch;  // an end in the other's interior
  touch.addGeometryDirectly(polyline({{0, 0}, {2, 0}}).release());
  touch.addGeometryDirectly(polyline({{1, 0}, {1, 1}}).release());
  EXPECT_FALSE(noded_as_given(touch, {0, 1}));
  OGRMultiLineString twice;  // one segment in both lines
  twice.addGeometryDirectly(polyline({{0, 0}, {1, 0}, {1, 1}}).release());
  twice.addGeometryDirectly(polyline({{1, 0}, {0, 0}, {0, 1}}).release());
  EXPECT_FALSE(noded_as_given(twice, {0, 1}));
}

TEST(CoastNodedAsGiven, FacesOfLinesNodedAsGivenAreGeosFaces) {
  // Two rings of a difference that part at shared vertices: faces as GEOS's noding gives them.
  OGRMultiLineString ml;
  ml.addGeometryDirectly(polyline({{0, 0}, {4, 0}, {4, 4}}).release());
  ml.addGeometryDirectly(polyline({{0, 0}, {1, 3}, {4, 4}}).release());
  ml.addGeometryDirectly(polyline({{4, 4}, {0, 4}, {0, 0}}).release());
  OwnedPolygons fs;
  ASSERT_TRUE(arrangement_faces(ml, fs));
  ASSERT_TRUE(noded_as_given(ml, {0, 1, 2}));
  OGRMultiLineString copy;
  for (int i = 0; i < 3; ++i) copy.addGeometry(ml.getGeometryRef(i));
  std::unique_ptr<OGRGeometry> first(copy.getGeometryRef(0)->clone());
  GeomPtr noded(copy.Union(first.get()));
  GeomPtr theirs(noded->Polygonize());
  OwnedPolygons ts;
  polygons_of(theirs.get(), ts);
  EXPECT_EQ(areas(fs), areas(ts));
  EXPECT_EQ(fs.size(), 2u);
}

}  // namespace
}  // namespace fdr::coast
