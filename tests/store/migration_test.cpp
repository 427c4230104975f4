// Databases made by older cellforge versions are migrated when opened: a
// database of schema version 1 (rowid tables with REAL columns, no face boxes,
// no spatial index, the loop_edges_by_edge index), made here with that version's
// DDL and rows, opens on both backends, and its models, versions and objects
// come back intact; the face boxes and the spatial index are built on the way.
#include <gtest/gtest.h>

#include <filesystem>
#include <tuple>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/property.h"
#include "cellforge/topo/snapshot.h"
#include "store/connection.h"
#include "store/model_rows.h"
#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge::testing {
namespace {

using Migration = StoreTest;

#define EXPECT_OK(expr)                         \
  do {                                          \
    const auto& r_ = (expr);                    \
    EXPECT_TRUE(r_.ok()) << r_.error().message; \
  } while (0)

// The DDL of schema version 1, as it was; {serial} is the backend's
// auto-numbered key.
constexpr const char* kSchema1[] = {
    R"(CREATE TABLE objects (
  id {serial},
  name TEXT NOT NULL UNIQUE))",
    R"(CREATE TABLE volumes (
  id {serial},
  name TEXT NOT NULL,
  version INTEGER NOT NULL,
  type TEXT NOT NULL,
  cx DOUBLE PRECISION NOT NULL, cy DOUBLE PRECISION NOT NULL, cz DOUBLE PRECISION NOT NULL,
  volume DOUBLE PRECISION NOT NULL,
  area DOUBLE PRECISION NOT NULL,
  min_x DOUBLE PRECISION NOT NULL, min_y DOUBLE PRECISION NOT NULL, min_z DOUBLE PRECISION NOT NULL,
  max_x DOUBLE PRECISION NOT NULL, max_y DOUBLE PRECISION NOT NULL, max_z DOUBLE PRECISION NOT NULL,
  source TEXT NOT NULL,
  created TEXT NOT NULL,
  n_vertices BIGINT NOT NULL, n_edges BIGINT NOT NULL, n_faces BIGINT NOT NULL,
  n_loops BIGINT NOT NULL, n_cells BIGINT NOT NULL, n_groups BIGINT NOT NULL,
  UNIQUE (name, version)))",
    R"(CREATE TABLE object_volumes (
  object_id BIGINT NOT NULL,
  ord INTEGER NOT NULL,
  volume_name TEXT NOT NULL,
  PRIMARY KEY (object_id, ord)))",
    R"(CREATE INDEX object_volumes_by_name ON object_volumes (volume_name))",
    R"(CREATE TABLE model_groups (
  volume_id BIGINT NOT NULL,
  group_key INTEGER NOT NULL,
  name TEXT NOT NULL,
  PRIMARY KEY (volume_id, group_key)))",
    R"(CREATE TABLE parameters (
  volume_id BIGINT NOT NULL,
  group_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  name TEXT NOT NULL,
  value TEXT NOT NULL,
  PRIMARY KEY (volume_id, group_key, ord)))",
    R"(CREATE TABLE cells (
  volume_id BIGINT NOT NULL,
  cell_key INTEGER NOT NULL,
  group_key INTEGER NOT NULL,
  PRIMARY KEY (volume_id, cell_key)))",
    R"(CREATE TABLE vertices (
  volume_id BIGINT NOT NULL,
  vertex_key INTEGER NOT NULL,
  x DOUBLE PRECISION NOT NULL, y DOUBLE PRECISION NOT NULL, z DOUBLE PRECISION NOT NULL,
  group_key INTEGER NOT NULL,
  PRIMARY KEY (volume_id, vertex_key)))",
    R"(CREATE TABLE edges (
  volume_id BIGINT NOT NULL,
  edge_key INTEGER NOT NULL,
  start_vertex INTEGER NOT NULL,
  end_vertex INTEGER NOT NULL,
  edge_type INTEGER NOT NULL,
  uses INTEGER NOT NULL,
  PRIMARY KEY (volume_id, edge_key)))",
    R"(CREATE TABLE surfaces (
  volume_id BIGINT NOT NULL,
  surface_key INTEGER NOT NULL,
  kind TEXT NOT NULL,
  cx DOUBLE PRECISION NOT NULL, cy DOUBLE PRECISION NOT NULL, cz DOUBLE PRECISION NOT NULL,
  ax DOUBLE PRECISION NOT NULL, ay DOUBLE PRECISION NOT NULL, az DOUBLE PRECISION NOT NULL,
  radius DOUBLE PRECISION NOT NULL, radius2 DOUBLE PRECISION NOT NULL,
  height DOUBLE PRECISION NOT NULL, segments INTEGER NOT NULL,
  PRIMARY KEY (volume_id, surface_key)))",
    R"(CREATE TABLE faces (
  volume_id BIGINT NOT NULL,
  face_key INTEGER NOT NULL,
  group_key INTEGER NOT NULL,
  front_cell INTEGER,
  back_cell INTEGER,
  surface_key INTEGER,
  nx DOUBLE PRECISION NOT NULL, ny DOUBLE PRECISION NOT NULL, nz DOUBLE PRECISION NOT NULL,
  d DOUBLE PRECISION NOT NULL,
  PRIMARY KEY (volume_id, face_key)))",
    R"(CREATE TABLE loops (
  volume_id BIGINT NOT NULL,
  loop_key INTEGER NOT NULL,
  face_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  kind TEXT NOT NULL,
  point_vertex INTEGER,
  PRIMARY KEY (volume_id, loop_key)))",
    R"(CREATE TABLE loop_edges (
  volume_id BIGINT NOT NULL,
  loop_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  edge_key INTEGER NOT NULL,
  reversed INTEGER NOT NULL,
  radial_ord INTEGER NOT NULL,
  PRIMARY KEY (volume_id, loop_key, ord)))",
    R"(CREATE INDEX loop_edges_by_edge ON loop_edges (volume_id, edge_key))",
    R"(CREATE VIEW latest_volumes AS
