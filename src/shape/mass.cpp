// Mass properties by the divergence theorem (mass.h). Positions are taken relative to
// the centre of the body's bounding box, so a body far from the origin loses no
// precision to cancellation (and a symmetric one sums symmetric terms).
#include "cellforge/shape/mass.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "cellforge/geom/polygon.h"

namespace cellforge::shape {

namespace {

struct Sums {
  // Six times the volume and 24 times its first moment about the reference: the
  // tetrahedra's determinants summed whole, divided once at the end.
  double volume6 = 0;
  Vec3 moment24;
  double area = 0;
  Vec3 area_moment;  // sum of triangle area * (centroid - reference)
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  bool any_vertex = false;
};

std::vector<std::vector<Vec3>> face_loops(const Model& m, FaceId f, Vec3 ref) {
  std::vector<std::vector<Vec3>> loops;
  for (LoopId l : m.loops_of(f)) {
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
  for (const auto& loop : loops) normal = newell_normal(loop, normal);
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
      const double tet = sign * dot(a, cross(b, c));  // six times the signed volume
      s.volume6 += tet;
      s.moment24 = s.moment24 + (a + b + c) * tet;
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
  out.volume = s.volume6 / 6;
  out.area = s.area;
  if (solid && s.volume6 != 0) {
    out.centroid = ref + s.moment24 / (4 * s.volume6);
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

// The groups for which `keep` is true: their vertices, and their faces with the
// cells behind (+1) or in front (-1) of each.
template <class Keep>
MassProperties accumulate(const Model& m, Keep keep) {
  Sums s;
  for (VertexId v : m.vertices()) {
    if (keep(m.group_of(v))) add_vertex(m.position(v), s);
  }
  const Vec3 ref = s.any_vertex ? (s.lo + s.hi) * 0.5 : Vec3{};
  bool solid = false;
  for (FaceId f : m.faces()) {
    if (!keep(m.group_of(f))) continue;
    const int sign = (m.back_volume(f).is_valid() ? 1 : 0) - (m.front_volume(f).is_valid() ? 1 : 0);
    solid = solid || m.back_volume(f).is_valid() || m.front_volume(f).is_valid();
    add_face(m, f, sign, ref, s);
  }
  return finish(s, solid, ref);
}

}  // namespace

MassProperties mass_properties(const Model& m) {
  return accumulate(m, [](GroupId) { return true; });
}

MassProperties mass_properties(const Model& m, GroupId g) {
  return accumulate(m, [g](GroupId x) { return x == g; });
}

MassProperties mass_properties(const Model& m, VolumeId c) {
  Sums s;
  auto bounds = [&](FaceId f) { return m.back_volume(f) == c || m.front_volume(f) == c; };
  for (FaceId f : m.faces()) {
    if (!bounds(f)) continue;
    for (LoopId l : m.loops_of(f)) {
      for (Vec3 p : m.loop_points(l)) add_vertex(p, s);
    }
  }
  const Vec3 ref = s.any_vertex ? (s.lo + s.hi) * 0.5 : Vec3{};
  for (FaceId f : m.faces()) {
    if (!bounds(f)) continue;
    const int sign = (m.back_volume(f) == c ? 1 : 0) - (m.front_volume(f) == c ? 1 : 0);
    add_face(m, f, sign, ref, s);
  }
  return finish(s, true, ref);
}

}  // namespace cellforge::shape
