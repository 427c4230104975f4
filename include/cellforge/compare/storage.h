// Storage accounting shared by the comparison baselines (compare/): how many
// records a topology structure holds, how many reference fields (pointers or
// indices) they carry, and how many bytes they take. Geometry (positions,
// surfaces) and attributes are not topology and are counted by none of them.
#pragma once

#include <cstddef>

#include "cellforge/topo/model.h"

namespace cellforge::compare {

struct StorageStats {
  std::size_t records = 0;     // records (nodes) of every kind, including the top-level ones
  std::size_t references = 0;  // pointer or index fields summed over all records
  std::size_t bytes = 0;       // sizeof(record) x count, plus containers' heap bytes
};

// The cellforge structure's own figures: every field of its records is a 32-bit
// index, so references = topology_bytes() / 4. Records count every slot of the
// vertex, edge, use, loop and face arrays plus the side, volume and group rows.
StorageStats cellforge_storage(const Model& m);

}  // namespace cellforge::compare
