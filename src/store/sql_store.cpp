// SqlStore: the schema of docs/database.md and every Store operation, written
// once over a Connection (sqlite_connection.cpp, pg_connection.cpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <limits>
#include <map>
#include <thread>
#include <variant>

#include "cellforge/topo/validate.h"
#include "store/connection.h"
#include "store/model_rows.h"

namespace cellforge::store {

namespace {

// 1: the first layout; 2: SQLite tables clustered on their keys with doubles
// kept bit for bit, face boxes and the spatial indexes; 3: PostgreSQL keeps the
// five large tables as blocks under views (SQLite as in 2); 4: the property
// tables of a model (properties, property_values) and the attachments of a
// version. Older databases are migrated when opened (migrate below).
constexpr int kSchemaVersion = 4;

// Faces per entry of the face_tiles spatial index: a tile is a run of
// consecutive face keys, indexed by the box of their boxes.
constexpr std::uint32_t kTileFaces = 64;

// {serial} becomes the backend's auto-numbered primary key type, {clustered} what
// keeps a table's rows in primary-key order, {double} the type of a column that
// gives back every IEEE double bit for bit. Keep in step with docs/database.md.
constexpr const char* kSchema[] = {
    R"(CREATE TABLE objects (
  id {serial},
  name TEXT NOT NULL UNIQUE))",
    R"(CREATE TABLE volumes (
  id {serial},
  name TEXT NOT NULL,
  version INTEGER NOT NULL,
  type TEXT NOT NULL,
  cx {double} NOT NULL, cy {double} NOT NULL, cz {double} NOT NULL,
  volume {double} NOT NULL,
  area {double} NOT NULL,
  min_x {double} NOT NULL, min_y {double} NOT NULL, min_z {double} NOT NULL,
  max_x {double} NOT NULL, max_y {double} NOT NULL, max_z {double} NOT NULL,
  source TEXT NOT NULL,
  created TEXT NOT NULL,
  n_vertices BIGINT NOT NULL, n_edges BIGINT NOT NULL, n_faces BIGINT NOT NULL,
  n_loops BIGINT NOT NULL, n_cells BIGINT NOT NULL, n_groups BIGINT NOT NULL,
  UNIQUE (name, version)))",
    R"(CREATE TABLE object_volumes (
  object_id BIGINT NOT NULL,
  ord INTEGER NOT NULL,
  volume_name TEXT NOT NULL,
  PRIMARY KEY (object_id, ord)){clustered})",
    R"(CREATE INDEX object_volumes_by_name ON object_volumes (volume_name))",
    R"(CREATE TABLE model_groups (
  volume_id BIGINT NOT NULL,
  group_key INTEGER NOT NULL,
  name TEXT NOT NULL,
  PRIMARY KEY (volume_id, group_key)){clustered})",
    R"(CREATE TABLE parameters (
  volume_id BIGINT NOT NULL,
  group_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  name TEXT NOT NULL,
  value TEXT NOT NULL,
  PRIMARY KEY (volume_id, group_key, ord)){clustered})",
    R"(CREATE TABLE cells (
  volume_id BIGINT NOT NULL,
  cell_key INTEGER NOT NULL,
  group_key INTEGER NOT NULL,
  PRIMARY KEY (volume_id, cell_key)){clustered})",
    R"(CREATE TABLE vertices (
  volume_id BIGINT NOT NULL,
  vertex_key INTEGER NOT NULL,
  x {double} NOT NULL, y {double} NOT NULL, z {double} NOT NULL,
  group_key INTEGER NOT NULL,
  PRIMARY KEY (volume_id, vertex_key)){clustered})",
    R"(CREATE TABLE edges (
  volume_id BIGINT NOT NULL,
  edge_key INTEGER NOT NULL,
  start_vertex INTEGER NOT NULL,
  end_vertex INTEGER NOT NULL,
  edge_type INTEGER NOT NULL,
  uses INTEGER NOT NULL,
  PRIMARY KEY (volume_id, edge_key)){clustered})",
    R"(CREATE TABLE surfaces (
  volume_id BIGINT NOT NULL,
  surface_key INTEGER NOT NULL,
  kind TEXT NOT NULL,
  cx {double} NOT NULL, cy {double} NOT NULL, cz {double} NOT NULL,
  ax {double} NOT NULL, ay {double} NOT NULL, az {double} NOT NULL,
  radius {double} NOT NULL, radius2 {double} NOT NULL,
  height {double} NOT NULL, segments INTEGER NOT NULL,
  PRIMARY KEY (volume_id, surface_key)){clustered})",
    R"(CREATE TABLE faces (
  volume_id BIGINT NOT NULL,
  face_key INTEGER NOT NULL,
  group_key INTEGER NOT NULL,
  front_cell INTEGER,
  back_cell INTEGER,
  surface_key INTEGER,
  nx {double} NOT NULL, ny {double} NOT NULL, nz {double} NOT NULL,
  d {double} NOT NULL,
  min_x {double} NOT NULL, min_y {double} NOT NULL, min_z {double} NOT NULL,
  max_x {double} NOT NULL, max_y {double} NOT NULL, max_z {double} NOT NULL,
  PRIMARY KEY (volume_id, face_key)){clustered})",
    R"(CREATE TABLE loops (
  volume_id BIGINT NOT NULL,
  loop_key INTEGER NOT NULL,
  face_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  kind TEXT NOT NULL,
  point_vertex INTEGER,
  PRIMARY KEY (volume_id, loop_key)){clustered})",
    R"(CREATE TABLE loop_edges (
  volume_id BIGINT NOT NULL,
  loop_key INTEGER NOT NULL,
  ord INTEGER NOT NULL,
  edge_key INTEGER NOT NULL,
  reversed INTEGER NOT NULL,
  radial_ord INTEGER NOT NULL,
  PRIMARY KEY (volume_id, loop_key, ord)){clustered})",
    R"(CREATE TABLE properties (
  volume_id BIGINT NOT NULL,
  property_key INTEGER NOT NULL,
  owner TEXT NOT NULL,
  name TEXT NOT NULL,
  type TEXT NOT NULL,
  PRIMARY KEY (volume_id, property_key)){clustered})",
    R"(CREATE TABLE property_values (
  volume_id BIGINT NOT NULL,
  property_key INTEGER NOT NULL,
  element_key BIGINT NOT NULL,
  int_value BIGINT,
  text_value TEXT,
  x {double}, y {double}, z {double}, w {double},
  PRIMARY KEY (volume_id, property_key, element_key)){clustered})",
    R"(CREATE TABLE attachments (
  volume_id BIGINT NOT NULL,
  ord INTEGER NOT NULL,
  name TEXT NOT NULL,
  version INTEGER NOT NULL,
  data TEXT NOT NULL,
  PRIMARY KEY (volume_id, ord)){clustered})",
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

// Child tables of a stored volume, for removal.
constexpr const char* kVolumeTables[] = {
    "model_groups", "parameters", "cells",      "vertices",        "edges",      "surfaces",
    "faces",        "loops",      "loop_edges", "property_values", "properties", "attachments"};

// ---- property values in the columns of table property_values

// int_value, text_value, x, y, z, w: integers in int_value (an unsigned 64-bit
// value above 2^63 - 1 as the signed integer of its bits), strings in text_value,
// a float or double in x, a colour in x y z w (r g b a), a vector in x y z. A NaN
// component is NULL (SQLite keeps no NaN; its sign and payload are not kept).
void write_value(RowWriter& w, const PropertyValue& v) {
  const auto real = [&](double d) { std::isnan(d) ? w.null() : w.d(d); };
  const auto nulls = [&](int n) {
    for (int k = 0; k < n; ++k) w.null();
  };
  if (const auto* i = std::get_if<std::int64_t>(&v)) {
    w.i(*i), nulls(5);
  } else if (const auto* u = std::get_if<std::uint64_t>(&v)) {
    w.i(static_cast<std::int64_t>(*u)), nulls(5);
  } else if (const auto* d = std::get_if<double>(&v)) {
    nulls(2), real(*d), nulls(3);
  } else if (const auto* t = std::get_if<std::string>(&v)) {
    w.null(), w.s(*t), nulls(4);
  } else if (const auto* c = std::get_if<Colour>(&v)) {
    nulls(2), real(c->r), real(c->g), real(c->b), real(c->a);
  } else if (const auto* p = std::get_if<Vec3>(&v)) {
    nulls(2), real(p->x), real(p->y), real(p->z), w.null();
  }
}

