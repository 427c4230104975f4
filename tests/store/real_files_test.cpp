// Models read from files, saved and loaded (issue 19): -0 coordinates come back bit
// for bit from a mesh file through import and either backend, and a model the loader
// would refuse is never stored.
#include <gtest/gtest.h>

#include <cmath>

#include "cellforge/io/mesh_io.h"
#include "cellforge/topo/validate.h"
#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using RealFiles = StoreTest;

std::string data_file(const std::string& name) {
  return std::string(CELLFORGE_TEST_DATA) + "/" + name;
}

TEST_P(RealFiles, NegativeZeroFromAMeshFileComesBackBitForBit) {
  for (const char* file : {"precision/negative_zero.obj", "nested/cube_sphere_cavity.stl",
                           "back_to_back/two_cubes_face.obj"}) {
    SCOPED_TRACE(file);
    Model m;
    ASSERT_OK(io::read_file(m, data_file(file)));
    ASSERT_OK(store_->put("file", m));
    auto got = store_->get("file");
    ASSERT_OK(got);
    expect_same_model(m, *got);  // compares the bytes of every coordinate
  }
  Model m;
  ASSERT_OK(io::read_file(m, data_file("precision/negative_zero.obj")));
  auto got = store_->get("file", 1);
  ASSERT_OK(got);
  int negative = 0;
  for (VertexId v : got->vertices()) {
    const Vec3 p = got->position(v);
    negative += std::signbit(p.x) + std::signbit(p.y) + std::signbit(p.z);
  }
  EXPECT_EQ(negative, 6);
}

TEST_P(RealFiles, AnInvalidModelIsNotStored) {
  MeshInput in = unit_cube();
  in.faces.back().back = -1;  // the wedges at that face's edges disagree
  const Model m = build(in);
  ASSERT_FALSE(validate(m).empty());
  auto put = store_->put("broken", m);
  ASSERT_FALSE(put.ok());
  EXPECT_NE(put.error().message.find("invalid"), std::string::npos) << put.error().message;
  auto versions = store_->versions("broken");
  EXPECT_TRUE(!versions.ok() || versions->empty());
}

CELLFORGE_BACKENDS(RealFiles);

}  // namespace
}  // namespace cellforge::testing
