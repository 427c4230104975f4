// Primitives: counts, Euler characteristic, closed-form volumes computed from the
// vertex layout independently of the builder, OpenSCAD vertex positions, attributes,
// surfaces, and the errors of bad parameters.
#include "cellforge/shape/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>
#include <tuple>

#include "shape/shape_test_util.h"
#include "cellforge/shape/mass.h"
#include "cellforge/topo/validate.h"
#include "support/checks.h"

namespace cellforge::shape {
namespace {

using testing::counts;
using testing::frustum_volume;
using testing::ngon_area;
using testing::rel_err;

constexpr double kPi = std::numbers::pi;

std::set<std::tuple<double, double, double>> positions(const Model& m, GroupId g) {
  std::set<std::tuple<double, double, double>> out;
  for (VertexId v : m.vertices()) {
    if (m.group_of(v) == g) out.insert({m.position(v).x, m.position(v).y, m.position(v).z});
  }
  return out;
}

TEST(Cube, CountsVolumeCentroidBox) {
  Model m;
  auto g = make_cube(m, {.size = {2, 3, 4}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 8);
  EXPECT_EQ(c.e, 12);
  EXPECT_EQ(c.f, 6);
  const MassProperties p = mass_properties(m, *g);
  EXPECT_TRUE(p.solid);
  EXPECT_DOUBLE_EQ(p.volume, 24);
  EXPECT_DOUBLE_EQ(p.area, 2 * (6 + 8 + 12));
  EXPECT_DOUBLE_EQ(p.centroid.x, 1);
  EXPECT_DOUBLE_EQ(p.centroid.y, 1.5);
  EXPECT_DOUBLE_EQ(p.centroid.z, 2);
  EXPECT_EQ(p.bbox_min, (Vec3{0, 0, 0}));
  EXPECT_EQ(p.bbox_max, (Vec3{2, 3, 4}));
  EXPECT_EQ(m.attribute(*g, "kind"), "cube");
  EXPECT_EQ(m.attribute(*g, "size"), "[2, 3, 4]");
  EXPECT_EQ(m.attribute(*g, "center"), "false");
}

TEST(Cube, Centered) {
  Model m;
  auto g = make_cube(m, {.size = {2, 2, 2}, .center = true});
  ASSERT_OK(g);
  const MassProperties p = mass_properties(m, *g);
  EXPECT_EQ(p.bbox_min, (Vec3{-1, -1, -1}));
  EXPECT_NEAR(p.centroid.x, 0, 1e-15);
  EXPECT_NEAR(p.centroid.y, 0, 1e-15);
  EXPECT_NEAR(p.centroid.z, 0, 1e-15);
  EXPECT_DOUBLE_EQ(p.volume, 8);
}

TEST(Cube, RejectsNonPositiveSize) {
  Model m;
  auto g = make_cube(m, {.size = {1, 0, 1}});
  ASSERT_FALSE(g.ok());
  EXPECT_NE(g.error().message.find("size.y"), std::string::npos) << g.error().message;
  EXPECT_TRUE(m.empty());
}

TEST(Cylinder, OpenScadLayoutCountsAndVolume) {
  Model m;
  auto g = make_cylinder(m, {.h = 5, .r1 = 3, .r2 = 1, .faceting = {.fn = 17}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 34);
  EXPECT_EQ(c.e, 51);
  EXPECT_EQ(c.f, 19);  // two 17-gon caps and 17 quads
  EXPECT_EQ(c.euler(), 2);
  const auto pos = positions(m, *g);
  for (int i = 0; i < 17; ++i) {
    const double phi = 360.0 * i / 17;
    EXPECT_TRUE(pos.count({3 * cos_degrees(phi), 3 * sin_degrees(phi), 0})) << i;
    EXPECT_TRUE(pos.count({1 * cos_degrees(phi), 1 * sin_degrees(phi), 5})) << i;
  }
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, frustum_volume(17, 3, 1, 5)), 1e-12);
  std::size_t ngons = 0, cone_faces = 0;
  for (FaceId f : m.faces()) {
    ngons += m.loop_length(m.outer_loop(f)) == 17;
    if (m.surface_of(f) != kInvalidIndex) {
      EXPECT_EQ(m.surface(m.surface_of(f)).kind, "cone");
      EXPECT_EQ(m.surface(m.surface_of(f)).segments, 17);
      ++cone_faces;
    }
  }
  EXPECT_EQ(ngons, 2u);
  EXPECT_EQ(cone_faces, 17u);
  std::size_t smooth = 0;
  for (EdgeId e : m.edges()) smooth += m.is_smooth(e);
  EXPECT_EQ(smooth, 17u);  // the lateral edges, not the cap rims
  EXPECT_EQ(m.attribute(*g, "segments"), "17");
  EXPECT_EQ(m.attribute(*g, "r1"), "3");
}

TEST(Cylinder, SegmentsFromLargerRadiusWithDefaults) {
  Model m;
  auto g = make_cylinder(m, {.h = 1, .r1 = 1, .r2 = 10});  // fragments(10) = 30
  ASSERT_OK(g);
  EXPECT_EQ(counts(m, *g).v, 60);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, frustum_volume(30, 1, 10, 1)), 1e-12);
}