// The value of `type` in columns c ... c+5 of r (as write_value puts it); an
// error names what is missing. restore() checks the range.
Result<PropertyValue> read_value(PropertyType type, const Row& r, int c) {
  using P = PropertyType;
  const auto real = [&](int k) {
    return r.is_null(c + 2 + k) ? std::numeric_limits<double>::quiet_NaN() : r.d(c + 2 + k);
  };
  switch (type) {
    case P::kInt8:
    case P::kInt16:
    case P::kInt32:
    case P::kInt64:
    case P::kUInt8:
    case P::kUInt16:
    case P::kUInt32:
    case P::kUInt64: {
      if (r.is_null(c)) return db_error("int_value is NULL");
      const std::int64_t i = r.i(c);
      if (type >= P::kUInt8) return PropertyValue(static_cast<std::uint64_t>(i));
      return PropertyValue(i);
    }
    case P::kFloat:
    case P::kDouble:
      return PropertyValue(real(0));
    case P::kString:
      if (r.is_null(c + 1)) return db_error("text_value is NULL");
      return PropertyValue(r.s(c + 1));
    case P::kColour:
      return PropertyValue(Colour{static_cast<float>(real(0)), static_cast<float>(real(1)),
                                  static_cast<float>(real(2)), static_cast<float>(real(3))});
    case P::kVec3:
      return PropertyValue(Vec3{real(0), real(1), real(2)});
  }
  return db_error("unknown type");
}

constexpr const char* kVolumeColumns =
    "id, name, version, type, cx, cy, cz, volume, area, min_x, min_y, min_z, max_x, max_y, max_z, "
    "source, created, n_vertices, n_edges, n_faces, n_loops, n_cells, n_groups";

VolumeInfo read_volume(const Row& r) {
  VolumeInfo v;
  v.id = r.i(0);
  v.name = r.s(1);
  v.version = static_cast<int>(r.i(2));
  v.type = r.s(3);
  v.centroid = {r.d(4), r.d(5), r.d(6)};
  v.volume = r.d(7);
  v.area = r.d(8);
  v.bbox_min = {r.d(9), r.d(10), r.d(11)};
  v.bbox_max = {r.d(12), r.d(13), r.d(14)};
  v.source = r.s(15);
  v.created = r.s(16);
  v.vertices = r.i(17);
  v.edges = r.i(18);
  v.faces = r.i(19);
  v.loops = r.i(20);
  v.cells = r.i(21);
  v.groups = r.i(22);
  return v;
}

std::string now_utc() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", &tm);
  char millis[8];
  std::snprintf(millis, sizeof millis, ".%03dZ", static_cast<int>(ms));
  return std::string(date) + millis;
}

Status check_text(const std::string& what, const std::string& s) {
  if (is_utf8(s)) return Status::Ok();
  return Error{ErrorCode::kInvalidInput, what + " is not valid UTF-8 (or holds a NUL byte)"};
}

// Every string a save writes must be valid UTF-8 (PostgreSQL text requires it,
// and both backends must accept the same models).
Status check_strings(const std::string& name, const ModelRows& rows, const PutOptions& o) {
  if (Status s = check_volume_name(name); !s) return s;
  if (Status s = check_text("the source script", o.source); !s) return s;
  if (!o.object.empty()) {
    if (Status s = check_volume_name(o.object); !s) {
      return Error{ErrorCode::kInvalidInput, "object name: " + s.error().message};
    }
  }
  for (const auto& g : rows.groups) {
    if (Status s = check_text("group name", g.name); !s) return s;
  }
  for (const auto& p : rows.parameters) {
    if (Status s = check_text("parameter '" + p.name + "'", p.name + p.value); !s) return s;
  }
  for (const auto& sf : rows.surfaces) {
    if (Status s = check_text("surface kind", sf.kind); !s) return s;
  }
  for (const auto& p : rows.properties) {
    const std::string what = "property '" + p.name + "'";
    if (Status s = check_text("a property name", p.name); !s) return s;
    if (p.type != PropertyType::kString) continue;
    if (Status s = check_text(what + ": the default", std::get<std::string>(p.fallback)); !s)
      return s;
    for (const auto& [key, value] : p.values) {
      if (Status s = check_text(what + ": the value of " + std::string(owner_name(p.owner)) + " " +
                                    std::to_string(key),
                                std::get<std::string>(value));
          !s) {
        return s;
      }
    }
  }
  for (std::size_t i = 0; i < o.attachments.size(); ++i) {
    const Attachment& a = o.attachments[i];
    if (Status s = check_text("attachment " + std::to_string(i) + "'s name", a.name); !s) return s;
    if (Status s = check_text("attachment '" + a.name + "'", a.data); !s) return s;
    for (std::size_t j = 0; j < i; ++j) {
      if (o.attachments[j].name == a.name)
        return Error{ErrorCode::kInvalidInput, "attachment '" + a.name + "' is there twice"};
    }
  }
  return Status::Ok();
}

class SqlStore final : public Store {
 public:
  explicit SqlStore(std::unique_ptr<Connection> c) : db_(std::move(c)) {}

  std::string backend() const override { return db_->backend(); }

  Status create_schema() {
    if (Status s = db_->begin_write("cellforge schema"); !s) return s;
    Status s = create_schema_locked();
    if (!s) {
      db_->rollback();
      return s;
    }
    return db_->commit();
  }

  Result<VolumeInfo> put(const std::string& name, const Model& m,
                         const PutOptions& options) override {
    // get() validates what it rebuilds: an invalid model would be stored but never
    // loaded, so it is refused before anything is written.
    if (auto violations = validate(m); !violations.empty())
      return Error{ErrorCode::kInvalidInput,
                   "the model is invalid, so the stored version could not be loaded: " +
                       to_string(violations)};
    VolumeInfo info;
    const ModelRows rows = to_rows(m, info);
    if (Status s = check_strings(name, rows, options); !s) return s.error();
    info.name = name;
    info.source = options.source;
    info.created = now_utc();
    if (Status s = db_->begin_write(name); !s) return s.error();
    Status s = put_locked(info, rows, options);
    if (!s) {
      db_->rollback();
      return s.error();
    }
    if (Status c = db_->commit(); !c) return c.error();
    return info;
  }

  Result<Model> get(const std::string& name, int version) override {
    ModelRows rows;
    if (Status s = read(name, version, [&](std::int64_t id) { return read_rows(id, rows); }); !s) {
      return s.error();
    }
    return to_model(rows);
  }

  Result<std::vector<Attachment>> get_attachments(const std::string& name, int version) override {
    std::vector<Attachment> out;
    Status s = read(name, version, [&](std::int64_t id) {
      return db_->select(
          "SELECT name, version, data FROM attachments WHERE volume_id = $1 ORDER BY ord", {id},
          [&](const Row& r) {
            out.push_back({r.s(0), static_cast<int>(r.i(1)), r.s(2)});
          });
    });
    if (!s) return s.error();
    return out;
  }

  Result<Model> get_faces_where(const std::string& name, const std::string& condition,
                                int version) override {
    ModelRows rows;
    Status s =
        read(name, version, [&](std::int64_t id) { return read_face_rows(id, condition, rows); });
    if (!s) return s.error();
    return to_model(rows);
  }

