// Versions, listing, removal, seed 004's Get* calls, the Table 1 view, read-only
// SQL and hostile names, on both backends.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <thread>

#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using StoreOps = StoreTest;

std::vector<std::string> names(Store& s) {
  auto l = s.list();
  EXPECT_TRUE(l.ok()) << l.error().message;
  std::vector<std::string> out;
  if (l) {
    for (const auto& v : l.value()) out.push_back(v.name + "@" + std::to_string(v.version));
  }
  return out;
}

std::string scalar(Store& s, const std::string& sql) {
  auto r = s.query(sql);
  EXPECT_TRUE(r.ok()) << sql << ": " << r.error().message;
  if (!r || r->rows.size() != 1 || r->rows[0].size() != 1 || !r->rows[0][0]) return "?";
  return *r->rows[0][0];
}

TEST_P(StoreOps, VersionsListInfoRemove) {
  const Model cube = build(unit_cube()), holed = build(cube_with_through_hole());
  PutOptions with_source;
  with_source.source = "cube(1);";
  auto v1 = store_->put("part", cube, with_source);
  ASSERT_OK(v1);
  EXPECT_EQ(v1->version, 1);
  auto v2 = store_->put("part", holed);
  ASSERT_OK(v2);
  EXPECT_EQ(v2->version, 2);
  ASSERT_OK(store_->put("other", cube));

  EXPECT_EQ(names(*store_), (std::vector<std::string>{"other@1", "part@2"}));
  auto latest = store_->get("part");
  ASSERT_OK(latest);
  expect_same_model(holed, latest.value());
  auto first = store_->get("part", 1);
  ASSERT_OK(first);
  expect_same_model(cube, first.value());
  EXPECT_FALSE(store_->get("part", 3).ok());
  EXPECT_FALSE(store_->get("absent").ok());

  auto info = store_->info("part", 1);
  ASSERT_OK(info);
  EXPECT_EQ(info->type, "solid");
  EXPECT_EQ(info->source, "cube(1);");
  EXPECT_DOUBLE_EQ(info->volume, 1.0);
  EXPECT_DOUBLE_EQ(info->area, 6.0);
  EXPECT_NEAR(info->centroid.x, 0.5, 1e-12);
  EXPECT_NEAR(info->centroid.y, 0.5, 1e-12);
  EXPECT_NEAR(info->centroid.z, 0.5, 1e-12);
  EXPECT_EQ(info->bbox_max, (Vec3{1, 1, 1}));
  EXPECT_EQ(info->faces, 6);
  EXPECT_EQ(info->edges, 12);
  EXPECT_EQ(info->vertices, 8);
  auto holed_info = store_->info("part");
  ASSERT_OK(holed_info);
  EXPECT_DOUBLE_EQ(holed_info->volume, 27.0 - 3.0);

  auto removed = store_->remove("part");
  ASSERT_OK(removed);
  EXPECT_EQ(removed.value(), 2);
  EXPECT_EQ(names(*store_), (std::vector<std::string>{"other@1"}));
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM faces"), "6");  // only "other" is left
  auto again = store_->remove("part");
  ASSERT_OK(again);
  EXPECT_EQ(again.value(), 0);
}

TEST_P(StoreOps, RemoveOneVersion) {
  const Model cube = build(unit_cube()), holed = build(cube_with_through_hole());
  ASSERT_OK(store_->put("part", cube));
  ASSERT_OK(store_->put("part", holed));
  ASSERT_OK(store_->put("part", cube));
  PutOptions in_scene;
  in_scene.object = "scene";
  ASSERT_OK(store_->put("part", holed, in_scene));
  auto one = store_->remove_version("part", 2);
  ASSERT_OK(one);
  EXPECT_EQ(one.value(), 1);
  // The others keep their numbers and their rows; the latest is still 4.
  EXPECT_EQ(names(*store_), (std::vector<std::string>{"part@4"}));
  EXPECT_FALSE(store_->get("part", 2).ok());
  auto v1 = store_->get("part", 1);
  ASSERT_OK(v1);
  expect_same_model(cube, v1.value());
  auto v4 = store_->get("part", 4);
  ASSERT_OK(v4);
  expect_same_model(holed, v4.value());
  auto holed_info = store_->info("part", 4);
  ASSERT_OK(holed_info);
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM faces"),
            std::to_string(6 + 6 + holed_info->faces));
  auto none = store_->remove_version("part", 2);
  ASSERT_OK(none);
  EXPECT_EQ(none.value(), 0);
  EXPECT_FALSE(store_->remove_version("part", 0).ok());
  // The object keeps the name while a version is left.
  auto scene = store_->get_object("scene");
  ASSERT_OK(scene);
  EXPECT_EQ(scene->size(), 1u);
  for (int v : {1, 3, 4}) ASSERT_OK(store_->remove_version("part", v));
  EXPECT_TRUE(names(*store_).empty());
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM faces"), "0");
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM object_volumes"), "0");
}