SELECT * FROM volumes v
WHERE v.version = (SELECT MAX(w.version) FROM volumes w WHERE w.name = v.name))",
    R"(CREATE VIEW volume_faces AS SELECT volume_id, face_key FROM faces)",
    R"(CREATE VIEW face_loops AS SELECT volume_id, face_key, loop_key, ord, kind FROM loops)",
    R"(CREATE VIEW edge_vertices AS
SELECT volume_id, edge_key, 0 AS end_index, start_vertex AS vertex_key FROM edges
UNION ALL
SELECT volume_id, edge_key, 1 AS end_index, end_vertex AS vertex_key FROM edges)",
    R"(CREATE VIEW face_edge_points AS
SELECT v.name AS volume, v.version AS version, l.face_key AS face, u.edge_key AS edge,
       u.reversed AS direction, e.edge_type AS edge_type, p.vertex_key AS point,
       p.x AS x, p.y AS y, p.z AS z, s.end_index AS start_end,
       u.loop_key AS loop, u.ord AS use_ord
FROM volumes v
JOIN loop_edges u ON u.volume_id = v.id
JOIN loops l ON l.volume_id = u.volume_id AND l.loop_key = u.loop_key
JOIN edges e ON e.volume_id = u.volume_id AND e.edge_key = u.edge_key
CROSS JOIN (SELECT 0 AS end_index UNION ALL SELECT 1 AS end_index) s
JOIN vertices p ON p.volume_id = u.volume_id
  AND p.vertex_key = CASE s.end_index WHEN 0 THEN e.start_vertex ELSE e.end_vertex END)",
};

std::unique_ptr<store::Connection> connect(const std::string& backend, const std::string& db) {
  auto c = backend == "sqlite" ? store::open_sqlite(db) : store::open_postgresql(db);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return c ? std::move(c.value()) : nullptr;
}

