// info's geometric findings (crossing loops, non-planar faces) with ids in text and
// JSON; the self-intersection test's planar fans against every pair tested
// one by one; provenance and colour of imported faces as property tables.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cellforge/geom/intersect.h"
#include "cellforge/io/diagnose.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/parts.h"
#include "io/intersect.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

TEST(Findings, NonPlanarAndCrossingFacesAreReportedWithIds) {
  MeshInput in;
  add_face(in, {{{0, 0, 0}, {1, 0, 0}, {1, 1, std::ldexp(1.0, -60)}, {0, 1, 0}}});  // f0
  add_face(in, {{{5, 0, 0}, {6, 1, 0}, {6, 0, 0}, {5, 1, 0}}});                        // f1, a bow tie
  const Model m = build(in);
  const io::Diagnosis d = io::diagnose(m);
  EXPECT_TRUE(d.valid);  // findings, not topology errors
  EXPECT_EQ(d.non_planar_faces, std::vector<FaceId>{FaceId(0)});
  EXPECT_EQ(d.self_crossing_faces, std::vector<FaceId>{FaceId(1)});
  const std::string text = io::to_text(d);
  EXPECT_NE(text.find("non_planar_faces: 1 (f0)"), std::string::npos) << text;
  EXPECT_NE(text.find("self_crossing_faces: 1 (f1)"), std::string::npos) << text;
  EXPECT_NE(text.find("finding: planarity: f0 is not planar"), std::string::npos) << text;
  const std::string json = io::to_json(d);
  EXPECT_NE(json.find("\"non_planar_faces\": [\"f0\"]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"self_crossing_faces\": [\"f1\"]"), std::string::npos) << json;
  EXPECT_NE(json.find("\"geometry_findings\": [\"crossing: l1 of f1 crosses itself"), std::string::npos)
      << json;
  EXPECT_NE(json.find("\"planarity: f0 is not planar: v3 lies off the plane of v0, v1, v2\"]"),
            std::string::npos)
      << json;
  io::DiagnoseOptions off;
  off.geometry = false;
  const io::Diagnosis skipped = io::diagnose(m, off);
  EXPECT_NE(io::to_text(skipped).find("non_planar_faces: not checked"), std::string::npos);
  EXPECT_NE(io::to_json(skipped).find("\"non_planar_faces\": null"), std::string::npos);
}

TEST(Findings, LongLoopCrossingFoundLikeAShortOne) {
  // A 200-gon whose last vertex is pulled across the loop: the crossing is found
  // (through the BVH of a long loop), and the plain 200-gon has none.
  for (bool pulled : {false, true}) {
    std::vector<Vec3> loop;
    for (int i = 0; i < 200; ++i) {
      const double a = 2 * M_PI * i / 200;
      loop.push_back({std::cos(a), std::sin(a), 0});
    }
    if (pulled) loop[150] = {0.5, 0.9, 0};
    MeshInput in;
    add_face(in, {loop});
    const GeometryFindings g = check_geometry(build(in));
    EXPECT_EQ(g.crossings.size(), pulled ? 1u : 0u) << to_string(g.crossings);
  }
}

// Every pair of faces whose triangles share no vertex and meet, one pair at a time.
std::set<std::pair<FaceId, FaceId>> brute_force_pairs(const Model& m) {
  std::vector<std::pair<FaceId, std::array<VertexId, 3>>> tris;
  for (FaceId f : m.faces())
    for (const auto& t : io::triangulate_face(m, f)) tris.push_back({f, t});
  std::set<std::pair<FaceId, FaceId>> out;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    for (std::size_t j = i + 1; j < tris.size(); ++j) {
      const auto &a = tris[i], &b = tris[j];
      if (a.first == b.first) continue;
      bool shared = false;
      for (VertexId u : a.second)
        for (VertexId v : b.second) shared |= u == v;
      if (shared) continue;
      const Vec3 pa[3] = {m.position(a.second[0]), m.position(a.second[1]), m.position(a.second[2])};
      const Vec3 pb[3] = {m.position(b.second[0]), m.position(b.second[1]), m.position(b.second[2])};
      if (triangles_meet(pa, pb)) out.insert(std::minmax(a.first, b.first));
    }
  }
  return out;
}

