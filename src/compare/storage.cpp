#include "cellforge/compare/storage.h"

namespace cellforge::compare {

StorageStats cellforge_storage(const Model& m) {
  // Records: edge slots (spare pairs too) and their use slots, two each; the runs of
  // the group index (vertex runs and the edge, face and volume runs).
  const std::size_t main_records = m.vertex_slots() + m.group_runs() + m.edge_slots() +
                                   m.use_slots() + m.loop_slots() + m.face_slots();
  const std::size_t main_bytes =
      m.vertex_slots() * Model::kVertexRecordBytes + m.vertex_group_runs() * 8 +
      m.free_vertex_slots() * 4 + m.edge_slots() * Model::kEdgeRecordBytes +
      m.use_slots() * Model::kUseRecordBytes + m.loop_slots() * Model::kLoopRecordBytes +
      m.face_slots() * Model::kFaceRecordBytes +
      // the group index beyond the vertex runs: edge, face and volume runs, and each
      // group's counts (16 B; group slots, like the 4 B below, as live groups)
      (m.group_runs() - m.vertex_group_runs()) * 8 + 16 * m.num_groups();
  const std::size_t bytes = m.topology_bytes();
  // The rest is the side table (12 B a row), volumes (8 B) and groups (4 B); the
  // side rows are not counted publicly, so they follow from the bytes.
  const std::size_t rest = bytes - main_bytes;
  const std::size_t fixed = 8 * m.num_volumes() + 4 * m.num_groups();
  const std::size_t sides = rest > fixed ? (rest - fixed) / 12 : 0;
  return {.records = main_records + sides + m.num_volumes() + m.num_groups(),
          .references = bytes / 4,
          .bytes = bytes};
}

}  // namespace cellforge::compare