// A database of schema version 1 in place of the test's (a new file; the test's
// schema dropped and made again).
std::unique_ptr<store::Connection> schema1_database(const std::string& backend,
                                                    const std::string& db) {
  if (backend == "sqlite") {
    for (const char* ext : {"", "-wal", "-shm"}) std::filesystem::remove(db + ext);
  }
  auto c = connect(backend, db);
  if (!c) return nullptr;
  if (backend == "postgresql") {
    std::string schema;
    EXPECT_OK(
        c->select("SELECT current_schema()", {}, [&](const store::Row& r) { schema = r.s(0); }));
    EXPECT_OK(c->exec("DROP SCHEMA " + schema + " CASCADE"));
    EXPECT_OK(c->exec("CREATE SCHEMA " + schema));
  }
  const std::string serial = backend == "sqlite"
                                 ? "INTEGER PRIMARY KEY"
                                 : "BIGINT GENERATED BY DEFAULT AS IDENTITY PRIMARY KEY";
  EXPECT_OK(c->exec("CREATE TABLE cellforge_schema (version INTEGER NOT NULL)"));
  EXPECT_OK(c->exec("INSERT INTO cellforge_schema (version) VALUES (1)"));
  for (std::string sql : kSchema1) {
    if (const auto at = sql.find("{serial}"); at != std::string::npos) sql.replace(at, 8, serial);
    EXPECT_OK(c->exec(sql));
  }
  return c;
}

// Writes m as version `version` of `name` the way schema 1 did (one INSERT per
// row, faces without boxes).
void put_v1(store::Connection& c, const std::string& name, int version, const Model& m) {
  VolumeInfo v = store::summarize(m);
  const store::ModelRows r = store::to_rows(m);
  std::int64_t id = -1;
  ASSERT_OK(c.select(
      "INSERT INTO volumes (name, version, type, cx, cy, cz, volume, area, min_x, min_y, min_z, "
      "max_x, max_y, max_z, source, created, n_vertices, n_edges, n_faces, n_loops, n_cells, "
      "n_groups) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, "
      "$17, $18, $19, $20, $21, $22) RETURNING id",
      {name,
       std::int64_t{version},
       v.type,
       v.centroid.x,
       v.centroid.y,
       v.centroid.z,
       v.volume,
       v.area,
       v.bbox_min.x,
       v.bbox_min.y,
       v.bbox_min.z,
       v.bbox_max.x,
       v.bbox_max.y,
       v.bbox_max.z,
       std::string("cube();"),
       std::string("2026-11-30T12:00:00.000Z"),
       v.vertices,
       v.edges,
       v.faces,
       v.loops,
       v.cells,
       v.groups},
      [&](const store::Row& row) { id = row.i(0); }));
  auto opt = [](std::int64_t k) { return k < 0 ? store::Value{} : store::Value{k}; };
  using I = std::int64_t;
  for (std::size_t i = 0; i < r.groups.size(); ++i) {
    ASSERT_OK(c.exec("INSERT INTO model_groups VALUES ($1, $2, $3)", {id, I(i), r.groups[i].name}));
  }
  for (std::size_t i = 0, ord = 0; i < r.parameters.size(); ++i) {
    ord = i > 0 && r.parameters[i - 1].group == r.parameters[i].group ? ord + 1 : 0;
    ASSERT_OK(c.exec(
        "INSERT INTO parameters VALUES ($1, $2, $3, $4, $5)",
        {id, I(r.parameters[i].group), I(ord), r.parameters[i].name, r.parameters[i].value}));
  }
  for (std::size_t i = 0; i < r.cells.size(); ++i) {
    ASSERT_OK(c.exec("INSERT INTO cells VALUES ($1, $2, $3)", {id, I(i), I(r.cells[i])}));
  }
  for (std::size_t i = 0; i < r.vertices.size(); ++i) {
    const auto& p = r.vertices[i];
    ASSERT_OK(c.exec("INSERT INTO vertices VALUES ($1, $2, $3, $4, $5, $6)",
                     {id, I(i), p.p.x, p.p.y, p.p.z, I(p.group)}));
  }
  for (std::size_t i = 0; i < r.edges.size(); ++i) {
    ASSERT_OK(c.exec("INSERT INTO edges VALUES ($1, $2, $3, $4, 1, $5)",
                     {id, I(i), I(r.edges[i].start), I(r.edges[i].end), I(r.edge_uses[i])}));
  }
  for (std::size_t i = 0; i < r.surfaces.size(); ++i) {
    const Surface& s = r.surfaces[i];
    ASSERT_OK(c.exec(
        "INSERT INTO surfaces VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13)",
        {id, I(i), s.kind, s.center.x, s.center.y, s.center.z, s.axis.x, s.axis.y, s.axis.z,
         s.radius, s.radius2, s.height, I(s.segments)}));
  }
  for (std::size_t i = 0; i < r.faces.size(); ++i) {
    const auto& f = r.faces[i];
    const auto& pl = r.planes[i];
    ASSERT_OK(c.exec("INSERT INTO faces VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10)",
                     {id, I(i), I(f.group), opt(f.front), opt(f.back), opt(f.surface), pl.normal.x,
                      pl.normal.y, pl.normal.z, pl.d}));
  }
  for (std::size_t i = 0; i < r.loops.size(); ++i) {
    const auto& l = r.loops[i];
    ASSERT_OK(c.exec("INSERT INTO loops VALUES ($1, $2, $3, $4, $5, $6)",
                     {id, I(i), I(l.face), I(l.ord), std::string(l.ord == 0 ? "outer" : "inner"),
                      opt(l.point_vertex)}));
  }
  for (const auto& u : r.uses) {
    ASSERT_OK(c.exec("INSERT INTO loop_edges VALUES ($1, $2, $3, $4, $5, $6)",
                     {id, I(u.loop), I(u.ord), I(u.edge), I(u.reversed ? 1 : 0), I(u.radial_ord)}));
  }
}

