// The comparison baselines answer the 9 adjacency queries with the same sets as
// cellforge on every model, the radial edge structure is linked as Weiler defines
// it, and the winged edge converter refuses exactly what it cannot hold.
#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <string>

#include "cellforge/compare/models.h"
#include "cellforge/compare/radial_edge.h"
#include "cellforge/compare/winged_edge.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/queries.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::compare {
namespace {

using testing::build;
using testing::edge_at;
using testing::vertex_at;

struct NamedModel {
  std::string name;
  MeshInput input;
  bool manifold;  // the winged edge structure holds it
};

// The seed of the random closed mesh, printed by the test that uses it.
constexpr std::uint32_t kRandomSeed = 20240607;

std::vector<NamedModel> all_models() {
  return {
      {"cube", testing::unit_cube(), true},
      {"cube_with_through_hole", testing::cube_with_through_hole(), true},
      {"sphere_fn16", sphere_model(16), true},
      {"sphere_fn7", sphere_model(7), true},
      {"two_cubes_sharing_edge", testing::two_cubes_sharing_edge(), false},
      {"book", testing::book(), false},
      {"two_cubes_sharing_vertex", testing::two_cubes_sharing_vertex(), false},
      {"random_closed_mesh", torus_model(13, 9, kRandomSeed), true},
      {"cube_with_dangling_face", testing::cube_with_dangling_face(), false},
      {"cube_with_wire_and_point", testing::cube_with_wire_and_point(), false},
      {"two_cubes_sharing_face", testing::two_cubes_sharing_face(), false},
      {"square_sheet_with_hole", testing::square_sheet_with_hole(), false},
      {"compare_cube_with_hole", cube_with_hole_model(), true},
      {"compare_two_cubes_edge", two_cubes_edge_model(), false},
      {"compare_two_cubes_vertex", two_cubes_vertex_model(), false},
      {"compare_book", book_model(), false},
  };
}

template <class T>
std::vector<T> sorted_unique(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  EXPECT_EQ(std::adjacent_find(v.begin(), v.end()), v.end()) << "an element listed twice";
  return v;
}

// All 9 queries from every element: the structure S answers the same sets as
// cellforge, each element once.
template <class S>
void expect_same_answers(const Model& m, const S& s, const std::string& what) {
  std::vector<VertexId> vs, vs2;
  std::vector<EdgeId> es, es2;
  std::vector<FaceId> fs, fs2;
  auto check = [&](auto& want, auto& got, auto from, const char* query) {
    EXPECT_EQ(sorted_unique(want), sorted_unique(got)) << what << ": " << query << " from " << from;
  };
  for (VertexId v : m.vertices()) {
    vertices_of(m, v, vs), s.vertices_of(v, vs2), check(vs, vs2, v, "V->V");
    edges_of(m, v, es), s.edges_of(v, es2), check(es, es2, v, "V->E");
    faces_of(m, v, fs), s.faces_of(v, fs2), check(fs, fs2, v, "V->F");
  }
  for (EdgeId e : m.edges()) {
    vertices_of(m, e, vs), s.vertices_of(e, vs2), check(vs, vs2, e, "E->V");
    edges_of(m, e, es), s.edges_of(e, es2), check(es, es2, e, "E->E");
    faces_of(m, e, fs), s.faces_of(e, fs2), check(fs, fs2, e, "E->F");
  }
  for (FaceId f : m.faces()) {
    vertices_of(m, f, vs), s.vertices_of(f, vs2), check(vs, vs2, f, "F->V");
    edges_of(m, f, es), s.edges_of(f, es2), check(es, es2, f, "F->E");
    faces_of(m, f, fs), s.faces_of(f, fs2), check(fs, fs2, f, "F->F");
  }
}

TEST(Structures, AllThreeGiveTheSameAnswerSetsOnEveryModel) {
  std::cout << "random closed mesh seed " << kRandomSeed << "\n";
  for (const NamedModel& nm : all_models()) {
    SCOPED_TRACE(nm.name);
    const Model m = build(nm.input);
    EXPECT_VALID(m);
    expect_same_answers(m, RadialEdge::from_model(m), "radial edge on " + nm.name);
    auto w = WingedEdge::from_model(m);
    EXPECT_EQ(w.ok(), nm.manifold) << (w.ok() ? "accepted" : w.error().message);
    if (w.ok()) expect_same_answers(m, *w, "winged edge on " + nm.name);
  }
}

TEST(Structures, ModelsBuiltByEulerOperatorsAgreeToo) {
  Model m;
  ASSERT_OK(euler_box_with_hole(m, {0, 0, 0}, {3, 3, 3}, 1, 2));
  ASSERT_OK(euler_nonmanifold_example(m));
  EXPECT_VALID(m);
  expect_same_answers(m, RadialEdge::from_model(m), "radial edge on Euler examples");
  Model box;
  ASSERT_OK(euler_box_with_hole(box, {0, 0, 0}, {3, 3, 3}, 1, 2));
  auto w = WingedEdge::from_model(box);
  ASSERT_OK(w);
  expect_same_answers(box, *w, "winged edge on the Euler box with hole");
}

// Faces whose loops name an element twice, where cellforge's F->E and F->V
// answers are deduplicated (its other faces skip that): a strut into the cube's
// top face, which the top loop runs along both ways, and a sheet whose loop
// touches itself at a vertex.
TEST(Structures, FacesThatRepeatAnElementAgreeToo) {
  Model strut = build(testing::unit_cube());
  const FaceId top = testing::face_at(strut, {0.5, 0.5, 1});
  ASSERT_OK(mev(strut, strut.outer_loop(top), vertex_at(strut, {1, 1, 1}), {0.5, 0.5, 1}));
  EXPECT_VALID(strut);
  ASSERT_TRUE(strut.may_repeat_elements(top));
  expect_same_answers(strut, RadialEdge::from_model(strut), "radial edge on a cube with a strut");

  MeshInput in;
  testing::add_face(in, {{{0, 0, 0}, {1, 1, 0}, {2, 0, 0}, {2, 2, 0}, {1, 1, 0}, {0, 2, 0}}});
  const Model pinched = build(in);
  EXPECT_VALID(pinched);
  ASSERT_TRUE(pinched.may_repeat_elements(*pinched.faces().begin()));
  expect_same_answers(pinched, RadialEdge::from_model(pinched), "radial edge on a pinched sheet");
}

// Weiler's invariants, walked from the top of the hierarchy.
TEST(RadialEdge, IsLinkedAsWeilerDefinesIt) {
  for (const NamedModel& nm : all_models()) {
    SCOPED_TRACE(nm.name);
    const Model m = build(nm.input);
    const RadialEdge r = RadialEdge::from_model(m);
    std::size_t faceuses = 0, loopuses = 0, edgeuses = 0;
    std::set<const RadialEdge::Face*> faces;
    for (const RadialEdge::Region* region = r.top().regions; region; region = region->next) {
      ASSERT_EQ(region->model, &r.top());
      for (const RadialEdge::Shell* shell = region->shells; shell; shell = shell->next) {
        ASSERT_EQ(shell->region, region);
        for (const RadialEdge::FaceUse* fu = shell->faceuses; fu; fu = fu->next) {
          ++faceuses;
          faces.insert(fu->face);
          ASSERT_EQ(fu->shell, shell);
          ASSERT_EQ(fu->mate->mate, fu);
          ASSERT_NE(fu->mate, fu);
          ASSERT_EQ(fu->mate->face, fu->face);
          ASSERT_NE(fu->mate->same_sense, fu->same_sense);
          for (const RadialEdge::LoopUse* lu = fu->loopuses; lu; lu = lu->next) {
            ++loopuses;
            ASSERT_EQ(lu->faceuse, fu);
            ASSERT_EQ(lu->mate->mate, lu);
            ASSERT_EQ(lu->mate->faceuse, fu->mate);
            ASSERT_EQ(lu->mate->loop, lu->loop);
            if (!lu->edgeuses) {
              ASSERT_EQ(lu->vertexuse->up.loopuse, lu);
              continue;
            }
            const RadialEdge::EdgeUse* eu = lu->edgeuses;
            do {
              ++edgeuses;
              ASSERT_EQ(eu->up.loopuse, lu);
              ASSERT_EQ(eu->next->prev, eu);
              ASSERT_EQ(eu->mate->mate, eu);
              ASSERT_EQ(eu->radial->radial, eu);
              ASSERT_EQ(eu->mate->edge, eu->edge);
              ASSERT_EQ(eu->radial->edge, eu->edge);
              ASSERT_EQ(eu->mate->up.loopuse, lu->mate);
              // A use ends where the next one starts; its mate runs the other way.
              ASSERT_EQ(eu->next->vertexuse->vertex, eu->mate->vertexuse->vertex);
              ASSERT_EQ(eu->vertexuse->up.edgeuse, eu);
              // Radial partners face each other: they run the edge opposite ways.
              ASSERT_TRUE(!eu->radial->in_loop || eu->radial->same_sense != eu->same_sense);
              eu = eu->next;
            } while (eu != lu->edgeuses);
          }
        }
      }
    }
    EXPECT_EQ(faces.size(), m.num_faces());
    EXPECT_EQ(faceuses, 2 * m.num_faces());
    EXPECT_EQ(loopuses, 2 * m.num_loops());
    EXPECT_EQ(edgeuses, 2 * m.num_edge_uses());
  }
}

// The radial cycle keeps cellforge's angular order around a non-manifold edge.
TEST(RadialEdge, KeepsTheAngularOrderAroundAnEdge) {
  for (const MeshInput& in : {testing::book(), testing::two_cubes_sharing_edge()}) {
    const Model m = build(in);
    for (EdgeId e : m.edges()) {
      std::vector<FaceId> want, got;
      faces_of(m, e, want);
      RadialEdge::from_model(m).faces_of(e, got);
      EXPECT_EQ(want, got) << e;
    }
  }
}

TEST(RadialEdge, CountsEveryRecordOfACube) {
  const Model m = build(testing::unit_cube());
  const StorageStats s = RadialEdge::from_model(m).storage();
  // model, region, shell; 6 faces, 12 faceuses, 6 loops, 12 loopuses; 12 edges,
  // 48 edgeuses, 48 vertexuses, 8 vertices.
  EXPECT_EQ(s.records, 3u + 6 + 12 + 6 + 12 + 12 + 48 + 48 + 8);
  EXPECT_EQ(s.references, 1u + 4 + 6 + 6 + 12 * 6 + 6 + 12 * 7 + 12 + 48 * 7 + 48 * 4 + 8);
  using R = RadialEdge;
  EXPECT_EQ(s.bytes, sizeof(R::TopModel) + sizeof(R::Region) + sizeof(R::Shell) +
                         6 * sizeof(R::Face) + 12 * sizeof(R::FaceUse) + 6 * sizeof(R::Loop) +
                         12 * sizeof(R::LoopUse) + 12 * sizeof(R::Edge) + 48 * sizeof(R::EdgeUse) +
                         48 * sizeof(R::VertexUse) + 8 * sizeof(R::Vertex));
  EXPECT_EQ(sizeof(R::EdgeUse), 64u);
  EXPECT_EQ(sizeof(R::VertexUse), 40u);
}

TEST(WingedEdge, CountsEveryRecordOfACubeWithAHole) {
  const Model m = build(testing::cube_with_through_hole());
  auto w = WingedEdge::from_model(m);
  ASSERT_OK(w);
  const StorageStats s = w->storage();
  // 16 vertices, 24 edges, 10 faces, 2 rings (the holes in top and bottom).
  EXPECT_EQ(s.records, 16u + 24 + 10 + 2);
  EXPECT_EQ(s.references, 16u * 3 + 24 * 10 + 10 * 4 + 2 * 2);
  EXPECT_EQ(s.bytes, 16 * sizeof(WingedEdge::Vertex) + 24 * sizeof(WingedEdge::Edge) +
                         10 * sizeof(WingedEdge::Face) + 2 * sizeof(WingedEdge::Ring));
}

TEST(Cellforge, StorageMatchesTheDocumentedRecordSizes) {
  const Model m = build(testing::unit_cube());
  const StorageStats s = cellforge_storage(m);
  EXPECT_EQ(s.bytes, m.topology_bytes());
  // Vertices 4 B, edges 16 and two use slots of 12 each, faces 8; no Loop
  // records (every face is one loop); one run of vertex groups (8), one side row
  // (12), one volume (8), one group (4); the group index: one run each of edges,
  // faces and volumes (8 each) and the group's counts (16).
  EXPECT_EQ(s.bytes, 8u * 4 + 12 * (16 + 2 * 12) + 6 * 8 + 8 + 12 + 8 + 4 + 3 * 8 + 16);
  EXPECT_EQ(s.references, s.bytes / 4);
  EXPECT_EQ(s.records, 8u + 1 + 12 + 24 + 6 + 1 + 1 + 1 + 3);
  // The book: three quads on one edge. Its nine boundary edges leave one use
  // slot each empty; the spine's third use takes an overflow slot of one spare
  // pair (an edge slot that is no edge). 8 vertices, 10 edges + 1 spare pair,
  // 3 faces; no volume.
  const Model book = build(testing::book());
  ASSERT_EQ(book.num_edges(), 10u);
  ASSERT_EQ(book.edge_slots(), 11u);
  ASSERT_EQ(book.num_edge_uses(), 12u);
  std::size_t overflow = 0;
  for (EdgeUseId u : book.edge_uses()) overflow += book.in_overflow_slot(u) ? 1 : 0;
  EXPECT_EQ(book.spare_pairs(), 1u);
  EXPECT_EQ(overflow, 1u);
  EXPECT_EQ(cellforge_storage(book).bytes,
            8u * 4 + 11 * (16 + 2 * 12) + 3 * 8 + 8 + 12 + 4 + 2 * 8 + 16);  // runs of edges, faces
  EXPECT_EQ(book.topology_bytes(), cellforge_storage(book).bytes);
  // The radial edge does not count the spare pair as an edge: model, region,
  // shell; 3 faces, 6 faceuses, 3 loops, 6 loopuses; 10 edges, 24 edgeuses, 24
  // vertexuses, 8 vertices.
  using R = RadialEdge;
  const StorageStats re = R::from_model(book).storage();
  EXPECT_EQ(re.records, 3u + 3 + 6 + 3 + 6 + 10 + 24 + 24 + 8);
  EXPECT_EQ(re.bytes, sizeof(R::TopModel) + sizeof(R::Region) + sizeof(R::Shell) +
                          3 * sizeof(R::Face) + 6 * sizeof(R::FaceUse) + 3 * sizeof(R::Loop) +
                          6 * sizeof(R::LoopUse) + 10 * sizeof(R::Edge) + 24 * sizeof(R::EdgeUse) +
                          24 * sizeof(R::VertexUse) + 8 * sizeof(R::Vertex));
  // A face with a hole lists its two loops in Loop records.
  const Model holed = build(testing::cube_with_through_hole());
  EXPECT_EQ(holed.num_loop_records(), 4u);
  EXPECT_EQ(holed.num_loops(), 12u);
}

std::string refusal(const MeshInput& in) {
  const Model m = build(in);
  auto w = WingedEdge::from_model(m);
  if (w.ok()) return "accepted";
  EXPECT_EQ(w.error().code, ErrorCode::kUnsupported);
  return w.error().message;
}

std::string edge_text(const Model& m, EdgeId e) {
  return "edge " + e.str() + " (" + m.start_of(e).str() + "-" + m.end_of(e).str() + ")";
}

TEST(WingedEdge, RefusesAnEdgeWithMoreThanTwoFaces) {
  const Model m = build(testing::two_cubes_sharing_edge());
  const EdgeId shared = edge_at(m, {1, 1, 0}, {1, 1, 1});
  EXPECT_EQ(refusal(testing::two_cubes_sharing_edge()),
            "winged edge cannot represent " + edge_text(m, shared) +
                ": it is used by 4 faces (non-manifold edge; a winged edge has exactly two faces)");
  const Model book = build(testing::book());
  const EdgeId spine = edge_at(book, {0, 0, 0}, {0, 0, 1});
  EXPECT_NE(refusal(testing::book()).find(edge_text(book, spine) + ": it is used by 3 faces"),
            std::string::npos)
      << refusal(testing::book());
  EXPECT_NE(refusal(testing::two_cubes_sharing_face()).find(": it is used by 3 faces"),
            std::string::npos);
}

TEST(WingedEdge, RefusesWireAndDanglingEdgesAndIsolatedVertices) {
  EXPECT_NE(refusal(testing::cube_with_wire_and_point()).find("cannot represent wire edge"),
            std::string::npos);
  const Model sheet = build(testing::square_sheet_with_hole());
  EXPECT_NE(refusal(testing::square_sheet_with_hole())
                .find("cannot represent dangling edge e0 (" + sheet.start_of(EdgeId(0)).str()),
            std::string::npos)
      << refusal(testing::square_sheet_with_hole());
  MeshInput point = testing::unit_cube();
  testing::add_point(point, {5, 5, 5});
  const Model pm = build(point);
  EXPECT_EQ(refusal(point), "winged edge cannot represent isolated vertex " +
                                vertex_at(pm, {5, 5, 5}).str() + ": it has no edge");
}

TEST(WingedEdge, RefusesAVertexWhereSolidsTouch) {
  const Model m = build(testing::two_cubes_sharing_vertex());
  EXPECT_EQ(refusal(testing::two_cubes_sharing_vertex()),
            "winged edge cannot represent non-manifold vertex " + vertex_at(m, {1, 1, 1}).str() +
                ": its 6 edges form more than one cycle of faces (the wings around it reach 3)");
}

TEST(WingedEdge, HoldsVerticesOfAnyDegree) {
  // Seed 000 figure 3: vertices with more than three edges (the sphere's caps are
  // 16-gons, so its ring vertices have degree 4; a random mesh has 4 to 8).
  const Model m = build(torus_model(11, 7, kRandomSeed));
  std::size_t max_degree = 0;
  for (VertexId v : m.vertices()) max_degree = std::max(max_degree, m.degree(v));
  EXPECT_GE(max_degree, 7u);
  EXPECT_TRUE(WingedEdge::from_model(m).ok());
}

}  // namespace
}  // namespace cellforge::compare
