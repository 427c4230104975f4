// snapshot / restore: the model as dense tables and back (snapshot.h).
// restore checks every key before touching the editor, rebuilds the records in key
// order and runs the validator, so hand-edited tables cannot produce a broken model.
#include "cellforge/topo/snapshot.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <numeric>
#include <type_traits>

#include "cellforge/topo/validate.h"
#include "topo/model_editor.h"

namespace cellforge::inline topo {

namespace {

constexpr std::int64_t kNone = Snapshot::kNone;

// Dense keys for the live ids of one kind, indexed by id.
template <class IdT, class Range>
std::vector<std::uint32_t> dense_keys(std::uint32_t slots, const Range& live) {
  std::vector<std::uint32_t> key(slots, kInvalidIndex);
  std::uint32_t next = 0;
  for (IdT id : live) key[id.value] = next++;
  return key;
}

std::int64_t opt_key(const std::vector<std::uint32_t>& keys, std::uint32_t id) {
  return id == kInvalidIndex ? kNone : static_cast<std::int64_t>(keys[id]);
}

Error inconsistent(const std::string& what) {
  return Error{ErrorCode::kInvalidInput, "inconsistent model tables: " + what};
}

// ---- property tables of the stored value types

static_assert(static_cast<int>(PropertyOwner::kVertex) == detail::kVertexProperty &&
              static_cast<int>(PropertyOwner::kEdge) == detail::kEdgeProperty &&
              static_cast<int>(PropertyOwner::kFace) == detail::kFaceProperty &&
              static_cast<int>(PropertyOwner::kCell) == detail::kVolumeProperty);

// f(std::type_identity<T>{}) for the C++ type T of `type`.
template <class F>
auto with_type(PropertyType type, F&& f) {
  using P = PropertyType;
  switch (type) {
    case P::kInt8:
      return f(std::type_identity<std::int8_t>{});
    case P::kInt16:
      return f(std::type_identity<std::int16_t>{});
    case P::kInt32:
      return f(std::type_identity<std::int32_t>{});
    case P::kInt64:
      return f(std::type_identity<std::int64_t>{});
    case P::kUInt8:
      return f(std::type_identity<std::uint8_t>{});
    case P::kUInt16:
      return f(std::type_identity<std::uint16_t>{});
    case P::kUInt32:
      return f(std::type_identity<std::uint32_t>{});
    case P::kUInt64:
      return f(std::type_identity<std::uint64_t>{});
    case P::kFloat:
      return f(std::type_identity<float>{});
    case P::kDouble:
      return f(std::type_identity<double>{});
    case P::kString:
      return f(std::type_identity<std::string>{});
    case P::kColour:
      return f(std::type_identity<Colour>{});
    case P::kVec3:
      break;
  }
  return f(std::type_identity<Vec3>{});
}

template <class T>
PropertyValue to_value(const T& v) {
  if constexpr (std::is_integral_v<T> && std::is_signed_v<T>)
    return std::int64_t{v};
  else if constexpr (std::is_integral_v<T>)
    return std::uint64_t{v};
  else if constexpr (std::is_floating_point_v<T>)
    return double{v};
  else
    return v;
}

// v must hold T's alternative, in T's range (check_value).
template <class T>
T from_value(const PropertyValue& v) {
  if constexpr (std::is_integral_v<T> && std::is_signed_v<T>)
    return static_cast<T>(std::get<std::int64_t>(v));
  else if constexpr (std::is_integral_v<T>)
    return static_cast<T>(std::get<std::uint64_t>(v));
  else if constexpr (std::is_floating_point_v<T>)
    return static_cast<T>(std::get<double>(v));
  else
    return std::get<T>(v);
}

// Equal bit for bit (floating-point values: -0.0 is not 0.0, a NaN is itself).
template <class T>
bool same_bits(const T& a, const T& b) {
  if constexpr (std::is_floating_point_v<T> || std::is_same_v<T, Colour> || std::is_same_v<T, Vec3>)
    return std::memcmp(&a, &b, sizeof(T)) == 0;
  else
    return a == b;
}

// The table of column c (of stored type T) over the live elements `live`.
template <class T, class Range>
void take_values(const detail::PropertyColumn& c, const Range& live, Snapshot::Property& out) {
  const auto& column = static_cast<const detail::TypedColumn<T>&>(c);
  out.fallback = to_value(column.default_value());
  std::uint32_t key = 0;
  for (auto id : live) {
    const T& v = column.get(id.value);
    if (!same_bits(v, column.default_value())) out.values.emplace_back(key, to_value(v));
    ++key;
  }
}

template <class Range>
void take_properties(const Model& m, PropertyOwner owner, const Range& live, Snapshot& r) {
  for (const auto& c : m.property_store().columns(static_cast<int>(owner))) {
    const std::optional<PropertyType> type = property_type_of(c->type());
    if (!type) continue;
    Snapshot::Property p{owner, c->name(), *type, {}, {}};
    with_type(*type, [&]<class T>(std::type_identity<T>) { take_values<T>(*c, live, p); });
    r.properties.push_back(std::move(p));
  }
}

// Every property table checked against the counts of its owner kind.
Status check_properties(const Snapshot& r, const std::size_t (&count)[4]) {
  for (std::size_t i = 0; i < r.properties.size(); ++i) {
    const Snapshot::Property& p = r.properties[i];
    const auto owner = static_cast<std::size_t>(p.owner);
    if (owner >= 4) return inconsistent("property " + std::to_string(i) + " has no owner kind");
    const std::string what = std::string(owner_name(p.owner)) + " property '" + p.name + "'";
    for (std::size_t j = 0; j < i; ++j) {
      if (r.properties[j].owner == p.owner && r.properties[j].name == p.name)
        return inconsistent(what + " is there twice");
    }
    if (Status s = check_value(p.type, p.fallback); !s)
      return inconsistent(what + ": default: " + s.error().message);
    for (std::size_t k = 0; k < p.values.size(); ++k) {
      const std::uint32_t key = p.values[k].first;
      const PropertyValue& value = p.values[k].second;
      if (key >= count[owner] || (k > 0 && key <= p.values[k - 1].first)) {
        return inconsistent(what + ": value " + std::to_string(k) + " names " +
                            std::string(owner_name(p.owner)) + " " + std::to_string(key) + " (of " +
                            std::to_string(count[owner]) + ", keys increasing)");
      }
      if (Status s = check_value(p.type, value); !s)
        return inconsistent(what + ": value of " + std::string(owner_name(p.owner)) + " " +
                            std::to_string(key) + ": " + s.error().message);
    }
  }
  return Status::Ok();
}

// The checked tables into m; slots[owner][key] is the slot of element `key`.
void put_properties(const Snapshot& r, const std::vector<std::uint32_t> (&slots)[4], Model& m) {
  for (const Snapshot::Property& p : r.properties) {
    with_type(p.type, [&]<class T>(std::type_identity<T>) {
      auto column = std::make_unique<detail::TypedColumn<T>>(p.name, from_value<T>(p.fallback));
      const auto owner = static_cast<std::size_t>(p.owner);
      for (const auto& [key, value] : p.values)
        column->at(slots[owner][key]) = from_value<T>(value);
      m.property_store().add(static_cast<int>(p.owner), std::move(column));
    });
  }
}

}  // namespace

Snapshot snapshot(const Model& m) {
  Snapshot r;
  std::uint32_t group_slots = 0, volume_slots = 0;
  for (GroupId g : m.groups()) group_slots = g.value + 1;
  for (VolumeId c : m.volumes()) volume_slots = c.value + 1;
  const auto gkey = dense_keys<GroupId>(group_slots, m.groups());
  const auto ckey = dense_keys<VolumeId>(volume_slots, m.volumes());
  const auto vkey = dense_keys<VertexId>(m.vertex_slots(), m.vertices());
  const auto ekey = dense_keys<EdgeId>(m.edge_slots(), m.edges());
  const auto fkey = dense_keys<FaceId>(m.face_slots(), m.faces());

  for (GroupId g : m.groups()) {
    r.groups.push_back({m.name(g)});
    for (const Attribute& a : m.attributes(g))
      r.parameters.push_back({gkey[g.value], a.key, a.value});
  }
  for (VolumeId c : m.volumes()) r.cells.push_back(gkey[m.group_of(c).value]);
  r.vertices.reserve(m.num_vertices());
  for (VertexId v : m.vertices()) r.vertices.push_back({m.position(v), gkey[m.group_of(v).value]});

  // Radial positions of every use, walking each edge's cycle from its first use;
  // below they are counted from the edge's use that comes first in the tables,
  // so that the rows do not depend on which use holds which slot.
  std::vector<std::uint32_t> radial_ord(m.use_slots(), 0);
  std::vector<std::uint32_t> cycle_length(m.edge_slots(), 0),
      radial_base(m.edge_slots(), kInvalidIndex);
  r.edges.reserve(m.num_edges());
  for (EdgeId e : m.edges()) {
    std::uint32_t n = 0;
    for (EdgeUseId u : m.radial(e)) radial_ord[u.value] = n++;
    cycle_length[e.value] = n;
    r.edges.push_back({vkey[m.start_of(e).value], vkey[m.end_of(e).value]});
  }
  for (std::uint32_t s = 0; s < m.num_surfaces(); ++s) r.surfaces.push_back(m.surface(s));

  r.faces.reserve(m.num_faces());
  r.loops.reserve(m.num_loops());
  r.uses.reserve(m.num_edge_uses());
  for (FaceId f : m.faces()) {
    Snapshot::Face row{gkey[m.group_of(f).value], opt_key(ckey, m.front_volume(f).value),
                       opt_key(ckey, m.back_volume(f).value), kNone};
    if (const std::uint32_t s = m.surface_of(f); s != kInvalidIndex) row.surface = s;
    r.faces.push_back(row);

    std::uint32_t ord = 0;
    for (LoopId l : m.loops_of(f)) {
      const auto loop_key = static_cast<std::uint32_t>(r.loops.size());
      Snapshot::Loop lr{fkey[f.value], ord, kNone};
      if (m.is_point_loop(l)) {
        lr.point_vertex = vkey[m.point_loop_vertex(l).value];
      } else {
        std::uint32_t k = 0;
        for (EdgeUseId u : m.uses_of(l)) {
          const EdgeId e = m.edge_of(u);
          std::uint32_t& base = radial_base[e.value];
          if (base == kInvalidIndex) base = radial_ord[u.value];
          const std::uint32_t ord =
              (radial_ord[u.value] + cycle_length[e.value] - base) % cycle_length[e.value];
          r.uses.push_back({loop_key, k++, ekey[e.value], m.is_reversed(u), ord});
        }
      }
      r.loops.push_back(lr);
      ++ord;
    }
  }
  take_properties(m, PropertyOwner::kVertex, m.vertices(), r);
  take_properties(m, PropertyOwner::kEdge, m.edges(), r);
  take_properties(m, PropertyOwner::kFace, m.faces(), r);
  take_properties(m, PropertyOwner::kCell, m.volumes(), r);
  return r;
}

Result<Model> restore(const Snapshot& r) {
  const std::size_t ng = r.groups.size(), nc = r.cells.size(), nv = r.vertices.size();
  const std::size_t ne = r.edges.size(), ns = r.surfaces.size(), nf = r.faces.size();
  const std::size_t nl = r.loops.size();
  // References first: the editor trusts its callers.
  for (const auto& p : r.parameters) {
    if (p.group >= ng) return inconsistent("a parameter names group " + std::to_string(p.group));
  }
  for (std::uint32_t g : r.cells) {
    if (g >= ng) return inconsistent("a cell names group " + std::to_string(g));
  }
  for (std::size_t i = 0; i < nv; ++i) {
    const Vec3 p = r.vertices[i].p;
    if (r.vertices[i].group >= ng || !std::isfinite(p.x) || !std::isfinite(p.y) ||
        !std::isfinite(p.z)) {
      return inconsistent("vertex " + std::to_string(i) + " has a bad group or coordinate");
    }
  }
  for (std::size_t i = 0; i < ne; ++i) {
    const auto& e = r.edges[i];
    if (e.start >= nv || e.end >= nv || e.start == e.end ||
        r.vertices[e.start].group != r.vertices[e.end].group) {
      return inconsistent("edge " + std::to_string(i) + " has bad vertices");
    }
  }
  for (std::size_t i = 0; i < nf; ++i) {
    const auto& f = r.faces[i];
    auto bad_cell = [&](std::int64_t c) {
      return c != kNone && (c < 0 || static_cast<std::size_t>(c) >= nc || r.cells[c] != f.group);
    };
    if (f.group >= ng || bad_cell(f.front) || bad_cell(f.back) ||
        (f.surface != kNone && (f.surface < 0 || static_cast<std::size_t>(f.surface) >= ns))) {
      return inconsistent("face " + std::to_string(i) + " has a bad group, cell or surface");
    }
  }
  std::vector<std::uint32_t> loop_size(nl, 0);
  std::vector<bool> has_point_loop(nv, false), has_edge(nv, false);
  for (const auto& e : r.edges) has_edge[e.start] = has_edge[e.end] = true;
  for (std::size_t i = 0; i < nl; ++i) {
    const auto& l = r.loops[i];
    const bool in_order =
        i == 0 ? l.ord == 0
               : (l.face == r.loops[i - 1].face ? l.ord == r.loops[i - 1].ord + 1 : l.ord == 0);
    if (l.face >= nf || !in_order || (i > 0 && l.face < r.loops[i - 1].face)) {
      return inconsistent("loop " + std::to_string(i) + " is out of face order");
    }
    if (l.point_vertex != kNone) {
      const auto v = static_cast<std::size_t>(l.point_vertex);
      if (l.point_vertex < 0 || v >= nv || has_point_loop[v] || has_edge[v]) {
        return inconsistent("point loop " + std::to_string(i) + " has a bad vertex");
      }
      has_point_loop[v] = true;
    }
  }
  for (std::size_t i = 0; i < r.uses.size(); ++i) {
    const auto& u = r.uses[i];
    if (u.loop >= nl || u.edge >= ne || r.loops[u.loop].point_vertex != kNone ||
        u.ord != loop_size[u.loop]++ || (i > 0 && u.loop < r.uses[i - 1].loop)) {
      return inconsistent("edge use " + std::to_string(i) + " is out of loop order");
    }
  }
  std::vector<bool> face_has_loop(nf, false);
  for (const auto& l : r.loops) face_has_loop[l.face] = true;
  for (std::size_t i = 0; i < nf; ++i) {
    if (!face_has_loop[i]) return inconsistent("face " + std::to_string(i) + " has no loop");
  }
  for (std::size_t i = 0; i < nl; ++i) {
    if (r.loops[i].point_vertex == kNone && loop_size[i] == 0) {
      return inconsistent("loop " + std::to_string(i) + " has no edge use");
    }
  }
  const std::size_t count[4] = {nv, ne, nf, nc};
  if (Status s = check_properties(r, count); !s) return s.error();

  Model m;
  {  // the editor ends (making the face marks exact) before m is checked and returned
    ModelEditor ed(m);
    std::vector<GroupId> groups;
    for (const auto& g : r.groups) groups.push_back(ed.new_group(g.name));
    for (const auto& p : r.parameters) m.set_attribute(groups[p.group], p.name, p.value);
    std::vector<VolumeId> cells;
    for (std::uint32_t g : r.cells) cells.push_back(ed.new_volume(groups[g]));
    std::vector<VertexId> vertices;
    vertices.reserve(nv);
    for (const auto& v : r.vertices) vertices.push_back(ed.new_vertex(groups[v.group], v.p));
    std::vector<EdgeId> edges;
    edges.reserve(ne);
    for (const auto& e : r.edges) edges.push_back(ed.new_edge(vertices[e.start], vertices[e.end]));
    for (const Surface& s : r.surfaces) m.add_surface(s);
    std::vector<FaceId> faces;
    faces.reserve(nf);
    auto cell = [&](std::int64_t c) { return c == kNone ? VolumeId() : cells[c]; };
    for (const auto& f : r.faces) {
      const FaceId face =
          ed.new_face(ed.intern_sides(cell(f.front), cell(f.back), groups[f.group]));
      if (f.surface != kNone) m.set_surface(face, static_cast<std::uint32_t>(f.surface));
      faces.push_back(face);
    }
    std::vector<EdgeUseId> uses(r.uses.size());
    std::size_t next_use = 0;
    for (std::size_t i = 0; i < nl; ++i) {
      const auto& l = r.loops[i];
      if (l.point_vertex != kNone) {
        ed.add_point_loop(faces[l.face], vertices[l.point_vertex]);
      } else {
        EdgeUseId first, prev;
        for (; next_use < r.uses.size() && r.uses[next_use].loop == i; ++next_use) {
          const auto& ur = r.uses[next_use];
          const EdgeUseId u = ed.new_use(edges[ur.edge], ur.reversed, faces[l.face]);
          uses[next_use] = u;
          if (prev.is_valid()) {
            ed.set_next(prev, u);
          } else {
            first = u;
          }
          prev = u;
        }
        ed.set_next(prev, first);
        ed.add_loop(faces[l.face], first);
      }
    }
    // Radial cycles in stored order.
    std::vector<std::uint32_t> by_edge(r.uses.size());
    std::iota(by_edge.begin(), by_edge.end(), 0u);
    std::sort(by_edge.begin(), by_edge.end(), [&](std::uint32_t a, std::uint32_t b) {
      const auto &x = r.uses[a], &y = r.uses[b];
      return x.edge != y.edge ? x.edge < y.edge : x.radial_ord < y.radial_ord;
    });
    std::vector<EdgeUseId> cycle;
    for (std::size_t i = 0; i < by_edge.size();) {
      const std::uint32_t e = r.uses[by_edge[i]].edge;
      cycle.clear();
      for (; i < by_edge.size() && r.uses[by_edge[i]].edge == e; ++i) {
        cycle.push_back(uses[by_edge[i]]);
      }
      ed.set_radial_cycle(edges[e], cycle);
    }
    std::vector<std::uint32_t> slots[4];
    for (VertexId v : vertices) slots[0].push_back(v.value);
    for (EdgeId e : edges) slots[1].push_back(e.value);
    for (FaceId f : faces) slots[2].push_back(f.value);
    for (VolumeId c : cells) slots[3].push_back(c.value);
    put_properties(r, slots, m);
  }

  if (auto violations = validate(m); !violations.empty()) {
    return inconsistent("the rebuilt model is invalid: " + to_string(violations));
  }
  return m;
}

}  // namespace cellforge::inline topo