int schema_version(store::Connection& c) {
  int v = -1;
  EXPECT_OK(c.select("SELECT MAX(version) FROM cellforge_schema", {},
                     [&](const store::Row& r) { v = static_cast<int>(r.i(0)); }));
  return v;
}

TEST_P(Migration, Schema1OpensWithItsModelsIntact) {
  store_.reset();
  const Model cube = build(unit_cube()), holed = build(cube_with_through_hole()),
              pages = build(book()), wired = build(cube_with_wire_and_point());
  {
    auto c = schema1_database(GetParam(), db_);
    ASSERT_TRUE(c);
    ASSERT_OK(c->begin_write("fill"));
    put_v1(*c, "cube", 1, cube);
    put_v1(*c, "cube", 2, holed);
    put_v1(*c, "book", 1, pages);
    put_v1(*c, "wired", 1, wired);
    ASSERT_OK(c->exec("INSERT INTO objects (name) VALUES ('scene')"));
    ASSERT_OK(c->exec("INSERT INTO object_volumes SELECT id, 0, 'cube' FROM objects"));
    ASSERT_OK(c->exec("INSERT INTO object_volumes SELECT id, 1, 'book' FROM objects"));
    ASSERT_OK(c->commit());
    ASSERT_EQ(schema_version(*c), 1);
  }
  auto opened = open_store(db_);
  ASSERT_OK(opened);
  store_ = std::move(opened.value());
  {
    auto c = connect(GetParam(), db_);
    ASSERT_TRUE(c);
    EXPECT_EQ(schema_version(*c), 4);
  }
  for (const auto& [name, version, model] :
       {std::tuple<const char*, int, const Model*>{"cube", 1, &cube},
        {"cube", 2, &holed},
        {"book", 1, &pages},
        {"wired", 1, &wired}}) {
    SCOPED_TRACE(std::string(name) + " version " + std::to_string(version));
    auto got = store_->get(name, version);
    ASSERT_OK(got);
    EXPECT_VALID(got.value());
    expect_same_model(*model, got.value());
    auto info = store_->info(name, version);
    ASSERT_OK(info);
    EXPECT_EQ(info->source, "cube();");
    EXPECT_EQ(info->faces, static_cast<std::int64_t>(model->num_faces()));
  }
  auto versions = store_->versions("cube");
  ASSERT_OK(versions);
  EXPECT_EQ(versions->size(), 2u);
  auto scene = store_->get_object("scene");
  ASSERT_OK(scene);
  EXPECT_EQ(scene.value(), (std::vector<std::string>{"cube", "book"}));

  // The face boxes and the spatial index were built: the unit cube's faces that
  // meet the slab x <= 0.25 are all but the face x = 1.
  auto in_box = store_->faces_in_box("cube", {{-1, -1, -1}, {0.25, 2, 2}}, 1);
  ASSERT_OK(in_box);
  EXPECT_EQ(in_box->size(), 5u);
  // Each migrated face box is the one a save computes.
  auto boxes = store_->query(
      "SELECT f.min_x, f.min_y, f.min_z, f.max_x, f.max_y, f.max_z FROM faces f JOIN volumes v "
      "ON v.id = f.volume_id WHERE v.name = 'cube' AND v.version = 2 ORDER BY f.face_key");
  ASSERT_OK(boxes);
  const auto want = store::to_rows(holed).boxes;
  ASSERT_EQ(boxes->rows.size(), want.size());
  for (std::size_t f = 0; f < want.size(); ++f) {
    const auto& row = boxes->rows[f];
    const QueryBox& b = want[f];
    const double c[] = {b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z};
    for (int k = 0; k < 6; ++k) EXPECT_EQ(std::stod(*row[k]), c[k]) << "face " << f << " " << k;
  }
  auto volumes = store_->volumes_in_box({{4.5, 4.5, 4.5}, {5.5, 5.5, 5.5}});
  ASSERT_OK(volumes);
  ASSERT_EQ(volumes->size(), 1u);  // the isolated point (5,5,5) of "wired"
  EXPECT_EQ(volumes->front().name, "wired");

  // Seed 004's Table 1 over the migrated rows, as user SQL.
  auto table1 = store_->query(
      "SELECT face, edge, direction FROM face_edge_points WHERE volume = 'cube' AND version = 1");
  ASSERT_OK(table1);
  EXPECT_EQ(table1->rows.size(), 48u);

  // The database goes on: a new version after the migrated ones, removal.
  auto put = store_->put("cube", cube);
  ASSERT_OK(put);
  EXPECT_EQ(put->version, 3);
  auto back = store_->get("cube");
  ASSERT_OK(back);
  expect_same_model(cube, back.value());
  auto removed = store_->remove("book");
  ASSERT_OK(removed);
  EXPECT_EQ(removed.value(), 1);
  EXPECT_FALSE(store_->get("book").ok());
}