TEST_P(StoreOps, TypesOfVolumes) {
  const std::pair<const char*, MeshInput> cases[] = {
      {"solid", two_cubes_sharing_face()},
      {"sheet", square_sheet_with_hole()},
      {"mixed", cube_with_wire_and_point()},
  };
  for (const auto& [type, in] : cases) {
    auto info = store_->put(type, build(in));
    ASSERT_OK(info);
    EXPECT_EQ(info->type, type);
  }
  MeshInput wire;
  wire.wires.push_back({add_point(wire, {0, 0, 0}), add_point(wire, {1, 0, 0})});
  auto info = store_->put("wire", build(wire));
  ASSERT_OK(info);
  EXPECT_EQ(info->type, "wire");
}

TEST_P(StoreOps, FacesEdgesPointsAlone) {
  ASSERT_OK(store_->put("holed", build(square_sheet_with_hole())));
  auto points = store_->get_points("holed");
  ASSERT_OK(points);
  EXPECT_EQ(points->size(), 8u);
  auto edges = store_->get_edges("holed");
  ASSERT_OK(edges);
  ASSERT_EQ(edges->size(), 8u);
  for (const StoredEdge& e : edges.value()) EXPECT_EQ(e.uses, 1u);
  auto faces = store_->get_faces("holed");
  ASSERT_OK(faces);
  ASSERT_EQ(faces->size(), 1u);
  const StoredFace& f = faces->front();
  ASSERT_EQ(f.loops.size(), 2u);  // the outer loop, then the hole
  EXPECT_EQ(f.loops[0].size(), 4u);
  EXPECT_EQ(f.loops[1].size(), 4u);
  EXPECT_FALSE(f.front_cell.has_value());
  EXPECT_EQ(std::abs(f.normal.z), 1.0);
  // The outer loop runs counterclockwise about the normal: the first point's
  // successor is where the geometry says.
  const Vec3 a = points->at(f.loops[0][0]).position, b = points->at(f.loops[0][1]).position;
  const Vec3 c = points->at(f.loops[0][2]).position;
  EXPECT_GT(dot(cross(b - a, c - b), f.normal), 0);
}

// Seed 004's Table 1 for the unit cube: every face, each edge of it with the
// face's direction on it, and both end points of the edge.
TEST_P(StoreOps, TableOneView) {
  ASSERT_OK(store_->put("cube", build(unit_cube())));
  auto t = store_->query(
      "SELECT face, edge, direction, edge_type, point, x, y, z, start_end FROM face_edge_points "
      "WHERE volume = 'cube' ORDER BY face, use_ord, start_end");
  ASSERT_OK(t);
  ASSERT_EQ(t->rows.size(), 6u * 4 * 2);
  EXPECT_EQ(t->columns, (std::vector<std::string>{"face", "edge", "direction", "edge_type", "point",
                                                  "x", "y", "z", "start_end"}));
  // Walking a face's uses, the end the face reaches (start_end == 1 - direction)
  // of one use is the end it leaves from on the next.
  for (std::size_t face = 0; face < 6; ++face) {
    for (std::size_t k = 0; k < 4; ++k) {
      auto row = [&](std::size_t use, int end) { return t->rows[face * 8 + use * 2 + end]; };
      const int dir = std::stoi(*row(k, 0)[2]);
      const int next_dir = std::stoi(*row((k + 1) % 4, 0)[2]);
      EXPECT_EQ(*row(k, 1 - dir)[4], *row((k + 1) % 4, next_dir)[4]) << "face " << face;
      EXPECT_EQ(*row(k, 0)[3], "1");
    }
  }
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM edge_vertices"), "24");
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM volume_faces"), "6");
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM face_loops WHERE kind = 'outer'"), "6");
}

