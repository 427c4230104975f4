// The solid primitives of primitives.h, each drafted as polygons and built through
// build_mesh (draft.h). Vertex positions follow OpenSCAD's formulas exactly.
#include "cellforge/shape/primitives.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "shape/draft.h"
#include "shape/sweep_draft.h"
#include "cellforge/shape/mass.h"
#include "cellforge/geom/predicates.h"

namespace cellforge::shape {

namespace {

bool positive(double x) { return x > 0 && std::isfinite(x); }

Status need_positive(const char* name, double x) {
  if (positive(x)) return Status::Ok();
  return invalid(std::string(name) + " must be positive and finite, got " + format_number(x));
}

Status need_non_negative(const char* name, double x) {
  if (x >= 0 && std::isfinite(x)) return Status::Ok();
  return invalid(std::string(name) + " must be >= 0 and finite, got " + format_number(x));
}

// n points of the circle of radius r at height z, at 360 i / n degrees from (r, 0)
// (OpenSCAD's generate_circle); r == 0 gives one apex vertex.
Loop ring(Draft& d, double r, double z, int n) {
  if (r == 0) return Loop(n, d.vertex({0, 0, z}));
  Loop out;
  for (int i = 0; i < n; ++i) {
    const double phi = (360.0 * i) / n;
    out.push_back(d.vertex({r * cos_degrees(phi), r * sin_degrees(phi), z}));
  }
  return out;
}

Loop without_repeats(const Loop& loop) {
  Loop out;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (loop[i] != loop[(i + 1) % loop.size()]) out.push_back(loop[i]);
  }
  return out;
}

// A solid between two coaxial regular n-gons (either may be an apex): caps and n
// sides, the sides on `surface` (or planar when -1).
void frustum_faces(Draft& d, double r1, double r2, double z1, double z2, int n, int surface) {
  const Loop bottom = ring(d, r1, z1, n);
  const Loop top = ring(d, r2, z2, n);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    d.face(without_repeats({bottom[i], bottom[j], top[j], top[i]}), surface);
  }
  if (r1 > 0) d.face(Loop(bottom.rbegin(), bottom.rend()));
  if (r2 > 0) d.face(top);
}

Status check_sides(int sides) {
  if (sides >= 3) return Status::Ok();
  return invalid("sides must be at least 3, got " + std::to_string(sides));
}

Result<GroupId> regular_solid(Model& m, const char* kind, int sides, double r1, double r2, double h,
                              bool center, std::uint64_t max_vertices) {
  if (Status s = check_sides(sides); !s) return s.error();
  if (Status s = check_vertex_count(2ull * static_cast<std::uint64_t>(sides), max_vertices,
                                    std::string(kind) + " sides=" + std::to_string(sides));
      !s)
    return s.error();
  if (Status s = need_positive("h", h); !s) return s.error();
  Draft d = Draft::solid(kind);
  d.attribute("sides", sides);
  d.attribute("h", h);
  d.attribute("center", center);
  const double z1 = center ? -h / 2 : 0, z2 = center ? h / 2 : h;
  frustum_faces(d, r1, r2, z1, z2, sides, -1);
  return commit(m, d);
}

}  // namespace

