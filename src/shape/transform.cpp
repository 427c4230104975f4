// Affine transforms (transform.h). Matrices follow OpenSCAD's formulas
// (src/core/TransformNode.cc, src/utils/degree_trig.cc) so that transformed
// primitives agree with OpenSCAD's vertex for vertex.
#include "cellforge/shape/transform.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <unordered_map>

#include "shape/draft.h"
#include "cellforge/shape/faceting.h"

namespace cellforge::shape {

namespace {

Transform linear(const double (&a)[3][3]) {
  Transform t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) t.m[i][j] = a[i][j];
  }
  return t;
}

// A = s Q with Q orthogonal (up to rounding): the transform maps spheres to spheres.
bool similarity(const Transform& t, double& s) {
  double g[3][3];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      g[i][j] = t.m[0][i] * t.m[0][j] + t.m[1][i] * t.m[1][j] + t.m[2][i] * t.m[2][j];
    }
  }
  const double s2 = g[0][0];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (std::fabs(g[i][j] - (i == j ? s2 : 0)) > 1e-12 * s2) return false;
    }
  }
  s = std::sqrt(s2);
  return true;
}

std::string matrix_text(const Transform& t) {
  std::string s = "[";
  for (int i = 0; i < 3; ++i) {
    s += i ? ", [" : "[";
    for (int j = 0; j < 4; ++j) s += (j ? ", " : "") + format_number(t.m[i][j]);
    s += "]";
  }
  return s + ", [0, 0, 0, 1]]";
}

}  // namespace

Transform Transform::translate(Vec3 v) {
  Transform t;
  t.m[0][3] = v.x;
  t.m[1][3] = v.y;
  t.m[2][3] = v.z;
  return t;
}

Transform Transform::scale(Vec3 s) {
  const double a[3][3] = {{s.x, 0, 0}, {0, s.y, 0}, {0, 0, s.z}};
  return linear(a);
}

Transform Transform::rotate(double degrees, Vec3 v) {
  const double s = sin_degrees(degrees), c = cos_degrees(degrees);
  const double len2 = dot(v, v);
  if (!(len2 > 0)) return identity();  // OpenSCAD: a zero axis is no rotation
  const Vec3 cv = v * ((1 - c) / len2);
  const Vec3 us = normalized(v) * s;
  const double a[3][3] = {{cv.x * v.x + c, cv.y * v.x - us.z, cv.z * v.x + us.y},
                          {cv.x * v.y + us.z, cv.y * v.y + c, cv.z * v.y - us.x},
                          {cv.x * v.z - us.y, cv.y * v.z + us.x, cv.z * v.z + c}};
  return linear(a);
}

Transform Transform::rotate_xyz(Vec3 d) {
  const double sx = sin_degrees(d.x), cx = cos_degrees(d.x);
  const double sy = sin_degrees(d.y), cy = cos_degrees(d.y);
  const double sz = sin_degrees(d.z), cz = cos_degrees(d.z);
  const double a[3][3] = {{cy * cz, cz * sx * sy - cx * sz, cx * cz * sy + sx * sz},
                          {cy * sz, cx * cz + sx * sy * sz, -cz * sx + cx * sy * sz},
                          {-sy, cy * sx, cx * cy}};
  return linear(a);
}

Transform Transform::mirror(Vec3 n) {
  const double len2 = dot(n, n);
  if (!(len2 > 0)) return identity();  // OpenSCAD: mirror([0, 0, 0]) does nothing
  const double c = 2.0 / len2;
  const double x = n.x, y = n.y, z = n.z;
  const double a[3][3] = {{1 - c * x * x, -c * x * y, -c * x * z},
                          {-c * y * x, 1 - c * y * y, -c * y * z},
                          {-c * z * x, -c * z * y, 1 - c * z * z}};
  return linear(a);
}

