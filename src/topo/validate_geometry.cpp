// Geometric findings (validate.h, check_geometry): faces whose vertices do not lie
// exactly on one plane, and loops that cross themselves in their face's plane.
//
// Planarity: the plane through the first three non-collinear vertices of the outer
// loop (geom/plane.h), and orient3d of every vertex of every loop against it.
// Crossings, on planar faces only: each loop projected along the exact dominant axis
// of that plane (a bijection of the plane, so incidences are kept), then every pair
// of its edges that share no vertex is tested with segments_meet, and every pair of
// consecutive edges for folding back onto each other. Edges that share a vertex are
// joined by the loop itself (a pinched loop passes a vertex twice on purpose).
// A long loop (a faceted circle's cap) finds its candidate pairs through a
// bounding-volume hierarchy over its edges' boxes in the plane, not all n^2 pairs.
#include <optional>

#include "cellforge/geom/bvh.h"

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/plane.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/topo/validate.h"

namespace cellforge::inline topo {

namespace {

std::optional<Plane> face_plane(const Model& m, FaceId f, std::vector<VertexId>& three) {
  const std::vector<VertexId> vs = m.loop_vertices(m.outer_loop(f));
  for (std::size_t i = 1; i < vs.size(); ++i) {
    if (m.position(vs[i]) == m.position(vs[0])) continue;
    for (std::size_t j = i + 1; j < vs.size(); ++j) {
      if (collinear3d(m.position(vs[0]), m.position(vs[i]), m.position(vs[j]))) continue;
      three = {vs[0], vs[i], vs[j]};
      return Plane::through(m.position(vs[0]), m.position(vs[i]), m.position(vs[j]));
    }
  }
  return std::nullopt;  // a degenerate face: every vertex on one line
}

void crossings(const Model& m, FaceId f, LoopId l, const Projection& proj, GeometryFindings& out) {
  const std::vector<VertexId> vs = m.loop_vertices(l);
  const std::size_t n = vs.size();
  if (n < 3) return;
  std::vector<Vec2> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = proj(m.position(vs[i]));
  const auto report = [&](std::size_t i, std::size_t j) {
    out.crossings.push_back({"crossing", l.str() + " of " + f.str() + " crosses itself: its edge " +
                                             vs[i].str() + "-" + vs[(i + 1) % n].str() + " meets " +
                                             vs[j].str() + "-" + vs[(j + 1) % n].str()});
    out.crossing_faces.push_back(f);
  };
  // Edges i and j (i + 1 < j), sharing no vertex, meet.
  const auto meet = [&](std::size_t i, std::size_t j) {
    const std::size_t next = (i + 1) % n;
    const VertexId a = vs[i], b = vs[next], c = vs[j], d = vs[(j + 1) % n];
    if (a == c || a == d || b == c || b == d) return false;
    return segments_meet(p[i], p[next], p[j], p[(j + 1) % n]);
  };
  if (n <= 64) {
    for (std::size_t i = 0; i < n; ++i) {
      if (edges_fold_back(p[i], p[(i + 1) % n], p[(i + 2) % n])) return report(i, (i + 1) % n);
      for (std::size_t j = i + 2; j < n; ++j)
        if (meet(i, j)) return report(i, j);
    }
    return;
  }
  // The first crossing in the order of the loop above: the least (i, j) found.
  std::vector<Box> boxes(n);
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i].add(Vec3{p[i].x, p[i].y, 0});
    boxes[i].add(Vec3{p[(i + 1) % n].x, p[(i + 1) % n].y, 0});
  }
  std::optional<std::pair<std::size_t, std::size_t>> first;
  const auto found = [&](std::size_t i, std::size_t j) {
    if (!first || std::make_pair(i, j) < *first) first = std::make_pair(i, j);
  };
  for (std::size_t i = 0; i < n; ++i)
    if (edges_fold_back(p[i], p[(i + 1) % n], p[(i + 2) % n])) found(i, (i + 1) % n);
  Bvh(std::move(boxes)).pairs([&](std::uint32_t a, std::uint32_t b) {
    const std::size_t i = std::min(a, b), j = std::max(a, b);
    if (j == i + 1 || (i == 0 && j == n - 1)) return;  // consecutive: folding, above
    if (meet(i, j)) found(i, j);
  });
  if (first) report(first->first, first->second);
}

}  // namespace

GeometryFindings check_geometry(const Model& m) {
  GeometryFindings g;
  std::vector<VertexId> three;
  for (FaceId f : m.faces()) {
    const std::optional<Plane> plane = face_plane(m, f, three);
    if (!plane) continue;
    bool planar = true;
    for (LoopId l : m.loops_of(f)) {
      for (VertexId v : m.loop_vertices(l)) {
        if (planar && plane->side(m.position(v)) != 0) {
          g.non_planar.push_back({"planarity", f.str() + " is not planar: " + v.str() +
                                                   " lies off the plane of " + three[0].str() +
                                                   ", " + three[1].str() + ", " + three[2].str()});
          g.non_planar_faces.push_back(f);
          planar = false;
        }
      }
    }
    if (!planar) continue;
    const Projection proj = plane->projection();
    for (LoopId l : m.loops_of(f)) crossings(m, f, l, proj, g);
  }
  return g;
}

}  // namespace cellforge::inline topo
