// Spatial queries and partial loads, on both backends: faces_in_box and
// volumes_in_box agree with a brute-force scan of the model on seeded random
// boxes (closed boxes: touching counts); the documented SQL over face_tiles runs
// from query(); get_faces_where loads exactly the faces its condition names, as
// a valid sheet model with the stored geometry, and runs user SQL read-only.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>
#include <set>

#include "cellforge/topo/builder.h"
#include "store/connection.h"
#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using Spatial = StoreTest;

QueryBox box_of(const std::vector<Vec3>& pts) {
  QueryBox b{pts.front(), pts.front()};
  for (const Vec3& p : pts) {
    b.min = {std::min(b.min.x, p.x), std::min(b.min.y, p.y), std::min(b.min.z, p.z)};
    b.max = {std::max(b.max.x, p.x), std::max(b.max.y, p.y), std::max(b.max.z, p.z)};
  }
  return b;
}

bool meets(const QueryBox& a, const QueryBox& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y &&
         a.min.z <= b.max.z && b.min.z <= a.max.z;
}

// The box of every face, by key (the model has no free slots: key = id order).
std::vector<QueryBox> face_boxes(const Model& m) {
  std::vector<QueryBox> out;
  for (FaceId f : m.faces()) {
    std::vector<Vec3> pts;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      for (const Vec3& p : m.loop_points(l)) pts.push_back(p);
    }
    out.push_back(box_of(pts));
  }
  return out;
}

std::vector<std::uint32_t> brute_force(const std::vector<QueryBox>& boxes, const QueryBox& q) {
  std::vector<std::uint32_t> out;
  for (std::uint32_t k = 0; k < boxes.size(); ++k) {
    if (meets(boxes[k], q)) out.push_back(k);
  }
  return out;
}

// Two grid sheets of 2 * 40^2 faces, one above the other, in one model.
Model two_sheets() {
  Model m = grid_sheet(40);
  const Model upper = grid_sheet(40, 2.5);
  MeshInput in;
  for (VertexId v : upper.vertices()) in.positions.push_back(upper.position(v));
  for (FaceId f : upper.faces()) {
    std::vector<std::uint32_t> loop;
    for (VertexId v : upper.loop_vertices(upper.outer_loop(f))) loop.push_back(v.value);
    in.faces.push_back({{loop}});
  }
  in.group_name = "upper";
  EXPECT_TRUE(build_mesh(m, in).ok());
  return m;
}

TEST_P(Spatial, FacesInBoxAgreeWithBruteForce) {
  const Model m = two_sheets();
  ASSERT_OK(store_->put("sheets", m));
  const std::vector<QueryBox> boxes = face_boxes(m);
  std::mt19937 rng(20);  // printed by the trace below
  std::uniform_real_distribution<double> at(-0.5, 4.5), size(0, 1.5), z(-0.5, 3.5);
  std::size_t nonempty = 0;
  for (int trial = 0; trial < 150; ++trial) {
    SCOPED_TRACE("seed 20, trial " + std::to_string(trial));
    QueryBox q;
    if (trial % 3 == 0) {
      // Corners on a vertex: faces that only touch the box are in.
      const Vec3 c = m.position(VertexId(static_cast<std::uint32_t>(rng() % m.num_vertices())));
      q = {c, {c.x + size(rng), c.y + size(rng), c.z + size(rng)}};
    } else {
      q.min = {at(rng), at(rng), z(rng)};
      q.max = {q.min.x + size(rng), q.min.y + size(rng), q.min.z + size(rng)};
    }
    auto got = store_->faces_in_box("sheets", q);
    ASSERT_OK(got);
    const auto want = brute_force(boxes, q);
    EXPECT_EQ(got.value(), want);
    nonempty += !want.empty();
  }
  EXPECT_GT(nonempty, 50u);  // the boxes were not all misses
}

TEST_P(Spatial, VolumesInBoxAgreeWithBruteForce) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> at(-10, 10), size(0.1, 4);
  std::map<std::string, QueryBox> stored;
  for (int k = 0; k < 12; ++k) {
    const Vec3 lo{at(rng), at(rng), at(rng)};
    MeshInput in;
    add_box(in, lo, {lo.x + size(rng), lo.y + size(rng), lo.z + size(rng)}, 0);
    in.volumes = 1;
    const Model m = build(in);
    const std::string name = "box" + std::to_string(k);
    auto info = store_->put(name, m);
    ASSERT_OK(info);
    stored[name] = {info->bbox_min, info->bbox_max};
  }
  ASSERT_OK(store_->put("nothing", Model()));  // no box: never found
  for (int trial = 0; trial < 60; ++trial) {
    SCOPED_TRACE("seed 7, trial " + std::to_string(trial));
    QueryBox q;
    q.min = {at(rng), at(rng), at(rng)};
    q.max = {q.min.x + size(rng), q.min.y + size(rng), q.min.z + size(rng)};
    if (trial == 0) q = stored["box3"];  // exactly one stored box: it meets itself
    auto got = store_->volumes_in_box(q);
    ASSERT_OK(got);
    std::vector<std::string> names, want;
    for (const VolumeInfo& v : got.value()) names.push_back(v.name);
    for (const auto& [name, b] : stored) {
      if (meets(b, q)) want.push_back(name);
    }
    EXPECT_EQ(names, want);
  }
}

