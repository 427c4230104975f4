// Use ids are slots of their edges (model.h): slot 2e and 2e + 1 for an edge's
// first two uses, overflow slots in spare pairs for the rest. These tests pin
// down what that promises: edge_of without a load, the first use of an edge
// whose slot 2e is empty, overflow slots reused, and uses that move to another
// edge taking its slots while their loops keep them in place.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "cellforge/topo/operators.h"
#include "cellforge/topo/queries.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

std::multiset<std::uint32_t> faces_at(const Model& m, EdgeId e) {
  std::multiset<std::uint32_t> out;
  EdgeUseId u = m.first_use(e);
  do {
    out.insert(m.face_of(u).value);
    u = m.radial_next(u);
  } while (u != m.first_use(e));
  return out;
}

TEST(UseSlots, AClosedManifoldFillsBothSlotsOfEveryEdge) {
  const Model m = build(unit_cube());
  EXPECT_EQ(m.use_slots(), 2 * m.edge_slots());
  EXPECT_EQ(m.num_edge_uses(), m.use_slots());
  EXPECT_EQ(m.spare_pairs(), 0u);
  for (EdgeUseId u : m.edge_uses()) {
    EXPECT_FALSE(m.in_overflow_slot(u));
    EXPECT_EQ(m.edge_of(u).value, u.value / 2);
    // In place: a forward use in slot 2e, a reversed one in 2e + 1, so its start
    // vertex is the end record of its own index.
    EXPECT_TRUE(m.is_in_place(u));
    EXPECT_EQ(m.use_start(u), m.vertex_of(m.edge_of(u), static_cast<int>(u.value & 1)));
  }
  for (FaceId f : m.faces()) EXPECT_FALSE(m.may_hold_unplaced_uses(f));
  for (EdgeId e : m.edges()) {
    EXPECT_EQ(m.first_use(e).value, 2 * e.value);
    EXPECT_EQ(m.radial_next(m.first_use(e)).value, 2 * e.value + 1);
  }
}

// A sheet of two quads on one edge, with either quad killed: every edge left
// with one use holds it in place and leaves the other slot empty; where that
// use is reversed, slot 2e is the empty one and names it.
TEST(UseSlots, ABoundaryEdgeLeavesOneSlotEmpty) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}}});
  add_face(in, {{{1, 0, 0}, {2, 0, 0}, {2, 1, 0}, {1, 1, 0}}});
  std::size_t reversed_alone = 0;
  for (int killed = 0; killed < 2; ++killed) {
    Model m = build(in);
    FaceId f;
    for (FaceId g : m.faces()) {
      if ((centroid_of(m, g).x < 1) == (killed == 0)) f = g;
    }
    ASSERT_OK(kill_face(m, f, {.kill_bare_edges = true}));
    EXPECT_VALID(m);
    for (EdgeId e : m.edges()) {
      ASSERT_EQ(m.use_count(e), 1u);
      const EdgeUseId u = m.first_use(e);
      ASSERT_TRUE(m.is_live(u));
      EXPECT_TRUE(m.is_in_place(u));
      EXPECT_FALSE(m.is_live(EdgeUseId(u.value ^ 1u)));
      reversed_alone += m.is_reversed(u) ? 1 : 0;
    }
  }
  EXPECT_GT(reversed_alone, 0u);
}

