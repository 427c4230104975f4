#include "shape/draft.h"

#include <cmath>

namespace cellforge::shape {

Draft Draft::solid(std::string kind) {
  Draft d;
  d.mesh.volumes = 1;
  d.mesh.group_name = kind;
  d.attribute("kind", std::move(kind));
  return d;
}

Draft Draft::sheet(std::string kind) {
  Draft d = solid(std::move(kind));
  d.mesh.volumes = 0;
  return d;
}

std::uint32_t Draft::vertex(Vec3 p) {
  mesh.positions.push_back(p);
  return static_cast<std::uint32_t>(mesh.positions.size() - 1);
}

int Draft::surface(Surface s) {
  surfaces.push_back(std::move(s));
  return static_cast<int>(surfaces.size() - 1);
}

void Draft::face(std::vector<Loop> loops, int surface) {
  MeshFace f;
  f.loops = std::move(loops);
  f.back = mesh.volumes > 0 ? 0 : -1;
  mesh.faces.push_back(std::move(f));
  face_surface.push_back(surface);
}

void Draft::attribute(std::string key, std::string value) {
  for (Attribute& a : attributes) {
    if (a.key == key) {
      a.value = std::move(value);
      return;
    }
  }
  attributes.push_back({std::move(key), std::move(value)});
}

void Draft::attribute(std::string key, double value) {
  attribute(std::move(key), format_number(value));
}

void Draft::attribute(std::string key, bool value) {
  attribute(std::move(key), std::string(value ? "true" : "false"));
}

void Draft::attribute(std::string key, int value) {
  attribute(std::move(key), std::to_string(value));
}

void Draft::faceting(const Faceting& f, int segments) {
  attribute("fn", f.fn);
  attribute("fa", f.fa);
  attribute("fs", f.fs);
  attribute("segments", segments);
}

Result<GroupId> commit(Model& m, const Draft& d) {
  // Every result finite and within the predicates' range (faceting.h).
  for (std::size_t i = 0; i < d.mesh.positions.size(); ++i) {
    const Vec3 p = d.mesh.positions[i];
    for (double c : {p.x, p.y, p.z}) {
      if (!(std::fabs(c) <= kMaxCoordinate)) {
        return invalid("the parameters put vertex " + std::to_string(i) + " at (" +
                       format_number(p.x) + ", " + format_number(p.y) + ", " + format_number(p.z) +
                       "), beyond the coordinate limit of 2^120 (about 1.3e36)");
      }
    }
  }
  auto built = build_mesh(m, d.mesh);
  if (!built) return built.error();
  const GroupId g = built->group;
  std::vector<std::uint32_t> ids(d.surfaces.size(), kInvalidIndex);
  for (std::size_t i = 0; i < d.face_surface.size(); ++i) {
    const int s = d.face_surface[i];
    if (s < 0) continue;
    if (ids[s] == kInvalidIndex) ids[s] = m.add_surface(d.surfaces[s]);
    m.set_surface(built->faces[i], ids[s]);
  }
  for (const Attribute& a : d.attributes) m.set_attribute(g, a.key, a.value);
  return g;
}

}  // namespace cellforge::shape