// The query docs/database.md gives for "the faces of volume V in a box", run as
// user SQL.
TEST_P(Spatial, DocumentedSqlUsesTheIndex) {
  const Model m = grid_sheet(30);
  ASSERT_OK(store_->put("grid", m));
  const QueryBox q{{0.95, 1.05, -1}, {1.45, 1.2, 1}};
  const std::string exact =
      " AND f.max_x >= 0.95 AND f.min_x <= 1.45 AND f.max_y >= 1.05 AND f.min_y <= 1.2"
      " AND f.max_z >= -1 AND f.min_z <= 1 ORDER BY f.face_key";
  const std::string volume = "t.volume_id = (SELECT id FROM latest_volumes WHERE name = 'grid')";
  const std::string sql =
      GetParam() == "sqlite"
          ? "SELECT f.face_key FROM face_tiles t CROSS JOIN faces f"
            "  ON f.volume_id = t.volume_id AND f.face_key BETWEEN t.first_face AND t.last_face"
            " WHERE " +
                volume +
                " AND t.max_x >= 0.95 AND t.min_x <= 1.45 AND t.max_y >= 1.05 AND t.min_y <= 1.2"
                " AND t.max_z >= -1 AND t.min_z <= 1" +
                exact
          : "SELECT f.face_key FROM face_tiles t"
            "  CROSS JOIN LATERAL face_range(t.volume_id, t.first_face, t.last_face) f"
            " WHERE " +
                volume + " AND t.box && cube(ARRAY[0.95, 1.05, -1], ARRAY[1.45, 1.2, 1])" + exact;
  auto r = store_->query(sql);
  ASSERT_OK(r);
  if (GetParam() == "sqlite") {  // the R*Tree answers the tile test (PostgreSQL may
                                 // rightly scan 29 tiles instead of using GiST)
    auto plan = store_->query("EXPLAIN QUERY PLAN " + sql);
    ASSERT_OK(plan);
    std::string text;
    for (const auto& row : plan->rows) text += (row.back() ? *row.back() : "") + "\n";
    EXPECT_NE(text.find("SCAN t VIRTUAL TABLE INDEX 2:"), std::string::npos) << text;
  } else {  // face_range reads the blocks of each tile's faces by their key
    // (EXPLAIN is not a query, so it runs on a connection of the store's role)
    auto c = store::open_postgresql(db_);
    ASSERT_OK(c);
    std::string text;
    ASSERT_OK(c.value()->select("EXPLAIN " + sql, {},
                                [&](const store::Row& row) { text += row.s(0) + "\n"; }));
    EXPECT_NE(text.find("Index Scan using face_blocks_pkey"), std::string::npos) << text;
  }
  std::vector<std::uint32_t> keys;
  for (const auto& row : r->rows) keys.push_back(static_cast<std::uint32_t>(std::stoul(*row[0])));
  const auto want = brute_force(face_boxes(m), q);
  EXPECT_FALSE(want.empty());
  EXPECT_EQ(keys, want);
  auto tiles = store_->query("SELECT COUNT(*) FROM face_tiles");
  ASSERT_OK(tiles);
  EXPECT_EQ(*tiles->rows[0][0], std::to_string((m.num_faces() + 63) / 64));
  ASSERT_OK(store_->remove("grid"));
  tiles = store_->query("SELECT COUNT(*) FROM face_tiles");
  ASSERT_OK(tiles);
  EXPECT_EQ(*tiles->rows[0][0], "0");
  auto boxes = store_->query("SELECT COUNT(*) FROM volume_boxes");
  ASSERT_OK(boxes);
  EXPECT_EQ(*boxes->rows[0][0], "0");
}

std::vector<FaceId> all_faces(const Model& m) {
  std::vector<FaceId> out;
  for (FaceId f : m.faces()) out.push_back(f);
  return out;
}

