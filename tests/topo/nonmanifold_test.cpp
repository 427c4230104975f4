// Non-manifold operators: each applied, validated and undone by its inverse, and
// each refusal checked.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "cellforge/topo/operators.h"
#include "cellforge/topo/queries.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

TEST(NonManifold, IsolatedVertexAndWireEdge) {
  Model m = build(unit_cube());
  const GroupId g = *m.groups().begin();
  const std::string before = canonical_dump(m);
  auto p = make_vertex(m, g, {3, 0, 0});
  ASSERT_OK(p);
  EXPECT_VALID(m);
  auto w = make_wire_edge(m, vertex_at(m, {1, 0, 0}), *p);
  ASSERT_OK(w);
  EXPECT_VALID(m);
  EXPECT_EQ(query<EdgeId>(m, vertex_at(m, {1, 0, 0})).size(), 4u);
  EXPECT_FALSE(kill_vertex(m, *p).ok());  // still has the wire
  ASSERT_OK(kill_wire_edge(m, *w));
  ASSERT_OK(kill_vertex(m, *p));
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), before);
  const auto refused = kill_wire_edge(m, edge_at(m, {0, 0, 0}, {1, 0, 0}));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("has 2 uses (a wire edge has none)"), std::string::npos);
}

// Shells joined through a wire see one void region where the wire reaches them (the
// validator once counted each shell's outside as a cavity; found by the OBJ fuzzer).
TEST(NonManifold, ShellsJoinedByAWireEncloseOnlyTheirCavities) {
  MeshInput sheets;
  add_face(sheets, {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  add_face(sheets, {{{5, 5, 5}, {6, 5, 5}, {5, 6, 5}}});
  sheets.wires.push_back({add_point(sheets, {1, 0, 0}), add_point(sheets, {5, 5, 5})});
  const Model two = build(sheets);
  EXPECT_VALID(two);
  EulerFigures f = euler_figures(two);
  EXPECT_EQ(f.components, 1);
  EXPECT_EQ(f.cavities, 0);
  EXPECT_EQ(f.lhs(), f.rhs());

  // A bare box inside a bare box, a wire from the inner one to the outer one's inner
  // wall: three regions of space (outside, between, inside the inner box), 2 cavities.
  MeshInput nested;
  add_box(nested, {0, 0, 0}, {4, 4, 4}, -1);
  add_box(nested, {1, 1, 1}, {2, 2, 2}, -1);
  nested.wires.push_back({add_point(nested, {2, 2, 2}), add_point(nested, {4, 4, 4})});
  const Model boxes = build(nested);
  EXPECT_VALID(boxes);
  f = euler_figures(boxes);
  EXPECT_EQ(f.components, 1);
  EXPECT_EQ(f.cavities, 2);
  EXPECT_EQ(f.lhs(), f.rhs());
}

TEST(NonManifold, FaceOnExistingEdgesMakesTheEdgeNonManifold) {
  Model m = build(unit_cube());
  const GroupId g = *m.groups().begin();
  const std::string before = canonical_dump(m);
  auto a = make_vertex(m, g, {1, -1, 2});
  auto b = make_vertex(m, g, {0, -1, 2});
  const std::string with_points = canonical_dump(m);
  auto fin = make_face(m, {{{vertex_at(m, {0, 0, 1}), vertex_at(m, {1, 0, 1}), *a, *b}}});
  ASSERT_OK(fin);
  EXPECT_VALID(m);
  EXPECT_EQ(m.use_count(edge_at(m, {0, 0, 1}, {1, 0, 1})), 3u);
  // The same model as the bulk builder makes from the fixture.
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(cube_with_dangling_face())));
  ASSERT_OK(kill_face(m, *fin, {.kill_bare_edges = true}));
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), with_points);
  ASSERT_OK(kill_vertex(m, *a));
  ASSERT_OK(kill_vertex(m, *b));
  EXPECT_EQ(canonical_dump(m), before);
  // A face of a solid cannot be killed while it bounds the volume.
  const auto refused = kill_face(m, face_at(m, {0.5, 0.5, 1}));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("bounds a volume"), std::string::npos);
}

