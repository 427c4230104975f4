// The 12 Euler operators: a cube and a cube with a through hole built step by step
// (validated after each step), every operator followed by its inverse giving back
// the model it started from, and every precondition refused with its message.
#include <gtest/gtest.h>

#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/queries.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

// The cube [0,1]^3 from Euler operators only (examples.cpp): mvsf, 3 mev, mef for
// the bottom, 4 mev for the verticals, 4 mef for the sides and the top.
struct EulerCube {
  Model m;
  GroupId g = make_group(m);
  EulerCube() { EXPECT_TRUE(euler_box_into(m, g, {0, 0, 0}, {1, 1, 1}, false).ok()); }
};

TEST(Euler, CubeFromOperators) {
  EulerCube c;
  EXPECT_EQ(c.m.num_vertices(), 8u);
  EXPECT_EQ(c.m.num_edges(), 12u);
  EXPECT_EQ(c.m.num_faces(), 6u);
  EXPECT_VALID(c.m);
  for (FaceId f : c.m.faces()) EXPECT_EQ(c.m.loop_length(c.m.outer_loop(f)), 4u);
  for (VertexId v : c.m.vertices()) EXPECT_EQ(c.m.degree(v), 3u);
  // With its volume, the cube the operators built is the one the bulk builder builds.
  std::vector<FaceSide> sides;
  for (FaceId f : c.m.faces()) sides.push_back({f, false});
  ASSERT_OK(make_volume(c.m, c.g, sides));
  EXPECT_VALID(c.m);
  EXPECT_EQ(canonical_dump(c.m), canonical_dump(build(unit_cube())));
}

TEST(Euler, CubeWithThroughHole) {
  // Start from the cube, build a smaller square inside the top and bottom with
  // mev + kemr, connect them, then kfmrh.
  EulerCube c;
  Model& m = c.m;
  const FaceId faces[2] = {face_at(m, {0.5, 0.5, 1}), face_at(m, {0.5, 0.5, 0})};
  std::vector<VertexId> inner[2];
  FaceId square[2];
  for (int s = 0; s < 2; ++s) {
    const FaceId f = faces[s];
    const double z = s == 0 ? 1 : 0;
    const LoopId outer = m.outer_loop(f);
    // A strut from a corner to (0.25,0.25,z), then kemr turns its end into a ring.
    auto ev = mev(m, outer, vertex_at(m, {0, 0, z}), {0.25, 0.25, z});
    ASSERT_OK(ev);
    EXPECT_VALID(m);
    EdgeUseId u = m.first_use(ev->edge);
    if (m.use_end(u) != ev->vertex) u = m.radial_next(u);
    auto ring = kemr(m, u);
    ASSERT_OK(ring);
    EXPECT_VALID(m);
    EXPECT_TRUE(m.is_point_loop(*ring));
    EXPECT_EQ(m.inner_loop_count(f), 1u);
    // Grow the point ring into a square.
    inner[s].push_back(ev->vertex);
    const Vec3 sq[3] = {{0.75, 0.25, z}, {0.75, 0.75, z}, {0.25, 0.75, z}};
    for (Vec3 p : sq) {
      auto e2 = mev(m, *ring, inner[s].back(), p);
      ASSERT_OK(e2);
      inner[s].push_back(e2->vertex);
    }
    auto closed = mef(m, *ring, inner[s].back(), inner[s].front());
    ASSERT_OK(closed);
    square[s] = closed->face;
    EXPECT_VALID(m);
  }
  // kfmrh: the bottom square's loop becomes a ring of the top square: a handle.
  auto ring = kfmrh(m, square[0], square[1]);
  ASSERT_OK(ring);
  EXPECT_VALID(m);
  const EulerFigures fig = euler_figures(m);
  EXPECT_EQ(fig.v - fig.e + fig.f, 2 * (1 - 1) + fig.r);  // h = 1
  auto back = mfkrh(m, *ring);
  ASSERT_OK(back);
  EXPECT_VALID(m);
}

// ---- each operator followed by its inverse gives back the same model

