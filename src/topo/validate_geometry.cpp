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
#include <optional>

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

void crossings(const Model& m, FaceId f, LoopId l, const Projection& proj,
               std::vector<Violation>& out) {
  const std::vector<VertexId> vs = m.loop_vertices(l);
  const std::size_t n = vs.size();
  if (n < 3) return;
  std::vector<Vec2> p(n);
  for (std::size_t i = 0; i < n; ++i) p[i] = proj(m.position(vs[i]));
  const auto report = [&](std::size_t i, std::size_t j) {
    out.push_back({"crossing", l.str() + " of " + f.str() + " crosses itself: its edge " +
                                   vs[i].str() + "-" + vs[(i + 1) % n].str() + " meets " +
                                   vs[j].str() + "-" + vs[(j + 1) % n].str()});
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t next = (i + 1) % n;
    if (edges_fold_back(p[i], p[next], p[(i + 2) % n])) return report(i, next);
    for (std::size_t j = i + 2; j < n; ++j) {
      const VertexId a = vs[i], b = vs[next], c = vs[j], d = vs[(j + 1) % n];
      if (a == c || a == d || b == c || b == d) continue;
      if (segments_meet(p[i], p[next], p[j], p[(j + 1) % n])) return report(i, j);
    }
  }
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
          planar = false;
        }
      }
    }
    if (!planar) continue;
    const Projection proj = plane->projection();
    for (LoopId l : m.loops_of(f)) crossings(m, f, l, proj, g.crossings);
  }
  return g;
}

}  // namespace cellforge::inline topo