TEST(NonManifold, BookFromThreeFaces) {
  Model m;
  const GroupId g = make_group(m);
  std::vector<VertexId> v;
  MeshInput in = book();
  for (Vec3 p : in.positions) v.push_back(*make_vertex(m, g, p));
  for (const MeshFace& f : in.faces) {
    std::vector<VertexId> loop;
    for (std::uint32_t i : f.loops[0]) loop.push_back(v[i]);
    ASSERT_OK(make_face(m, {{loop}}));
    EXPECT_VALID(m);
  }
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(book())));
}

TEST(NonManifold, GlueAndUnglueFaces) {
  // Two cubes stacked, each with its own copy of the middle square on shared
  // edges; glue makes the one shared face of the fixture.
  MeshInput in;
  add_box(in, {0, 0, 0}, {1, 1, 1}, 0);
  add_box(in, {0, 0, 1}, {1, 1, 2}, 1);
  Model m = build(in);
  EXPECT_VALID(m);
  const std::string apart = canonical_dump(m);
  FaceId lower_top, upper_bottom;
  for (FaceId f : m.faces()) {
    if (centroid_of(m, f) == Vec3{0.5, 0.5, 1}) {
      (m.face_normal(f).z > 0 ? lower_top : upper_bottom) = f;
    }
  }
  ASSERT_OK(glue_faces(m, lower_top, upper_bottom));
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_faces(), 11u);
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(two_cubes_sharing_face())));
  auto g = unglue_face(m, lower_top);
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), apart);
  // Refusals.
  const auto same = glue_faces(m, lower_top, lower_top);
  EXPECT_NE(same.error().message.find("both faces are"), std::string::npos);
  const auto not_matching = glue_faces(m, lower_top, face_at(m, {0.5, 0.5, 2}));
  ASSERT_FALSE(not_matching.ok());
  EXPECT_NE(not_matching.error().message.find("do not run over edge"), std::string::npos);
  const auto one_sided = unglue_face(m, lower_top);
  EXPECT_NE(one_sided.error().message.find("does not have volumes on both sides"),
            std::string::npos);
}

TEST(NonManifold, SplitAndMergeEdgeAndVertex) {
  Model m = build(two_cubes_sharing_edge());
  const std::string before = canonical_dump(m);
  const EdgeId e = edge_at(m, {1, 1, 0}, {1, 1, 1});
  std::vector<EdgeUseId> b_uses;
  for (EdgeUseId u = m.first_use(e), first = u;;) {
    if (centroid_of(m, m.face_of(u)).x > 1 || centroid_of(m, m.face_of(u)).y > 1) {
      b_uses.push_back(u);
    }
    u = m.radial_next(u);
    if (u == first) break;
  }
  ASSERT_EQ(b_uses.size(), 2u);
  auto e2 = split_edge(m, e, b_uses);
  ASSERT_OK(e2);
  EXPECT_VALID(m);
  EXPECT_EQ(m.use_count(e), 2u);
  EXPECT_EQ(m.use_count(*e2), 2u);
  // Now split both end vertices: B's edges move to new vertices; the cubes part.
  std::vector<VertexId> made;
  for (Vec3 p : {Vec3{1, 1, 0}, Vec3{1, 1, 1}}) {
    const VertexId v = vertex_at(m, p);
    std::vector<EdgeEnd> moving;
    for (EdgeEnd end = m.first_end(v), first = end;;) {
      const EdgeId x = end.edge;
      const Vec3 o = m.position(m.vertex_of(x, 1 - end.end));
      if (x == *e2 || o.x > 1 || o.y > 1) moving.push_back(end);
      end = m.next_end_around(end);
      if (end == first) break;
    }
    // Moving only part of B's edges would cut B's loops at the vertex.
    std::vector<EdgeEnd> half(moving.begin(), moving.begin() + 1);
    const auto refused = split_vertex(m, v, half);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().message.find("across the split"), std::string::npos);
    auto w = split_vertex(m, v, moving);
    ASSERT_OK(w);
    made.push_back(*w);
    EXPECT_VALID(m);
  }
  EXPECT_EQ(euler_figures(m).components, 2);
  EXPECT_EQ(m.num_vertices(), 16u);
  // And back.
  for (std::size_t i = 0; i < made.size(); ++i) {
    ASSERT_OK(merge_vertices(m, vertex_at(m, i == 0 ? Vec3{1, 1, 0} : Vec3{1, 1, 1}), made[i]));
    EXPECT_VALID(m);
  }
  ASSERT_OK(merge_edges(m, e, *e2));
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), before);
  const auto far = merge_edges(m, e, edge_at(m, {0, 0, 0}, {1, 0, 0}));
  EXPECT_NE(far.error().message.find("do not join the same vertices"), std::string::npos);
  const auto apart = merge_vertices(m, vertex_at(m, {0, 0, 0}), vertex_at(m, {2, 2, 1}));
  EXPECT_NE(apart.error().message.find("at different positions"), std::string::npos);
}

