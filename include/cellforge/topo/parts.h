// Groups as parts: a group taken out into a model of its own, and a model's groups
// added to another, each with the map from the old ids to the new ones.
//
// Both copy the topology exactly as the snapshot does (snapshot.h: edge directions,
// where each loop starts, loop and radial order, point loops, coincident edges,
// free-standing cells), the positions, the groups' names and attributes, the faces'
// analytic surfaces and the property tables (property.h; a property of another
// value type under the same name in the target is left as it is and the values
// are not copied). They read only the groups copied, through the group index
// (Model::faces(g) and friends), so their cost is that of the part, not of the
// model. A valid source gives a valid result.
#pragma once

#include <functional>
#include <vector>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

// Old id -> new id, indexed by the old id's slot; invalid for an id not copied.
struct IdMaps {
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
  std::vector<FaceId> faces;
  std::vector<VolumeId> volumes;
  std::vector<GroupId> groups;

  VertexId operator[](VertexId old) const { return at(vertices, old); }
  EdgeId operator[](EdgeId old) const { return at(edges, old); }
  FaceId operator[](FaceId old) const { return at(faces, old); }
  VolumeId operator[](VolumeId old) const { return at(volumes, old); }
  GroupId operator[](GroupId old) const { return at(groups, old); }

 private:
  template <class IdT>
  static IdT at(const std::vector<IdT>& map, IdT old) {
    return old.is_valid() && old.value < map.size() ? map[old.value] : IdT();
  }
};

struct Extracted {
  Model model;  // one group: g's copy
  IdMaps ids;   // m's ids -> model's ids
};

// A new model holding a copy of group g of m (m is unchanged). An error when g is
// not a live group.
Result<Extracted> extract(const Model& m, GroupId g);

// Adds a copy of every group of `other` to m, as new groups; returns other's ids ->
// m's ids. An error (m unchanged) when other is m itself, or when m would pass the
// id limits (Model::kMaxEdges, kMaxFaces).
Result<IdMaps> append(Model& m, const Model& other);

// append, with every copied position p put at place(p): a copy moved by any map that
// keeps each loop turning as it did (a mirror would need the loops reversed). The
// faces' analytic surfaces are not copied, since their parameters do not follow the
// map. The topology is copied record by record, which costs a fraction of building
// the moved mesh again (topo/builder.h).
Result<IdMaps> append(Model& m, const Model& other, const std::function<Vec3(Vec3)>& place);

}  // namespace cellforge::inline topo
