// make_polyhedron: OpenSCAD's polyhedron(points, faces), checked before it is built.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "shape/draft.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/volume.h"

namespace cellforge::shape {

namespace {

std::string face_name(std::size_t f) { return "face " + std::to_string(f); }

Status check_indices(const PolyhedronOptions& o) {
  for (std::size_t i = 0; i < o.points.size(); ++i) {
    const Vec3 p = o.points[i];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
      return invalid("point " + std::to_string(i) + " is not finite");
    }
  }
  if (o.faces.size() < 4) {
    return invalid("a polyhedron needs at least 4 faces, got " + std::to_string(o.faces.size()));
  }
  for (std::size_t f = 0; f < o.faces.size(); ++f) {
    const auto& face = o.faces[f];
    if (face.size() < 3) {
      return invalid(face_name(f) + " has " + std::to_string(face.size()) + " points (at least 3)");
    }
    for (std::uint32_t i : face) {
      if (i >= o.points.size()) {
        return invalid(face_name(f) + " names point " + std::to_string(i) + " but there are " +
                       std::to_string(o.points.size()) + " points");
      }
    }
    auto sorted = face;
    std::sort(sorted.begin(), sorted.end());
    if (auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end()) {
      return invalid(face_name(f) + " names point " + std::to_string(*dup) + " twice");
    }
  }
  return Status::Ok();
}

// Collinear points, or a point off the plane of the first three non-collinear ones.
Status check_planar(const PolyhedronOptions& o) {
  for (std::size_t f = 0; f < o.faces.size(); ++f) {
    const auto& face = o.faces[f];
    const Vec3 a = o.points[face[0]], b = o.points[face[1]];
    std::size_t k = 2;
    while (k < face.size() && collinear3d(a, b, o.points[face[k]])) ++k;
    if (k == face.size()) return invalid(face_name(f) + " is degenerate: its points are collinear");
    const Vec3 c = o.points[face[k]];
    const Vec3 n = normalized(cross(b - a, c - a));
    for (std::size_t i = 2; i < face.size(); ++i) {
      const Vec3 p = o.points[face[i]];
      const bool off = o.planarity_tolerance > 0 ? std::fabs(dot(p - a, n)) > o.planarity_tolerance
                                                 : orient3d(a, b, c, p) != 0;
      if (off) {
        return invalid(face_name(f) + " is not planar: point " + std::to_string(face[i]) +
                       " lies off the plane of points " + std::to_string(face[0]) + ", " +
                       std::to_string(face[1]) + ", " + std::to_string(face[k]));
      }
    }
  }
  return Status::Ok();
}

// Closed and consistently oriented: every edge is used as often in each direction.
Status check_closed(const std::vector<Loop>& faces) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::pair<int, std::size_t>> balance;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Loop& loop = faces[f];
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t a = loop[i], b = loop[(i + 1) % loop.size()];
      auto& entry = balance[{std::min(a, b), std::max(a, b)}];
      entry.first += a < b ? 1 : -1;
      entry.second = f;
    }
  }
  for (const auto& [edge, entry] : balance) {
    if (entry.first == 0) continue;
    return invalid("the surface is open or inconsistently oriented at edge (" +
                   std::to_string(edge.first) + ", " + std::to_string(edge.second) + ") of " +
                   face_name(entry.second) + ": it runs " + std::to_string(std::abs(entry.first)) +
                   " more time(s) one way than the other");
  }
  return Status::Ok();
}

}  // namespace

Result<GroupId> make_polyhedron(Model& m, const PolyhedronOptions& o) {
  if (Status s = check_indices(o); !s) return s.error();
  if (Status s = check_planar(o); !s) return s.error();
  std::vector<Loop> faces = o.faces;
  if (o.clockwise) {
    for (Loop& f : faces) std::reverse(f.begin(), f.end());
  }
  if (Status s = check_closed(faces); !s) return s.error();
  if (volume_sign(o.points, faces) <= 0) {
    return invalid(std::string("the faces point inward (the enclosed volume is not positive); ") +
                   (o.clockwise ? "list each face clockwise seen from outside"
                                : "list each face counterclockwise seen from outside"));
  }
  Draft d = Draft::solid("polyhedron");
  d.attribute("points", static_cast<int>(o.points.size()));
  d.attribute("faces", static_cast<int>(o.faces.size()));
  // Points no face names are dropped, as OpenSCAD drops them.
  std::vector<std::uint32_t> index(o.points.size(), kInvalidIndex);
  for (Loop& f : faces) {
    for (std::uint32_t& i : f) {
      if (index[i] == kInvalidIndex) index[i] = d.vertex(o.points[i]);
      i = index[i];
    }
    d.face(std::move(f));
  }
  return commit(m, d);
}

}  // namespace cellforge::shape