TEST(Euler, InversesRestoreTheModel) {
  EulerCube c;
  Model& m = c.m;
  const std::string before = canonical_dump(m);
  auto same = [&](const char* what) {
    EXPECT_VALID(m);
    EXPECT_EQ(canonical_dump(m), before) << what;
  };
  const FaceId top = face_at(m, {0.5, 0.5, 1});
  const LoopId lt = m.outer_loop(top);
  const VertexId a = vertex_at(m, {0, 0, 1}), b = vertex_at(m, {1, 1, 1});
  {  // mev / kev
    auto r = mev(m, lt, a, {0.5, 0.5, 1});
    ASSERT_OK(r);
    EXPECT_VALID(m);
    ASSERT_OK(kev(m, r->edge, r->vertex));
    same("mev/kev");
  }
  {  // mef / kef
    auto r = mef(m, lt, a, b);
    ASSERT_OK(r);
    EXPECT_VALID(m);
    EXPECT_EQ(m.num_faces(), 7u);
    ASSERT_OK(kef(m, r->edge, r->face));
    same("mef/kef");
  }
  {  // semv / jekv
    const EdgeId e = edge_at(m, {0, 0, 1}, {1, 0, 1});
    auto r = semv(m, e, {0.5, 0, 1});
    ASSERT_OK(r);
    EXPECT_VALID(m);
    EXPECT_EQ(m.loop_length(lt), 5u);
    ASSERT_OK(jekv(m, r->edge, r->vertex));
    same("semv/jekv");
  }
  {  // mev + kemr / mekr + kev
    auto r = mev(m, lt, a, {0.5, 0.5, 1});
    ASSERT_OK(r);
    const std::string strut = canonical_dump(m);
    EdgeUseId u = m.first_use(r->edge);
    if (m.use_end(u) != r->vertex) u = m.radial_next(u);
    auto ring = kemr(m, u);
    ASSERT_OK(ring);
    EXPECT_VALID(m);
    auto e = mekr(m, lt, a, *ring, r->vertex);
    ASSERT_OK(e);
    EXPECT_VALID(m);
    EXPECT_EQ(canonical_dump(m), strut) << "kemr/mekr";
    ASSERT_OK(kev(m, *e, r->vertex));
    same("kemr/mekr");
  }
  {  // mvsf / kvsf
    auto r = mvsf(m, c.g, {5, 5, 5});
    ASSERT_OK(r);
    EXPECT_VALID(m);
    ASSERT_OK(kvsf(m, r->vertex, r->face));
    same("mvsf/kvsf");
  }
}

TEST(Euler, CubeWithThroughHoleMatchesTheBulkBuilder) {
  Model m;
  auto g = euler_box_with_hole(m, {0, 0, 0}, {3, 3, 3}, 1, 2);
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_vertices(), 16u);
  EXPECT_EQ(m.num_edges(), 24u);
  EXPECT_EQ(m.num_faces(), 10u);
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(cube_with_through_hole())));
}

TEST(Euler, NonManifoldExampleMatchesTheBulkBuilder) {
  Model m;
  ASSERT_OK(euler_nonmanifold_example(m));
  EXPECT_VALID(m);
  MeshInput in = two_cubes_sharing_edge();
  in.wires.push_back({add_point(in, {1, 1, 1}), add_point(in, {2, 2, 2})});
  add_point(in, {3, 0, 0});
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(in)));
  EXPECT_EQ(m.use_count(edge_at(m, {1, 1, 0}, {1, 1, 1})), 4u);
}

TEST(Euler, KfmrhAndMfkrhAreInverse) {
  // Two disjoint shells in one group: kfmrh joins them (a handle), mfkrh undoes it.
  Model m;
  const GroupId g = make_group(m);
  auto s1 = mvsf(m, g, {0, 0, 0});
  auto s2 = mvsf(m, g, {1, 0, 0});
  ASSERT_OK(s1);
  ASSERT_OK(s2);
  const std::string before = canonical_dump(m);
  auto ring = kfmrh(m, s1->face, s2->face);
  ASSERT_OK(ring);
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_faces(), 1u);
  EXPECT_EQ(m.inner_loop_count(s1->face), 1u);
  ASSERT_OK(mfkrh(m, *ring));
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), before);
}

// ---- every precondition refused: error text checked, model unchanged

template <class Fn>
void expect_refused(Model& m, Fn op, const std::string& text) {
  const std::string before = raw_dump(m);
  const auto r = op();
  ASSERT_FALSE(r.ok()) << "expected refusal: " << text;
  EXPECT_NE(r.error().message.find(text), std::string::npos)
      << "message: " << r.error().message << "\nexpected to contain: " << text;
  EXPECT_EQ(raw_dump(m), before) << "a refused operation changed the model";
}

