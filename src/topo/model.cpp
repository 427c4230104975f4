// Model: read access to the cycle structure, iteration, sizes, attributes.
#include "cellforge/topo/model.h"

#include <algorithm>
#include <iterator>

#include "cellforge/geom/polygon.h"

namespace cellforge::inline topo {

namespace {

template <class IdT>
LiveIds<IdT> live_range(const Model& m, std::uint32_t slots) {
  return LiveIds<IdT>(&m, slots, [](const void* p, std::uint32_t i) {
    return static_cast<const Model*>(p)->is_live(IdT(i));
  });
}

template <class IdT>
GroupMembers<IdT> group_range(const Model& m, const std::vector<detail::GroupRun>& runs, GroupId g,
                              std::uint32_t slots) {
  return GroupMembers<IdT>(&m, runs, g.value, slots, [](const void* p, std::uint32_t i) {
    return static_cast<const Model*>(p)->is_live(IdT(i));
  });
}

}  // namespace

GroupMembers<VertexId> Model::vertices(GroupId g) const {
  return group_range<VertexId>(*this, vertex_groups_, g, vertex_slots());
}
GroupMembers<EdgeId> Model::edges(GroupId g) const {
  return group_range<EdgeId>(*this, edge_groups_, g, edge_slots());
}
GroupMembers<FaceId> Model::faces(GroupId g) const {
  return group_range<FaceId>(*this, face_groups_, g, face_slots());
}
GroupMembers<VolumeId> Model::volumes(GroupId g) const {
  return group_range<VolumeId>(*this, volume_groups_, g, static_cast<std::uint32_t>(volumes_.size()));
}

GroupId Model::group_of(VertexId v) const {
  assert(is_live(v));
  const auto after = std::upper_bound(
      vertex_groups_.begin(), vertex_groups_.end(), v.value,
      [](std::uint32_t x, const GroupRun& run) { return x < run.first; });
  return GroupId(std::prev(after)->group);
}

bool Model::empty() const {
  for (std::size_t n : live_) {
    if (n != 0) return false;
  }
  return true;
}

LiveIds<VertexId> Model::vertices() const { return live_range<VertexId>(*this, vertex_slots()); }
LiveIds<EdgeId> Model::edges() const { return live_range<EdgeId>(*this, edge_slots()); }
LiveIds<EdgeUseId> Model::edge_uses() const { return live_range<EdgeUseId>(*this, use_slots()); }
std::vector<LoopId> Model::loops() const {
  std::vector<LoopId> out;
  out.reserve(num_loops());
  for (FaceId f : faces()) {
    if (faces_[f.value].first != kInvalidIndex) out.push_back(LoopId(f.value));
  }
  for (FaceId f : faces()) {
    for (LoopId l = next_loop(LoopId(f.value)); l.is_valid(); l = next_loop(l)) out.push_back(l);
  }
  return out;
}

bool Model::is_live(LoopId l) const {
  if (!l.is_valid()) return false;
  if (!(l.value & kInnerLoopBit)) return is_live(FaceId(l.value)) && faces_[l.value].first != kInvalidIndex;
  const std::uint32_t r = l.value & ~kInnerLoopBit;
  if (r >= loops_.size() || loops_[r].first == kDead) return false;
  const FaceId f = face_of(l);  // a listed face's first record is its outer loop
  return f.is_valid() && is_live(f) && faces_[f.value].first != (r | kTagBit);
}
LiveIds<FaceId> Model::faces() const { return live_range<FaceId>(*this, face_slots()); }
LiveIds<VolumeId> Model::volumes() const {
  return live_range<VolumeId>(*this, static_cast<std::uint32_t>(volumes_.size()));
}
LiveIds<GroupId> Model::groups() const {
  return live_range<GroupId>(*this, static_cast<std::uint32_t>(groups_.size()));
}

std::size_t Model::degree(VertexId v) const {
  const auto ends = ends_around(v);
  return static_cast<std::size_t>(std::distance(ends.begin(), ends.end()));
}

std::size_t Model::use_count(EdgeId e) const {
  const auto uses = radial(e);
  return static_cast<std::size_t>(std::distance(uses.begin(), uses.end()));
}

EdgeUseId Model::loop_prev(EdgeUseId u) const {
  EdgeUseId p = u;
  while (loop_next(p) != u) p = loop_next(p);
  return p;
}

LoopId Model::loop_of(EdgeUseId u) const {
  const FaceId f = face_of(u);
  if (!(faces_[f.value].first & kTagBit)) return LoopId(f.value);  // the face's only loop
  for (LoopId l : loops_of(f)) {
    for (EdgeUseId w : uses_of(l))
      if (w == u) return l;
  }
  return LoopId();
}

std::size_t Model::loop_length(LoopId l) const {
  const auto uses = uses_of(l);
  return static_cast<std::size_t>(std::distance(uses.begin(), uses.end()));
}

std::size_t Model::inner_loop_count(FaceId f) const {
  std::size_t n = 0;
  for (LoopId l = next_loop(outer_loop(f)); l.is_valid(); l = next_loop(l)) ++n;
  return n;
}

std::vector<VertexId> Model::loop_vertices(LoopId l) const {
  std::vector<VertexId> out;
  const EdgeUseId first = loop_first(l);
  if (!first.is_valid()) {
    out.push_back(point_loop_vertex(l));
    return out;
  }
  for (EdgeUseId u : uses_of(l)) out.push_back(use_start(u));
  return out;
}

std::vector<Vec3> Model::loop_points(LoopId l) const {
  std::vector<Vec3> out;
  for (VertexId v : loop_vertices(l)) out.push_back(position(v));
  return out;
}

Vec3 Model::face_normal(FaceId f) const {
  return newell_normal(loop_points(outer_loop(f)));
}

std::size_t Model::spare_pairs() const {
  std::size_t n = 0;
  for (std::uint32_t i = 0; i < edge_slots(); ++i) n += is_spare_pair(i) ? 1 : 0;
  return n;
}

std::size_t Model::topology_bytes() const {
  static_assert(sizeof(VertexRec) == kVertexRecordBytes);
  static_assert(2 * sizeof(EndRec) == kEdgeRecordBytes);
  static_assert(sizeof(UseRec) + sizeof(std::uint32_t) == kUseRecordBytes);
  static_assert(sizeof(LoopRec) == kLoopRecordBytes);
  static_assert(sizeof(FaceRec) == kFaceRecordBytes);
  return vertices_.size() * sizeof(VertexRec) + group_runs() * sizeof(GroupRun) +
         group_counts_.size() * sizeof(GroupCounts) +
         free_vertices_.size() * sizeof(std::uint32_t) + ends_.size() * sizeof(EndRec) +
         uses_.size() * sizeof(UseRec) + radial_.size() * sizeof(std::uint32_t) +
         loops_.size() * sizeof(LoopRec) +
         faces_.size() * sizeof(FaceRec) + sides_.size() * sizeof(SidesRec) +
         volumes_.size() * sizeof(VolumeRec) + groups_.size() * sizeof(std::uint32_t);
}

void Model::set_attribute(GroupId g, std::string key, std::string value) {
  for (Attribute& a : groups_[g.value].attributes) {
    if (a.key == key) {
      a.value = std::move(value);
      return;
    }
  }
  groups_[g.value].attributes.push_back({std::move(key), std::move(value)});
}

std::string Model::attribute(GroupId g, const std::string& key) const {
  for (const Attribute& a : groups_[g.value].attributes) {
    if (a.key == key) return a.value;
  }
  return {};
}

std::uint32_t Model::add_surface(Surface s) {
  surfaces_.push_back(std::move(s));
  return static_cast<std::uint32_t>(surfaces_.size() - 1);
}

void Model::set_surface(FaceId f, std::uint32_t surface) {
  if (face_surface_.size() <= f.value) face_surface_.resize(faces_.size(), kInvalidIndex);
  face_surface_[f.value] = surface;
}

bool Model::is_smooth(EdgeId e) const {
  const EdgeUseId first = first_use(e);
  if (!first.is_valid() || radial_next(first) == first) return false;
  const std::uint32_t s = surface_of(face_of(first));
  if (s == kInvalidIndex) return false;
  for (EdgeUseId u : radial(e))
    if (surface_of(face_of(u)) != s) return false;
  return true;
}

}  // namespace cellforge::inline topo
