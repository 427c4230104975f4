// Mass properties by the divergence theorem (mass.h). Positions are taken relative to
// a reference vertex of the body, so a body far from the origin loses no precision
// to cancellation.
#include "cellforge/build/mass.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace cellforge::build {

namespace {

struct Sums {
  double volume = 0;
  Vec3 moment;  // sum of tetrahedron volume * (centroid - reference)
  double area = 0;
  Vec3 area_moment;  // sum of triangle area * (centroid - reference)
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool any_vertex = false;
};

std::vector<std::vector<Vec3>> face_loops(const Model& m, FaceId f, Vec3 ref) {
  std::vector<std::vector<Vec3>> loops;
  for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
    loops.push_back(m.loop_points(l));
    for (Vec3& p : loops.back()) p = p - ref;
  }
  return loops;
}

// Adds face f: its area always, and its cone volume with `sign` (+1 when the cell is
// behind it, -1 in front, 0 when it bounds no counted cell).
void add_face(const Model& m, FaceId f, int sign, Vec3 ref, Sums& s) {
  const auto loops = face_loops(m, f, ref);
  Vec3 normal;
  for (const auto& loop : loops) {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      normal = normal + cross(loop[i], loop[(i + 1) % loop.size()]);
    }
  }
  const double len = length(normal);
  if (len == 0) return;
  const Vec3 unit = normal / len;
  s.area += len / 2;
  for (const auto& loop : loops) {
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) {
      const Vec3 a = loop[0], b = loop[i], c = loop[i + 1];
      const double tri = dot(unit, cross(b - a, c - a)) / 2;
      s.area_moment = s.area_moment + (a + b + c) * (tri / 3);
      if (sign == 0) continue;
      const double tet = sign * dot(a, cross(b, c)) / 6;
      s.volume += tet;
      s.moment = s.moment + (a + b + c) * (tet / 4);
    }
  }
}

void add_vertex(Vec3 p, Sums& s) {
  s.lo = {std::min(s.lo.x, p.x), std::min(s.lo.y, p.y), std::min(s.lo.z, p.z)};
  s.hi = {std::max(s.hi.x, p.x), std::max(s.hi.y, p.y), std::max(s.hi.z, p.z)};
  s.any_vertex = true;
}

MassProperties finish(const Sums& s, bool solid, Vec3 ref) {
  MassProperties out;
  out.solid = solid;
  out.volume = s.volume;
  out.area = s.area;
  if (solid && s.volume != 0) {
    out.centroid = ref + s.moment / s.volume;
  } else if (s.area != 0) {
    out.centroid = ref + s.area_moment / s.area;
  } else {
    out.centroid = ref;
  }
  if (s.any_vertex) {
    out.bbox_min = s.lo;
    out.bbox_max = s.hi;
  }
  return out;
}

}  // namespace

MassProperties mass_properties(const Model& m, GroupId g) {
  Sums s;
  Vec3 ref;
  bool have_ref = false;
  for (VertexId v : m.vertices()) {
    if (m.group_of(v) != g) continue;
    if (!have_ref) ref = m.position(v);
    have_ref = true;
    add_vertex(m.position(v), s);
  }
  bool solid = false;
  for (FaceId f : m.faces()) {
    if (m.group_of(f) != g) continue;
    const int sign = (m.back_volume(f).is_valid() ? 1 : 0) - (m.front_volume(f).is_valid() ? 1 : 0);
    solid = solid || m.back_volume(f).is_valid() || m.front_volume(f).is_valid();
    add_face(m, f, sign, ref, s);
  }
  return finish(s, solid, ref);
}

MassProperties mass_properties(const Model& m, VolumeId c) {
  Sums s;
  Vec3 ref;
  bool have_ref = false;
  for (FaceId f : m.faces()) {
    const int sign = (m.back_volume(f) == c ? 1 : 0) - (m.front_volume(f) == c ? 1 : 0);
    if (m.back_volume(f) != c && m.front_volume(f) != c) continue;
    if (!have_ref) ref = m.loop_points(m.outer_loop(f)).front();
    have_ref = true;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      for (Vec3 p : m.loop_points(l)) add_vertex(p, s);
    }
    add_face(m, f, sign, ref, s);
  }
  return finish(s, true, ref);
}

}  // namespace cellforge::build
