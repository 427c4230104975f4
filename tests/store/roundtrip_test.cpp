// Save and load are lossless on both backends: every topology fixture, the
// Euler-operator examples (point loops, merged edges, freed slots), names,
// parameters and surfaces, and seeded random non-manifold assemblies.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using RoundTrip = StoreTest;

void round_trip(Store& store, const std::string& name, const Model& m) {
  SCOPED_TRACE(name);
  auto put = store.put(name, m);
  ASSERT_TRUE(put.ok()) << put.error().message;
  auto got = store.get(name);
  ASSERT_TRUE(got.ok()) << got.error().message;
  EXPECT_VALID(got.value());
  expect_same_model(m, got.value());
}

TEST_P(RoundTrip, EveryFixture) {
  const std::pair<const char*, MeshInput> fixtures[] = {
      {"unit_cube", unit_cube()},
      {"cube_with_through_hole", cube_with_through_hole()},
      {"two_cubes_sharing_edge", two_cubes_sharing_edge()},
      {"two_cubes_sharing_vertex", two_cubes_sharing_vertex()},
      {"cube_with_dangling_face", cube_with_dangling_face()},
      {"cube_with_wire_and_point", cube_with_wire_and_point()},
      {"book", book()},
      {"two_cubes_sharing_face", two_cubes_sharing_face()},
      {"square_sheet_with_hole", square_sheet_with_hole()},
  };
  for (const auto& [name, in] : fixtures) round_trip(*store_, name, build(in));
}

TEST_P(RoundTrip, EulerExamplesWithFreedSlots) {
  Model box_hole;
  ASSERT_OK(euler_box_with_hole(box_hole, {0, 0, 0}, {3, 3, 1}, 1, 2, "block"));
  round_trip(*store_, "euler_box_with_hole", box_hole);

  Model nm;
  ASSERT_OK(euler_nonmanifold_example(nm, "nm"));
  round_trip(*store_, "euler_nonmanifold", nm);

  // kemr leaves a point loop (a loop that is one vertex): the bulk builder cannot
  // make one, the store must.
  Model pl;
  auto g = make_group(pl, "point loop");
  auto vf = mvsf(pl, g, {0.5, 0.25, 0});
  ASSERT_OK(vf);
  auto ev = mev(pl, pl.outer_loop(vf->face), vf->vertex, {1.5, 0.25, 0});
  ASSERT_OK(ev);
  auto ring = kemr(pl, pl.first_use(ev->edge));
  ASSERT_OK(ring);
  EXPECT_VALID(pl);
  round_trip(*store_, "point_loop", pl);
}

TEST_P(RoundTrip, NamesParametersAndSurfaces) {
  MeshInput in = unit_cube();
  in.group_name = "körper 'one'";
  Model m;
  auto built = build_mesh(m, in);
  ASSERT_OK(built);
  m.set_attribute(built->group, "kind", "cube");
  m.set_attribute(built->group, "size", "1\t2\n3 \\ done");
  Surface s{"cylinder", {0.5, 0.5, 0}, {0, 0, 1}, 0.5, 0, 1, 32};
  m.set_surface(built->faces[0], m.add_surface(s));
  auto second = build_mesh(m, two_cubes_sharing_face());  // a second group
  ASSERT_OK(second);
  m.set_attribute(second->group, "op", "union");
  round_trip(*store_, "attributed", m);

  auto info = store_->info("attributed");
  ASSERT_OK(info);
  ASSERT_EQ(info->parameters.size(), 3u);
  EXPECT_EQ(info->parameters[1].value, "1\t2\n3 \\ done");
  EXPECT_EQ(info->groups, 2);
}

// Unit cells of a grid with i + j + k even never share a face, only edges and
// vertices: random subsets are non-manifold assemblies. Coordinates are random
// doubles; some boxes are bare surfaces; wires and isolated points are added.
Model random_assembly(std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> real(-1e3, 1e3), step(1e-3, 10);
  const double ox = real(rng), oy = real(rng), oz = real(rng), h = step(rng);
  auto at = [&](int i, int j, int k) { return Vec3{ox + i * h, oy + j * h, oz + k * h}; };
  MeshInput in;
  int volumes = 0;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      for (int k = 0; k < 3; ++k) {
        if ((i + j + k) % 2 != 0 || rng() % 3 == 0) continue;
        const int volume = rng() % 4 == 0 ? -1 : volumes++;
        add_box(in, at(i, j, k), at(i + 1, j + 1, k + 1), volume);
      }
    }
  }
  in.volumes = volumes;
  const int wires = static_cast<int>(rng() % 4);
  for (int w = 0; w < wires; ++w) {
    const std::uint32_t a = add_point(in, at(5 + w, 0, 0)), b = add_point(in, at(5 + w, 1, 1));
    in.wires.push_back({a, b});
  }
  for (int p = static_cast<int>(rng() % 3); p > 0; --p) add_point(in, at(9, p, 0));
  in.group_name = "random " + std::to_string(seed);
  return build(in);
}

TEST_P(RoundTrip, SeededRandomAssemblies) {
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Model m = random_assembly(seed);
    EXPECT_VALID(m);
    round_trip(*store_, "random", m);  // each seed a new version of one name
  }
  auto versions = store_->versions("random");
  ASSERT_OK(versions);
  EXPECT_EQ(versions->size(), 12u);
  auto first = store_->get("random", 1);
  ASSERT_OK(first);
  expect_same_model(random_assembly(1), first.value());
}

// Bit for bit: negative zero, subnormals and extremes come back as stored
// (expect_same_model compares the bytes of every coordinate).
TEST_P(RoundTrip, SignedZeroSubnormalsAndExtremes) {
  MeshInput in;
  const std::uint32_t a = add_point(in, {-0.0, -0.0, -0.0}), b = add_point(in, {1e308, 5e-324, 0.0});
  const std::uint32_t c = add_point(in, {-1e308, -2.2250738585072014e-308, 0.1 + 0.2});
  const std::uint32_t d = add_point(in, {-0.0, 1.0 / 3.0, -5e-324});
  in.faces.push_back({{{a, b, c}}});
  in.faces.push_back({{{a, c, d}}});
  const Model m = build(in);
  round_trip(*store_, "extremes", m);
  auto got = store_->get("extremes");
  ASSERT_OK(got);
  EXPECT_TRUE(std::signbit(got->position(VertexId(0)).x));
  EXPECT_TRUE(std::signbit(got->position(VertexId(3)).x));
}

TEST_P(RoundTrip, EmptyModel) { round_trip(*store_, "nothing", Model()); }

CELLFORGE_BACKENDS(RoundTrip);

}  // namespace
}  // namespace cellforge::testing