Result<GroupId> make_cube(Model& m, const CubeOptions& o) {
  if (Status s = need_positive("size.x", o.size.x); !s) return s.error();
  if (Status s = need_positive("size.y", o.size.y); !s) return s.error();
  if (Status s = need_positive("size.z", o.size.z); !s) return s.error();
  Draft d = Draft::solid("cube");
  d.attribute("size", "[" + format_number(o.size.x) + ", " + format_number(o.size.y) + ", " +
                          format_number(o.size.z) + "]");
  d.attribute("center", o.center);
  const Vec3 lo = o.center ? o.size * -0.5 : Vec3{};
  const Vec3 hi = o.center ? o.size * 0.5 : o.size;
  for (int i = 0; i < 8; ++i) {  // corner i has bits (x, y, z)
    d.vertex({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
  }
  for (const Loop& f : {Loop{0, 2, 3, 1}, Loop{4, 5, 7, 6}, Loop{0, 1, 5, 4}, Loop{2, 6, 7, 3},
                        Loop{0, 4, 6, 2}, Loop{1, 3, 7, 5}}) {
    d.face(f);
  }
  return commit(m, d);
}

Result<GroupId> make_cylinder(Model& m, const CylinderOptions& o) {
  if (Status s = need_positive("h", o.h); !s) return s.error();
  if (Status s = need_non_negative("r1", o.r1); !s) return s.error();
  if (Status s = need_non_negative("r2", o.r2); !s) return s.error();
  if (o.r1 == 0 && o.r2 == 0) return invalid("r1 and r2 are both 0");
  if (Status s = check_faceting(o.faceting); !s) return s.error();
  const int n = fragments(std::max(o.r1, o.r2), o.faceting);
  if (Status s = check_vertex_count(2ull * static_cast<std::uint64_t>(n), o.faceting.max_vertices,
                                    "a cylinder of " + std::to_string(n) + " segments");
      !s)
    return s.error();
  const double z1 = o.center ? -o.h / 2 : 0, z2 = o.center ? o.h / 2 : o.h;
  Draft d = Draft::solid("cylinder");
  d.attribute("h", o.h);
  d.attribute("r1", o.r1);
  d.attribute("r2", o.r2);
  d.attribute("center", o.center);
  d.faceting(o.faceting, n);
  const int side = d.surface(Surface{.kind = o.r1 == o.r2 ? "cylinder" : "cone",
                                     .center = {0, 0, z1},
                                     .radius = o.r1,
                                     .radius2 = o.r2,
                                     .height = o.h,
                                     .segments = n});
  frustum_faces(d, o.r1, o.r2, z1, z2, n, side);
  return commit(m, d);
}

Result<GroupId> make_sphere(Model& m, const SphereOptions& o) {
  if (Status s = need_positive("r", o.r); !s) return s.error();
  if (Status s = check_faceting(o.faceting); !s) return s.error();
  const int n = fragments(o.r, o.faceting);
  const int rings = static_cast<int>((static_cast<std::int64_t>(n) + 1) / 2);
  if (Status s = check_vertex_count(
          static_cast<std::uint64_t>(n) * static_cast<std::uint64_t>(rings),
          o.faceting.max_vertices, "a sphere of " + std::to_string(n) + " segments");
      !s)
    return s.error();
  Draft d = Draft::solid("sphere");
  d.attribute("r", o.r);
  d.faceting(o.faceting, n);
  d.attribute("rings", rings);
  const int surface = d.surface(
      Surface{.kind = "sphere", .center = {}, .radius = o.r, .height = 2 * o.r, .segments = n});
  std::vector<Loop> ring_of(rings);
  for (int i = 0; i < rings; ++i) {
    const double phi = (180.0 * (i + 0.5)) / rings;
    ring_of[i] = ring(d, o.r * sin_degrees(phi), o.r * cos_degrees(phi), n);
  }
  d.face(ring_of[0], surface);
  for (int i = 0; i + 1 < rings; ++i) {
    for (int j = 0; j < n; ++j) {
      const int k = (j + 1) % n;
      d.face(Loop{ring_of[i][j], ring_of[i + 1][j], ring_of[i + 1][k], ring_of[i][k]}, surface);
    }
  }
  d.face(Loop(ring_of.back().rbegin(), ring_of.back().rend()), surface);
  return commit(m, d);
}

Result<GroupId> make_torus(Model& m, const TorusOptions& o) {
  if (Status s = need_positive("r", o.minor_radius); !s) return s.error();
  if (Status s = need_positive("R", o.major_radius); !s) return s.error();
  if (o.minor_radius >= o.major_radius) {
    return invalid("the minor radius r = " + format_number(o.minor_radius) +
                   " must be less than the major radius R = " + format_number(o.major_radius) +
                   " (the profile would reach the axis)");
  }
  auto profile = circle(o.minor_radius, o.faceting);
  if (!profile) return profile.error();
  for (Vec2& p : profile->loops[0]) p.x += o.major_radius;
  auto d = revolve_draft(*profile, RotateExtrudeOptions{.faceting = o.faceting});
  if (!d) return d.error();
  d->attribute("kind", std::string("torus"));
  d->mesh.group_name = "torus";
  d->attribute("R", o.major_radius);
  d->attribute("r", o.minor_radius);
  d->attribute("profile_segments", static_cast<int>(profile->loops[0].size()));
  d->surfaces = {Surface{.kind = "torus",
                         .center = {},
                         .radius = o.major_radius,
                         .radius2 = o.minor_radius,
                         .height = 2 * o.minor_radius}};
  for (const Attribute& a : d->attributes) {
    if (a.key == "segments") d->surfaces[0].segments = std::stoi(a.value);
  }
  std::fill(d->face_surface.begin(), d->face_surface.end(), 0);
  return commit(m, *d);
}

Result<GroupId> make_regular_prism(Model& m, const RegularPrismOptions& o) {
  if (Status s = need_positive("r", o.r); !s) return s.error();
  auto g = regular_solid(m, "prism", o.sides, o.r, o.r, o.h, o.center, o.max_vertices);
  if (g) m.set_attribute(*g, "r", format_number(o.r));
  return g;
}

Result<GroupId> make_pyramid(Model& m, const PyramidOptions& o) {
  if (Status s = need_positive("r", o.r); !s) return s.error();
  auto g = regular_solid(m, "pyramid", o.sides, o.r, 0, o.h, o.center, o.max_vertices);
  if (g) m.set_attribute(*g, "r", format_number(o.r));
  return g;
}

Result<GroupId> make_frustum(Model& m, const FrustumOptions& o) {
  if (Status s = need_positive("r1", o.r1); !s) return s.error();
  if (Status s = need_positive("r2", o.r2); !s) return s.error();
  auto g = regular_solid(m, "frustum", o.sides, o.r1, o.r2, o.h, o.center, o.max_vertices);
  if (g) {
    m.set_attribute(*g, "r1", format_number(o.r1));
    m.set_attribute(*g, "r2", format_number(o.r2));
  }
  return g;
}

Result<GroupId> make_prism(Model& m, const Region& base, double h, bool center) {
  auto region = checked(base);
  if (!region) return region.error();
  auto d = extrude_draft(*region, LinearExtrudeOptions{.height = h, .center = center});
  if (!d) return d.error();
  d->attribute("kind", std::string("prism"));
  d->mesh.group_name = "prism";
  d->attribute("base_area", area(*region));
  return commit(m, *d);
}

}  // namespace cellforge::shape
