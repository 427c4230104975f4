// The model tables as SQL sees them give back every stored value exactly: on
// PostgreSQL the five large tables are views that unpack blocks (docs/database.md,
// "Storage on PostgreSQL"), rebuilding each double from its bits in SQL; on
// SQLite they are the tables themselves. Doubles are compared bit for bit with
// what the save computed (-0.0, subnormals, 1e300 and values that are not round
// in binary), integers and NULLs as numbers.
#include <gtest/gtest.h>

#include <cstring>

#include "cellforge/topo/builder.h"
#include "store/model_rows.h"
#include "store/store_fixture.h"
#include "support/checks.h"

namespace cellforge::testing {
namespace {

using Views = StoreTest;

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

TEST_P(Views, GiveTheStoredValuesBitForBit) {
  MeshInput in;
  in.positions = {{-0.0, 0.1, 1e300},
                  {0.30000000000000004, -0.0, 1e300},
                  {-0.0, -2.5e-310, 1e300},
                  {5e-324, 7.0, -1.5},
                  {-1e-300, 7.25, -1.5}};
  in.faces = {{{{0, 1, 2}}}, {{{1, 3, 4}}}};
  Model m;
  ASSERT_OK(build_mesh(m, in));
  ASSERT_OK(store_->put("bits", m));
  const store::ModelRows rows = store::to_rows(m);
  auto v = store_->query("SELECT vertex_key, x, y, z, group_key FROM vertices ORDER BY vertex_key");
  ASSERT_OK(v);
  ASSERT_EQ(v->rows.size(), rows.vertices.size());
  for (std::size_t i = 0; i < rows.vertices.size(); ++i) {
    const auto& row = v->rows[i];
    EXPECT_EQ(*row[0], std::to_string(i));
    const Vec3& p = rows.vertices[i].p;
    EXPECT_TRUE(same_bits(std::strtod(row[1]->c_str(), nullptr), p.x)) << *row[1];
    EXPECT_TRUE(same_bits(std::strtod(row[2]->c_str(), nullptr), p.y)) << *row[2];
    EXPECT_TRUE(same_bits(std::strtod(row[3]->c_str(), nullptr), p.z)) << *row[3];
  }
  auto f = store_->query(
      "SELECT face_key, group_key, front_cell, back_cell, surface_key, nx, ny, nz, d, min_x, "
      "min_y, min_z, max_x, max_y, max_z FROM faces ORDER BY face_key");
  ASSERT_OK(f);
  ASSERT_EQ(f->rows.size(), rows.faces.size());
  for (std::size_t i = 0; i < rows.faces.size(); ++i) {
    const auto& row = f->rows[i];
    EXPECT_EQ(*row[0], std::to_string(i));
    EXPECT_FALSE(row[2].has_value());  // a sheet: no cells, no surface
    EXPECT_FALSE(row[3].has_value());
    EXPECT_FALSE(row[4].has_value());
    const auto& pl = rows.planes[i];
    const QueryBox& b = rows.boxes[i];
    const double want[] = {pl.normal.x, pl.normal.y, pl.normal.z, pl.d,    b.min.x,
                           b.min.y,     b.min.z,     b.max.x,     b.max.y, b.max.z};
    for (int k = 0; k < 10; ++k) {
      EXPECT_TRUE(same_bits(std::strtod(row[5 + k]->c_str(), nullptr), want[k]))
          << "face " << i << " column " << 5 + k << ": " << *row[5 + k];
    }
  }
  auto uses = store_->query(
      "SELECT loop_key, ord, edge_key, reversed, radial_ord FROM loop_edges ORDER BY loop_key, "
      "ord");
  ASSERT_OK(uses);
  ASSERT_EQ(uses->rows.size(), rows.uses.size());
  for (std::size_t i = 0; i < rows.uses.size(); ++i) {
    const auto& u = rows.uses[i];
    EXPECT_EQ(uses->rows[i],
              (std::vector<std::optional<std::string>>{
                  std::to_string(u.loop), std::to_string(u.ord), std::to_string(u.edge),
                  std::string(u.reversed ? "1" : "0"), std::to_string(u.radial_ord)}));
  }
  auto loops = store_->query("SELECT loop_key, face_key, ord, kind, point_vertex FROM loops");
  ASSERT_OK(loops);
  ASSERT_EQ(loops->rows.size(), rows.loops.size());
  EXPECT_EQ(*loops->rows[1][3], "outer");
  EXPECT_FALSE(loops->rows[1][4].has_value());
  auto edges = store_->query("SELECT COUNT(*), MIN(edge_type), MAX(edge_type) FROM edges");
  ASSERT_OK(edges);
  EXPECT_EQ(edges->rows[0],
            (std::vector<std::optional<std::string>>{std::to_string(rows.edges.size()), "1", "1"}));
}

CELLFORGE_BACKENDS(Views);

}  // namespace
}  // namespace cellforge::testing