// The outer-loop positions of every face, as a set: what a partial load must
// hold exactly.
std::multiset<std::vector<Vec3>> face_loops(const Model& m, const std::vector<FaceId>& faces) {
  std::multiset<std::vector<Vec3>> out;
  for (FaceId f : faces) {
    std::vector<Vec3> pts;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      for (const Vec3& p : m.loop_points(l)) pts.push_back(p);
      pts.push_back({-1e300, 0, 0});  // between loops
    }
    out.insert(pts);
  }
  return out;
}

TEST_P(Spatial, PartialLoadHoldsExactlyTheNamedFaces) {
  const Model m = two_sheets();
  ASSERT_OK(store_->put("sheets", m));
  const std::vector<QueryBox> boxes = face_boxes(m);
  const std::vector<FaceId> all = all_faces(m);

  struct Case {
    std::string condition;
    std::function<bool(std::uint32_t key, FaceId f)> wanted;
  };
  const Case cases[] = {
      {"f.group_key = 1", [&](std::uint32_t, FaceId f) { return m.group_of(f).value == 1; }},
      {"f.max_x <= 1.0 AND f.min_y >= 2.0",
       [&](std::uint32_t k, FaceId) { return boxes[k].max.x <= 1.0 && boxes[k].min.y >= 2.0; }},
      {"f.face_key % 7 = 3 AND v.name = 'sheets'",
       [&](std::uint32_t k, FaceId) { return k % 7 == 3; }},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.condition);
    auto part = store_->get_faces_where("sheets", c.condition);
    ASSERT_OK(part);
    EXPECT_VALID(part.value());
    std::vector<FaceId> wanted;
    for (std::uint32_t k = 0; k < all.size(); ++k) {
      if (c.wanted(k, all[k])) wanted.push_back(all[k]);
    }
    ASSERT_FALSE(wanted.empty());
    EXPECT_EQ(part->num_faces(), wanted.size());
    EXPECT_EQ(part->num_volumes(), 0u);  // a sheet
    EXPECT_EQ(part->num_groups(), m.num_groups());
    const std::vector<FaceId> got = all_faces(part.value());
    EXPECT_EQ(face_loops(part.value(), got), face_loops(m, wanted));
  }
  // Every face of a sheet model: the partial load is the whole model, exactly.
  auto whole = store_->get_faces_where("sheets", "1 = 1");
  ASSERT_OK(whole);
  expect_same_model(m, whole.value());
  auto none = store_->get_faces_where("sheets", "f.face_key < 0");
  ASSERT_OK(none);
  EXPECT_EQ(none->num_faces(), 0u);
  EXPECT_FALSE(store_->get_faces_where("absent", "1 = 1").ok());
}

TEST_P(Spatial, PartialLoadOfASolidKeepsStoredDirections) {
  const Model m = build(two_cubes_sharing_face());
  ASSERT_OK(store_->put("cubes", m));
  // The shared face and the faces of the lower cube's bottom half: a sheet
  // through a non-manifold-free cut of a solid.
  auto part = store_->get_faces_where("cubes", "f.min_z = 0 OR f.max_z <= 1");
  ASSERT_OK(part);
  EXPECT_VALID(part.value());
  std::vector<FaceId> wanted;
  for (FaceId f : m.faces()) {
    const QueryBox b = face_boxes(m)[f.value];
    if (b.min.z == 0 || b.max.z <= 1) wanted.push_back(f);
  }
  EXPECT_EQ(part->num_faces(), wanted.size());
  const std::vector<FaceId> got = all_faces(part.value());
  EXPECT_EQ(face_loops(part.value(), got), face_loops(m, wanted));
}

TEST_P(Spatial, PartialLoadConditionsRunReadOnly) {
  ASSERT_OK(store_->put("cube", build(unit_cube())));
  for (const char* condition : {"1 = 1); DROP TABLE volumes; --", "1 = 1; DELETE FROM faces",
                                "f.face_key IN (DELETE FROM faces RETURNING face_key)", "no_such"}) {
    SCOPED_TRACE(condition);
    auto r = store_->get_faces_where("cube", condition);
    EXPECT_FALSE(r.ok());
    if (!r) {
      EXPECT_EQ(r.error().code, ErrorCode::kDatabase);
    }
  }
  auto faces = store_->query("SELECT COUNT(*) FROM faces");
  ASSERT_OK(faces);
  EXPECT_EQ(*faces->rows[0][0], "6");
  auto part = store_->get_faces_where("cube", "(SELECT COUNT(*) FROM volumes) = 1 AND f.nz = 1");
  ASSERT_OK(part);
  EXPECT_EQ(part->num_faces(), 1u);
}

CELLFORGE_BACKENDS(Spatial);

}  // namespace
}  // namespace cellforge::testing