TEST_P(StoreOps, QueriesAreReadOnly) {
  ASSERT_OK(store_->put("cube", build(unit_cube())));
  for (const char* sql : {"DELETE FROM volumes", "DROP TABLE volumes", "UPDATE vertices SET x = 7",
                          "INSERT INTO objects (name) VALUES ('x')", "SELECT 1; DROP TABLE volumes",
                          "CREATE TABLE evil (a INTEGER)"}) {
    auto r = store_->query(sql);
    EXPECT_FALSE(r.ok()) << sql;
    if (!r) {
      EXPECT_EQ(r.error().code, ErrorCode::kDatabase);
    }
  }
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM volumes"), "1");
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM vertices WHERE x = 7"), "0");
  auto r = store_->query("SELECT name, n_faces FROM latest_volumes");
  ASSERT_OK(r);
  ASSERT_EQ(r->rows.size(), 1u);
  EXPECT_EQ(*r->rows[0][0], "cube");
  EXPECT_EQ(*r->rows[0][1], "6");
  EXPECT_FALSE(store_->query("SELECT * FROM no_such_table").ok());
}

// Issue 18: user SQL reaches nothing but the model tables. PostgreSQL: no COPY
// (to a program, a file or the client), no server files, no signals to other
// backends, no configuration reloads or checkpoints, whatever the connection's
// role may do. SQLite: no fts3_tokenizer (its one-argument form hands out a heap
// pointer), no load_extension.
TEST_P(StoreOps, UserSqlReachesOnlyTheModel) {
  ASSERT_OK(store_->put("cube", build(unit_cube())));
  const std::vector<std::string> refused =
      GetParam() == "postgresql"
          ? std::vector<std::string>{"COPY (SELECT 1) TO PROGRAM 'id'",
                                     "COPY (SELECT 1) TO '/tmp/cellforge_copy_test'",
                                     "COPY (SELECT 1) TO STDOUT",
                                     "COPY volumes TO STDOUT",
                                     "SELECT pg_read_file('PG_VERSION')",
                                     "SELECT * FROM pg_ls_dir('.')",
                                     "SELECT pg_terminate_backend(pg_backend_pid())",
                                     "SELECT pg_reload_conf()",
                                     "CHECKPOINT",
                                     "SET ROLE NONE",
                                     "SELECT set_config('role', 'none', true), "
                                     "pg_read_file('PG_VERSION')",
                                     "SELECT 1) q; SELECT pg_read_file('PG_VERSION') --"}
          : std::vector<std::string>{"SELECT fts3_tokenizer('simple')",
                                     "SELECT hex(fts3_tokenizer('porter'))",
                                     "SELECT load_extension('/nonexistent')"};
  for (const std::string& sql : refused) {
    auto r = store_->query(sql);
    EXPECT_FALSE(r.ok()) << sql << " ran: " << (r ? std::to_string(r->rows.size()) + " rows" : "");
  }
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM faces"), "6");
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM face_edge_points WHERE volume = 'cube'"), "48");
  // The store itself still works after every refusal.
  ASSERT_OK(store_->put("cube", build(unit_cube())));
}

// A query that runs too long is cancelled and reported, and the store goes on.
TEST_P(StoreOps, QueriesHaveATimeLimit) {
  const std::string slow =
      GetParam() == "postgresql"
          ? "SELECT pg_sleep(30)"
          : "WITH RECURSIVE n(i) AS (SELECT 1 UNION ALL SELECT i + 1 FROM n) "
            "SELECT COUNT(*) FROM n";
  QueryOptions o;
  o.timeout = 0.5;
  const auto t0 = std::chrono::steady_clock::now();
  auto r = store_->query(slow, o);
  const double took =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("time limit"), std::string::npos) << r.error().message;
  EXPECT_LT(took, 10.0);
  EXPECT_EQ(scalar(*store_, "SELECT 1 + 1"), "2");
}

