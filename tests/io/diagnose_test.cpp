// The mesh report: non-manifold places named by id, boundary, orientation,
// degenerate, duplicate and intersecting faces, mass properties.
#include "cellforge/io/diagnose.h"

#include <gtest/gtest.h>

#include "cellforge/shape/mass.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using testing::edge_at;
using testing::read_fixture;
using testing::vertex_at;

TEST(Diagnose, TwoCubesSharingAnEdgeAreNonManifoldThere) {
  const Model m = read_fixture("two_cubes_edge.stl");
  EXPECT_VALID(m);
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_FALSE(d.manifold);
  EXPECT_TRUE(d.closed);
  EXPECT_EQ(d.non_manifold_edges, std::vector<EdgeId>{edge_at(m, {1, 1, 0}, {1, 1, 1})});
  EXPECT_TRUE(d.non_manifold_vertices.empty());
  EXPECT_EQ(d.volumes, 2u);
  EXPECT_DOUBLE_EQ(d.mass.volume, 2);
  EXPECT_TRUE(d.self_intersections.empty());
  const std::string json = io::to_json(d);
  EXPECT_NE(json.find("\"non_manifold_edges\": [\"" + d.non_manifold_edges[0].str() + "\"]"),
            std::string::npos)
      << json;
}

TEST(Diagnose, TwoCubesSharingAVertexNameIt) {
  const Model m = read_fixture("two_cubes_vertex.stl");
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_TRUE(d.non_manifold_edges.empty());
  EXPECT_EQ(d.non_manifold_vertices, std::vector<VertexId>{vertex_at(m, {1, 1, 1})});
  EXPECT_FALSE(d.manifold);
}

TEST(Diagnose, OpenBoxHasFourBoundaryEdges) {
  const Model m = read_fixture("open_box.stl");
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_FALSE(d.closed);
  EXPECT_EQ(d.boundary_edges.size(), 4u);
  EXPECT_EQ(d.volumes, 0u);
  EXPECT_EQ(d.mass.volume, 0);
}

TEST(Diagnose, FlippedTriangleIsInconsistentAndRepairable) {
  const Model m = read_fixture("flipped_triangle.stl");
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_EQ(d.inconsistent_edges.size(), 3u);
  EXPECT_EQ(d.volumes, 0u);  // not a consistently oriented shell
  const Model fixed =
      read_fixture("flipped_triangle.stl", {.import = {.repair_orientation = true}});
  const io::Diagnosis f = io::diagnose(fixed);
  EXPECT_TRUE(f.inconsistent_edges.empty());
  EXPECT_EQ(f.volumes, 1u);
  EXPECT_DOUBLE_EQ(f.mass.volume, 1);
}

TEST(Diagnose, InsideOutCubeIsTurnedOutward) {
  MeshInput in = testing::unit_cube();
  io::PolygonSoup soup;
  soup.positions = in.positions;
  for (auto& f : in.faces) soup.polygons.push_back({f.loops[0].rbegin(), f.loops[0].rend()});
  Model m;
  auto r = io::import_soup(m, soup, {.repair_orientation = true});
  ASSERT_OK(r);
  EXPECT_EQ(r->report.flipped_faces, 6u);
  EXPECT_DOUBLE_EQ(shape::mass_properties(m).volume, 1);
}

TEST(Diagnose, DegenerateAndDuplicateFaces) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 0}};
  soup.polygons = {{0, 1, 2}, {2, 1, 0}, {0, 1, 3}, {1, 4, 2}};  // {1,4,2} is {1,0,2} again
  Model m;
  auto r = io::import_soup(m, soup, {});
  ASSERT_OK(r);
  const io::Diagnosis d = io::diagnose(m);
  ASSERT_EQ(d.degenerate_faces.size(), 1u);  // 0, 1, 3 lie on the x axis
  ASSERT_EQ(d.duplicate_faces.size(), 2u);   // three faces on {0, 1, 2}: two pairs
}

TEST(Diagnose, PolygonsCollapsedByWeldingAreDroppedAndReported) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1e-9, 0, 0}, {1, 1, 0}};
  soup.polygons = {{0, 1, 2}, {0, 3, 2}, {1, 4, 2}};
  Model welded;
  auto r = io::import_soup(welded, soup, {.weld_tolerance = 1e-6});
  ASSERT_OK(r);
  EXPECT_EQ(r->report.degenerate_dropped, 1u);
  EXPECT_EQ(r->report.degenerate_polygons, std::vector<std::size_t>{1});
  EXPECT_EQ(welded.num_faces(), 2u);
  EXPECT_EQ(welded.num_vertices(), 4u);
  Model exact;
  auto e = io::import_soup(exact, soup, {});
  ASSERT_OK(e);
  EXPECT_EQ(exact.num_vertices(), 5u);
  EXPECT_EQ(exact.num_faces(), 3u);
}

TEST(Diagnose, SelfIntersectionsOfOverlappingCubes) {
  MeshInput in;
  testing::add_box(in, {0, 0, 0}, {2, 2, 2}, -1);
  testing::add_box(in, {1, 1, 1}, {3, 3, 3}, -1);
  const Model m = testing::build(in);
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_FALSE(d.self_intersections.empty());
  // Touching cubes (sharing a face region but no vertex) intersect too; cubes
  // apart do not.
  MeshInput apart;
  testing::add_box(apart, {0, 0, 0}, {1, 1, 1}, -1);
  testing::add_box(apart, {1.5, 0, 0}, {2.5, 1, 1}, -1);
  EXPECT_TRUE(io::diagnose(testing::build(apart)).self_intersections.empty());
  MeshInput touching;
  testing::add_box(touching, {0, 0, 0}, {1, 1, 1}, -1);
  testing::add_box(touching, {1, 0.25, 0.25}, {2, 0.75, 0.75}, -1);
  EXPECT_FALSE(io::diagnose(testing::build(touching)).self_intersections.empty());
}

TEST(Diagnose, MassPropertiesOfTheHoledCube) {
  const Model m = testing::build(testing::cube_with_through_hole());
  const io::MassProperties p = shape::mass_properties(m);
  EXPECT_DOUBLE_EQ(p.volume, 24);
  EXPECT_DOUBLE_EQ(p.area, 6 * 9 - 2 + 4 * 3);
  EXPECT_NEAR(p.centroid.x, 1.5, 1e-12);
  EXPECT_NEAR(p.centroid.z, 1.5, 1e-12);
  EXPECT_EQ(p.bbox_max, (Vec3{3, 3, 3}));
}

TEST(Diagnose, SharedFaceCountsForBothCells) {
  const Model m = testing::build(testing::two_cubes_sharing_face());
  EXPECT_DOUBLE_EQ(shape::mass_properties(m).volume, 2);
}

TEST(Diagnose, JsonHasTheKeysOfTheIssue) {
  const std::string json = io::to_json(io::diagnose(read_fixture("cube.obj")));
  for (const char* key :
       {"vertices", "edges", "faces", "loops", "volumes", "groups", "euler_characteristic_surface",
        "euler_characteristic_solid", "valid", "closed", "manifold", "volume", "area", "centroid",
        "bbox", "warnings"})
    EXPECT_NE(json.find("\"" + std::string(key) + "\": "), std::string::npos) << key;
  // The surface of a cube is a sphere (2); the solid cube is a ball (1).
  EXPECT_NE(json.find("\"euler_characteristic_surface\": 2,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"euler_characteristic_solid\": 1,"), std::string::npos) << json;
  EXPECT_NE(json.find("\"volume\": 1,"), std::string::npos) << json;
}

}  // namespace
}  // namespace cellforge