TEST(Cylinder, ConeHasAnApex) {
  Model m;
  auto g = make_cylinder(m, {.h = 2, .r1 = 1, .r2 = 0, .center = true, .faceting = {.fn = 8}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 9);
  EXPECT_EQ(c.f, 9);
  EXPECT_EQ(c.euler(), 2);
  EXPECT_TRUE(positions(m, *g).count({0, 0, 1}));
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, frustum_volume(8, 1, 0, 2)), 1e-12);
  EXPECT_NEAR(mass_properties(m, *g).centroid.z, -0.5, 1e-12);  // a quarter up from the base
}

TEST(Cylinder, InvertedCone) {
  Model m;
  auto g = make_cylinder(m, {.h = 2, .r1 = 0, .r2 = 1, .faceting = {.fn = 5}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_EQ(counts(m, *g).euler(), 2);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, frustum_volume(5, 0, 1, 2)), 1e-12);
}

TEST(Cylinder, Errors) {
  Model m;
  EXPECT_FALSE(make_cylinder(m, {.h = 0}).ok());
  EXPECT_FALSE(make_cylinder(m, {.r1 = -1}).ok());
  auto both = make_cylinder(m, {.r1 = 0, .r2 = 0});
  ASSERT_FALSE(both.ok());
  EXPECT_NE(both.error().message.find("r1 and r2"), std::string::npos);
  EXPECT_TRUE(m.empty());
}

// The faceted sphere is a stack of frusta between its rings (OpenSCAD's layout), so
// its volume is sum over bands of (dz / 3) k (rho1^2 + rho1 rho2 + rho2^2).
double sphere_volume(double r, int n) {
  const int rings = (n + 1) / 2;
  double v = 0;
  for (int i = 0; i + 1 < rings; ++i) {
    const double p1 = kPi * (i + 0.5) / rings, p2 = kPi * (i + 1.5) / rings;
    const double rho1 = r * std::sin(p1), rho2 = r * std::sin(p2);
    v += frustum_volume(n, rho1, rho2, r * (std::cos(p1) - std::cos(p2)));
  }
  return v;
}

TEST(Sphere, OpenScadLayout) {
  for (int fn : {3, 4, 5, 8, 17, 32}) {
    Model m;
    auto g = make_sphere(m, {.r = 10, .faceting = {.fn = static_cast<double>(fn)}});
    ASSERT_OK(g);
    EXPECT_VALID(m);
    const int rings = (fn + 1) / 2;
    const auto c = counts(m, *g);
    EXPECT_EQ(c.v, rings * fn) << fn;
    EXPECT_EQ(c.f, 2 + (rings - 1) * fn) << fn;
    EXPECT_EQ(c.euler(), 2) << fn;
    EXPECT_LE(rel_err(mass_properties(m, *g).volume, sphere_volume(10, fn)), 1e-12) << fn;
    const auto pos = positions(m, *g);
    for (int i = 0; i < rings; ++i) {
      const double phi = 180.0 * (i + 0.5) / rings;
      const double rho = 10 * sin_degrees(phi), z = 10 * cos_degrees(phi);
      for (int j = 0; j < fn; ++j) {
        const double a = 360.0 * j / fn;
        EXPECT_TRUE(pos.count({rho * cos_degrees(a), rho * sin_degrees(a), z})) << fn;
      }
    }
    EXPECT_FALSE(pos.count({0, 0, 10}));  // no pole vertex
  }
}

// The geometry check on faceted solids: no loop crosses itself; a sphere's quads may
// be off their plane in doubles (a finding, not an error); a cube's faces are planar.
TEST(Sphere, GeometryFindingsAreOnlyPlanarity) {
  Model m;
  ASSERT_TRUE(make_sphere(m, {.r = 10, .faceting = {.fn = 32}}));
  const GeometryFindings g = check_geometry(m);
  EXPECT_TRUE(g.crossings.empty()) << to_string(g.crossings);
  for (const Violation& v : g.non_planar) EXPECT_EQ(v.check, "planarity");
  Model cube;
  ASSERT_TRUE(make_cube(cube, {.size = {1, 2, 3}}));
  EXPECT_TRUE(check_geometry(cube).non_planar.empty());
  EXPECT_TRUE(check_geometry(cube).crossings.empty());
}