TEST_P(StoreOps, HostileNamesAreDataOrRefused) {
  const Model cube = build(unit_cube());
  const std::string stored[] = {"x'); DROP TABLE volumes;--", "Robert\"); DROP TABLE faces; --",
                                "立方体 'ü'", "%_\\", std::string(1024, 'n')};
  for (const std::string& name : stored) {
    auto put = store_->put(name, cube);
    ASSERT_TRUE(put.ok()) << name << ": " << put.error().message;
    auto got = store_->get(name);
    ASSERT_TRUE(got.ok()) << name << ": " << got.error().message;
    expect_same_model(cube, got.value());
    auto info = store_->info(name);
    ASSERT_OK(info);
    EXPECT_EQ(info->name, name);
  }
  const std::vector<std::string> before = names(*store_);
  EXPECT_EQ(before.size(), std::size(stored));
  const std::string refused[] = {
      "", std::string(1025, 'n'), "bad\xff\xfe", std::string("a\0b", 3), "line\nbreak", "\xc0\xaf",
      // C1 controls (U+0085 next line, U+009B) and the bidi marks that make a name
      // read otherwise than it is stored (U+202E right-to-left override, U+2066).
      "a\xc2\x85"
      "b",
      "c\xc2\x9b", "evil\xe2\x80\xaegpj.stl", "iso\xe2\x81\xa6x", "\xe2\x80\x8f",
      "para\xe2\x80\xa9"};
  for (const std::string& name : refused) {
    auto put = store_->put(name, cube);
    ASSERT_FALSE(put.ok()) << name;
    EXPECT_EQ(put.error().code, ErrorCode::kInvalidInput);
    EXPECT_FALSE(put.error().message.empty());
  }
  EXPECT_EQ(names(*store_), before);
  EXPECT_EQ(scalar(*store_, "SELECT COUNT(*) FROM faces"), std::to_string(6 * std::size(stored)));
  // Every call that takes a name says what is wrong with one it refuses, on both
  // backends (PostgreSQL used to print the server's encoding error and the SQL).
  for (const std::string& name : {std::string("bad\xff\xfe"), std::string("r\xe2\x80\xaeo")}) {
    const std::string why = name[0] == 'b' ? "a volume name must be valid UTF-8"
                                           : "a volume name must not hold invisible direction";
    for (const auto& error :
         {store_->get(name).ok() ? std::string() : store_->get(name).error().message,
          store_->info(name).ok() ? std::string() : store_->info(name).error().message,
          store_->remove(name).ok() ? std::string() : store_->remove(name).error().message,
          store_->remove_version(name, 1).ok() ? std::string()
                                               : store_->remove_version(name, 1).error().message,
          store_->versions(name).ok() ? std::string() : store_->versions(name).error().message,
          store_->get_faces_where(name, "1 = 1").ok()
              ? std::string()
              : store_->get_faces_where(name, "1 = 1").error().message}) {
      EXPECT_EQ(error.rfind(why, 0), 0u) << "got: " << error;
    }
  }
  // Lookups with hostile names find nothing and change nothing.
  EXPECT_FALSE(store_->get("x' OR '1'='1").ok());
  auto rm = store_->remove("x' OR '1'='1");
  ASSERT_OK(rm);
  EXPECT_EQ(rm.value(), 0);
  EXPECT_EQ(names(*store_), before);
}

TEST_P(StoreOps, Objects) {
  const Model cube = build(unit_cube());
  PutOptions in_scene;
  in_scene.object = "scene";
  ASSERT_OK(store_->put("a", cube, in_scene));
  ASSERT_OK(store_->put("b", cube, in_scene));
  ASSERT_OK(store_->put("a", cube, in_scene));  // a new version, listed once
  auto scene = store_->get_object("scene");
  ASSERT_OK(scene);
  EXPECT_EQ(scene.value(), (std::vector<std::string>{"a", "b"}));
  ASSERT_OK(store_->remove("a"));
  scene = store_->get_object("scene");
  ASSERT_OK(scene);
  EXPECT_EQ(scene.value(), (std::vector<std::string>{"b"}));
  EXPECT_FALSE(store_->get_object("nowhere").ok());
}

// Writers on separate connections save one name at once: every save becomes its
// own version and loads intact.
TEST_P(StoreOps, ConcurrentWritersKeepEverySave) {
  constexpr int kWriters = 4, kSaves = 3;
  std::vector<std::thread> threads;
  std::vector<std::string> errors(kWriters);
  for (int w = 0; w < kWriters; ++w) {
    threads.emplace_back([&, w] {
      auto store = open_store(db_);
      if (!store) {
        errors[w] = store.error().message;
        return;
      }
      for (int k = 0; k < kSaves; ++k) {
        auto put = store.value()->put("shared", grid_sheet(20 + w, k));
        if (!put) errors[w] = put.error().message;
      }
    });
  }
  for (auto& t : threads) t.join();
  for (const auto& e : errors) EXPECT_EQ(e, "");
  auto versions = store_->versions("shared");
  ASSERT_OK(versions);
  ASSERT_EQ(versions->size(), std::size_t{kWriters * kSaves});
  for (int v = 1; v <= kWriters * kSaves; ++v) {
    EXPECT_EQ(versions->at(v - 1).version, v);
    auto m = store_->get("shared", v);
    ASSERT_TRUE(m.ok()) << m.error().message;
    EXPECT_VALID(m.value());
  }
}

CELLFORGE_BACKENDS(StoreOps);

}  // namespace
}  // namespace cellforge::testing