Result<Transform> Transform::from_matrix(const std::array<std::array<double, 4>, 4>& rows) {
  for (const auto& row : rows) {
    for (double x : row) {
      if (!std::isfinite(x)) return invalid("the matrix has a non-finite entry");
    }
  }
  if (rows[3] != std::array<double, 4>{0, 0, 0, 1}) {
    return Error{ErrorCode::kUnsupported,
                 "the last row of the matrix must be [0, 0, 0, 1] (projective transforms are "
                 "not affine)"};
  }
  Transform t;
  for (int i = 0; i < 3; ++i) t.m[i] = rows[i];
  return t;
}

Vec3 Transform::apply(Vec3 p) const {
  return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
          m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
          m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
}

Vec3 Transform::apply_linear(Vec3 v) const {
  return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
          m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
          m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
}

double Transform::determinant() const {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
         m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Transform Transform::operator*(const Transform& o) const {
  Transform t;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 4; ++j) {
      double s = j == 3 ? m[i][3] : 0;
      for (int k = 0; k < 3; ++k) s += m[i][k] * o.m[k][j];
      t.m[i][j] = s;
    }
  }
  return t;
}

Result<GroupId> transformed(Model& m, GroupId g, const Transform& t) {
  if (!m.is_live(g)) return Error{ErrorCode::kInvalidId, "no group " + g.str()};
  for (const auto& row : t.m) {
    for (double x : row) {
      if (!std::isfinite(x)) return invalid("the transform has a non-finite entry");
    }
  }
  const double det = t.determinant();
  if (det == 0) return invalid("the transform is singular (determinant 0): " + matrix_text(t));
  const bool flip = det < 0;

  Draft d;
  d.mesh.group_name = m.name(g);
  std::unordered_map<std::uint32_t, std::uint32_t> vertex, volume;
  for (VertexId v : m.vertices()) {
    if (m.group_of(v) == g) vertex[v.value] = d.vertex(t.apply(m.position(v)));
  }
  for (VolumeId c : m.volumes()) {
    if (m.group_of(c) == g) volume[c.value] = static_cast<std::uint32_t>(d.mesh.volumes++);
  }
  double s = 0;
  const bool keep_surfaces = similarity(t, s);
  std::unordered_map<std::uint32_t, int> surface;
  for (FaceId f : m.faces()) {
    if (m.group_of(f) != g) continue;
    MeshFace face;
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) {
        return Error{ErrorCode::kUnsupported,
                     "face " + f.str() + " has a point loop, which transformed() cannot copy"};
      }
      face.loops.emplace_back();
      for (VertexId v : m.loop_vertices(l)) face.loops.back().push_back(vertex.at(v.value));
      if (flip) std::reverse(face.loops.back().begin(), face.loops.back().end());
    }
    if (m.front_volume(f).is_valid())
      face.front = static_cast<int>(volume.at(m.front_volume(f).value));
    if (m.back_volume(f).is_valid())
      face.back = static_cast<int>(volume.at(m.back_volume(f).value));
    d.mesh.faces.push_back(std::move(face));
    int local = -1;
    const std::uint32_t sid = m.surface_of(f);
    if (keep_surfaces && sid != kInvalidIndex) {
      auto [it, fresh] = surface.try_emplace(sid, 0);
      if (fresh) {
        Surface out = m.surface(sid);
        out.center = t.apply(out.center);
        out.axis = normalized(t.apply_linear(out.axis));
        out.radius *= s;
        out.radius2 *= s;
        out.height *= s;
        it->second = d.surface(std::move(out));
      }
      local = it->second;
    }
    d.face_surface.push_back(local);
  }
  for (EdgeId e : m.edges()) {
    if (m.group_of(e) == g && m.is_wire(e)) {
      d.wire(vertex.at(m.start_of(e).value), vertex.at(m.end_of(e).value));
    }
  }
  d.attributes = m.attributes(g);
  const std::string before = m.attribute(g, "transform");
  d.attribute("transform", before.empty() ? matrix_text(t) : matrix_text(t) + " * " + before);
  return commit(m, d);
}

}  // namespace cellforge::shape