TEST(Sphere, DefaultFacetingAndCentroid) {
  Model m;
  auto g = make_sphere(m, {.r = 10});  // fragments(10) = 30 with $fa = 12, $fs = 2
  ASSERT_OK(g);
  EXPECT_EQ(m.attribute(*g, "segments"), "30");
  EXPECT_EQ(m.attribute(*g, "rings"), "15");
  const MassProperties p = mass_properties(m, *g);
  EXPECT_NEAR(p.centroid.x, 0, 1e-12);
  EXPECT_NEAR(p.centroid.z, 0, 1e-12);
  EXPECT_LT(p.volume, 4.0 / 3 * kPi * 1000);
  EXPECT_GT(p.volume, 0.95 * 4.0 / 3 * kPi * 1000);
  for (FaceId f : m.faces()) EXPECT_EQ(m.surface(m.surface_of(f)).kind, "sphere");
}

TEST(Sphere, TinyRadiusGetsThreeSegments) {
  Model m;
  auto g = make_sphere(m, {.r = 1e-7});
  ASSERT_OK(g);
  EXPECT_EQ(m.attribute(*g, "segments"), "3");
  EXPECT_EQ(counts(m, *g).v, 6);
}

// Revolving a polygon in m sections of angle d: V = m sin(d) * integral of x dA
// (the Jacobian of the bilinear map between two section planes is x sin d).
double torus_volume(double big_r, double r, int n_profile, int m_sections) {
  return m_sections * std::sin(2 * kPi / m_sections) * big_r * ngon_area(n_profile, r);
}

TEST(Torus, VolumeAndEuler) {
  Model m;
  auto g = make_torus(m, {.major_radius = 5, .minor_radius = 1, .faceting = {.fn = 24}});
  ASSERT_OK(g);
  EXPECT_VALID(m);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 24 * 24);
  EXPECT_EQ(c.f, 24 * 24);
  EXPECT_EQ(c.euler(), 0);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, torus_volume(5, 1, 24, 24)), 1e-12);
  EXPECT_TRUE(positions(m, *g).count({-6, 0, 0}));  // a full turn starts on -x
  EXPECT_EQ(m.attribute(*g, "kind"), "torus");
  for (FaceId f : m.faces()) EXPECT_EQ(m.surface(m.surface_of(f)).kind, "torus");
}

TEST(Torus, DefaultFaceting) {
  Model m;
  auto g = make_torus(m, {.major_radius = 5, .minor_radius = 1});
  ASSERT_OK(g);
  // Profile: fragments(1) = 5; revolution: fragments(6) = ceil(2 pi 6 / 2) = 19.
  EXPECT_EQ(counts(m, *g).v, 5 * 19);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, torus_volume(5, 1, 5, 19)), 1e-12);
  EXPECT_VALID(m);
}

TEST(Torus, MinorRadiusMustBeSmaller) {
  Model m;
  EXPECT_FALSE(make_torus(m, {.major_radius = 1, .minor_radius = 1}).ok());
}

TEST(RegularSolids, PrismPyramidFrustum) {
  Model m;
  auto prism = make_regular_prism(m, {.sides = 6, .r = 2, .h = 3});
  auto pyramid = make_pyramid(m, {.sides = 4, .r = 1, .h = 3});
  auto frustum = make_frustum(m, {.sides = 5, .r1 = 2, .r2 = 1, .h = 4, .center = true});
  ASSERT_OK(prism);
  ASSERT_OK(pyramid);
  ASSERT_OK(frustum);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *prism).volume, ngon_area(6, 2) * 3), 1e-12);
  EXPECT_LE(rel_err(mass_properties(m, *pyramid).volume, 2.0 * 3 / 3), 1e-12);
  EXPECT_LE(rel_err(mass_properties(m, *frustum).volume, frustum_volume(5, 2, 1, 4)), 1e-12);
  EXPECT_EQ(counts(m, *pyramid).v, 5);
  EXPECT_EQ(counts(m, *pyramid).euler(), 2);
  EXPECT_EQ(m.attribute(*frustum, "kind"), "frustum");
  EXPECT_FALSE(make_regular_prism(m, {.sides = 2}).ok());
}

TEST(Prism, OverPolygonWithHoleVolumeIsAreaTimesHeight) {
  auto base = polygon({{0, 0}, {7, 0}, {7, 5}, {3, 8}, {0, 5}}, {{{2, 2}, {4, 2}, {3, 4}}});
  ASSERT_OK(base);
  const double a = area(*base);
  EXPECT_DOUBLE_EQ(a, 35 + 10.5 - 2);  // 7x5 + roof triangle 7*3/2 - hole 2
  Model m;
  auto g = make_prism(m, *base, 2.5);
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, a * 2.5), 1e-12);
  const auto c = counts(m, *g);
  EXPECT_EQ(c.v, 16);
  EXPECT_EQ(c.e, 24);
  EXPECT_EQ(c.f, 10);  // 2 caps with holes, 5 + 3 walls: v - e + f = 2 (1 - 1) + 2 rings
}

