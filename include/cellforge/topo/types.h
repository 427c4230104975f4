// The small value types of the topology: an edge end, the steps of the face and
// vertex walks, a face's analytic surface and a group's attributes (model.h).
#pragma once

#include <string>

#include "cellforge/geom/vec.h"
#include "cellforge/ids.h"

namespace cellforge::inline topo {

// The analytic surface a face was faceted from (seed 000 keeps a primitive's
// defining parameters on the body; drawings, the database and feature queries
// read them). Faces without one are plain planar polygons.
struct Surface {
  std::string kind;  // "cylinder", "cone", "sphere", "torus", ...
  Vec3 center;
  Vec3 axis{0, 0, 1};
  double radius = 0;   // cylinder/sphere radius, cone base radius, torus major radius
  double radius2 = 0;  // cone top radius, torus minor radius
  double height = 0;
  int segments = 0;
  friend bool operator==(const Surface&, const Surface&) = default;
};

// A primitive's kind and parameters as the user gave them ("sphere", {"r", "10"},
// {"fn", "32"}), kept on its group.
struct Attribute {
  std::string key;
  std::string value;
  friend bool operator==(const Attribute&, const Attribute&) = default;
};

// One end of an edge, as seen from a vertex's edge cycle.
struct EdgeEnd {
  EdgeId edge;
  int end = 0;  // 0: the edge's start vertex, 1: its end vertex
  friend constexpr bool operator==(EdgeEnd, EdgeEnd) = default;
};

// One use of a face walk (Model::for_each_face_use): the use and its edge.
struct FaceUse {
  EdgeUseId use;
  EdgeId edge;
};

// One step of a vertex walk (Model::for_each_end_around): the edge end at the
// vertex and the vertex at the edge's other end.
struct VertexEnd {
  EdgeEnd end;
  VertexId other;
};

}  // namespace cellforge::inline topo
