// The 9 adjacency queries against hand-computed answers on the non-manifold
// fixtures. Answers are compared as sets of positions / centroids; each query
// must list every element once.
#include "cellforge/topo/queries.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "cellforge/topo/builder.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;
using P = Vec3;

template <class T>
bool unique(std::vector<T> v) {
  std::sort(v.begin(), v.end());
  return std::adjacent_find(v.begin(), v.end()) == v.end();
}

template <class Out, class In>
std::vector<Out> q(const Model& m, In x) {
  auto out = query<Out>(m, x);
  EXPECT_TRUE(unique(out)) << "an answer lists an element twice";
  return out;
}

TEST(Queries, CubeCorner) {
  Model m = build(unit_cube());
  const VertexId v = vertex_at(m, {0, 0, 0});
  EXPECT_EQ(positions(m, q<VertexId>(m, v)), (std::set<P>{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}));
  EXPECT_EQ(q<EdgeId>(m, v).size(), 3u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, v)),
            (std::set<P>{{0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}}));
  const EdgeId e = edge_at(m, {0, 0, 0}, {1, 0, 0});
  EXPECT_EQ(positions(m, q<VertexId>(m, e)), (std::set<P>{{0, 0, 0}, {1, 0, 0}}));
  EXPECT_EQ(q<EdgeId>(m, e).size(), 4u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, e)), (std::set<P>{{0.5, 0.5, 0}, {0.5, 0, 0.5}}));
  const FaceId f = face_at(m, {0.5, 0.5, 1});
  EXPECT_EQ(q<VertexId>(m, f).size(), 4u);
  EXPECT_EQ(q<EdgeId>(m, f).size(), 4u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, f)),
            (std::set<P>{{0.5, 0, 0.5}, {0.5, 1, 0.5}, {0, 0.5, 0.5}, {1, 0.5, 0.5}}));
}

// F->V lists a loop's vertices in loop order; its walk takes two vertices from
// each edge it looks up, so loops of odd length end on a half pair. A pentagonal
// prism has two 5-gons (odd) and five quads (even); each face must list its input
// loop, up to where the loop starts.
TEST(Queries, FaceVerticesInLoopOrderOnOddAndEvenLoops) {
  std::vector<Vec3> p;
  for (int z = 0; z < 2; ++z) {
    p.push_back({0, 0, double(z)});
    p.push_back({2, 0, double(z)});
    p.push_back({3, 2, double(z)});
    p.push_back({1, 3, double(z)});
    p.push_back({-1, 2, double(z)});
  }
  std::vector<std::vector<std::uint32_t>> loops = {{4, 3, 2, 1, 0}, {5, 6, 7, 8, 9}};
  for (std::uint32_t i = 0; i < 5; ++i) loops.push_back({i, (i + 1) % 5, (i + 1) % 5 + 5, i + 5});
  Model m;
  const auto built = build_mesh(m, solid_input(p, loops));
  ASSERT_TRUE(built) << built.error().message;
  for (std::size_t k = 0; k < loops.size(); ++k) {
    std::vector<VertexId> want;
    for (std::uint32_t i : loops[k]) want.push_back(built->vertices[i]);
    const auto got = q<VertexId>(m, built->faces[k]);
    ASSERT_EQ(got.size(), want.size()) << "face " << k;
    const auto at = std::find(want.begin(), want.end(), got.front());
    ASSERT_NE(at, want.end()) << "face " << k;
    std::rotate(want.begin(), at, want.end());
    EXPECT_EQ(got, want) << "face " << k;
  }
}

TEST(Queries, TwoCubesSharingAnEdge) {
  Model m = build(two_cubes_sharing_edge());
  const VertexId v = vertex_at(m, {1, 1, 0});
  EXPECT_EQ(positions(m, q<VertexId>(m, v)),
            (std::set<P>{{0, 1, 0}, {1, 0, 0}, {1, 1, 1}, {2, 1, 0}, {1, 2, 0}}));
  EXPECT_EQ(q<EdgeId>(m, v).size(), 5u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, v)), (std::set<P>{{0.5, 0.5, 0},
                                                        {0.5, 1, 0.5},
                                                        {1, 0.5, 0.5},
                                                        {1.5, 1.5, 0},
                                                        {1.5, 1, 0.5},
                                                        {1, 1.5, 0.5}}));
  const EdgeId e = edge_at(m, {1, 1, 0}, {1, 1, 1});
  EXPECT_EQ(q<VertexId>(m, e).size(), 2u);
  EXPECT_EQ(q<EdgeId>(m, e).size(), 8u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, e)),
            (std::set<P>{{0.5, 1, 0.5}, {1, 0.5, 0.5}, {1.5, 1, 0.5}, {1, 1.5, 0.5}}));
  const FaceId f = face_at(m, {1, 0.5, 0.5});
  EXPECT_EQ(positions(m, q<VertexId>(m, f)),
            (std::set<P>{{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}}));
  EXPECT_EQ(q<EdgeId>(m, f).size(), 4u);
  EXPECT_EQ(face_keys(m, q<FaceId>(m, f)), (std::set<P>{{0.5, 0.5, 0},
                                                        {0.5, 0.5, 1},
                                                        {0.5, 0, 0.5},
                                                        {0.5, 1, 0.5},
                                                        {1.5, 1, 0.5},
                                                        {1, 1.5, 0.5}}));
}