  Result<std::vector<std::uint32_t>> faces_in_box(const std::string& name, const QueryBox& box,
                                                  int version) override {
    std::vector<std::uint32_t> out;
    Status s = read(name, version, [&](std::int64_t id) {
      std::vector<Value> p{id};
      for (double c : {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z}) {
        p.emplace_back(c);
      }
      // The tiles that meet the box (through the spatial index), then the exact
      // box of each of their faces: in one join where faces are rows, by the
      // faces' keys where they are packed in blocks (PostgreSQL).
      if (db_->stored_in("faces") == "faces") {
        return db_->select("SELECT f.face_key FROM " + db_->tiles_then_faces() +
                               " WHERE t.volume_id = $1 AND " + db_->overlaps("t", 2) + " AND " +
                               box_test("f", 2) + " ORDER BY f.face_key",
                           p, [&](const Row& r) { out.push_back(key(r, 0)); });
      }
      std::vector<std::uint32_t> keys;
      Status st = db_->select(
          "SELECT t.first_face, t.last_face FROM face_tiles t WHERE "
          "t.volume_id = $1 AND " +
              db_->overlaps("t", 2) + " ORDER BY t.id",
          p, [&](const Row& r) {
            for (std::uint32_t k = key(r, 0); k <= key(r, 1); ++k) {
              keys.push_back(k);
            }
          });
      if (!st || keys.empty()) return st;
      std::sort(keys.begin(), keys.end());
      return rows_of(
          *db_, "faces", "face_key, min_x, min_y, min_z, max_x, max_y, max_z", id,
          [&](const Row& r) {
            if (r.d(4) >= box.min.x && r.d(1) <= box.max.x && r.d(5) >= box.min.y &&
                r.d(2) <= box.max.y && r.d(6) >= box.min.z && r.d(3) <= box.max.z) {
              out.push_back(key(r, 0));
            }
          },
          "face_key", &keys);
    });
    if (!s) return s.error();
    return out;
  }

  Result<std::vector<VolumeInfo>> volumes_in_box(const QueryBox& box) override {
    std::vector<Value> p;
    for (double c : {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z}) {
      p.emplace_back(c);
    }
    return volumes(std::string("SELECT ") + kVolumeColumns +
                       " FROM volumes WHERE id IN (SELECT b.id FROM volume_boxes b WHERE " +
                       db_->overlaps("b", 1) + ") AND " + box_test("volumes", 1),
                   p);
  }

  Result<std::vector<StoredPoint>> get_points(const std::string& name, int version) override {
    std::vector<StoredPoint> out;
    Status s = read(name, version, [&](std::int64_t id) {
      return rows_of(*db_, "vertices", "vertex_key, x, y, z", id, [&](const Row& r) {
        out.push_back({key(r, 0), {r.d(1), r.d(2), r.d(3)}});
      });
    });
    if (!s) return s.error();
    return out;
  }

  Result<std::vector<StoredEdge>> get_edges(const std::string& name, int version) override {
    std::vector<StoredEdge> out;
    Status s = read(name, version, [&](std::int64_t id) {
      return rows_of(*db_, "edges", "edge_key, start_vertex, end_vertex, uses", id,
                     [&](const Row& r) {
                       out.push_back({key(r, 0), key(r, 1), key(r, 2), key(r, 3)});
                     });
    });
    if (!s) return s.error();
    return out;
  }

  Result<std::vector<StoredFace>> get_faces(const std::string& name, int version) override {
    std::vector<StoredFace> out;
    Status s = read(name, version, [&](std::int64_t id) -> Status {
      auto cell = [](const Row& r, int c) {
        return r.is_null(c) ? std::nullopt : std::optional<std::uint32_t>(key(r, c));
      };
      Status st = rows_of(
          *db_, "faces", "face_key, front_cell, back_cell, nx, ny, nz, d", id, [&](const Row& r) {
            out.push_back(
                {key(r, 0), {}, cell(r, 1), cell(r, 2), {r.d(3), r.d(4), r.d(5)}, r.d(6)});
          });
      if (!st) return st;
      std::vector<std::pair<std::uint32_t, std::uint32_t>> loop_at;  // (face, index in loops)
      bool bad = false;
      st = rows_of(*db_, "loops", "face_key, point_vertex", id, [&](const Row& r) {
        if (key(r, 0) >= out.size()) {
          bad = true;
          return;
        }
        auto& loops = out[key(r, 0)].loops;
        loop_at.emplace_back(key(r, 0), static_cast<std::uint32_t>(loops.size()));
        loops.emplace_back();
        if (!r.is_null(1)) loops.back().push_back(key(r, 1));
      });
      if (!st) return st;
      std::vector<std::pair<std::uint32_t, std::uint32_t>> ends;  // per edge
      st = rows_of(*db_, "edges", "start_vertex, end_vertex", id,
                   [&](const Row& r) { ends.emplace_back(key(r, 0), key(r, 1)); });
      if (!st) return st;
      st = rows_of(*db_, "loop_edges", "loop_key, edge_key, reversed", id, [&](const Row& r) {
        if (key(r, 0) >= loop_at.size() || key(r, 1) >= ends.size()) {
          bad = true;
          return;
        }
        const auto [face, index] = loop_at[key(r, 0)];
        const auto& e = ends[key(r, 1)];
        out[face].loops[index].push_back(r.i(2) == 0 ? e.first : e.second);
      });
      if (st && bad) st = db_error("stored volume: a loop or edge use names a missing key");
      return st;
    });
    if (!s) return s.error();
    return out;
  }

  Result<VolumeInfo> info(const std::string& name, int version) override {
    VolumeInfo out;
    Status s = read(name, version, [&](std::int64_t id) -> Status {
      Status st =
          db_->select(std::string("SELECT ") + kVolumeColumns + " FROM volumes WHERE id = $1", {id},
                      [&](const Row& r) { out = read_volume(r); });
      if (!st) return st;
      return db_->select(
          "SELECT name, value FROM parameters WHERE volume_id = $1 ORDER BY group_key, ord", {id},
          [&](const Row& r) {
            out.parameters.push_back({r.s(0), r.s(1)});
          });
    });
    if (!s) return s.error();
    return out;
  }

  Result<std::vector<VolumeInfo>> list() override {
    return volumes(std::string("SELECT ") + kVolumeColumns + " FROM latest_volumes", {});
  }

  Result<std::vector<VolumeInfo>> versions(const std::string& name) override {
    if (Status s = check_volume_name(name); !s) return s.error();
    return volumes(std::string("SELECT ") + kVolumeColumns + " FROM volumes WHERE name = $1",
                   {name});
  }

  Result<int> remove(const std::string& name) override { return remove_where(name, 0); }

  Result<int> remove_version(const std::string& name, int version) override {
    if (version < 1) {
      return Error{ErrorCode::kInvalidInput,
                   "a version is a number from 1, not " + std::to_string(version)};
    }
    return remove_where(name, version);
  }

  // Removes every version of `name` (version 0) or one.
  Result<int> remove_where(const std::string& name, int version) {
    if (Status s = check_volume_name(name); !s) return s.error();
    if (Status s = db_->begin_write(name); !s) return s.error();
    std::vector<std::int64_t> ids;
    Status s = version > 0 ? db_->select("SELECT id FROM volumes WHERE name = $1 AND version = $2",
                                         {name, std::int64_t{version}},
                                         [&](const Row& r) { ids.push_back(r.i(0)); })
                           : db_->select("SELECT id FROM volumes WHERE name = $1", {name},
                                         [&](const Row& r) { ids.push_back(r.i(0)); });
    for (std::int64_t id : ids) {
      for (const char* table : kVolumeTables) {
        if (s) {
          s = db_->exec("DELETE FROM " + db_->stored_in(table) + " WHERE volume_id = $1", {id});
        }
      }
    }
    for (std::int64_t id : ids) {
      if (s) {
        s = db_->exec("DELETE FROM face_tiles WHERE id BETWEEN $1 AND $2",
                      {tile_id(id, 0), tile_id(id + 1, 0) - 1});
      }
      if (s) s = db_->exec("DELETE FROM volume_boxes WHERE id = $1", {id});
      if (s) s = db_->exec("DELETE FROM volumes WHERE id = $1", {id});
    }
    // The name leaves its objects when its last version goes.
    bool left = false;
    if (s) {
      s = db_->select("SELECT 1 FROM volumes WHERE name = $1 LIMIT 1", {name},
                      [&](const Row&) { left = true; });
    }
    if (s && !left) s = db_->exec("DELETE FROM object_volumes WHERE volume_name = $1", {name});
    if (!s) {
      db_->rollback();
      return s.error();
    }
    if (Status c = db_->commit(); !c) return c.error();
    return static_cast<int>(ids.size());
  }

