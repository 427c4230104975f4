// Snapshot: a model as plain, id-free tables, and back. It keeps everything the
// bulk builder would recompute or lose — edge directions, where each loop starts,
// loop order, radial order, point loops, coincident edges, free-standing cells — so
// snapshot(restore(snapshot(m))) == snapshot(m): the same topology and geometry, the
// same vertex, edge, face, volume and group ids when m has no free slots (edge uses
// and loops are renumbered in face order; the order of each vertex's edge cycle is
// not kept). The model database stores it; lossless file formats can too.
//
// Keys are dense: the live entities of each kind numbered 0, 1, ... in increasing
// id order; loops in face order, then loop order; uses in loop order.
//
// Property tables (property.h) of the stored value types are kept too, each with
// its default and the values of the elements that differ from it (bit for bit:
// -0.0 differs from 0.0), by key; tables of other value types are left out.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"
#include "cellforge/topo/property.h"

namespace cellforge::inline topo {

struct Snapshot {
  static constexpr std::int64_t kNone = -1;  // an absent key

  struct Group {
    std::string name;
    friend bool operator==(const Group&, const Group&) = default;
  };
  struct Parameter {
    std::uint32_t group;
    std::string name, value;
    friend bool operator==(const Parameter&, const Parameter&) = default;
  };
  struct Vertex {
    Vec3 p;
    std::uint32_t group;
    friend bool operator==(const Vertex&, const Vertex&) = default;
  };
  struct Edge {
    std::uint32_t start, end;
    friend bool operator==(const Edge&, const Edge&) = default;
  };
  struct Face {
    std::uint32_t group;
    std::int64_t front = kNone, back = kNone, surface = kNone;
    friend bool operator==(const Face&, const Face&) = default;
  };
  struct Loop {
    std::uint32_t face;
    std::uint32_t ord;  // 0: the outer loop
    std::int64_t point_vertex = kNone;
    friend bool operator==(const Loop&, const Loop&) = default;
  };
  struct Use {
    std::uint32_t loop;
    std::uint32_t ord;  // position in its loop, 0 = the loop's first use
    std::uint32_t edge;
    bool reversed;
    std::uint32_t radial_ord;  // position in its edge's radial cycle, 0 = the first use
    friend bool operator==(const Use&, const Use&) = default;
  };

  struct Property {
    PropertyOwner owner;
    std::string name;  // unique among the properties of one owner kind
    PropertyType type;
    PropertyValue fallback;  // the default
    // (key, value) of the elements whose value is not the default, keys increasing.
    std::vector<std::pair<std::uint32_t, PropertyValue>> values;
    friend bool operator==(const Property&, const Property&) = default;
  };

  std::vector<Group> groups;
  std::vector<Parameter> parameters;  // in group, then attribute order
  std::vector<std::uint32_t> cells;   // the group of each 3-cell
  std::vector<Vertex> vertices;
  std::vector<Edge> edges;
  std::vector<Surface> surfaces;
  std::vector<Face> faces;
  std::vector<Loop> loops;
  std::vector<Use> uses;
  std::vector<Property> properties;  // by owner kind, then in the order they were added
  friend bool operator==(const Snapshot&, const Snapshot&) = default;
};

Snapshot snapshot(const Model& m);
// Rebuilds the model. Every key (and every property value's type and range) is
// checked before anything is built, and the result must pass validate();
// otherwise an error (kInvalidInput) names the first offending row.
Result<Model> restore(const Snapshot& s);

}  // namespace cellforge::inline topo