// The migration is one transaction: one that fails half-way (here a table in the
// way of a rename, after the views were dropped) leaves version 1 as it was, and
// the next open migrates.
TEST_P(Migration, AFailedMigrationChangesNothing) {
  store_.reset();
  const Model cube = build(unit_cube());
  {
    auto c = schema1_database(GetParam(), db_);
    ASSERT_TRUE(c);
    put_v1(*c, "cube", 1, cube);
    ASSERT_OK(c->exec("CREATE TABLE loops_old (x INTEGER)"));
  }
  auto opened = open_store(db_);
  ASSERT_FALSE(opened.ok());
  {
    auto c = connect(GetParam(), db_);
    ASSERT_TRUE(c);
    EXPECT_EQ(schema_version(*c), 1);
    std::int64_t rows = -1;
    ASSERT_OK(c->select("SELECT COUNT(*) FROM face_edge_points", {},
                        [&](const store::Row& r) { rows = r.i(0); }));
    EXPECT_EQ(rows, 48);  // the views of version 1 are back, over its rows
    ASSERT_OK(c->exec("DROP TABLE loops_old"));
  }
  opened = open_store(db_);
  ASSERT_OK(opened);
  store_ = std::move(opened.value());
  auto got = store_->get("cube");
  ASSERT_OK(got);
  expect_same_model(cube, got.value());
}

