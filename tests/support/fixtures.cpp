#include "support/fixtures.h"

#include <gtest/gtest.h>

#include <tuple>

#include "cellforge/topo/queries.h"

namespace cellforge {
bool operator<(const Vec3& a, const Vec3& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}
}  // namespace cellforge

namespace cellforge::testing {

std::vector<Vec3> box_corners(Vec3 lo, Vec3 hi) {
  std::vector<Vec3> c;
  for (int i = 0; i < 8; ++i) {
    c.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  }
  return c;
}

std::vector<std::vector<std::uint32_t>> box_faces() {
  return {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
}

std::uint32_t add_point(MeshInput& in, Vec3 p) {
  for (std::uint32_t i = 0; i < in.positions.size(); ++i) {
    if (in.positions[i] == p) return i;
  }
  in.positions.push_back(p);
  return static_cast<std::uint32_t>(in.positions.size() - 1);
}

std::size_t add_face(MeshInput& in, const std::vector<std::vector<Vec3>>& loops, int front,
                     int back) {
  MeshFace f;
  for (const auto& loop : loops) {
    auto& idx = f.loops.emplace_back();
    for (Vec3 p : loop) idx.push_back(add_point(in, p));
  }
  f.front = front;
  f.back = back;
  in.volumes = std::max({in.volumes, front + 1, back + 1});
  in.faces.push_back(std::move(f));
  return in.faces.size() - 1;
}

std::vector<std::size_t> add_box(MeshInput& in, Vec3 lo, Vec3 hi, int volume) {
  const std::vector<Vec3> c = box_corners(lo, hi);
  std::vector<std::size_t> out;
  for (const auto& f : box_faces()) {
    std::vector<Vec3> loop;
    for (std::uint32_t i : f) loop.push_back(c[i]);
    out.push_back(add_face(in, {loop}, -1, volume));
  }
  return out;
}

MeshInput unit_cube() {
  MeshInput in;
  add_box(in, {0, 0, 0}, {1, 1, 1}, 0);
  return in;
}

MeshInput cube_with_through_hole() {
  MeshInput in;
  auto sq = [](double a, double b, double z, bool ccw) {
    std::vector<Vec3> s = {{a, a, z}, {b, a, z}, {b, b, z}, {a, b, z}};
    if (!ccw) std::reverse(s.begin(), s.end());
    return s;
  };
  // Top (normal +z): outer ccw, hole cw; bottom (normal -z): the reverse.
  add_face(in, {sq(0, 3, 3, true), sq(1, 2, 3, false)}, -1, 0);
  add_face(in, {sq(0, 3, 0, false), sq(1, 2, 0, true)}, -1, 0);
  // Outer walls, outward.
  const std::vector<Vec3> c = box_corners({0, 0, 0}, {3, 3, 3});
  const auto faces = box_faces();
  for (int i = 2; i < 6; ++i) {
    std::vector<Vec3> loop;
    for (std::uint32_t k : faces[i]) loop.push_back(c[k]);
    add_face(in, {loop}, -1, 0);
  }
  // Hole walls, facing the hole's axis: the inner box's side faces reversed.
  const std::vector<Vec3> h = box_corners({1, 1, 0}, {2, 2, 3});
  for (int i = 2; i < 6; ++i) {
    std::vector<Vec3> loop;
    for (std::uint32_t k : faces[i]) loop.push_back(h[k]);
    std::reverse(loop.begin(), loop.end());
    add_face(in, {loop}, -1, 0);
  }
  return in;
}

MeshInput two_cubes_sharing_edge() {
  MeshInput in;
  add_box(in, {0, 0, 0}, {1, 1, 1}, 0);
  add_box(in, {1, 1, 0}, {2, 2, 1}, 1);
  return in;
}

MeshInput two_cubes_sharing_vertex() {
  MeshInput in;
  add_box(in, {0, 0, 0}, {1, 1, 1}, 0);
  add_box(in, {1, 1, 1}, {2, 2, 2}, 1);
  return in;
}

MeshInput cube_with_dangling_face() {
  MeshInput in = unit_cube();
  add_face(in, {{{0, 0, 1}, {1, 0, 1}, {1, -1, 2}, {0, -1, 2}}});
  return in;
}

MeshInput cube_with_wire_and_point() {
  MeshInput in = unit_cube();
  const std::uint32_t a = add_point(in, {1, 1, 1}), b = add_point(in, {2, 2, 2});
  in.wires.push_back({a, b});
  add_point(in, {5, 5, 5});
  return in;
}

MeshInput book() {
  MeshInput in;
  const Vec3 a{0, 0, 0}, b{0, 0, 1};
  for (Vec3 d : {Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{-1, -1, 0}}) {
    add_face(in, {{a, a + d, b + d, b}});
  }
  return in;
}

MeshInput two_cubes_sharing_face() {
  MeshInput in;
  const std::vector<Vec3> lo = box_corners({0, 0, 0}, {1, 1, 1});
  const std::vector<Vec3> hi = box_corners({0, 0, 1}, {1, 1, 2});
  const auto faces = box_faces();
  for (int i = 0; i < 6; ++i) {
    if (i == 1) continue;  // the lower cube's top is the shared face
    std::vector<Vec3> loop;
    for (std::uint32_t k : faces[i]) loop.push_back(lo[k]);
    add_face(in, {loop}, -1, 0);
  }
  {
    std::vector<Vec3> loop;
    for (std::uint32_t k : faces[1]) loop.push_back(lo[k]);
    add_face(in, {loop}, 1, 0);  // normal +z: cell 1 in front, cell 0 behind
  }
  for (int i = 1; i < 6; ++i) {
    std::vector<Vec3> loop;
    for (std::uint32_t k : faces[i]) loop.push_back(hi[k]);
    add_face(in, {loop}, -1, 1);
  }
  return in;
}

MeshInput square_sheet_with_hole() {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {3, 0, 0}, {3, 3, 0}, {0, 3, 0}},
                {{1, 1, 0}, {1, 2, 0}, {2, 2, 0}, {2, 1, 0}}});
  return in;
}

