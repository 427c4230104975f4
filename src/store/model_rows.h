// A Model as the rows of the database tables (docs/database.md), and back: the
// model's Snapshot (topo/snapshot.h: dense keys, lossless, restored with checks and
// validation) plus derived columns.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/model.h"
#include "cellforge/topo/snapshot.h"

namespace cellforge::store {

inline constexpr std::int64_t kNone = Snapshot::kNone;  // a NULL key

// The rows of one stored volume: the model's snapshot plus the derived columns the
// tables carry for SQL's sake (each face's plane, each edge's use count).
struct ModelRows : Snapshot {
  struct Plane {
    Vec3 normal;
    double d = 0;
  };
  std::vector<Plane> planes;             // per face
  std::vector<QueryBox> boxes;           // per face: the box of its loops' points
  std::vector<std::uint32_t> edge_uses;  // per edge

  std::uint64_t row_count() const {
    return groups.size() + parameters.size() + cells.size() + vertices.size() + edges.size() +
           surfaces.size() + faces.size() + loops.size() + uses.size();
  }
};

ModelRows to_rows(const Model& m);
// The same, and summarize(m), the derived columns and the summary computed on a
// second thread while this one takes the snapshot (the model is only read).
ModelRows to_rows(const Model& m, VolumeInfo& summary);
// Rebuilds the model; refuses (kDatabase) rows that reference missing keys or
// that do not form a valid model.
Result<Model> to_model(const ModelRows& rows);

// Type, mass properties, bounding box and counts of m (the summary columns of
// table `volumes`); id, name, version, source and created are left empty.
VolumeInfo summarize(const Model& m);

// True when s is valid UTF-8 (no overlong forms, no surrogates) without NUL.
bool is_utf8(const std::string& s);

}  // namespace cellforge::store