// Schema 4 added three tables to schema 3 (properties, property_values,
// attachments) and changed nothing else, so a database of version 3 is this
// one without them. It opens with its models intact and then keeps properties
// and attachments, which user SQL can read.
TEST_P(Migration, Schema3GainsPropertiesAndAttachments) {
  const Model cube = build(unit_cube()), pages = build(book());
  ASSERT_OK(store_->put("cube", cube, {.source = "cube();"}));
  ASSERT_OK(store_->put("book", pages));
  store_.reset();
  {
    auto c = connect(GetParam(), db_);
    ASSERT_TRUE(c);
    ASSERT_OK(c->begin_write("to 3"));
    for (const char* t : {"properties", "property_values", "attachments"})
      ASSERT_OK(c->exec(std::string("DROP TABLE ") + t));
    ASSERT_OK(c->exec("UPDATE cellforge_schema SET version = 3"));
    ASSERT_OK(c->commit());
  }
  auto opened = open_store(db_);
  ASSERT_OK(opened);
  store_ = std::move(opened.value());
  {
    auto c = connect(GetParam(), db_);
    ASSERT_TRUE(c);
    EXPECT_EQ(schema_version(*c), 4);
  }
  for (const auto& [name, model] : {std::pair<const char*, const Model*>{"cube", &cube}, {"book", &pages}}) {
    SCOPED_TRACE(name);
    auto got = store_->get(name);
    ASSERT_OK(got);
    expect_same_model(*model, got.value());
    auto attached = store_->get_attachments(name);
    ASSERT_OK(attached);
    EXPECT_TRUE(attached->empty());
  }
  EXPECT_EQ(store_->info("cube")->source, "cube();");
  // The views stand: seed 004's Table 1 over the old rows.
  auto table1 = store_->query("SELECT face FROM face_edge_points WHERE volume = 'cube'");
  ASSERT_OK(table1);
  EXPECT_EQ(table1->rows.size(), 48u);

  Model tagged = cube;
  auto tag = add_property<FaceProperty<std::int32_t>>(tagged, "tag", -1);
  ASSERT_OK(tag);
  tag->set(*tagged.faces().begin(), 5);
  ASSERT_OK(store_->put("cube", tagged, {.attachments = {{"note", 1, "made before 4"}}}));
  auto back = store_->get("cube");
  ASSERT_OK(back);
  EXPECT_EQ(snapshot(back.value()), snapshot(tagged));
  EXPECT_EQ(store_->get_attachments("cube").value(),
            (std::vector<Attachment>{{"note", 1, "made before 4"}}));
  auto rows = store_->query(
      "SELECT p.name, v.element_key, v.int_value FROM properties p JOIN property_values v ON "
      "v.volume_id = p.volume_id AND v.property_key = p.property_key ORDER BY v.element_key");
  ASSERT_OK(rows);
  ASSERT_EQ(rows->rows.size(), 2u);  // the default and face 0
  EXPECT_EQ(*rows->rows[1][2], "5");
  auto notes = store_->query("SELECT data FROM attachments");
  ASSERT_OK(notes);
  ASSERT_EQ(notes->rows.size(), 1u);
  EXPECT_EQ(*notes->rows[0][0], "made before 4");
}

TEST_P(Migration, NewerSchemaIsRefused) {
  store_.reset();
  {
    auto c = connect(GetParam(), db_);
    ASSERT_TRUE(c);
    ASSERT_OK(c->exec("UPDATE cellforge_schema SET version = 99"));
  }
  auto opened = open_store(db_);
  ASSERT_FALSE(opened.ok());
  EXPECT_NE(opened.error().message.find("schema version 99"), std::string::npos)
      << opened.error().message;
}

CELLFORGE_BACKENDS(Migration);

}  // namespace
}  // namespace cellforge::testing