  Result<std::vector<std::string>> get_object(const std::string& name) override {
    if (Status s = check_volume_name(name); !s) return s.error();
    std::vector<std::string> out;
    bool found = false;
    if (Status s = db_->begin_read(); !s) return s.error();
    Status s = db_->select("SELECT id FROM objects WHERE name = $1", {name},
                           [&](const Row&) { found = true; });
    if (s && found) {
      s = db_->select(
          "SELECT ov.volume_name FROM object_volumes ov JOIN objects o ON o.id = ov.object_id "
          "WHERE o.name = $1 ORDER BY ov.ord",
          {name}, [&](const Row& r) { out.push_back(r.s(0)); });
    }
    if (!s) {
      db_->rollback();
      return s.error();
    }
    if (Status c = db_->commit(); !c) return c.error();
    if (!found) return Error{ErrorCode::kInvalidInput, "no object named '" + name + "'"};
    return out;
  }

  Result<QueryResult> query(const std::string& sql, const QueryOptions& options) override {
    QueryResult out;
    QueryCallbacks collect;
    collect.columns = [&](const std::vector<std::string>& c) { out.columns = c; };
    collect.row = [&](const QueryRow& r) {
      out.rows.push_back(r.values);
      out.kinds.push_back(r.kinds);
      return true;
    };
    auto truncated = db_->read_only_query(sql, options, collect);
    if (!truncated) return truncated.error();
    out.truncated = truncated.value();
    return out;
  }

  Result<bool> query_each(const std::string& sql, const QueryOptions& options,
                          const QueryCallbacks& callbacks) override {
    return db_->read_only_query(sql, options, callbacks);
  }

 private:
  static std::uint32_t key(const Row& r, int c) { return static_cast<std::uint32_t>(r.i(c)); }

  // The rows of stored volume `id` in one of the model tables, the given columns
  // in key order; with `keys`, only those whose `key_column` is one of them.
  static Status rows_of(Connection& db, const std::string& table, const std::string& columns,
                        std::int64_t id, const RowFn& fn, const std::string& key_column = "",
                        const std::vector<std::uint32_t>* keys = nullptr) {
    const std::string order = table == "loop_edges" ? "loop_key, ord"
                              : table == "vertices" ? "vertex_key"
                              : table == "edges"    ? "edge_key"
                              : table == "faces"    ? "face_key"
                              : table == "loops"    ? "loop_key"
                              : table == "cells"    ? "cell_key"
                                                    : "";
    return db.read_volume_rows(table, columns, order, id, key_column, keys, fn);
  }

  // The DDL of the current schema, each statement with the table it belongs to
  // (empty for views and functions).
  std::vector<std::pair<std::string, std::string>> current_ddl() const {
    std::vector<std::pair<std::string, std::string>> ddl;
    auto add = [&](std::string sql) {
      for (const auto& [from, to] :
           {std::pair<std::string, std::string>{"{serial}", db_->serial_primary_key()},
            {"{clustered}", db_->clustered()},
            {"{double}", db_->double_type()}}) {
        for (std::size_t at; (at = sql.find(from)) != std::string::npos;) {
          sql.replace(at, from.size(), to);
        }
      }
      std::string table;
      for (const char* prefix : {"CREATE TABLE ", "CREATE VIRTUAL TABLE ", "CREATE INDEX "}) {
        if (sql.rfind(prefix, 0) != 0) continue;
        std::size_t at = std::strlen(prefix);
        if (std::strcmp(prefix, "CREATE INDEX ") == 0) at = sql.find(" ON ") + 4;
        table = sql.substr(at, sql.find_first_of(" (", at) - at);
      }
      if (sql.rfind("CREATE TABLE ", 0) == 0) {
        for (std::string& d : db_->table_ddl(table, sql)) {
          const bool view = d.rfind("CREATE VIEW", 0) == 0 || d.rfind("CREATE OR REPLACE", 0) == 0;
          ddl.emplace_back(view ? "" : table, std::move(d));
        }
        return;
      }
      ddl.emplace_back(table, std::move(sql));
    };
    for (const char* sql : kSchema) add(sql);
    for (const std::string& spatial : db_->spatial_schema()) add(spatial);
    return ddl;
  }

  Status create_schema_locked() {
    if (Status s =
            db_->exec("CREATE TABLE IF NOT EXISTS cellforge_schema (version INTEGER NOT NULL)");
        !s) {
      return s;
    }
    int version = 0;
    if (Status s = db_->select("SELECT MAX(version) FROM cellforge_schema", {},
                               [&](const Row& r) {
                                 if (!r.is_null(0)) version = static_cast<int>(r.i(0));
                               });
        !s) {
      return s;
    }
    if (version == kSchemaVersion) return Status::Ok();
    if (version < 0 || version > kSchemaVersion) {
      return db_error("the database has schema version " + std::to_string(version) +
                      "; this cellforge knows versions 1 to " + std::to_string(kSchemaVersion));
    }
    if (version != 0) return migrate(version);
    for (const auto& [table, sql] : current_ddl()) {
      if (Status s = db_->exec(sql); !s) return s;
    }
    for (const std::string& grant : db_->reader_schema()) {
      if (Status s = db_->exec(grant); !s) return s;
    }
    return db_->exec("INSERT INTO cellforge_schema (version) VALUES ($1)",
                     {std::int64_t{kSchemaVersion}});
  }