TEST(SelfIntersections, FansGiveThePairsOfThePlainTest) {
  // A cap of 96 thin triangles fanned from rim vertex 0 of a 98-gon at z = 0, and
  // triangles around it: piercing its interior, lying in its plane across it,
  // touching it with a vertex inside, on a rim vertex, along a rim edge, above it,
  // and one meeting the plane outside the cap.
  MeshInput in;
  const int n = 98;
  std::vector<std::uint32_t> rim;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n;
    rim.push_back(add_point(in, {10 * std::cos(a), 10 * std::sin(a), 0}));
  }
  for (int i = 1; i + 1 < n; ++i) in.faces.push_back({{{rim[0], rim[i], rim[i + 1]}}, -1, -1});
  add_face(in, {{{1, 1, -1}, {2, 1, 1}, {1, 2, 1}}});                      // pierces
  add_face(in, {{{-3, -3, 0}, {3, -4, 0}, {0, 4, 0}}});                    // in the plane
  add_face(in, {{{-5, 2, 0}, {-5, 3, 2}, {-6, 2, 2}}});                    // a vertex inside
  add_face(in, {{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}}});                       // above
  add_face(in, {{{20, 0, 0}, {21, 0, 1}, {20, 1, 1}}});                    // plane, outside
  const auto p = [&](int i) { return in.positions[rim[i]]; };
  add_face(in, {{p(30), p(31), p(30) + Vec3{0, 0, -3}}});                 // a rim edge
  add_face(in, {{p(60), p(60) + Vec3{1, 0, 4}, p(60) + Vec3{0, 1, 4}}});  // a rim vertex
  add_face(in, {{p(0), p(0) + Vec3{1, 0, 4}, p(0) + Vec3{0, 1, 4}}});     // the hub
  const Model m = build(in);
  const auto found = io::self_intersections(m);
  const std::set<std::pair<FaceId, FaceId>> got(found.begin(), found.end());
  const auto want = brute_force_pairs(m);
  EXPECT_EQ(got, want);
  EXPECT_GT(want.size(), 5u);  // the piercing, coplanar and touching triangles meet the cap
}

TEST(SelfIntersections, CylinderCapsAsFans) {
  Model made;
  shape::CylinderOptions c;
  c.h = 3;
  c.r1 = c.r2 = 2;
  c.faceting.fn = 150;
  ASSERT_OK(shape::make_cylinder(made, c));
  const Model m = round_trip(made, io::Format::kStl);  // caps as fans of triangles
  EXPECT_EQ(m.num_faces(), 4u * 150 - 4);
  EXPECT_TRUE(io::self_intersections(m).empty());
  EXPECT_TRUE(brute_force_pairs(m).empty());
  // A copy shifted half way up: its side crosses the first cylinder's caps.
  Model two = m;
  ASSERT_OK(append(two, [&] {
    Model shifted;
    MeshInput in;
    for (VertexId v : m.vertices()) add_point(in, m.position(v) + Vec3{1, 0, 1.5});
    for (FaceId f : m.faces()) {
      std::vector<std::uint32_t> loop;
      for (VertexId v : m.loop_vertices(m.outer_loop(f))) loop.push_back(v.value);
      in.faces.push_back({{loop}, -1, -1});
    }
    EXPECT_TRUE(build_mesh(shifted, in).ok());
    return shifted;
  }()));
  const auto found = io::self_intersections(two);
  const std::set<std::pair<FaceId, FaceId>> got(found.begin(), found.end());
  EXPECT_EQ(got, brute_force_pairs(two));
  EXPECT_FALSE(found.empty());
}

TEST(Provenance, ImportedFacesNameTheirPolygonAndColour) {
  // An OFF square pyramid with face colours (integers 0..255 and fractions).
  const std::string off =
      "OFF\n5 5 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 1\n"
      "4 0 3 2 1 255 0 0\n3 0 1 4 0 255 0\n3 1 2 4 0.0 0.0 1.0 0.5\n3 2 3 4\n3 3 0 4 0 0 0\n";
  Model m;
  auto r = io::read_model(m, bytes_of(off), io::Format::kOff);
  ASSERT_OK(r);
  auto source = find_property<FaceProperty<std::uint32_t>>(m, io::kSourcePolygonProperty);
  auto colour = find_property<FaceProperty<Colour>>(m, io::kColourProperty);
  ASSERT_TRUE(source.is_valid());
  ASSERT_TRUE(colour.is_valid());
  std::vector<std::uint32_t> sources;
  for (FaceId f : m.faces()) sources.push_back(source[f]);
  EXPECT_EQ(sources, (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  const FaceId base = *m.faces().begin();
  EXPECT_EQ(colour[base], (Colour{1, 0, 0, 1}));
  EXPECT_EQ(colour[FaceId(2)], (Colour{0, 0, 1, 0.5f}));
  EXPECT_EQ(colour[FaceId(3)], Colour{});  // none given: white
  // An edit: splitting the base keeps its provenance and colour on the old face,
  // the new face starts from the defaults; extract carries the tables.
  auto split = mef(m, m.outer_loop(base), vertex_at(m, {0, 0, 0}), vertex_at(m, {1, 1, 0}));
  ASSERT_OK(split);
  EXPECT_EQ(source[base], 0u);
  EXPECT_EQ(source[split->face], kInvalidIndex);
  EXPECT_EQ(colour[base], (Colour{1, 0, 0, 1}));
  auto part = extract(m, r->group);
  ASSERT_OK(part);
  auto moved = find_property<FaceProperty<Colour>>(part->model, io::kColourProperty);
  ASSERT_TRUE(moved.is_valid());
  EXPECT_EQ(moved[part->ids[FaceId(1)]], (Colour{0, 1, 0, 1}));
  // Merged coplanar triangles name the first polygon of their patch.
  const std::string two = "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n";
  Model merged;
  io::ReadOptions o;
  o.import.merge_coplanar = true;
  ASSERT_OK(io::read_model(merged, bytes_of(two), io::Format::kOff, o));
  ASSERT_EQ(merged.num_faces(), 1u);
  EXPECT_EQ(find_property<FaceProperty<std::uint32_t>>(merged, io::kSourcePolygonProperty)[FaceId(0)], 0u);
}

}  // namespace
}  // namespace cellforge
