// The model database (seed 004, widened for loops, non-manifold topology and
// versions): one interface, `Store`, over SQLite (a file, the default) and
// PostgreSQL (a `postgresql://` connection string). Both backends hold the same
// schema (docs/database.md) and behave the same.
//
// A stored *volume* is one named Model (every group in it) at one version: the
// seed's Volume record. The Model's 3-cells (VolumeId) are rows of the `cells`
// table inside that record. Saving a name again adds a version; loading takes
// the latest version unless one is asked for.
//
// Guarantees: a save is one transaction (a process killed mid-save leaves the
// previous versions intact); names and values are bound parameters, never SQL
// text; put/get is lossless (same topology including loop order, edge direction
// and radial order, bit-identical coordinates, the property tables of the stored
// value types, topo/property.h). A loaded model is validated. A version may keep
// attachments beside its model (topo/attachment.h: the exact form of a Boolean
// result, boolean/exact.h), given back byte for byte by get_attachments.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/topo/attachment.h"
#include "cellforge/topo/model.h"

namespace cellforge {

struct PutOptions {
  std::string source = {};  // the CSG script the model came from, if any
  std::string object = {};  // when not empty, the volume is also listed in this object (scene)
  // Called now and then during a save with the number of rows written so far.
  std::function<void(std::uint64_t rows)> progress = {};
  // Kept with this version (table attachments): names and data valid UTF-8
  // without NUL, names distinct; otherwise the save is refused.
  std::vector<Attachment> attachments = {};
};

// One stored version of a named model: the row of table `volumes`.
struct VolumeInfo {
  std::int64_t id = 0;
  std::string name;
  int version = 0;
  std::string type;  // "solid", "sheet", "wire", "mixed" or "empty"
  Vec3 centroid;
  double volume = 0;  // enclosed by the faces that bound 3-cells
  double area = 0;    // of every face
  Vec3 bbox_min, bbox_max;
  std::string source;
  std::string created;  // UTC, ISO 8601
  std::int64_t vertices = 0, edges = 0, faces = 0, loops = 0, cells = 0, groups = 0;
  std::vector<Attribute> parameters;  // of every group, in group then attribute order
};

// Seed 004's Getpoints / Getedges / Getfaces: one kind of element alone, keyed by
// its number inside the stored volume (0, 1, ... in the saved model's id order).
struct StoredPoint {
  std::uint32_t key = 0;
  Vec3 position;
};
struct StoredEdge {
  std::uint32_t key = 0;
  std::uint32_t start = 0, end = 0;  // point keys
  std::uint32_t uses = 0;            // faces around it: 0 wire, 2 manifold, 3+ non-manifold
};
struct StoredFace {
  std::uint32_t key = 0;
  // loops[0] the outer loop, then the inner loops; each a cycle of point keys in
  // loop order (one point for a point loop).
  std::vector<std::vector<std::uint32_t>> loops;
  std::optional<std::uint32_t> front_cell, back_cell;
  Vec3 normal;  // unit normal of its plane n.x + d = 0
  double d = 0;
};

// An axis-aligned box, closed: a face or volume box meets it when the two
// overlap or touch on every axis.
struct QueryBox {
  Vec3 min, max;
};

// How a user query runs.
struct QueryOptions {
  double timeout = 300;       // seconds; a query still running then is cancelled (an error)
  std::size_t max_rows = 0;   // when not 0, at most this many rows are read
};

// What a value of a query's answer was in the database.
enum class ValueKind : std::uint8_t { kText, kInteger, kReal, kBlob };

// The answer of a read-only SQL query, values as text (nullopt for NULL): numbers
// as the database prints them (reals with 17 significant digits on SQLite; "inf",
// "Infinity", "NaN" for the non-finite ones), blobs as "\x" and two hex digits a
// byte on both backends (PostgreSQL's bytea form). `kinds` has the shape of `rows`.
struct QueryResult {
  std::vector<std::string> columns;
  std::vector<std::vector<std::optional<std::string>>> rows;
  std::vector<std::vector<ValueKind>> kinds;
  bool truncated = false;  // the query had more rows than max_rows
};

// One row of a query's answer handed over as it is read (Store::query_each):
// values and kinds as in QueryResult.
struct QueryRow {
  std::vector<std::optional<std::string>> values;
  std::vector<ValueKind> kinds;
};

// What receives a streamed answer: `columns` once, before any row; then `row` for
// each row in order. When `row` returns false the query stops there (no more
// rows are read and the database stops working on it).
struct QueryCallbacks {
  std::function<void(const std::vector<std::string>&)> columns;
  std::function<bool(const QueryRow&)> row;
};

class Store {
 public:
  virtual ~Store() = default;