  // Brings a database of schema version `from` (1, 2 or 3) to the current one, in
  // the schema's write transaction (so a failure or a kill leaves it as it was).
  // From 1 or 2: the tables whose layout changed are renamed to <name>_old, the
  // current schema's tables, indexes and views are created, the rows are copied
  // (PostgreSQL packs them into blocks on the server; version 1 gains the face
  // boxes, computed from the loops' points, and the spatial indexes), and the old
  // tables are dropped. From 3 (and on the way from 1 or 2): the tables that 4
  // added (properties, property_values, attachments) are created empty, since no
  // earlier version stored properties or attachments.
  Status migrate(int from) {
    const bool pg = db_->backend() == "postgresql";
    // SQLite 1 -> 2 rebuilt every table (clustered, doubles without affinity); on
    // PostgreSQL only the packed tables change (faces also gained its box in 2).
    std::vector<std::string> rebuilt;
    if (pg && from < 3) {
      rebuilt = {"vertices", "edges", "faces", "loops", "loop_edges"};
    } else if (from == 1) {
      rebuilt = {"objects",    "volumes", "object_volumes", "model_groups",
                 "parameters", "cells",   "vertices",       "edges",
                 "surfaces",   "faces",   "loops",          "loop_edges"};
    }
    std::vector<std::string> steps;
    if (from < 3) {
      for (const char* view :
           {"face_edge_points", "edge_vertices", "face_loops", "volume_faces", "latest_volumes"}) {
        steps.push_back(std::string("DROP VIEW IF EXISTS ") + view);
      }
      steps.push_back("DROP INDEX IF EXISTS loop_edges_by_edge");
    }
    if (!pg && from == 1) steps.push_back("DROP INDEX IF EXISTS object_volumes_by_name");
    for (const std::string& t : rebuilt)
      steps.push_back("ALTER TABLE " + t + " RENAME TO " + t + "_old");
    for (const std::string& step : steps) {
      if (Status s = db_->exec(step); !s) return s;
    }
    // The current schema: what is missing (the tables renamed above or added
    // since `from`, with their indexes; in version 1 the spatial indexes; every
    // view unless from 3, whose views stand).
    const auto ddl = current_ddl();
    std::map<std::string, bool> exists;
    for (const auto& [table, sql] : ddl) {
      if (table.empty() || exists.count(table)) continue;
      bool found = false;
      Status s = pg ? db_->select("SELECT 1 WHERE to_regclass($1) IS NOT NULL", {table},
                                  [&](const Row&) { found = true; })
                    : db_->select("SELECT 1 FROM sqlite_master WHERE name = $1", {table},
                                  [&](const Row&) { found = true; });
      if (!s) return s;
      exists[table] = found;
    }
    for (const auto& [table, sql] : ddl) {
      if (table.empty() ? from >= 3 : exists[table]) continue;
      if (Status s = db_->exec(sql); !s) return s;
    }
    steps.clear();
    if (from == 1) {
      // The box of each face: of the points of its loops (the start of each use,
      // or a point loop's vertex), as put computes it.
      steps.push_back(R"(CREATE TEMP TABLE faces_boxed AS
SELECT f.*, b.min_x, b.min_y, b.min_z, b.max_x, b.max_y, b.max_z
FROM faces_old f JOIN (
  SELECT q.volume_id, q.face_key, MIN(p.x) AS min_x, MIN(p.y) AS min_y, MIN(p.z) AS min_z,
         MAX(p.x) AS max_x, MAX(p.y) AS max_y, MAX(p.z) AS max_z
  FROM (SELECT u.volume_id, l.face_key,
               CASE WHEN u.reversed = 0 THEN e.start_vertex ELSE e.end_vertex END AS vertex_key
        FROM loop_edges_old u
        JOIN loops_old l ON l.volume_id = u.volume_id AND l.loop_key = u.loop_key
        JOIN edges_old e ON e.volume_id = u.volume_id AND e.edge_key = u.edge_key
        UNION ALL
        SELECT volume_id, face_key, point_vertex FROM loops_old WHERE point_vertex IS NOT NULL) q
  JOIN vertices_old p ON p.volume_id = q.volume_id AND p.vertex_key = q.vertex_key
  GROUP BY q.volume_id, q.face_key) b ON b.volume_id = f.volume_id AND b.face_key = f.face_key)");
    }
    for (const std::string& t : rebuilt) {
      const std::string source = t == "faces" && from == 1 ? "faces_boxed" : t + "_old";
      std::vector<std::string> pack = db_->pack_rows(t, source);
      if (pack.empty()) pack.push_back("INSERT INTO " + t + " SELECT * FROM " + source);
      for (std::string& p : pack) steps.push_back(std::move(p));
    }
    if (from == 1) {
      const std::string tile = std::to_string(kTileFaces);
      steps.push_back(
          "INSERT INTO face_tiles (id, min_x, max_x, min_y, max_y, min_z, max_z, volume_id, "
          "first_face, last_face) SELECT volume_id * 4294967296 + face_key / " +
          tile +
          ", MIN(min_x), MAX(max_x), MIN(min_y), MAX(max_y), MIN(min_z), MAX(max_z), volume_id, "
          "MIN(face_key), MAX(face_key) FROM faces GROUP BY volume_id, face_key / " +
          tile);
      steps.push_back(
          "INSERT INTO volume_boxes (id, min_x, max_x, min_y, max_y, min_z, max_z) SELECT id, "
          "min_x, max_x, min_y, max_y, min_z, max_z FROM volumes WHERE n_vertices > 0");
      steps.push_back("DROP TABLE faces_boxed");
    }
    for (const std::string& t : rebuilt) steps.push_back("DROP TABLE " + t + "_old");
    for (const std::string& grant : db_->reader_schema()) steps.push_back(grant);
    steps.push_back("DELETE FROM cellforge_schema");
    for (const std::string& step : steps) {
      if (Status s = db_->exec(step); !s) return s;
    }
    return db_->exec("INSERT INTO cellforge_schema (version) VALUES ($1)",
                     {std::int64_t{kSchemaVersion}});
  }

  Status put_locked(VolumeInfo& info, const ModelRows& rows, const PutOptions& o) {
    Status s =
        db_->select("SELECT COALESCE(MAX(version), 0) FROM volumes WHERE name = $1", {info.name},
                    [&](const Row& r) { info.version = static_cast<int>(r.i(0)) + 1; });
    if (!s) return s;
    s = db_->select(
        "INSERT INTO volumes (name, version, type, cx, cy, cz, volume, area, min_x, min_y, min_z, "
        "max_x, max_y, max_z, source, created, n_vertices, n_edges, n_faces, n_loops, n_cells, "
        "n_groups) VALUES ($1, $2, $3, $4, $5, $6, $7, $8, $9, $10, $11, $12, $13, $14, $15, $16, "
        "$17, $18, $19, $20, $21, $22) RETURNING id",
        {info.name,       std::int64_t{info.version},
         info.type,       info.centroid.x,
         info.centroid.y, info.centroid.z,
         info.volume,     info.area,
         info.bbox_min.x, info.bbox_min.y,
         info.bbox_min.z, info.bbox_max.x,
         info.bbox_max.y, info.bbox_max.z,
         info.source,     info.created,
         info.vertices,   info.edges,
         info.faces,      info.loops,
         info.cells,      info.groups},
        [&](const Row& r) { info.id = r.i(0); });
    if (!s) return s;
    if (s = write_rows(info.id, rows, {info.bbox_min, info.bbox_max}, o.progress); !s) return s;
    if (s = write_attachments(info.id, o.attachments); !s) return s;
    if (!o.object.empty()) s = add_to_object(o.object, info.name);
    return s;
  }

  Status add_to_object(const std::string& object, const std::string& volume) {
    Status s =
        db_->exec("INSERT INTO objects (name) VALUES ($1) ON CONFLICT (name) DO NOTHING", {object});
    std::int64_t id = 0, ord = 0;
    if (s) {
      s = db_->select("SELECT id FROM objects WHERE name = $1", {object},
                      [&](const Row& r) { id = r.i(0); });
    }
    bool listed = false;
    if (s) {
      s = db_->select(
          "SELECT COALESCE(MAX(ord) + 1, 0), COUNT(CASE WHEN volume_name = $2 THEN 1 END) "
          "FROM object_volumes WHERE object_id = $1",
          {id, volume}, [&](const Row& r) {
            ord = r.i(0);
            listed = r.i(1) > 0;
          });
    }
    if (s && !listed) {
      s = db_->exec("INSERT INTO object_volumes (object_id, ord, volume_name) VALUES ($1, $2, $3)",
                    {id, ord, volume});
    }
    return s;
  }