TEST(Queries, TwoCubesSharingAVertex) {
  Model m = build(two_cubes_sharing_vertex());
  const VertexId v = vertex_at(m, {1, 1, 1});
  EXPECT_EQ(q<EdgeId>(m, v).size(), 6u);
  EXPECT_EQ(q<VertexId>(m, v).size(), 6u);
  EXPECT_EQ(q<FaceId>(m, v).size(), 6u);
  // Faces meeting only at the vertex are not F->F neighbours.
  const FaceId top = face_at(m, {0.5, 0.5, 1});
  EXPECT_EQ(q<FaceId>(m, top).size(), 4u);
}

TEST(Queries, CubeWithDanglingFace) {
  Model m = build(cube_with_dangling_face());
  const EdgeId hinge = edge_at(m, {0, 0, 1}, {1, 0, 1});
  EXPECT_EQ(face_keys(m, q<FaceId>(m, hinge)),
            (std::set<P>{{0.5, 0.5, 1}, {0.5, 0, 0.5}, {0.5, -0.5, 1.5}}));
  const FaceId fin = face_at(m, {0.5, -0.5, 1.5});
  EXPECT_EQ(face_keys(m, q<FaceId>(m, fin)), (std::set<P>{{0.5, 0.5, 1}, {0.5, 0, 0.5}}));
  const VertexId corner = vertex_at(m, {0, 0, 1});
  EXPECT_EQ(q<EdgeId>(m, corner).size(), 4u);
  EXPECT_EQ(q<FaceId>(m, corner).size(), 4u);
}

TEST(Queries, CubeWithWireAndPoint) {
  Model m = build(cube_with_wire_and_point());
  const VertexId v = vertex_at(m, {1, 1, 1});
  EXPECT_EQ(positions(m, q<VertexId>(m, v)),
            (std::set<P>{{0, 1, 1}, {1, 0, 1}, {1, 1, 0}, {2, 2, 2}}));
  EXPECT_EQ(q<FaceId>(m, v).size(), 3u);
  const EdgeId wire = edge_at(m, {1, 1, 1}, {2, 2, 2});
  EXPECT_TRUE(m.is_wire(wire));
  EXPECT_TRUE(q<FaceId>(m, wire).empty());
  EXPECT_EQ(q<EdgeId>(m, wire).size(), 3u);
  const VertexId lone = vertex_at(m, {5, 5, 5});
  EXPECT_TRUE(q<VertexId>(m, lone).empty());
  EXPECT_TRUE(q<EdgeId>(m, lone).empty());
  EXPECT_TRUE(q<FaceId>(m, lone).empty());
  // The top face's neighbours do not include anything through the wire.
  EXPECT_EQ(q<FaceId>(m, face_at(m, {0.5, 0.5, 1})).size(), 4u);
}

TEST(Queries, BookListsPagesInAngularOrder) {
  Model m = build(book());
  const EdgeId spine = edge_at(m, {0, 0, 0}, {0, 0, 1});
  const std::vector<FaceId> pages = q<FaceId>(m, spine);
  ASSERT_EQ(pages.size(), 3u);
  // Angles of the pages about +z: +x at 0, +y at 90, (-1,-1) at 225 degrees.
  std::vector<double> angle;
  for (FaceId f : pages) {
    const Vec3 c = centroid_of(m, f);
    angle.push_back(std::atan2(c.y, c.x));
  }
  const bool up = m.position(m.end_of(spine)).z > m.position(m.start_of(spine)).z;
  // Right-handed about the edge's axis: counterclockwise seen from +z when the edge
  // points up, clockwise when it points down.
  int increasing = 0;
  for (int i = 0; i < 3; ++i) {
    double d = angle[(i + 1) % 3] - angle[i];
    if (d < 0) d += 2 * M_PI;
    increasing += d < M_PI ? 1 : 0;
  }
  EXPECT_EQ(increasing, up ? 3 : 0);
  for (FaceId f : pages) EXPECT_EQ(q<FaceId>(m, f).size(), 2u);
  EXPECT_EQ(q<EdgeId>(m, vertex_at(m, {0, 0, 0})).size(), 4u);
}

TEST(Queries, TwoCubesSharingAFace) {
  Model m = build(two_cubes_sharing_face());
  const FaceId shared = face_at(m, {0.5, 0.5, 1});
  EXPECT_TRUE(m.front_volume(shared).is_valid());
  EXPECT_TRUE(m.back_volume(shared).is_valid());
  EXPECT_NE(m.front_volume(shared), m.back_volume(shared));
  EXPECT_EQ(q<FaceId>(m, shared).size(), 8u);  // four walls below, four above
  const EdgeId e = edge_at(m, {0, 0, 1}, {1, 0, 1});
  EXPECT_EQ(q<FaceId>(m, e).size(), 3u);
  EXPECT_EQ(q<FaceId>(m, vertex_at(m, {0, 0, 1})).size(), 5u);
}

}  // namespace
}  // namespace cellforge