TEST(Prism, ConcavePolygonRelativeError) {
  // An L-shape with awkward coordinates: area * height to 1e-12.
  auto base = polygon({{0.1, 0.2}, {3.3, 0.2}, {3.3, 1.7}, {1.9, 1.7}, {1.9, 4.4}, {0.1, 4.4}});
  ASSERT_OK(base);
  Model m;
  auto g = make_prism(m, *base, 0.7, true);
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_LE(rel_err(mass_properties(m, *g).volume, area(*base) * 0.7), 1e-12);
}

PolyhedronOptions tetrahedron() {
  // OpenSCAD's convention: each face clockwise seen from outside.
  return {.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},
          .faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}}};
}

TEST(Polyhedron, Tetrahedron) {
  Model m;
  auto g = make_polyhedron(m, tetrahedron());
  ASSERT_OK(g);
  EXPECT_VALID(m);
  EXPECT_DOUBLE_EQ(mass_properties(m, *g).volume, 1.0 / 6);
}

TEST(Polyhedron, ErrorsNameTheFace) {
  Model m;
  auto bad_index = tetrahedron();
  bad_index.faces[2] = {0, 2, 9};
  auto r = make_polyhedron(m, bad_index);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("face 2 names point 9"), std::string::npos) << r.error().message;

  auto open = tetrahedron();
  open.faces.pop_back();
  open.faces.push_back({0, 1, 2});  // a duplicate instead of the last face
  r = make_polyhedron(m, open);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("open"), std::string::npos) << r.error().message;

  auto inward = tetrahedron();
  inward.clockwise = false;
  r = make_polyhedron(m, inward);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("inward"), std::string::npos) << r.error().message;

  // A cube whose top face has one corner lifted: face 1 is not planar.
  PolyhedronOptions cube{
      .points = {{0, 0, 0},
                 {1, 0, 0},
                 {0, 1, 0},
                 {1, 1, 0},
                 {0, 0, 1},
                 {1, 0, 1},
                 {0, 1, 1},
                 {1, 1, 1.001}},
      .faces = {
          {0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1}, {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}}};
  r = make_polyhedron(m, cube);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("face 1 is not planar"), std::string::npos) << r.error().message;
  EXPECT_TRUE(m.empty());
  cube.planarity_tolerance = 0.01;  // the lifted corner is 0.001 off: accepted
  auto lifted = make_polyhedron(m, cube);
  ASSERT_OK(lifted);
  EXPECT_VALID(m);
  cube.points[7].z = 1;
  cube.planarity_tolerance = 0;
  auto ok = make_polyhedron(m, cube);
  ASSERT_OK(ok);
  EXPECT_VALID(m);
  EXPECT_DOUBLE_EQ(mass_properties(m, *ok).volume, 1);
}

}  // namespace
}  // namespace cellforge::shape

namespace cellforge::shape {
namespace {

// Every segment count from 3 to 40: valid, Euler 2 (genus 0) or 0 (torus), volume as
// the closed form.
TEST(Primitives, EverySegmentCountValidates) {
  for (int n = 3; n <= 40; ++n) {
    const Faceting f{.fn = static_cast<double>(n)};
    Model m;
    auto s = make_sphere(m, {.r = 3, .faceting = f});
    auto c = make_cylinder(m, {.h = 2, .r1 = 1, .r2 = 2, .center = true, .faceting = f});
    auto t = make_torus(m, {.major_radius = 3, .minor_radius = 1, .faceting = f});
    ASSERT_OK(s);
    ASSERT_OK(c);
    ASSERT_OK(t);
    EXPECT_VALID(m);
    EXPECT_EQ(counts(m, *s).euler(), 2) << n;
    EXPECT_EQ(counts(m, *c).euler(), 2) << n;
    EXPECT_EQ(counts(m, *t).euler(), 0) << n;
    EXPECT_LE(rel_err(mass_properties(m, *s).volume, sphere_volume(3, n)), 1e-12) << n;
    EXPECT_LE(rel_err(mass_properties(m, *c).volume, frustum_volume(n, 1, 2, 2)), 1e-12) << n;
    EXPECT_LE(rel_err(mass_properties(m, *t).volume, torus_volume(3, 1, n, n)), 1e-12) << n;
  }
}

}  // namespace
}  // namespace cellforge::shape
