// extract / append (parts.h): copies groups between models through the editor, in
// the order restore (snapshot.cpp) rebuilds a model: groups, volumes, vertices,
// edges, faces with their loops and uses, then every radial cycle in its source
// order. Each group's elements come from the group index, so only the groups
// copied are read.
#include "cellforge/topo/parts.h"

#include <span>

#include "cellforge/topo/property.h"
#include "topo/model_editor.h"

namespace cellforge::inline topo {

namespace {

// The property columns of src's kind `kind`, copied into dst for the ids `map`
// gives (old slot -> new id).
template <class IdT>
void copy_properties(Model& dst, const Model& src, int kind, const std::vector<IdT>& map) {
  for (const auto& column : src.property_store().columns(kind)) {
    detail::PropertyColumn* to = dst.property_store().find(kind, column->name());
    if (!to) to = dst.property_store().add(kind, column->empty_like());
    if (to->type() != column->type()) continue;
    for (std::uint32_t i = 0; i < map.size(); ++i)
      if (map[i].is_valid()) column->copy_to(i, *to, map[i].value);
  }
}

// place: where each position goes (null: where it is); surfaces: whether the faces'
// analytic surfaces are copied.
IdMaps copy_groups(Model& dst, const Model& src, std::span<const GroupId> groups,
                   const std::function<Vec3(Vec3)>& place = nullptr, bool surfaces = true) {
  IdMaps ids;
  ids.groups.assign(groups.empty() ? 0 : groups.back().value + 1, GroupId());
  for (GroupId g : groups)
    if (g.value >= ids.groups.size()) ids.groups.resize(g.value + 1);
  ids.vertices.assign(src.vertex_slots(), VertexId());
  ids.edges.assign(src.edge_slots(), EdgeId());
  ids.faces.assign(src.face_slots(), FaceId());
  std::uint32_t volume_slots = 0;
  for (GroupId g : groups)
    for (VolumeId c : src.volumes(g)) volume_slots = std::max(volume_slots, c.value + 1);
  ids.volumes.assign(volume_slots, VolumeId());
  std::vector<EdgeUseId> use_map(src.use_slots());
  std::vector<std::uint32_t> surface_map(src.num_surfaces(), kInvalidIndex);
  {
    ModelEditor ed(dst);
    for (GroupId g : groups) {
      const GroupId ng = ed.new_group(src.name(g));
      for (const Attribute& a : src.attributes(g)) dst.set_attribute(ng, a.key, a.value);
      ids.groups[g.value] = ng;
    }
    for (GroupId g : groups)
      for (VolumeId c : src.volumes(g)) ids.volumes[c.value] = ed.new_volume(ids.groups[g.value]);
    for (GroupId g : groups)
      for (VertexId v : src.vertices(g))
        ids.vertices[v.value] = ed.new_vertex(ids.groups[g.value], place ? place(src.position(v)) : src.position(v));
    for (GroupId g : groups)
      for (EdgeId e : src.edges(g))
        ids.edges[e.value] = ed.new_edge(ids[src.start_of(e)], ids[src.end_of(e)]);
    for (GroupId g : groups) {
      for (FaceId f : src.faces(g)) {
        const FaceId nf = ed.new_face(
            ed.intern_sides(ids[src.front_volume(f)], ids[src.back_volume(f)], ids.groups[g.value]));
        ids.faces[f.value] = nf;
        if (const std::uint32_t s = src.surface_of(f); surfaces && s != kInvalidIndex) {
          if (surface_map[s] == kInvalidIndex) surface_map[s] = dst.add_surface(src.surface(s));
          dst.set_surface(nf, surface_map[s]);
        }
        for (LoopId l : src.loops_of(f)) {
          if (src.is_point_loop(l)) {
            ed.add_point_loop(nf, ids[src.point_loop_vertex(l)]);
            continue;
          }
          EdgeUseId first, prev;
          for (EdgeUseId u : src.uses_of(l)) {
            const EdgeUseId w = ed.new_use(ids[src.edge_of(u)], src.is_reversed(u), nf);
            use_map[u.value] = w;
            if (prev.is_valid())
              ed.set_next(prev, w);
            else
              first = w;
            prev = w;
          }
          ed.set_next(prev, first);
          ed.add_loop(nf, first);
        }
      }
    }
    std::vector<EdgeUseId> cycle;
    for (GroupId g : groups) {
      for (EdgeId e : src.edges(g)) {
        cycle.clear();
        for (EdgeUseId u : src.radial(e)) cycle.push_back(use_map[u.value]);
        ed.set_radial_cycle(ids.edges[e.value], cycle);
      }
    }
  }
  copy_properties(dst, src, detail::kVertexProperty, ids.vertices);
  copy_properties(dst, src, detail::kEdgeProperty, ids.edges);
  copy_properties(dst, src, detail::kFaceProperty, ids.faces);
  copy_properties(dst, src, detail::kVolumeProperty, ids.volumes);
  return ids;
}

// The edge and face slots that copying `groups` of src into m may need (spare
// pairs counted as one per overflow use, an upper bound).
Status check_limits(const Model& m, const Model& src, std::span<const GroupId> groups) {
  std::size_t edges = 0, faces = 0, overflow = 0;
  for (GroupId g : groups) {
    edges += src.num_edges(g);
    faces += src.num_faces(g);
    for (EdgeId e : src.edges(g)) {
      const std::size_t n = src.use_count(e);
      overflow += n > 2 ? n - 2 : 0;
    }
  }
  if (m.edge_slots() + edges + overflow >= Model::kMaxEdges)
    return Error{ErrorCode::kInvalidInput, "too many edges: " + std::to_string(m.edge_slots() + edges)};
  if (m.face_slots() + faces >= Model::kMaxFaces)
    return Error{ErrorCode::kInvalidInput, "too many faces: " + std::to_string(m.face_slots() + faces)};
  return Status::Ok();
}

Result<IdMaps> append_all(Model& m, const Model& other, const std::function<Vec3(Vec3)>& place, bool surfaces) {
  if (&m == &other) return Error{ErrorCode::kInvalidInput, "append: a model cannot be appended to itself"};
  std::vector<GroupId> groups;
  for (GroupId g : other.groups()) groups.push_back(g);
  if (Status s = check_limits(m, other, groups); !s) return s.error();
  return copy_groups(m, other, groups, place, surfaces);
}

}  // namespace

Result<Extracted> extract(const Model& m, GroupId g) {
  if (!m.is_live(g)) return Error{ErrorCode::kInvalidInput, "extract: " + g.str() + " is not a live group"};
  Extracted out;
  const GroupId one[] = {g};
  out.ids = copy_groups(out.model, m, one);
  return out;
}

Result<IdMaps> append(Model& m, const Model& other) { return append_all(m, other, nullptr, true); }

Result<IdMaps> append(Model& m, const Model& other, const std::function<Vec3(Vec3)>& place) {
  return append_all(m, other, place, /*surfaces=*/false);
}

}  // namespace cellforge::inline topo
