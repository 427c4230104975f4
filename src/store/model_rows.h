// A Model as the rows of the database tables (docs/database.md), and back.
//
// Keys are dense per stored volume: the live entities of each kind numbered
// 0, 1, ... in increasing id order (loops and edge uses in face and loop order),
// so a model with no free slots comes back with the same ids. Loading rebuilds
// every record with the topology's editor from these rows, which keeps what the
// bulk builder would recompute (edge direction, loop start, radial order, point
// loops, coincident edges), then validates the result.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/model.h"

namespace cellforge::store {

inline constexpr std::int64_t kNone = -1;  // a NULL key

struct ModelRows {
  struct Group {
    std::string name;
  };
  struct Parameter {
    std::uint32_t group;
    std::string name, value;
  };
  struct Vertex {
    Vec3 p;
    std::uint32_t group;
  };
  struct Edge {
    std::uint32_t start, end;
    std::uint32_t uses;
  };
  struct Face {
    std::uint32_t group;
    std::int64_t front = kNone, back = kNone, surface = kNone;
    Vec3 normal;
    double d = 0;
  };
  struct Loop {
    std::uint32_t face;
    std::uint32_t ord;  // 0: the outer loop
    std::int64_t point_vertex = kNone;
  };
  struct Use {
    std::uint32_t loop;
    std::uint32_t ord;  // position in its loop, 0 = the loop's first use
    std::uint32_t edge;
    bool reversed;
    std::uint32_t radial_ord;  // position in its edge's radial cycle, 0 = the first use
  };

  std::vector<Group> groups;
  std::vector<Parameter> parameters;  // in group, then attribute order
  std::vector<std::uint32_t> cells;   // the group of each 3-cell
  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Surface> surfaces;
  std::vector<Face> faces;
  std::vector<Loop> loops;  // in face, then loop order
  std::vector<Use> uses;    // in loop, then use order

  std::uint64_t row_count() const {
    return groups.size() + parameters.size() + cells.size() + vertices.size() + edges.size() +
           surfaces.size() + faces.size() + loops.size() + uses.size();
  }
};

ModelRows to_rows(const Model& m);
// Rebuilds the model; refuses (kDatabase) rows that reference missing keys or
// that do not form a valid model.
Result<Model> to_model(const ModelRows& rows);

// Type, mass properties, bounding box and counts of m (the summary columns of
// table `volumes`); id, name, version, source and created are left empty.
VolumeInfo summarize(const Model& m);

// True when s is valid UTF-8 (no overlong forms, no surrogates) without NUL.
bool is_utf8(const std::string& s);

}  // namespace cellforge::store