  Status write_rows(std::int64_t id, const ModelRows& r, const QueryBox& volume_box,
                    const std::function<void(std::uint64_t)>& progress) {
    std::uint64_t done = 0;
    auto insert = [&](const char* table, int columns, std::size_t n, const FillFn& fill) {
      std::function<void(std::uint64_t)> report;
      if (progress) report = [&, base = done](std::uint64_t k) { progress(base + k); };
      Status s = db_->bulk_insert(table, columns, n, fill, report);
      done += n;
      return s;
    };
    Status s = insert("model_groups", 3, r.groups.size(), [&](std::size_t i, RowWriter& w) {
      w.i(id), w.i(static_cast<std::int64_t>(i)), w.s(r.groups[i].name);
    });
    std::vector<std::int64_t> param_ord(r.parameters.size());
    for (std::size_t i = 0; i < r.parameters.size(); ++i) {
      param_ord[i] =
          i > 0 && r.parameters[i - 1].group == r.parameters[i].group ? param_ord[i - 1] + 1 : 0;
    }
    if (s) {
      s = insert("parameters", 5, r.parameters.size(), [&](std::size_t i, RowWriter& w) {
        const auto& p = r.parameters[i];
        w.i(id), w.i(p.group), w.i(param_ord[i]), w.s(p.name), w.s(p.value);
      });
    }
    if (s) {
      s = insert("cells", 3, r.cells.size(), [&](std::size_t i, RowWriter& w) {
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.i(r.cells[i]);
      });
    }
    if (s) {
      s = insert("vertices", 6, r.vertices.size(), [&](std::size_t i, RowWriter& w) {
        const auto& v = r.vertices[i];
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.d(v.p.x), w.d(v.p.y), w.d(v.p.z),
            w.i(v.group);
      });
    }
    if (s) {
      s = insert("edges", 6, r.edges.size(), [&](std::size_t i, RowWriter& w) {
        const auto& e = r.edges[i];
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.i(e.start), w.i(e.end), w.i(1),
            w.i(r.edge_uses[i]);
      });
    }
    if (s) {
      s = insert("surfaces", 13, r.surfaces.size(), [&](std::size_t i, RowWriter& w) {
        const Surface& f = r.surfaces[i];
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.s(f.kind), w.d(f.center.x), w.d(f.center.y),
            w.d(f.center.z), w.d(f.axis.x), w.d(f.axis.y), w.d(f.axis.z), w.d(f.radius),
            w.d(f.radius2), w.d(f.height), w.i(f.segments);
      });
    }
    if (s) {
      s = insert("faces", 16, r.faces.size(), [&](std::size_t i, RowWriter& w) {
        const auto& f = r.faces[i];
        const QueryBox& b = r.boxes[i];
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.i(f.group), w.opt(f.front), w.opt(f.back),
            w.opt(f.surface), w.d(r.planes[i].normal.x), w.d(r.planes[i].normal.y),
            w.d(r.planes[i].normal.z), w.d(r.planes[i].d), w.d(b.min.x), w.d(b.min.y), w.d(b.min.z),
            w.d(b.max.x), w.d(b.max.y), w.d(b.max.z);
      });
    }
    if (s) {
      static const std::string kOuter = "outer", kInner = "inner";
      s = insert("loops", 6, r.loops.size(), [&](std::size_t i, RowWriter& w) {
        const auto& l = r.loops[i];
        w.i(id), w.i(static_cast<std::int64_t>(i)), w.i(l.face), w.i(l.ord),
            w.s(l.ord == 0 ? kOuter : kInner), w.opt(l.point_vertex);
      });
    }
    if (s) {
      s = insert("loop_edges", 6, r.uses.size(), [&](std::size_t i, RowWriter& w) {
        const auto& u = r.uses[i];
        w.i(id), w.i(u.loop), w.i(u.ord), w.i(u.edge), w.i(u.reversed ? 1 : 0), w.i(u.radial_ord);
      });
    }
    if (s) s = write_properties(id, r, insert);
    const std::vector<QueryBox> tiles = tile_boxes(r.boxes);
    if (s) {
      s = insert("face_tiles", 10, tiles.size(), [&](std::size_t t, RowWriter& w) {
        const QueryBox& b = tiles[t];
        const auto first = static_cast<std::int64_t>(t * kTileFaces);
        const auto last =
            static_cast<std::int64_t>(std::min<std::size_t>((t + 1) * kTileFaces, r.faces.size())) -
            1;
        w.i(tile_id(id, t)), w.d(b.min.x), w.d(b.max.x), w.d(b.min.y), w.d(b.max.y), w.d(b.min.z),
            w.d(b.max.z), w.i(id), w.i(first), w.i(last);
      });
    }
    if (s && !r.vertices.empty()) {  // the box of a model without points is empty
      s = insert("volume_boxes", 7, 1, [&](std::size_t, RowWriter& w) {
        w.i(id), w.d(volume_box.min.x), w.d(volume_box.max.x), w.d(volume_box.min.y),
            w.d(volume_box.max.y), w.d(volume_box.min.z), w.d(volume_box.max.z);
      });
    }
    return s;
  }

  // The property tables of r: one row each in properties, and in property_values
  // its default (element_key -1) and the values that differ from it.
  template <class Insert>
  static Status write_properties(std::int64_t id, const ModelRows& r, Insert& insert) {
    static const std::string kOwners[] = {std::string(owner_name(PropertyOwner::kVertex)),
                                          std::string(owner_name(PropertyOwner::kEdge)),
                                          std::string(owner_name(PropertyOwner::kFace)),
                                          std::string(owner_name(PropertyOwner::kCell))};
    std::vector<std::string> types;
    for (const auto& p : r.properties) types.emplace_back(type_name(p.type));
    Status s = insert("properties", 5, r.properties.size(), [&](std::size_t i, RowWriter& w) {
      const auto& p = r.properties[i];
      w.i(id), w.i(static_cast<std::int64_t>(i)), w.s(kOwners[static_cast<std::size_t>(p.owner)]),
          w.s(p.name), w.s(types[i]);
    });
    struct ValueRow {
      std::int64_t property, element;
      const PropertyValue* value;
    };
    std::vector<ValueRow> values;
    for (std::size_t i = 0; i < r.properties.size(); ++i) {
      const auto& p = r.properties[i];
      values.push_back({static_cast<std::int64_t>(i), -1, &p.fallback});
      for (const auto& [key, value] : p.values)
        values.push_back({static_cast<std::int64_t>(i), key, &value});
    }
    if (s) {
      s = insert("property_values", 9, values.size(), [&](std::size_t i, RowWriter& w) {
        w.i(id), w.i(values[i].property), w.i(values[i].element);
        write_value(w, *values[i].value);
      });
    }
    return s;
  }

  Status write_attachments(std::int64_t id, const std::vector<Attachment>& attachments) {
    return db_->bulk_insert("attachments", 5, attachments.size(),
                            [&](std::size_t i, RowWriter& w) {
                              const Attachment& a = attachments[i];
                              w.i(id), w.i(static_cast<std::int64_t>(i)), w.s(a.name),
                                  w.i(a.version), w.s(a.data);
                            },
                            {});
  }

  // The property tables of stored volume `id` into r.
  Status read_properties(std::int64_t id, ModelRows& r) {
    Status bad = Status::Ok();
    Status s = db_->select(
        "SELECT property_key, owner, name, type FROM properties WHERE volume_id = $1 ORDER BY "
        "property_key",
        {id}, [&](const Row& row) {
          const auto owner = owner_from_name(row.s(1));
          const auto type = type_from_name(row.s(3));
          if (bad &&
              (row.i(0) != static_cast<std::int64_t>(r.properties.size()) || !owner || !type)) {
            bad = db_error("stored volume: property " + std::to_string(row.i(0)) + " ('" +
                           row.s(2) + "') has an unknown owner or type ('" + row.s(1) + "', '" +
                           row.s(3) + "') or is out of key order");
          }
          if (bad) r.properties.push_back({owner.value(), row.s(2), type.value(), {}, {}});
        });
    if (!s) return s;
    if (!bad) return bad;
    std::vector<bool> has_default(r.properties.size(), false);
    s = db_->bulk_select(
        "SELECT property_key, element_key, int_value, text_value, x, y, z, w FROM property_values "
        "WHERE volume_id = $1 ORDER BY property_key, element_key",
        {id}, [&](const Row& row) {
          if (!bad) return;
          const std::int64_t k = row.i(0), element = row.i(1);
          if (k < 0 || k >= static_cast<std::int64_t>(r.properties.size()) || element < -1 ||
              element > std::int64_t{0xFFFFFFFF}) {
            bad = db_error("stored volume: a property value names property " + std::to_string(k) +
                           ", element " + std::to_string(element));
            return;
          }
          Snapshot::Property& p = r.properties[static_cast<std::size_t>(k)];
          auto value = read_value(p.type, row, 2);
          if (!value) {
            bad = db_error(
                "stored volume: property '" + p.name + "', " +
                (element < 0 ? std::string("its default")
                             : std::string(owner_name(p.owner)) + " " + std::to_string(element)) +
                ": " + value.error().message + " for a " + std::string(type_name(p.type)));
            return;
          }
          if (element < 0) {
            has_default[static_cast<std::size_t>(k)] = true;
            p.fallback = std::move(*value);
          } else {
            p.values.emplace_back(static_cast<std::uint32_t>(element), std::move(*value));
          }
        });
    if (!s) return s;
    if (!bad) return bad;
    for (std::size_t k = 0; k < has_default.size(); ++k) {
      if (!has_default[k])
        return db_error("stored volume: property '" + r.properties[k].name + "' has no default");
    }
    return Status::Ok();
  }

