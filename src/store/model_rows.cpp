// Model <-> rows: the snapshot (topo/snapshot.h) and the derived columns; the
// volume summary (type, mass properties, bounding box) of a model.
#include "store/model_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <thread>

#include "cellforge/shape/mass.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/topo/validate.h"

namespace cellforge::store {

namespace {

// The derived columns: each face's plane and box, each edge's use count.
void add_derived(const Model& m, ModelRows& r) {
  r.planes.reserve(m.num_faces());
  r.boxes.reserve(m.num_faces());
  for (FaceId f : m.faces()) {
    const Vec3 first = m.position(m.loop_vertices(m.outer_loop(f)).front());
    QueryBox box{first, first};
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      for (const Vec3& p : m.loop_points(l)) {
        box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y), std::min(box.min.z, p.z)};
        box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y), std::max(box.max.z, p.z)};
      }
    }
    double largest = 0;
    for (double c : {box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z}) {
      largest = std::max(largest, std::abs(c));
    }
    const double scale = largest > 0 ? std::ldexp(1.0, -std::ilogb(largest)) : 1.0;
    Vec3 area;
    for (LoopId l : m.loops_of(f)) {  // of the points times a power of two: no overflow
      std::vector<Vec3> pts = m.loop_points(l);
      for (Vec3& p : pts) p = p * scale;
      area = newell_normal(pts, area);
    }
    const Vec3 n = normalized(area);
    r.planes.push_back({n, -dot(n, first)});
    r.boxes.push_back(box);
  }
  r.edge_uses.reserve(m.num_edges());
  for (EdgeId e : m.edges()) r.edge_uses.push_back(static_cast<std::uint32_t>(m.use_count(e)));
}

}  // namespace

ModelRows to_rows(const Model& m) {
  ModelRows r;
  static_cast<Snapshot&>(r) = snapshot(m);
  add_derived(m, r);
  return r;
}

ModelRows to_rows(const Model& m, VolumeInfo& summary) {
  ModelRows r;
  std::thread other([&] {
    add_derived(m, r);
    summary = summarize(m);
  });
  Snapshot s = snapshot(m);
  other.join();
  static_cast<Snapshot&>(r) = std::move(s);
  return r;
}

Result<Model> to_model(const ModelRows& r) {
  auto m = restore(r);
  if (!m) return Error{ErrorCode::kDatabase, "stored volume: " + m.error().message};
  return m;
}

VolumeInfo summarize(const Model& m) {
  VolumeInfo info;
  info.vertices = static_cast<std::int64_t>(m.num_vertices());
  info.edges = static_cast<std::int64_t>(m.num_edges());
  info.faces = static_cast<std::int64_t>(m.num_faces());
  info.loops = static_cast<std::int64_t>(m.num_loops());
  info.cells = static_cast<std::int64_t>(m.num_volumes());
  info.groups = static_cast<std::int64_t>(m.num_groups());
  for (GroupId g : m.groups()) {
    for (const Attribute& a : m.attributes(g)) info.parameters.push_back(a);
  }

  bool solid = false, sheet = false, wire = false;
  for (EdgeId e : m.edges()) wire = wire || m.is_wire(e);
  for (VertexId v : m.vertices()) wire = wire || m.degree(v) == 0;

  for (FaceId f : m.faces()) {
    (m.back_volume(f).is_valid() || m.front_volume(f).is_valid() ? solid : sheet) = true;
  }
  const shape::MassProperties mass = shape::mass_properties(m);
  info.volume = mass.volume;
  info.area = mass.area;
  info.centroid = mass.centroid;
  info.bbox_min = mass.bbox_min;
  info.bbox_max = mass.bbox_max;
  const int kinds = int{solid} + int{sheet} + int{wire};
  info.type = kinds == 0  ? "empty"
              : kinds > 1 ? "mixed"
              : solid     ? "solid"
              : sheet     ? "sheet"
                          : "wire";
  return info;
}

bool is_utf8(const std::string& s) {
  const auto* p = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char c = p[i];
    if (c == 0) return false;
    if (c < 0x80) {
      ++i;
      continue;
    }
    std::size_t len;
    std::uint32_t cp;
    if ((c & 0xE0) == 0xC0) {
      len = 2, cp = c & 0x1F;
    } else if ((c & 0xF0) == 0xE0) {
      len = 3, cp = c & 0x0F;
    } else if ((c & 0xF8) == 0xF0) {
      len = 4, cp = c & 0x07;
    } else {
      return false;
    }
    if (i + len > n) return false;
    for (std::size_t k = 1; k < len; ++k) {
      if ((p[i + k] & 0xC0) != 0x80) return false;
      cp = (cp << 6) | (p[i + k] & 0x3F);
    }
    static constexpr std::uint32_t kMin[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < kMin[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += len;
  }
  return true;
}

}  // namespace cellforge::store