Model build(const MeshInput& in) {
  Model m;
  auto r = build_mesh(m, in);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
  return m;
}

VertexId vertex_at(const Model& m, Vec3 p) {
  for (VertexId v : m.vertices()) {
    if (m.position(v) == p) return v;
  }
  ADD_FAILURE() << "no vertex at " << p;
  return {};
}

EdgeId edge_at(const Model& m, Vec3 a, Vec3 b) {
  for (EdgeId e : m.edges()) {
    const Vec3 s = m.position(m.start_of(e)), t = m.position(m.end_of(e));
    if ((s == a && t == b) || (s == b && t == a)) return e;
  }
  ADD_FAILURE() << "no edge " << a << " - " << b;
  return {};
}

Vec3 centroid_of(const Model& m, FaceId f) {
  Vec3 c;
  const std::vector<Vec3> pts = m.loop_points(m.outer_loop(f));
  for (Vec3 p : pts) c = c + p;
  return c / static_cast<double>(pts.size());
}

FaceId face_at(const Model& m, Vec3 centroid) {
  for (FaceId f : m.faces()) {
    if (length(centroid_of(m, f) - centroid) < 1e-12) return f;
  }
  ADD_FAILURE() << "no face with centroid " << centroid;
  return {};
}

std::set<Vec3> positions(const Model& m, const std::vector<VertexId>& vs) {
  std::set<Vec3> out;
  for (VertexId v : vs) out.insert(m.position(v));
  return out;
}

std::set<std::pair<Vec3, Vec3>> edge_keys(const Model& m, const std::vector<EdgeId>& es) {
  std::set<std::pair<Vec3, Vec3>> out;
  for (EdgeId e : es) {
    Vec3 a = m.position(m.start_of(e)), b = m.position(m.end_of(e));
    if (b < a) std::swap(a, b);
    out.insert({a, b});
  }
  return out;
}

std::set<Vec3> face_keys(const Model& m, const std::vector<FaceId>& fs) {
  std::set<Vec3> out;
  for (FaceId f : fs) out.insert(centroid_of(m, f));
  return out;
}

}  // namespace cellforge::testing
