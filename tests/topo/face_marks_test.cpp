// The face marks (model.h): kRepeatFace says a face's loops may name an edge or a
// vertex twice, so that F->E and F->V answers of an unmarked face skip the
// dedupe. Every edit sets it on the faces it changes, and the end of the edit
// makes all three marks exact; the validator checks that outside an edit each
// mark is set exactly where it is needed.
#include <gtest/gtest.h>

#include <algorithm>

#include "cellforge/topo/operators.h"
#include "cellforge/topo/queries.h"
#include "cellforge/topo/snapshot.h"
#include "cellforge/topo/validate.h"
#include "support/checks.h"
#include "topo/model_editor.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

template <class T>
bool all_distinct(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) == v.end();
}

TEST(FaceMarks, FacesOfTheFixturesRepeatNothing) {
  for (const MeshInput& in : {unit_cube(), cube_with_through_hole(), two_cubes_sharing_edge(),
                              cube_with_dangling_face(), book()}) {
    const Model m = build(in);
    EXPECT_VALID(m);
    std::vector<VertexId> vs;
    std::vector<EdgeId> es;
    for (FaceId f : m.faces()) {
      EXPECT_FALSE(m.may_repeat_elements(f)) << f.str();
      vertices_of(m, f, vs);
      edges_of(m, f, es);
      EXPECT_TRUE(all_distinct(vs));
      EXPECT_EQ(vs.size(), es.size());  // one loop or loops apart: as many corners as sides
    }
  }
}

// A face whose outer loop passes through one vertex twice: A B C D B F, with
// the loop touching itself at B = (1,1,0). Split at B, the face repeats
// nothing; merged again, it repeats B.
TEST(FaceMarks, AFacePinchedAtAVertexIsMarkedWhileItIsPinched) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 2, 0}, {1, 1, 0}, {0, 2, 0}}});
  Model m = build(in);
  EXPECT_VALID(m);
  const FaceId f = *m.faces().begin();
  const VertexId b = vertex_at(m, {1, 1, 0});
  std::vector<VertexId> vs;
  std::vector<EdgeId> es;
  auto expect_answers = [&](std::size_t vertices) {
    vertices_of(m, f, vs);
    edges_of(m, f, es);
    EXPECT_EQ(vs.size(), vertices);
    EXPECT_TRUE(all_distinct(vs));
    EXPECT_EQ(es.size(), 6u);
    EXPECT_TRUE(all_distinct(es));
  };
  EXPECT_TRUE(m.may_repeat_elements(f));
  expect_answers(5);

  // The visit D -> B -> F moves to a new vertex w (the ends of edges DB and BF).
  const EdgeId db = edge_at(m, {2, 2, 0}, {1, 1, 0});
  const EdgeId bf = edge_at(m, {1, 1, 0}, {0, 2, 0});
  std::vector<EdgeEnd> moving;
  for (EdgeId e : {db, bf}) moving.push_back({e, m.start_of(e) == b ? 0 : 1});
  auto w = split_vertex(m, b, moving);
  ASSERT_OK(w);
  EXPECT_VALID(m);
  EXPECT_FALSE(m.may_repeat_elements(f));
  expect_answers(6);

  ASSERT_OK(merge_vertices(m, b, *w));
  EXPECT_VALID(m);
  EXPECT_TRUE(m.may_repeat_elements(f));
  expect_answers(5);
}

// mev into a face's loop makes a dangling edge that the loop runs along twice:
// the face repeats that edge (and its inner vertex) until kev takes it away.
TEST(FaceMarks, ADanglingEdgeInAFaceIsMarkedUntilItIsKilled) {
  Model m = build(unit_cube());
  const FaceId f = face_at(m, {0.5, 0.5, 1});
  const VertexId corner = vertex_at(m, {1, 1, 1});
  auto strut = mev(m, m.outer_loop(f), corner, {0.5, 0.5, 1});
  ASSERT_OK(strut);
  EXPECT_VALID(m);
  EXPECT_TRUE(m.may_repeat_elements(f));
  std::vector<EdgeId> es;
  edges_of(m, f, es);
  EXPECT_EQ(es.size(), 5u);
  EXPECT_TRUE(all_distinct(es));
  std::vector<VertexId> vs;
  vertices_of(m, f, vs);
  EXPECT_EQ(vs.size(), 5u);
  EXPECT_TRUE(all_distinct(vs));
  for (FaceId g : m.faces()) EXPECT_EQ(m.may_repeat_elements(g), g == f) << g.str();

  ASSERT_OK(kev(m, strut->edge, strut->vertex));
  EXPECT_VALID(m);
  EXPECT_FALSE(m.may_repeat_elements(f));
}