TEST(Euler, PreconditionsAreRefused) {
  EulerCube c;
  Model& m = c.m;
  const FaceId top = face_at(m, {0.5, 0.5, 1}), side = face_at(m, {0.5, 0, 0.5});
  const LoopId lt = m.outer_loop(top);
  const VertexId a = vertex_at(m, {0, 0, 1}), far = vertex_at(m, {1, 1, 0});
  const EdgeId e = edge_at(m, {0, 0, 1}, {1, 0, 1});
  expect_refused(
      m, [&] { return mvsf(m, GroupId(7), {}); }, "mvsf: group g7 is not a live");
  expect_refused(
      m, [&] { return kvsf(m, a, top); }, "kvsf: face");
  expect_refused(
      m, [&] { return mev(m, lt, far, {}); }, "mev: vertex");
  expect_refused(
      m, [&] { return mev(m, LoopId(999), a, {}); }, "mev: loop l999 is not a live");
  expect_refused(
      m, [&] { return kev(m, e, a); }, "kev: vertex");
  expect_refused(
      m, [&] { return kev(m, e, far); }, "is not an end of edge");
  expect_refused(
      m, [&] { return mef(m, lt, a, a); }, "mef: the two vertices are both");
  expect_refused(
      m, [&] { return mef(m, lt, a, far); }, "is not on loop");
  expect_refused(
      m,
      [&] {
        return kef(m, e, face_at(m, {0.5, 1, 0.5}));
      },
      "is not a face of edge");
  expect_refused(
      m, [&] { return kemr(m, m.first_use(e)); }, "are in different loops");
  expect_refused(
      m, [&] { return kemr(m, EdgeUseId(12345)); }, "kemr: edge use u12345");
  expect_refused(
      m, [&] { return mekr(m, lt, a, lt, far); }, "mekr: both loops are");
  expect_refused(
      m, [&] { return mekr(m, lt, a, m.outer_loop(side), far); }, "belong to different faces");
  expect_refused(
      m, [&] { return kfmrh(m, top, top); }, "kfmrh: both faces are");
  expect_refused(
      m, [&] { return mfkrh(m, lt); }, "is the outer loop of face");
  expect_refused(
      m, [&] { return semv(m, EdgeId(555), {}); }, "semv: edge e555");
  expect_refused(
      m, [&] { return jekv(m, e, a); }, "has 3 edges (must have 2)");
  expect_refused(
      m, [&] { return jekv(m, e, far); }, "is not an end of edge");
  {  // kef on faces bounding different volumes
    Model two = build(two_cubes_sharing_face());
    const EdgeId shared_edge = edge_at(two, {0, 0, 1}, {1, 0, 1});
    expect_refused(
        two,
        [&] {
          return kef(two, shared_edge, face_at(two, {0.5, 0.5, 1}));
        },
        "has 3 uses (must have 2)");
  }
  {  // kef across faces of different volumes, or run the same way
    MeshInput in = unit_cube();
    in.faces[0].back = -1;
    Model open = build(in);
    const EdgeId rim = edge_at(open, {0, 0, 0}, {1, 0, 0});
    expect_refused(
        open,
        [&] {
          return kef(open, rim, face_at(open, {0.5, 0.5, 0}));
        },
        "bound different volumes");
    in = unit_cube();
    std::reverse(in.faces[0].loops[0].begin(), in.faces[0].loops[0].end());
    Model flipped = build(in);
    const EdgeId rim2 = edge_at(flipped, {0, 0, 0}, {1, 0, 0});
    expect_refused(
        flipped,
        [&] {
          return kef(flipped, rim2, face_at(flipped, {0.5, 0.5, 0}));
        },
        "in the same direction");
  }
  {  // jekv with mismatched uses; kev on a non-strut; mekr onto an outer loop
    Model w;
    const GroupId g = make_group(w);
    auto p = make_vertex(w, g, {0, 0, 0});
    auto q = make_vertex(w, g, {1, 0, 0});
    auto r = make_vertex(w, g, {2, 0, 0});
    auto e1 = make_wire_edge(w, *p, *q);
    auto e2 = make_wire_edge(w, *q, *r);
    ASSERT_OK(e1);
    ASSERT_OK(e2);
    expect_refused(
        w, [&] { return make_wire_edge(w, *p, *p); }, "both ends are");
    EXPECT_TRUE(jekv(w, *e2, *q).ok());  // wires join
    EXPECT_VALID(w);
    expect_refused(
        w, [&] { return jekv(w, *e1, *p); }, "has 1 edges (must have 2)");
  }
  {  // kev that would leave a point loop at a vertex with other edges
    Model s;
    const GroupId g = make_group(s);
    auto vf = mvsf(s, g, {0, 0, 0});
    const LoopId l = s.outer_loop(vf->face);
    auto e1 = mev(s, l, vf->vertex, {1, 0, 0});
    ASSERT_OK(e1);
    auto wire_end = make_vertex(s, g, {0, 5, 0});
    ASSERT_OK(make_wire_edge(s, vf->vertex, *wire_end));
    expect_refused(
        s, [&] { return kev(s, e1->edge, e1->vertex); }, "would become a point loop");
    // a vertex that carries a point loop takes no wire edge
    auto other = mvsf(s, g, {9, 9, 9});
    expect_refused(
        s, [&] { return make_wire_edge(s, other->vertex, *wire_end); }, "carries point loop");
  }
}

}  // namespace
}  // namespace cellforge