// The book's three pages all run the spine the same way: one use takes its
// place, the next the other slot, the third an overflow slot, and the two faces
// that hold them are marked; the face walks agree with the accessors on all.
TEST(UseSlots, UsesNotInPlaceMarkTheirFaces) {
  const Model m = build(book());
  const EdgeId spine = edge_at(m, {0, 0, 0}, {0, 0, 1});
  std::size_t in_place = 0, marked = 0;
  EdgeUseId u = m.first_use(spine);
  do {
    in_place += m.is_in_place(u) ? 1 : 0;
    EXPECT_EQ(m.may_hold_unplaced_uses(m.face_of(u)), !m.is_in_place(u));
    u = m.radial_next(u);
  } while (u != m.first_use(spine));
  for (FaceId f : m.faces()) marked += m.may_hold_unplaced_uses(f) ? 1 : 0;
  EXPECT_EQ(in_place, 1u);
  EXPECT_EQ(marked, 2u);
  for (FaceId f : m.faces()) {
    std::vector<VertexId> walked;
    m.for_each_face_vertex(f, [&](VertexId v) { walked.push_back(v); });
    EXPECT_EQ(walked, m.loop_vertices(m.outer_loop(f)));
    std::vector<EdgeId> edges;
    m.for_each_face_use(f, [&](const Model::FaceUse& x) { edges.push_back(x.edge); });
    ASSERT_EQ(edges.size(), 4u);
    EdgeUseId w = m.loop_first(m.outer_loop(f));
    for (EdgeId e : edges) {
      EXPECT_EQ(e, m.edge_of(w));
      w = m.loop_next(w);
    }
  }
}

TEST(UseSlots, TheThirdUseOfAnEdgeTakesAnOverflowSlotThatNamesTheEdge) {
  const Model m = build(book());
  const EdgeId spine = edge_at(m, {0, 0, 0}, {0, 0, 1});
  ASSERT_EQ(m.use_count(spine), 3u);
  std::size_t overflow = 0;
  EdgeUseId u = m.first_use(spine);
  do {
    EXPECT_EQ(m.edge_of(u), spine);
    if (m.in_overflow_slot(u)) {
      ++overflow;
      EXPECT_TRUE(m.is_spare_pair(u.value / 2));
      EXPECT_FALSE(m.is_live(EdgeId(u.value / 2)));
    }
    u = m.radial_next(u);
  } while (u != m.first_use(spine));
  EXPECT_EQ(overflow, 1u);
  EXPECT_EQ(query<FaceId>(m, spine).size(), 3u);
  // The spare pair is not an edge: the edge iteration and counts skip it.
  EXPECT_EQ(m.num_edges(), 10u);
  std::size_t listed = 0;
  for (EdgeId e : m.edges()) listed += e.is_valid() ? 1 : 0;
  EXPECT_EQ(listed, 10u);
}

// Kills each page of the book in turn, so that every slot of the spine (2e,
// 2e + 1 and the overflow slot) is emptied once while the other two uses stay,
// and makes the page again: the spine's first use must always be one of its
// uses, and making the page again reuses the freed slot.
TEST(UseSlots, AnEdgeKeepsItsFirstUseWhenItsSlotEmpties) {
  const MeshInput in = book();
  for (std::size_t page = 0; page < in.faces.size(); ++page) {
    Model m = build(in);
    const std::string before = canonical_dump(m);
    const EdgeId spine = edge_at(m, {0, 0, 0}, {0, 0, 1});
    const std::uint32_t slots = m.edge_slots();
    FaceId f;
    std::vector<VertexId> loop;
    for (FaceId g : m.faces()) {
      if (f.is_valid()) break;
      std::vector<VertexId> vs = m.loop_vertices(m.outer_loop(g));
      std::vector<VertexId> want;
      for (std::uint32_t i : in.faces[page].loops[0]) want.push_back(vertex_at(m, in.positions[i]));
      if (std::is_permutation(vs.begin(), vs.end(), want.begin(), want.end())) {
        f = g;
        loop = want;
      }
    }
    ASSERT_TRUE(f.is_valid());
    ASSERT_OK(kill_face(m, f, {.kill_bare_edges = true}));
    EXPECT_VALID(m);
    ASSERT_EQ(m.use_count(spine), 2u);
    EXPECT_TRUE(m.is_live(m.first_use(spine)));
    EXPECT_EQ(m.edge_of(m.first_use(spine)), spine);
    EXPECT_EQ(query<FaceId>(m, spine).size(), 2u);
    ASSERT_OK(make_face(m, {{loop}}));
    EXPECT_VALID(m);
    EXPECT_EQ(m.edge_slots(), slots) << "page " << page << ": a freed slot was not reused";
    EXPECT_EQ(canonical_dump(m), before);
  }
}