  // "sqlite" or "postgresql".
  virtual std::string backend() const = 0;

  // Saves m under `name` as a new version (1 for a new name). Names must be 1 to
  // 1024 bytes of valid UTF-8 without control characters (C0, DEL, C1) or the
  // invisible direction marks and overrides (U+061C, U+200E, U+200F, U+202A-U+202E,
  // U+2066-U+2069) and line or paragraph separators (U+2028, U+2029); other names
  // are refused with kInvalidInput and nothing is written. Every call that takes a
  // name refuses such a name the same way, on both backends.
  virtual Result<VolumeInfo> put(const std::string& name, const Model& m,
                                 const PutOptions& options = {}) = 0;
  // Loads a version (0: the latest).
  virtual Result<Model> get(const std::string& name, int version = 0) = 0;
  // The attachments of a version (0: the latest), in the order they were saved;
  // empty when it has none.
  virtual Result<std::vector<Attachment>> get_attachments(const std::string& name,
                                                          int version = 0) = 0;
  virtual Result<std::vector<StoredPoint>> get_points(const std::string& name, int version = 0) = 0;
  virtual Result<std::vector<StoredEdge>> get_edges(const std::string& name, int version = 0) = 0;
  virtual Result<std::vector<StoredFace>> get_faces(const std::string& name, int version = 0) = 0;
  // A partial load: the faces of a version that satisfy `condition`, an SQL
  // condition on the row `f` of table faces and the row `v` of table volumes
  // (e.g. "f.group_key = 1", or a spatial query on face_tiles, docs/database.md),
  // with their loops, edges and vertices, as a sheet model (no 3-cells, no wires,
  // no isolated points; every group and surface kept; the property tables with
  // the values of the elements loaded, a cell table with its default alone), validated. Edge directions,
  // loop starts and radial order are the stored ones. The condition runs
  // read-only; a condition that is not one read-only SQL expression is refused.
  virtual Result<Model> get_faces_where(const std::string& name, const std::string& condition,
                                        int version = 0) = 0;
  // The keys of the faces of a version whose bounding boxes meet `box`, in key
  // order: an indexed query (the face_tiles spatial index, then each face's box).
  virtual Result<std::vector<std::uint32_t>> faces_in_box(const std::string& name,
                                                          const QueryBox& box,
                                                          int version = 0) = 0;
  // Every stored version whose bounding box meets `box` (volume_boxes), by name
  // and version.
  virtual Result<std::vector<VolumeInfo>> volumes_in_box(const QueryBox& box) = 0;

  virtual Result<VolumeInfo> info(const std::string& name, int version = 0) = 0;
  // The latest version of every name, by name.
  virtual Result<std::vector<VolumeInfo>> list() = 0;
  // Every version of one name, oldest first.
  virtual Result<std::vector<VolumeInfo>> versions(const std::string& name) = 0;
  // Removes every version of `name`; returns how many there were (0: none).
  virtual Result<int> remove(const std::string& name) = 0;
  // Removes one version of `name`; returns 1, or 0 when there is no such version.
  // The other versions keep their numbers.
  virtual Result<int> remove_version(const std::string& name, int version) = 0;
  // The volume names listed in an object (scene), in the order they were added.
  virtual Result<std::vector<std::string>> get_object(const std::string& name) = 0;

  // Runs one SQL query that must not write (refused otherwise), with the rights of
  // a reader of the model tables only (docs/database.md, "User SQL").
  virtual Result<QueryResult> query(const std::string& sql, const QueryOptions& options = {}) = 0;
  // The same query, streamed: each row goes to `callbacks` as soon as it is read,
  // and none is kept, so memory does not grow with the answer (SQLite steps the
  // statement; PostgreSQL reads in single-row mode). Rows read before an error
  // have been handed over when the error is returned. The result says whether
  // rows were left out by options.max_rows (QueryResult::truncated).
  virtual Result<bool> query_each(const std::string& sql, const QueryOptions& options,
                                  const QueryCallbacks& callbacks) = 0;
};

// Opens (creating the schema if needed) the database named by `db`: a
// `postgresql://` or `postgres://` URL selects PostgreSQL, anything else is an
// SQLite file path ("" means "cellforge.db").
Result<std::unique_ptr<Store>> open_store(const std::string& db);

// Checks a volume name as put() does; the error says what is wrong.
Status check_volume_name(const std::string& name);

}  // namespace cellforge