  // The id of tile t of a stored volume in face_tiles: one range per volume.
  static std::int64_t tile_id(std::int64_t volume_id, std::size_t t) {
    return volume_id * (std::int64_t{1} << 32) + static_cast<std::int64_t>(t);
  }

  // The box of every kTileFaces consecutive faces.
  static std::vector<QueryBox> tile_boxes(const std::vector<QueryBox>& faces) {
    std::vector<QueryBox> tiles;
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const QueryBox& b = faces[i];
      if (i % kTileFaces == 0) {
        tiles.push_back(b);
        continue;
      }
      QueryBox& t = tiles.back();
      t.min = {std::min(t.min.x, b.min.x), std::min(t.min.y, b.min.y), std::min(t.min.z, b.min.z)};
      t.max = {std::max(t.max.x, b.max.x), std::max(t.max.y, b.max.y), std::max(t.max.z, b.max.z)};
    }
    return tiles;
  }

  // Runs `body` on the id of (name, version) inside one read transaction.
  template <class Body>
  Status read(const std::string& name, int version, Body body) {
    if (Status s = check_volume_name(name); !s) return s;
    if (Status s = db_->begin_read(); !s) return s;
    std::int64_t id = -1;
    Status s = version > 0
                   ? db_->select("SELECT id FROM volumes WHERE name = $1 AND version = $2",
                                 {name, std::int64_t{version}}, [&](const Row& r) { id = r.i(0); })
                   : db_->select(
                         "SELECT id FROM volumes WHERE name = $1 ORDER BY version DESC "
                         "LIMIT 1",
                         {name}, [&](const Row& r) { id = r.i(0); });
    if (s && id < 0) {
      s = Error{ErrorCode::kInvalidInput,
                "no volume named '" + name + "'" +
                    (version > 0 ? " with version " + std::to_string(version) : std::string())};
    }
    if (s) s = body(id);
    if (!s) {
      db_->rollback();
      return s;
    }
    return db_->commit();
  }

  Status read_rows(std::int64_t id, ModelRows& r) {
    const std::vector<std::int64_t> p{id};
    auto opt = [](const Row& row, int c) { return row.is_null(c) ? kNone : row.i(c); };
    if (!helper_) {
      if (auto another = db_->open_another()) helper_ = std::move(another.value());
    }
    Status helper_status = Status::Ok();
    std::thread helper;
    if (helper_) helper = std::thread([&] { helper_status = read_uses_elsewhere(id, r.uses); });
    Status s = read_small_tables(id, r);
    if (s) {
      s = db_->bulk_select("SELECT group_key FROM cells WHERE volume_id = $1 ORDER BY cell_key", p,
                           [&](const Row& row) { r.cells.push_back(key(row, 0)); });
    }
    if (s) {
      s = rows_of(*db_, "vertices", "x, y, z, group_key", id, [&](const Row& row) {
        r.vertices.push_back({{row.d(0), row.d(1), row.d(2)}, key(row, 3)});
      });
    }
    if (s) {
      s = rows_of(*db_, "edges", "start_vertex, end_vertex, uses", id, [&](const Row& row) {
        r.edges.push_back({key(row, 0), key(row, 1)});
        r.edge_uses.push_back(key(row, 2));
      });
    }
    if (s) {
      s = rows_of(*db_, "faces", "group_key, front_cell, back_cell, surface_key, nx, ny, nz, d", id,
                  [&](const Row& row) {
                    r.faces.push_back({key(row, 0), opt(row, 1), opt(row, 2), opt(row, 3)});
                    r.planes.push_back({{row.d(4), row.d(5), row.d(6)}, row.d(7)});
                  });
    }
    if (s) {
      s = rows_of(*db_, "loops", "face_key, ord, point_vertex", id, [&](const Row& row) {
        r.loops.push_back({key(row, 0), key(row, 1), opt(row, 2)});
      });
    }
    if (s) s = read_properties(id, r);
    if (helper.joinable()) helper.join();
    if (s) s = helper_status;
    if (s && !helper_) s = read_uses(*db_, id, r.uses);
    return s;
  }

  static Status read_uses(Connection& db, std::int64_t id, std::vector<Snapshot::Use>& uses) {
    return rows_of(
        db, "loop_edges", "loop_key, ord, edge_key, reversed, radial_ord", id, [&](const Row& row) {
          uses.push_back({key(row, 0), key(row, 1), key(row, 2), row.i(3) != 0, key(row, 4)});
        });
  }

  // The edge uses (nearly half the rows) of stored volume `id`, read on the
  // second connection in a read transaction of its own. The rows of a committed
  // version never change, so that snapshot holds the same rows as the first one
  // if it holds the volume at all.
  Status read_uses_elsewhere(std::int64_t id, std::vector<Snapshot::Use>& uses) {
    Connection& db = *helper_;
    if (Status s = db.begin_read(); !s) return s;
    bool found = false;
    Status s =
        db.select("SELECT id FROM volumes WHERE id = $1", {id}, [&](const Row&) { found = true; });
    if (s && !found) s = db_error("the volume was removed while it was read");
    if (s) s = read_uses(db, id, uses);
    if (!s) {
      db.rollback();
      return s;
    }
    return db.commit();
  }

  // Groups, parameters and surfaces: what a partial load keeps whole.
  Status read_small_tables(std::int64_t id, ModelRows& r) {
    const std::vector<Value> p{id};
    Status s = db_->select("SELECT name FROM model_groups WHERE volume_id = $1 ORDER BY group_key",
                           p, [&](const Row& row) { r.groups.push_back({row.s(0)}); });
    if (s) {
      s = db_->select(
          "SELECT group_key, name, value FROM parameters WHERE volume_id = $1 "
          "ORDER BY group_key, ord",
          p, [&](const Row& row) {
            r.parameters.push_back({key(row, 0), row.s(1), row.s(2)});
          });
    }
    if (s) {
      s = db_->select(
          "SELECT kind, cx, cy, cz, ax, ay, az, radius, radius2, height, segments FROM surfaces "
          "WHERE volume_id = $1 ORDER BY surface_key",
          p, [&](const Row& row) {
            r.surfaces.push_back({row.s(0),
                                  {row.d(1), row.d(2), row.d(3)},
                                  {row.d(4), row.d(5), row.d(6)},
                                  row.d(7),
                                  row.d(8),
                                  row.d(9),
                                  static_cast<int>(row.i(10))});
          });
    }
    return s;
  }

  // The rows of the faces named by `condition` and of what they use, renumbered
  // densely as a sheet model: no cells, and the stored radial order among the
  // uses kept (restore sorts each edge's uses by radial_ord).
  Status read_face_rows(std::int64_t id, const std::string& condition, ModelRows& r) {
    auto opt = [](const Row& row, int c) { return row.is_null(c) ? kNone : row.i(c); };
    std::vector<std::uint32_t> face_keys;
    // In key order, sorted here: on PostgreSQL the key is computed by the faces
    // view, and the server would sort every row the condition keeps.
    std::vector<std::pair<std::uint32_t, Snapshot::Face>> named;
    Status s = db_->untrusted_select(
        "SELECT f.face_key, f.group_key, f.surface_key FROM faces f JOIN volumes v ON v.id = "
        "f.volume_id WHERE f.volume_id = $1 AND (" +
            condition + ")",
        {id}, [&](const Row& row) {
          named.push_back({key(row, 0), {key(row, 1), kNone, kNone, opt(row, 2)}});
        });
    std::sort(named.begin(), named.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [k, f] : named) {
      face_keys.push_back(k);
      r.faces.push_back(f);
    }
    if (s) s = read_small_tables(id, r);
    if (s) s = db_->before_key_set_reads();
    std::vector<std::uint32_t> loop_keys;
    if (s) {
      s = rows_of(
          *db_, "loops", "loop_key, face_key, ord, point_vertex", id,
          [&](const Row& row) {
            loop_keys.push_back(key(row, 0));
            r.loops.push_back({key(row, 1), key(row, 2), opt(row, 3)});
          },
          "face_key", &face_keys);
    }
    std::vector<std::uint32_t> edge_keys;
    if (s) {
      s = rows_of(
          *db_, "loop_edges", "loop_key, ord, edge_key, reversed, radial_ord", id,
          [&](const Row& row) {
            r.uses.push_back({key(row, 0), key(row, 1), key(row, 2), row.i(3) != 0, key(row, 4)});
            edge_keys.push_back(key(row, 2));
          },
          "loop_key", &loop_keys);
    }
    std::sort(edge_keys.begin(), edge_keys.end());
    edge_keys.erase(std::unique(edge_keys.begin(), edge_keys.end()), edge_keys.end());
    std::vector<std::uint32_t> vertex_keys;
    if (s) {
      s = rows_of(
          *db_, "edges", "start_vertex, end_vertex, uses", id,
          [&](const Row& row) {
            r.edges.push_back({key(row, 0), key(row, 1)});
            r.edge_uses.push_back(key(row, 2));
            vertex_keys.push_back(key(row, 0));
            vertex_keys.push_back(key(row, 1));
          },
          "edge_key", &edge_keys);
    }
    for (const auto& l : r.loops) {
      if (l.point_vertex != kNone)
        vertex_keys.push_back(static_cast<std::uint32_t>(l.point_vertex));
    }
    std::sort(vertex_keys.begin(), vertex_keys.end());
    vertex_keys.erase(std::unique(vertex_keys.begin(), vertex_keys.end()), vertex_keys.end());
    if (s) {
      s = rows_of(
          *db_, "vertices", "x, y, z, group_key", id,
          [&](const Row& row) {
            r.vertices.push_back({{row.d(0), row.d(1), row.d(2)}, key(row, 3)});
          },
          "vertex_key", &vertex_keys);
    }
    if (!s) return s;
    // Stored keys to dense ones; a key the rows name but the set lacks is left
    // out of range, for restore to refuse.
    const auto renumber = [](const std::vector<std::uint32_t>& keys, std::uint32_t k) {
      const auto at = std::lower_bound(keys.begin(), keys.end(), k);
      return at != keys.end() && *at == k ? static_cast<std::uint32_t>(at - keys.begin())
                                          : static_cast<std::uint32_t>(keys.size());
    };
    for (auto& l : r.loops) {
      l.face = renumber(face_keys, l.face);
      if (l.point_vertex != kNone) {
        l.point_vertex = renumber(vertex_keys, static_cast<std::uint32_t>(l.point_vertex));
      }
    }
    for (auto& u : r.uses)
      u.loop = renumber(loop_keys, u.loop), u.edge = renumber(edge_keys, u.edge);
    for (auto& e : r.edges)
      e.start = renumber(vertex_keys, e.start), e.end = renumber(vertex_keys, e.end);
    // The property tables, with the values of the elements loaded (renumbered);
    // a cell table keeps its default alone, as there are no cells.
    ModelRows all;
    if (Status p = read_properties(id, all); !p) return p;
    const std::vector<std::uint32_t> no_cells;
    for (Snapshot::Property& p : all.properties) {
      const std::vector<std::uint32_t>& keys = p.owner == PropertyOwner::kVertex ? vertex_keys
                                               : p.owner == PropertyOwner::kEdge ? edge_keys
                                               : p.owner == PropertyOwner::kFace ? face_keys
                                                                                 : no_cells;
      Snapshot::Property kept{p.owner, p.name, p.type, std::move(p.fallback), {}};
      for (auto& [k, v] : p.values) {
        const std::uint32_t dense = renumber(keys, k);
        if (dense < keys.size()) kept.values.emplace_back(dense, std::move(v));
      }
      r.properties.push_back(std::move(kept));
    }
    return Status::Ok();
  }

  Result<std::vector<VolumeInfo>> volumes(const std::string& sql, const std::vector<Value>& p) {
    std::vector<VolumeInfo> out;
    if (Status s = db_->begin_read(); !s) return s.error();
    Status s = db_->select(sql, p, [&](const Row& r) { out.push_back(read_volume(r)); });
    if (!s) {
      db_->rollback();
      return s.error();
    }
    if (Status c = db_->commit(); !c) return c.error();
    // Byte order of names, the same on every backend whatever its collation.
    std::sort(out.begin(), out.end(), [](const VolumeInfo& a, const VolumeInfo& b) {
      return a.name != b.name ? a.name < b.name : a.version < b.version;
    });
    return out;
  }

  std::unique_ptr<Connection> db_;
  std::unique_ptr<Connection> helper_;  // reads in parallel with db_ (read_rows)
};

}  // namespace

