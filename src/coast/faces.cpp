// The faces of an arrangement of lines, cluster by cluster (faces.hpp).
#include "coast/faces.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include "base/parallel.hpp"
#include "pslg/segment_grid.hpp"

namespace fdr::coast {
namespace {

constexpr std::size_t kFaceScanLines = 16;  // face_point: the scan lines tried

Box2 segment_box(const OGRLineString* l, int i) {
  Box2 b;
  b.add({l->getX(i), l->getY(i)});
  b.add({l->getX(i + 1), l->getY(i + 1)});
  return b;
}

bool boxes_meet(const Box2& a, const Box2& b) {
  return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y;
}

}  // namespace

std::unique_ptr<OGRMultiLineString> noded_as_given(const OGRMultiLineString& lines, const std::vector<int>& members) {
  struct PairHash {
    std::size_t operator()(const std::pair<double, double>& p) const {
      return static_cast<std::size_t>(point_key(p.first, p.second));
    }
  };
  std::unordered_map<std::pair<double, double>, Index, PairHash> id;
  std::vector<Point2> pts;
  std::vector<int> uses;  // vertex occurrences (a closed line's start twice)
  std::vector<std::vector<Index>> at(members.size());
  for (std::size_t m = 0; m < members.size(); ++m) {
    const OGRLineString* l = lines.getGeometryRef(members[m]);
    for (int k = 0; k < l->getNumPoints(); ++k) {
      const auto [it, fresh] = id.try_emplace({l->getX(k), l->getY(k)}, static_cast<Index>(pts.size()));
      if (fresh) {
        pts.push_back({l->getX(k), l->getY(k)});
        uses.push_back(0);
      }
      ++uses[it->second];
      at[m].push_back(it->second);
    }
  }
  std::vector<pslg::Segment> segs;
  std::unordered_set<std::uint64_t> seen;
  for (const auto& v : at)
    for (std::size_t k = 0; k + 1 < v.size(); ++k) {
      const Index a = std::min(v[k], v[k + 1]), b = std::max(v[k], v[k + 1]);
      if (a == b || !seen.insert((static_cast<std::uint64_t>(a) << 32) | b).second) return nullptr;
      segs.push_back({v[k], v[k + 1]});
    }
  const pslg::Contacts ct = pslg::find_contacts(pts, segs, nullptr);
  if (!ct.segment_pairs.empty() || !ct.vertex_on_segment.empty()) return nullptr;
  auto out = std::make_unique<OGRMultiLineString>();
  for (const auto& v : at) {
    auto line = std::make_unique<OGRLineString>();
    for (std::size_t k = 0; k < v.size(); ++k) {
      line->addPoint(pts[v[k]].x, pts[v[k]].y);
      if (k > 0 && k + 1 < v.size() && uses[v[k]] > 1) {
        out->addGeometryDirectly(line.release());
        line = std::make_unique<OGRLineString>();
        line->addPoint(pts[v[k]].x, pts[v[k]].y);
      }
    }
    out->addGeometryDirectly(line.release());
  }
  return out;
}

namespace {

// The faces of one cluster's lines: noded (as given when they are, noded_as_given; else by GEOS:
// OGR 3.6 has no unary union, the union with one of them nodes them all) and polygonized. False
// when GEOS fails.
bool cluster_faces(const OGRMultiLineString& lines, const std::vector<int>& members, OwnedPolygons& out) {
  GeomPtr noded = noded_as_given(lines, members);
  if (!noded) {
    OGRMultiLineString ml;
    for (const int i : members) ml.addGeometry(lines.getGeometryRef(i));
    std::unique_ptr<OGRGeometry> first(ml.getGeometryRef(0)->clone());
    noded.reset(ml.Union(first.get()));
  }
  if (!noded) return false;
  if (wkbFlatten(noded->getGeometryType()) == wkbLineString) {  // Polygonize wants a collection
    auto m = std::make_unique<OGRMultiLineString>();
    m->addGeometryDirectly(noded.release());
    noded = std::move(m);
  }
  GeomPtr faces(noded->Polygonize());
  if (!faces) return false;
  polygons_of(faces.get(), out);
  return true;
}

}  // namespace

bool face_point(const OGRPolygon& f, Point2& p) {
  std::vector<double> ys;
  for (int k = -1; k < f.getNumInteriorRings(); ++k) {
    const OGRLinearRing* r = k < 0 ? f.getExteriorRing() : f.getInteriorRing(k);
    for (int i = 0; i < r->getNumPoints(); ++i) ys.push_back(r->getY(i));
  }
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<std::size_t> gaps;  // between consecutive vertex heights, the widest first
  for (std::size_t i = 0; i + 1 < ys.size(); ++i) gaps.push_back(i);
  std::stable_sort(gaps.begin(), gaps.end(), [&](std::size_t i, std::size_t j) { return ys[i + 1] - ys[i] > ys[j + 1] - ys[j]; });
  if (gaps.size() > kFaceScanLines) gaps.resize(kFaceScanLines);
  std::vector<double> xs;
  struct Span {
    double width;
    Point2 mid;
  };
  std::vector<Span> spans;
  for (const std::size_t i : gaps) {
    const double y = 0.5 * (ys[i] + ys[i + 1]);
    xs.clear();
    for (int k = -1; k < f.getNumInteriorRings(); ++k) {
      const OGRLinearRing* r = k < 0 ? f.getExteriorRing() : f.getInteriorRing(k);
      for (int j = 0; j + 1 < r->getNumPoints(); ++j) {
        const double x0 = r->getX(j), y0 = r->getY(j), x1 = r->getX(j + 1), y1 = r->getY(j + 1);
        if ((y0 < y) != (y1 < y)) xs.push_back(x0 + (y - y0) * (x1 - x0) / (y1 - y0));
      }
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t j = 0; j + 1 < xs.size(); j += 2)
      if (xs[j + 1] > xs[j]) spans.push_back({xs[j + 1] - xs[j], {0.5 * (xs[j] + xs[j + 1]), y}});
  }
  std::stable_sort(spans.begin(), spans.end(), [](const Span& a, const Span& b) { return a.width > b.width; });
  const Prepared pf(&f);
  for (const Span& s : spans) {
    const OGRPoint pt(s.mid.x, s.mid.y);
    if (pf.contains(&pt)) {
      p = s.mid;
      return true;
    }
  }
  p = {0, 0};
  return false;
}

std::vector<std::vector<int>> line_clusters(const OGRMultiLineString& lines) {
  const int n = lines.getNumGeometries();
  Box2 box;
  std::size_t nseg = 0;
  double total = 0;
  for (int i = 0; i < n; ++i) {
    const OGRLineString* l = lines.getGeometryRef(i);
    for (int k = 0; k + 1 < l->getNumPoints(); ++k) {
      const Point2 a{l->getX(k), l->getY(k)}, b{l->getX(k + 1), l->getY(k + 1)};
      box.add(a);
      box.add(b);
      total += dist(a, b);
      ++nseg;
    }
  }
  std::vector<int> parent(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) parent[static_cast<std::size_t>(i)] = i;
  auto find = [&](int i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  if (nseg > 0) {
    pslg::SegmentGrid grid(box, nseg, total / static_cast<double>(nseg));
    std::vector<int> seg_line;
    std::vector<std::pair<int, int>> seg_at;  // (line, first vertex)
    seg_line.reserve(nseg);
    for (int i = 0; i < n; ++i) {
      const OGRLineString* l = lines.getGeometryRef(i);
      for (int k = 0; k + 1 < l->getNumPoints(); ++k) {
        grid.add_segment(static_cast<Index>(seg_at.size()), {l->getX(k), l->getY(k)}, {l->getX(k + 1), l->getY(k + 1)});
        seg_at.emplace_back(i, k);
      }
    }
    std::vector<Index> near;
    for (std::size_t s = 0; s < seg_at.size(); ++s) {
      const auto [i, k] = seg_at[s];
      const Box2 b = segment_box(lines.getGeometryRef(i), k);
      grid.segments_near(b, &near);
      for (const Index t : near) {
        const auto [j, m] = seg_at[t];
        if (find(i) == find(j)) continue;
        if (boxes_meet(b, segment_box(lines.getGeometryRef(j), m))) parent[static_cast<std::size_t>(find(i))] = find(j);
      }
    }
  }
  std::vector<int> id(static_cast<std::size_t>(n), -1);
  std::vector<std::vector<int>> out;
  for (int i = 0; i < n; ++i) {
    int& c = id[static_cast<std::size_t>(find(i))];
    if (c < 0) {
      c = static_cast<int>(out.size());
      out.emplace_back();
    }
    out[static_cast<std::size_t>(c)].push_back(i);
  }
  return out;
}

// Why clusters: GEOS nodes and polygonizes the whole at once, and where its fast noding fails on
// one spot it snaps and nodes everything again; its polygonizer places every hole with a point
// index per candidate shell. Clusters whose lines never meet share no face boundary, so each
// is polygonized alone; only faces that hold another cluster need its faces taken out.
bool arrangement_faces(const OGRMultiLineString& lines, OwnedPolygons& faces) {
  const auto clusters = line_clusters(lines);
  const std::size_t nc = clusters.size();
  std::vector<OwnedPolygons> per(nc);
  std::atomic<bool> failed{false};
  parallel_chunks(nc, [&](std::size_t c, unsigned) {
    GdalQuiet quiet;
    if (!failed && !cluster_faces(lines, clusters[c], per[c])) failed = true;
  });
  if (failed) return false;
  // Each cluster's box and a point on it (its first vertex: on none of the other clusters'
  // segments, whose boxes it does not meet).
  std::vector<OGREnvelope> cenv(nc);
  std::vector<Point2> cpt(nc);
  Box2 all;
  for (std::size_t c = 0; c < nc; ++c) {
    for (const int i : clusters[c]) {
      OGREnvelope e;
      lines.getGeometryRef(i)->getEnvelope(&e);
      cenv[c].Merge(e);
    }
    const OGRLineString* l = lines.getGeometryRef(clusters[c].front());
    cpt[c] = {l->getX(0), l->getY(0)};
    all.add(cpt[c]);
  }
  pslg::SegmentGrid points(all, nc, std::sqrt(all.width() * all.height() / static_cast<double>(std::max<std::size_t>(nc, 1))));
  for (std::size_t c = 0; c < nc; ++c) points.add_point(static_cast<Index>(c), cpt[c]);
  std::vector<Index> near;
  for (std::size_t c = 0; c < nc; ++c)
    for (auto& f : per[c]) {
      OGREnvelope fe;
      f->getEnvelope(&fe);
      Box2 fb;
      fb.add({fe.MinX, fe.MinY});
      fb.add({fe.MaxX, fe.MaxY});
      points.points_near(fb, &near);
      std::sort(near.begin(), near.end());
      std::unique_ptr<Prepared> pf;
      std::vector<std::size_t> inside;
      for (const Index d : near) {
        if (d == c || !fe.Contains(cenv[d])) continue;
        if (!pf) pf = std::make_unique<Prepared>(f.get());
        const OGRPoint pt(cpt[d].x, cpt[d].y);
        if (pf->contains(&pt)) inside.push_back(d);
      }
      if (inside.empty()) continue;
      auto held = std::make_unique<OGRMultiPolygon>();
      for (const std::size_t d : inside)
        for (const auto& g : per[d]) held->addGeometry(g.get());
      if (held->IsEmpty()) continue;  // lines without faces: no area to take out
      pf.reset();
      GeomPtr u(held->UnionCascaded());
      GeomPtr cut = u ? GeomPtr(f->Difference(u.get())) : nullptr;
      if (!cut) return false;
      OwnedPolygons ps;
      polygons_of(cut.get(), ps);
      if (ps.size() != 1) return false;
      f = std::move(ps[0]);
    }
  for (auto& v : per)
    for (auto& f : v) faces.push_back(std::move(f));
  return true;
}

}  // namespace fdr::coast