// split_edge moves uses to a new edge: they take its slots (new ids), their
// loops and faces keep them in place, and a hundred split/merge round trips
// reuse the same slots instead of growing the model.
TEST(UseSlots, MovedUsesTakeSlotsOfTheirNewEdgeAndAreReused) {
  Model m = build(two_cubes_sharing_edge());
  const std::string before = canonical_dump(m);
  const EdgeId e = edge_at(m, {1, 1, 0}, {1, 1, 1});
  ASSERT_EQ(m.use_count(e), 4u);
  const std::uint32_t slots_before = m.edge_slots();
  std::uint32_t slots_after_first = 0;
  for (int round = 0; round < 100; ++round) {
    std::vector<EdgeUseId> moving;
    EdgeUseId u = m.first_use(e);
    do {
      const Vec3 c = centroid_of(m, m.face_of(u));
      if (c.x > 1 || c.y > 1) moving.push_back(u);
      u = m.radial_next(u);
    } while (u != m.first_use(e));
    ASSERT_EQ(moving.size(), 2u);
    std::multiset<std::uint32_t> moved_faces;
    for (EdgeUseId x : moving) moved_faces.insert(m.face_of(x).value);
    auto e2 = split_edge(m, e, moving);
    ASSERT_OK(e2);
    ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
    EXPECT_EQ(faces_at(m, *e2), moved_faces);
    EdgeUseId w = m.first_use(*e2);
    do {
      EXPECT_EQ(w.value / 2, e2->value);  // the new edge's own slots
      w = m.radial_next(w);
    } while (w != m.first_use(*e2));
    ASSERT_OK(merge_edges(m, e, *e2));
    ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
    ASSERT_EQ(canonical_dump(m), before);
    if (round == 0) slots_after_first = m.edge_slots();
    EXPECT_EQ(m.edge_slots(), slots_after_first) << "round " << round;
  }
  EXPECT_LE(slots_after_first, slots_before + 2);
}

// A use that starts its loop moves with the loop's start: the face record
// names its new id. A fourth page on the book's spine, its loop starting with
// the spine (b -> a), is split off the spine and merged back.
TEST(UseSlots, AMovedUseThatStartsItsLoopStaysItsStart) {
  Model m = build(book());
  const std::string before = canonical_dump(m);
  const VertexId a = vertex_at(m, {0, 0, 0}), b = vertex_at(m, {0, 0, 1});
  const GroupId g = m.group_of(a);
  const VertexId c = *make_vertex(m, g, {-1, 1, 0}), d = *make_vertex(m, g, {-1, 1, 1});
  const std::vector<VertexId> loop{b, a, c, d};
  auto f = make_face(m, {{loop}});
  ASSERT_OK(f);
  ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
  const EdgeId spine = edge_at(m, {0, 0, 0}, {0, 0, 1});
  const EdgeUseId first = m.loop_first(m.outer_loop(*f));
  ASSERT_EQ(m.edge_of(first), spine);
  EXPECT_TRUE(m.in_overflow_slot(first));  // the spine's fourth use
  auto e2 = split_edge(m, spine, {first});
  ASSERT_OK(e2);
  ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
  const EdgeUseId moved = m.loop_first(m.outer_loop(*f));
  EXPECT_EQ(m.edge_of(moved), *e2);
  EXPECT_EQ(moved.value, 2 * e2->value);
  EXPECT_EQ(m.loop_vertices(m.outer_loop(*f)), loop);
  EXPECT_EQ(m.use_count(spine), 3u);
  ASSERT_OK(merge_edges(m, spine, *e2));
  ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
  EXPECT_EQ(m.loop_vertices(m.outer_loop(*f)), loop);
  EXPECT_EQ(m.edge_of(m.loop_first(m.outer_loop(*f))), spine);
  ASSERT_OK(kill_face(m, *f, {.kill_bare_edges = true}));
  ASSERT_OK(kill_vertex(m, c));
  ASSERT_OK(kill_vertex(m, d));
  ASSERT_TRUE(validate(m).empty()) << to_string(validate(m));
  EXPECT_EQ(canonical_dump(m), before);
}

}  // namespace
}  // namespace cellforge
