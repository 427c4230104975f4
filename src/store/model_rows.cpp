// Model <-> rows: the snapshot (topo/snapshot.h) and the derived columns; the
// volume summary (type, mass properties, bounding box) of a model.
#include "store/model_rows.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "cellforge/topo/validate.h"

namespace cellforge::store {

namespace {

// Newell vector of a loop: twice its vector area.
Vec3 newell(const std::vector<Vec3>& pts) {
  Vec3 n;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const Vec3 a = pts[i], b = pts[(i + 1) % pts.size()];
    n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
  }
  return n;
}

}  // namespace

ModelRows to_rows(const Model& m) {
  ModelRows r;
  static_cast<Snapshot&>(r) = snapshot(m);
  r.planes.reserve(r.faces.size());
  for (FaceId f : m.faces()) {
    Vec3 area;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      area = area + newell(m.loop_points(l));
    }
    const Vec3 n = normalized(area);
    r.planes.push_back({n, -dot(n, m.position(m.loop_vertices(m.outer_loop(f)).front()))});
  }
  r.edge_uses.reserve(r.edges.size());
  for (EdgeId e : m.edges()) r.edge_uses.push_back(static_cast<std::uint32_t>(m.use_count(e)));
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

  // Area of every face; volume and centroid by the divergence theorem over the
  // faces that bound cells (seen from a cell, its face's normal points out when the
  // cell is behind the face), as fans of signed tetrahedra from the origin.
  double volume = 0, area = 0;
  Vec3 vol_moment, area_moment;
  for (FaceId f : m.faces()) {
    const double w =
        (m.back_volume(f).is_valid() ? 1.0 : 0.0) - (m.front_volume(f).is_valid() ? 1.0 : 0.0);
    (m.back_volume(f).is_valid() || m.front_volume(f).is_valid() ? solid : sheet) = true;
    Vec3 face_area;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      const std::vector<Vec3> p = m.loop_points(l);
      for (std::size_t i = 1; i + 1 < p.size(); ++i) {
        const Vec3 c = cross(p[i] - p[0], p[i + 1] - p[0]);
        face_area = face_area + c;
        area_moment = area_moment + ((p[0] + p[i] + p[i + 1]) / 3.0) * (length(c) / 2);
        const double tet = w * dot(p[0], cross(p[i], p[i + 1])) / 6.0;
        volume += tet;
        vol_moment = vol_moment + ((p[0] + p[i] + p[i + 1]) / 4.0) * tet;
      }
    }
    area += length(face_area) / 2;
  }
  info.volume = volume;
  info.area = area;
  Vec3 sum;
  bool first = true;
  for (VertexId v : m.vertices()) {
    const Vec3 p = m.position(v);
    sum = sum + p;
    if (first) info.bbox_min = info.bbox_max = p;
    first = false;
    info.bbox_min = {std::min(info.bbox_min.x, p.x), std::min(info.bbox_min.y, p.y),
                     std::min(info.bbox_min.z, p.z)};
    info.bbox_max = {std::max(info.bbox_max.x, p.x), std::max(info.bbox_max.y, p.y),
                     std::max(info.bbox_max.z, p.z)};
  }
  if (volume != 0) {
    info.centroid = vol_moment / volume;
  } else if (area > 0) {
    info.centroid = area_moment / area;
  } else if (m.num_vertices() > 0) {
    info.centroid = sum / static_cast<double>(m.num_vertices());
  }
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