// An edit sets the repeat mark on every face it changes; when the editor goes out
// of scope the marks are exact again (semv and jekv leave no face marked).
TEST(FaceMarks, AreExactWhenTheEditEnds) {
  Model m = build(unit_cube());
  const FaceId f = face_at(m, {0.5, 0.5, 1});
  const EdgeId e = edge_at(m, {0, 0, 1}, {1, 0, 1});
  auto split = semv(m, e, {0.5, 0, 1});
  ASSERT_OK(split);
  EXPECT_FALSE(m.being_edited());
  EXPECT_VALID(m);
  for (FaceId g : m.faces()) {
    EXPECT_FALSE(m.may_repeat_elements(g)) << g.str();
    EXPECT_FALSE(m.may_hold_unplaced_uses(g)) << g.str();
  }
  ASSERT_OK(jekv(m, split->edge, split->vertex));
  EXPECT_VALID(m);
  EXPECT_FALSE(m.may_repeat_elements(f));
}

// A model rebuilt from its tables (snapshots, the database, JSON) comes back with
// no edit left open and with exact marks: the same ones as the original.
TEST(FaceMarks, ARestoredModelHasExactMarksAndNoEditOpen) {
  Model m = build(unit_cube());
  const FaceId top = face_at(m, {0.5, 0.5, 1});
  ASSERT_OK(mev(m, m.outer_loop(top), vertex_at(m, {1, 1, 1}), {0.5, 0.5, 1}));
  MeshInput pinched;
  add_face(pinched, {{{5, 0, 0}, {6, 1, 0}, {7, 0, 0}, {7, 2, 0}, {6, 1, 0}, {5, 2, 0}}});
  ASSERT_OK(build_mesh(m, pinched));
  auto back = restore(snapshot(m));
  ASSERT_OK(back);
  EXPECT_FALSE(back->being_edited());
  EXPECT_VALID(*back);  // outside an edit the validator checks the marks are exact
  std::size_t repeating = 0;
  for (FaceId f : back->faces()) repeating += back->may_repeat_elements(f) ? 1 : 0;
  EXPECT_EQ(repeating, 2u);  // the cube's top face (the strut) and the pinched sheet
  // A later edit on the restored model makes the marks it touches exact again.
  const VertexId tip = vertex_at(*back, {0.5, 0.5, 1});
  std::vector<FaceId> fs;
  faces_of(*back, tip, fs);
  ASSERT_EQ(fs.size(), 1u);
  const FaceId again = fs[0];
  ASSERT_TRUE(back->may_repeat_elements(again));
  std::vector<EdgeId> es;
  edges_of(*back, tip, es);
  ASSERT_EQ(es.size(), 1u);
  ASSERT_OK(kev(*back, es[0], tip));
  EXPECT_FALSE(back->being_edited());
  EXPECT_VALID(*back);
  EXPECT_FALSE(back->may_repeat_elements(again));
}

// The validator's side: a face that repeats a vertex without the mark is an
// error, and so, outside an edit, is the mark on a face that repeats nothing.
// (The marks are flipped behind the editor's back: no call of it would.)
TEST(FaceMarks, TheValidatorCatchesAMissingOrNeedlessMark) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 2, 0}, {1, 1, 0}, {0, 2, 0}}});
  add_face(in, {{{5, 0, 0}, {6, 0, 0}, {6, 1, 0}, {5, 1, 0}}});
  Model m = build(in);
  const FaceId pinched = face_at(m, {1, 1, 0});
  const FaceId square = face_at(m, {5.5, 0.5, 0});
  ASSERT_TRUE(m.may_repeat_elements(pinched));
  ASSERT_FALSE(m.may_repeat_elements(square));
  for (FaceId f : {pinched, square}) {
    Model bad = m;
    {
      ModelEditor ed(bad);
      ed.rec(f).sides ^= ModelEditor::kRepeatFace;
    }
    const std::string found = to_string(validate(bad));
    EXPECT_NE(found.find("[marks] " + f.str()), std::string::npos) << found;
  }
}

}  // namespace
}  // namespace cellforge
