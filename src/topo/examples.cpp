#include "cellforge/topo/examples.h"

#include "cellforge/topo/operators.h"
#include "topo/operators_common.h"

namespace cellforge::inline topo {

namespace {

Vec3 corner(Vec3 lo, Vec3 hi, int i) {
  return {(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
}

VertexId find_vertex(const Model& m, GroupId g, Vec3 p) {
  for (VertexId v : m.vertices()) {
    if (m.group_of(v) == g && m.position(v) == p) return v;
  }
  return {};
}

}  // namespace

Status euler_box_into(Model& m, GroupId g, Vec3 lo, Vec3 hi, bool solid) {
  VertexId v[8];
  auto vf = mvsf(m, g, corner(lo, hi, 0));
  CF_CHECK(vf.ok() ? Status::Ok() : Status(vf.error()));
  v[0] = vf->vertex;
  const LoopId top = m.outer_loop(vf->face);
  const int ring[4] = {0, 1, 3, 2};  // bottom corners counterclockwise seen from +z
  for (int i = 1; i < 4; ++i) {
    auto ev = mev(m, top, v[ring[i - 1]], corner(lo, hi, ring[i]));
    if (!ev) return ev.error();
    v[ring[i]] = ev->vertex;
  }
  // The new face runs 2 -> 3 -> 1 -> 0 (normal -z): the bottom; the first face
  // keeps 0 -> 1 -> 3 -> 2 and is lifted into the top.
  if (auto ef = mef(m, top, v[2], v[0]); !ef) return ef.error();
  for (int i = 0; i < 4; ++i) {
    auto ev = mev(m, top, v[ring[i]], corner(lo, hi, ring[i] + 4));
    if (!ev) return ev.error();
    v[ring[i] + 4] = ev->vertex;
  }
  for (int i = 0; i < 4; ++i) {
    if (auto ef = mef(m, top, v[ring[i] + 4], v[ring[(i + 1) % 4] + 4]); !ef) return ef.error();
  }
  if (!solid) return Status::Ok();
  // The box's six faces are those at its corner 0 or its corner 7.
  std::vector<FaceSide> all;
  for (FaceId f : m.faces()) {
    if (m.group_of(f) != g || m.back_volume(f).is_valid()) continue;
    for (VertexId c : m.loop_vertices(m.outer_loop(f))) {
      if (c == v[0] || c == v[7]) {
        all.push_back({f, false});
        break;
      }
    }
  }
  auto c = make_volume(m, g, all);
  return c ? Status::Ok() : Status(c.error());
}

Result<GroupId> euler_box(Model& m, Vec3 lo, Vec3 hi, bool solid, std::string name) {
  const GroupId g = make_group(m, std::move(name));
  if (Status s = euler_box_into(m, g, lo, hi, solid); !s) return s.error();
  return g;
}

Result<GroupId> euler_box_with_hole(Model& m, Vec3 lo, Vec3 hi, double a, double b,
                                    std::string name) {
  auto g = euler_box(m, lo, hi, false, std::move(name));
  if (!g) return g;
  FaceId square[2];
  VertexId inner[2][4];
  for (int s = 0; s < 2; ++s) {
    const double z = s == 0 ? hi.z : lo.z;
    FaceId face;
    for (FaceId f : m.faces()) {
      if (m.group_of(f) != *g) continue;
      bool flat = true;
      for (Vec3 p : m.loop_points(m.outer_loop(f))) flat = flat && p.z == z;
      if (flat) face = f;
    }
    // The rim corners counterclockwise seen from the face's front (+z on top, -z
    // on the bottom). mef below gives the cap this order and leaves the face's
    // ring the reverse: clockwise from the front, as an inner loop runs.
    const Vec3 rim_top[4] = {{a, a, z}, {b, a, z}, {b, b, z}, {a, b, z}};
    const Vec3 rim_bottom[4] = {{a, a, z}, {a, b, z}, {b, b, z}, {b, a, z}};
    const Vec3* rim = s == 0 ? rim_top : rim_bottom;
    const VertexId c0 = find_vertex(m, *g, {lo.x, lo.y, z});
    auto strut = mev(m, m.outer_loop(face), c0, rim[0]);
    if (!strut) return strut.error();
    EdgeUseId u = m.first_use(strut->edge);
    if (m.use_end(u) != strut->vertex) u = m.radial_next(u);
    auto ring = kemr(m, u);
    if (!ring) return ring.error();
    inner[s][0] = strut->vertex;
    for (int i = 1; i < 4; ++i) {
      auto ev = mev(m, *ring, inner[s][i - 1], rim[i]);
      if (!ev) return ev.error();
      inner[s][i] = ev->vertex;
    }
    auto cap = mef(m, *ring, inner[s][0], inner[s][3]);
    if (!cap) return cap.error();
    square[s] = cap->face;
  }
  // The two caps become one face with a ring (a handle), then the walls.
  auto ring = kfmrh(m, square[0], square[1]);
  if (!ring) return ring.error();
  LoopId outer = m.outer_loop(square[0]);
  auto bridge = mekr(m, outer, inner[0][0], *ring, inner[1][0]);
  if (!bridge) return bridge.error();
  for (int i = 1; i < 4; ++i) {
    // Match each top rim corner with the bottom one below it.
    VertexId below;
    for (int k = 0; k < 4; ++k) {
      const Vec3 t = m.position(inner[0][i]), p = m.position(inner[1][k]);
      if (t.x == p.x && t.y == p.y) below = inner[1][k];
    }
    auto wall = mef(m, outer, inner[0][i], below);
    if (!wall) return wall.error();
    // Carry on along whichever of the two loops still holds the next rim corner.
    if (i < 3 && !ops::on_loop(m, outer, inner[0][i + 1])) outer = m.outer_loop(wall->face);
  }
  std::vector<FaceSide> sides;
  for (FaceId f : m.faces()) {
    if (m.group_of(f) == *g) sides.push_back({f, false});
  }
  auto c = make_volume(m, *g, sides);
  if (!c) return c.error();
  return g;
}

Result<GroupId> euler_nonmanifold_example(Model& m, std::string name) {
  const GroupId g = make_group(m, std::move(name));
  if (Status s = euler_box_into(m, g, {0, 0, 0}, {1, 1, 1}, true); !s) return s.error();
  if (Status s = euler_box_into(m, g, {1, 1, 0}, {2, 2, 1}, true); !s) return s.error();
  // Join the coincident corners, then the coincident edges: one edge, four faces.
  VertexId keep[2];
  for (int i = 0; i < 2; ++i) {
    const Vec3 p{1, 1, double(i)};
    VertexId a, b;
    for (VertexId v : m.vertices()) {
      if (m.group_of(v) == g && m.position(v) == p) (a.is_valid() ? b : a) = v;
    }
    if (Status s = merge_vertices(m, a, b); !s) return s.error();
    keep[i] = a;
  }
  EdgeId first, second;
  for (EdgeEnd end = m.first_end(keep[0]), start = end;;) {
    if (m.vertex_of(end.edge, 1 - end.end) == keep[1])
      (first.is_valid() ? second : first) = end.edge;
    end = m.next_end_around(end);
    if (end == start) break;
  }
  if (Status s = merge_edges(m, first, second); !s) return s.error();
  auto tip = make_vertex(m, g, {2, 2, 2});
  if (!tip) return tip.error();
  if (auto w = make_wire_edge(m, find_vertex(m, g, {1, 1, 1}), *tip); !w) return w.error();
  if (auto p = make_vertex(m, g, {3, 0, 0}); !p) return p.error();
  return g;
}

}  // namespace cellforge::inline topo