Result<std::unique_ptr<Store>> make_sql_store(std::unique_ptr<Connection> connection) {
  auto store = std::make_unique<SqlStore>(std::move(connection));
  if (Status s = store->create_schema(); !s) return s.error();
  return std::unique_ptr<Store>(std::move(store));
}

}  // namespace cellforge::store

namespace cellforge {

Status check_volume_name(const std::string& name) {
  constexpr std::size_t kMaxName = 1024;
  if (name.empty()) return Error{ErrorCode::kInvalidInput, "a volume name must not be empty"};
  if (name.size() > kMaxName) {
    return Error{ErrorCode::kInvalidInput, "a volume name is at most " + std::to_string(kMaxName) +
                                               " bytes; this one has " +
                                               std::to_string(name.size())};
  }
  if (!store::is_utf8(name)) {
    return Error{ErrorCode::kInvalidInput, "a volume name must be valid UTF-8"};
  }
  for (std::size_t i = 0; i < name.size(); ++i) {
    const auto c = static_cast<unsigned char>(name[i]);
    if (c < 0x20 || c == 0x7F) {
      return Error{ErrorCode::kInvalidInput, "a volume name must not hold control characters"};
    }
    // Valid UTF-8 here: decode the code point of a lead byte.
    if (c < 0xC0) continue;
    const std::size_t n = c < 0xE0 ? 2 : c < 0xF0 ? 3 : 4;
    std::uint32_t cp = c & (0x7F >> n);
    for (std::size_t k = 1; k < n; ++k)
      cp = (cp << 6) | (static_cast<unsigned char>(name[i + k]) & 0x3F);
    char hex[16];
    std::snprintf(hex, sizeof hex, "U+%04X", static_cast<unsigned>(cp));
    if (cp >= 0x80 && cp <= 0x9F) {
      return Error{ErrorCode::kInvalidInput,
                   std::string("a volume name must not hold control characters (") + hex +
                       " at byte " + std::to_string(i) + ")"};
    }
    if (cp == 0x061C || cp == 0x200E || cp == 0x200F || (cp >= 0x202A && cp <= 0x202E) ||
        (cp >= 0x2066 && cp <= 0x2069) || cp == 0x2028 || cp == 0x2029) {
      return Error{ErrorCode::kInvalidInput,
                   std::string("a volume name must not hold invisible direction or line marks (") +
                       hex + " at byte " + std::to_string(i) + ")"};
    }
  }
  return Status::Ok();
}

Result<std::unique_ptr<Store>> open_store(const std::string& db) {
  const bool pg = db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
  auto connection =
      pg ? store::open_postgresql(db) : store::open_sqlite(db.empty() ? "cellforge.db" : db);
  if (!connection) return connection.error();
  return store::make_sql_store(std::move(connection.value()));
}

}  // namespace cellforge