TEST(NonManifold, MakeAndKillVolume) {
  MeshInput in = unit_cube();
  for (MeshFace& f : in.faces) f.back = -1;
  in.volumes = 0;
  Model m = build(in);
  const GroupId g = *m.groups().begin();
  EXPECT_VALID(m);
  std::vector<FaceSide> sides;
  for (FaceId f : m.faces()) sides.push_back({f, false});
  // Missing one face: the sides do not close.
  std::vector<FaceSide> open(sides.begin(), sides.end() - 1);
  const auto refused = make_volume(m, g, open);
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("do not close at edge"), std::string::npos);
  // The fronts run the wrong way round for an outward... they close too (the
  // inside-out solid), but the backs are the solid.
  auto c = make_volume(m, g, sides);
  ASSERT_OK(c);
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(unit_cube())));
  const auto twice = make_volume(m, g, sides);
  EXPECT_NE(twice.error().message.find("already bounds"), std::string::npos);
  ASSERT_OK(kill_volume(m, *c));
  EXPECT_VALID(m);
  EXPECT_EQ(canonical_dump(m), canonical_dump(build(in)));
  EXPECT_EQ(sides_of(m, *c).size(), 0u);
}

}  // namespace
}  // namespace cellforge

namespace cellforge {
namespace {

// Vertices keep their group in runs of ids (model.h): made, killed and made
// again in random groups, every live vertex still reports the group it was made
// in, and a model built group by group needs one run per group.
TEST(NonManifold, VertexGroupsSurviveSlotReuse) {
  Model m;
  const GroupId groups[3] = {make_group(m, "a"), make_group(m, "b"), make_group(m, "c")};
  std::map<VertexId, GroupId> want;
  std::mt19937 rng(11);
  for (int step = 0; step < 3000; ++step) {
    if (!want.empty() && rng() % 3 == 0) {
      auto it = want.begin();
      std::advance(it, static_cast<long>(rng() % want.size()));
      ASSERT_OK(kill_vertex(m, it->first));
      want.erase(it);
    } else {
      const GroupId g = groups[rng() % 3];
      auto v = make_vertex(m, g, {double(step), 0, 0});
      ASSERT_OK(v);
      want[*v] = g;
    }
    if (step % 100 == 0) {
      for (const auto& [v, g] : want) ASSERT_EQ(m.group_of(v), g) << v << " at step " << step;
    }
  }
  for (const auto& [v, g] : want) ASSERT_EQ(m.group_of(v), g) << v;
  EXPECT_VALID(m);

  Model blocks;
  for (int k = 0; k < 3; ++k) {
    const GroupId g = make_group(blocks);
    for (int i = 0; i < 100; ++i) ASSERT_OK(make_vertex(blocks, g, {double(i), double(k), 0}));
  }
  // 300 vertices of 4 B, three runs of 8 B, three groups of 4 B and their counts
  // in the group index (16 B each).
  EXPECT_EQ(blocks.topology_bytes(), 300u * 4 + 3 * 8 + 3 * 4 + 3 * 16);
}

}  // namespace
}  // namespace cellforge
