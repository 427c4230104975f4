// linear_extrude and rotate_extrude (sweep.h). Both walk a profile — closed loops of
// a region, or one open polyline — and make one ring of vertices per slice (per
// section of the revolution), side faces between consecutive rings, and caps where
// the profile is closed and the sweep is not.
#include "cellforge/shape/sweep.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "shape/sweep_draft.h"

namespace cellforge::shape {

namespace {

struct Profile {
  std::vector<std::vector<Vec2>> loops;
  bool closed = true;  // false: one open polyline
};

std::size_t edge_count(const Profile& p, std::size_t l) {
  return p.closed ? p.loops[l].size() : p.loops[l].size() - 1;
}

// Drops consecutive repeats (cyclically), as collapsed vertices on the axis make them.
Loop without_repeats(Loop loop) {
  Loop out;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (loop[i] != loop[(i + 1) % loop.size()]) out.push_back(loop[i]);
  }
  return out;
}

Loop reversed(Loop loop) {
  std::reverse(loop.begin(), loop.end());
  return loop;
}

Status check_polyline(const Polyline& p) {
  if (p.points.size() < 2) {
    return invalid("a polyline needs at least 2 points, got " + std::to_string(p.points.size()));
  }
  for (std::size_t i = 0; i < p.points.size(); ++i) {
    if (!std::isfinite(p.points[i].x) || !std::isfinite(p.points[i].y)) {
      return invalid("polyline point " + std::to_string(i) + " is not finite");
    }
    if (i > 0 && p.points[i] == p.points[i - 1]) {
      return invalid("polyline points " + std::to_string(i - 1) + " and " + std::to_string(i) +
                     " coincide");
    }
  }
  return Status::Ok();
}

// ---------------------------------------------------------------- linear_extrude

double lerp(double a, double b, double t) { return (1 - t) * a + t * b; }

double helix_slices(double r_sqr, double height, double twist, const Faceting& f) {
  twist = std::fabs(twist);
  const int min_slices = std::max(saturated_count(std::ceil(twist / 120.0)), 1);
  if (std::sqrt(r_sqr) < kGridFine || !std::isfinite(f.fn)) return min_slices;
  if (f.fn > 0.0) return std::max(saturated_count(std::ceil(twist / 360.0 * f.fn)), min_slices);
  const double t = twist * std::numbers::pi / 180;
  const double c = height / t;
  const double arc = t * std::sqrt(r_sqr + c * c);
  const int fa_slices = saturated_count(std::ceil(twist / std::max(f.fa, kMinimumFaFs)));
  const int fs_slices = saturated_count(std::ceil(arc / std::max(f.fs, kMinimumFaFs)));
  return std::max(std::min(fa_slices, fs_slices), min_slices);
}

int conical_helix_slices(double r_sqr, double height, double twist, double scale,
                         const Faceting& f) {
  twist = std::fabs(twist);
  const double r = std::sqrt(r_sqr);
  const int min_slices = std::max(saturated_count(std::ceil(twist / 120.0)), 1);
  if (r < kGridFine || !std::isfinite(f.fn)) return min_slices;
  if (f.fn > 0.0) return std::max(saturated_count(std::ceil(twist * f.fn / 360)), min_slices);
  const double rads = twist * std::numbers::pi / 180;
  const double end = scale > 1 ? rads * scale / (scale - 1) : rads / (1 - scale);
  const double start = end - rads;
  const double a = r / end;
  auto spiral = [a](double th) { return 0.5 * a * (th * std::sqrt(1 + th * th) + std::asinh(th)); };
  const double len = spiral(end) - spiral(start);
  const double total = std::sqrt(len * len + height * height);
  const int fs_slices = saturated_count(std::ceil(total / std::max(f.fs, kMinimumFaFs)));
  const int fa_slices = saturated_count(std::ceil(twist / std::max(f.fa, kMinimumFaFs)));
  return std::max(std::min(fa_slices, fs_slices), min_slices);
}

int diagonal_slices(double delta_sqr, double height, const Faceting& f) {
  if (std::sqrt(delta_sqr) < kGridFine || !std::isfinite(f.fn)) return 1;
  if (f.fn > 0.0) return std::max(saturated_count(f.fn), 1);
  const double len = std::sqrt(delta_sqr + height * height);
  return std::max(saturated_count(std::ceil(len / std::max(f.fs, kMinimumFaFs))), 1);
}

int slices_for(const Profile& p, const LinearExtrudeOptions& o) {
  if (o.slices > 0) return o.slices;
  double r_sqr = 0, delta_sqr = 0;
  for (const auto& loop : p.loops) {
    for (Vec2 v : loop) {
      r_sqr = std::max(r_sqr, v.x * v.x + v.y * v.y);
      const double dx = v.x - v.x * o.scale_x, dy = v.y - v.y * o.scale_y;
      delta_sqr = std::max(delta_sqr, dx * dx + dy * dy);
    }
  }
  const double h = o.height;
  if (o.twist != 0) {
    if (o.scale_x == 1.0 && o.scale_y == 1.0) return helix_slices(r_sqr, h, o.twist, o.faceting);
    if (o.scale_x != o.scale_y) {
      return std::max<int>(diagonal_slices(delta_sqr, h, o.faceting),
                           helix_slices(r_sqr, h, o.twist, o.faceting));
    }
    return conical_helix_slices(r_sqr, h, o.twist, o.scale_x, o.faceting);
  }
  if (o.scale_x != o.scale_y) return diagonal_slices(delta_sqr, h, o.faceting);
  return 1;
}

Status check_extrude(const LinearExtrudeOptions& o, bool has_holes) {
  if (!(o.height > 0) || !std::isfinite(o.height)) {
    return invalid("height must be positive, got " + format_number(o.height));
  }
  if (!std::isfinite(o.twist)) return invalid("twist must be finite");
  if (!(o.scale_x >= 0) || !(o.scale_y >= 0) || !std::isfinite(o.scale_x) ||
      !std::isfinite(o.scale_y)) {
    return invalid("scale must be non-negative and finite, got [" + format_number(o.scale_x) +
                   ", " + format_number(o.scale_y) + "]");
  }
  if ((o.scale_x == 0) != (o.scale_y == 0)) {
    return Error{ErrorCode::kUnsupported,
                 "scale 0 on one axis only would flatten the top into a segment"};
  }
  if (o.scale_x == 0 && has_holes) {
    return Error{ErrorCode::kUnsupported,
                 "scale 0 closes the top in an apex, which a region with holes cannot have"};
  }
  if (o.slices < 0) return invalid("slices must be >= 0, got " + std::to_string(o.slices));
  return check_faceting(o.faceting);
}

std::uint64_t point_count(const std::vector<std::vector<Vec2>>& loops) {
  std::uint64_t n = 0;
  for (const auto& l : loops) n += l.size();
  return n;
}

// The profile's points once per slice boundary, checked before anything is made.
Status check_extrude_size(const Profile& p, const LinearExtrudeOptions& o, int slices) {
  return check_vertex_count(point_count(p.loops) * (static_cast<std::uint64_t>(slices) + 1),
                            o.faceting.max_vertices,
                            "linear_extrude of " + std::to_string(slices) + " slices");
}

void extrude_attributes(Draft& d, const LinearExtrudeOptions& o, int slices) {
  d.attribute("height", o.height);
  d.attribute("center", o.center);
  d.attribute("twist", o.twist);
  d.attribute("scale", "[" + format_number(o.scale_x) + ", " + format_number(o.scale_y) + "]");
  d.attribute("slices", slices);
}

// ring[k][l][i]: vertex of profile point i of loop l in slice k.
void extrude_into(Draft& d, const Profile& p, const LinearExtrudeOptions& o, int slices) {
  const bool apex = o.scale_x == 0 && o.scale_y == 0;
  const bool split = o.twist != 0 || o.scale_x != o.scale_y;
  const double z0 = o.center ? -o.height / 2 : 0, z1 = o.center ? o.height / 2 : o.height;
  std::vector<std::vector<std::vector<std::uint32_t>>> ring(slices + 1);
  std::vector<std::vector<std::vector<Vec2>>> at(slices + 1);
  for (int k = 0; k <= slices; ++k) {
    const double t = static_cast<double>(k) / slices;
    const double sx = lerp(1, o.scale_x, t), sy = lerp(1, o.scale_y, t);
    const double c = cos_degrees(-o.twist * t), s = sin_degrees(-o.twist * t);
    const double z = lerp(z0, z1, t);
    const std::uint32_t top = apex && k == slices ? d.vertex({0, 0, z1}) : 0;
    for (const auto& loop : p.loops) {
      ring[k].emplace_back();
      at[k].emplace_back();
      for (Vec2 v : loop) {
        const Vec2 q{sx * (c * v.x - s * v.y), sy * (s * v.x + c * v.y)};
        at[k].back().push_back(q);
        ring[k].back().push_back(apex && k == slices ? top : d.vertex({q.x, q.y, z}));
      }
    }
  }
  for (std::size_t l = 0; l < p.loops.size(); ++l) {
    const std::size_t n = p.loops[l].size();
    for (std::size_t i = 0; i < edge_count(p, l); ++i) {
      const std::size_t j = (i + 1) % n;
      for (int k = 0; k < slices; ++k) {
        const std::uint32_t a = ring[k][l][i], b = ring[k][l][j];
        const std::uint32_t c = ring[k + 1][l][j], e = ring[k + 1][l][i];
        if (apex && k + 1 == slices) {
          d.face(Loop{a, b, c});
        } else if (!split) {
          d.face(Loop{a, b, c, e});
        } else {
          const Vec3 pa = d.mesh.positions[a], pb = d.mesh.positions[b];
          const Vec3 pc = d.mesh.positions[c], pe = d.mesh.positions[e];
          if (dot(pc - pa, pc - pa) <= dot(pe - pb, pe - pb)) {
            d.face(Loop{a, b, c});
            d.face(Loop{a, c, e});
          } else {
            d.face(Loop{a, b, e});
            d.face(Loop{b, c, e});
          }
        }
      }
    }
  }
  if (!p.closed) return;
  std::vector<Loop> bottom, top;
  for (std::size_t l = 0; l < p.loops.size(); ++l) {
    bottom.push_back(reversed(ring[0][l]));
    top.push_back(ring[slices][l]);
  }
  d.face(std::move(bottom));
  if (!apex) d.face(std::move(top));
}

// ---------------------------------------------------------------- rotate_extrude

struct Revolution {
  int sections = 0;
  bool closed = false;  // a full turn
  double start = 0;
  bool standard = true;  // x >= 0 turning counterclockwise (or both mirrored)
};

Result<Revolution> plan_revolution(const std::vector<std::vector<Vec2>>& loops,
                                   const RotateExtrudeOptions& o) {
  if (!std::isfinite(o.angle) || o.angle == 0 || std::fabs(o.angle) > 360) {
    return invalid("angle must be in [-360, 360] and not 0, got " + format_number(o.angle));
  }
  if (o.start && !std::isfinite(*o.start)) return invalid("start must be finite");
  double min_x = 0, max_x = 0;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (std::size_t i = 0; i < loops[l].size(); ++i) {
      min_x = std::min(min_x, loops[l][i].x);
      max_x = std::max(max_x, loops[l][i].x);
      if (min_x < 0 && max_x > 0) {
        return invalid("the profile crosses the axis x = 0 (loop " + std::to_string(l) + " point " +
                       std::to_string(i) + " is at x = " + format_number(loops[l][i].x) +
                       "; x ranges over [" + format_number(min_x) + ", " + format_number(max_x) +
                       "])");
      }
    }
  }
  if (min_x == max_x) return invalid("the profile lies on the axis x = 0");
  if (Status s = check_faceting(o.faceting); !s) return s.error();
  Revolution r;
  r.closed = std::fabs(o.angle) == 360;
  r.sections = arc_fragments(max_x - min_x, o.angle, o.faceting);
  if (Status s = check_vertex_count(
          point_count(loops) * (static_cast<std::uint64_t>(r.sections) + 1),
          o.faceting.max_vertices, "rotate_extrude of " + std::to_string(r.sections) + " sections");
      !s)
    return s.error();
  r.start = o.start.value_or(r.closed ? 180.0 : 0.0);
  r.standard = (min_x >= 0) == (o.angle > 0);
  return r;
}

void revolve_attributes(Draft& d, const RotateExtrudeOptions& o, const Revolution& r) {
  d.attribute("angle", o.angle);
  d.attribute("start", r.start);
  d.faceting(o.faceting, r.sections);
}

// Vertices per (section j, loop l, point i), as the end of the profile edge into i
// (`in`) and the start of the edge out of i (`out`). A point on the axis is one
// vertex; in a full turn a point on the axis between two points off it gets two
// coincident vertices, one per cone it tips, so that each shell stays manifold (the
// two cones touch at a point, as two solids may).
struct Rings {
  std::vector<std::vector<std::vector<std::uint32_t>>> in, out;
};

Rings revolve_vertices(Draft& d, const std::vector<std::vector<Vec2>>& loops,
                       const RotateExtrudeOptions& o, const Revolution& r, bool closed_profile) {
  const int rings = r.closed ? r.sections : r.sections + 1;
  Rings ring{std::vector<std::vector<std::vector<std::uint32_t>>>(rings), {}};
  std::vector<std::vector<std::uint32_t>> axis_in(loops.size()), axis_out(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    const std::size_t n = loops[l].size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 v = loops[l][i];
      const std::uint32_t id = v.x == 0 ? d.vertex({0, 0, v.y}) : 0;
      axis_in[l].push_back(id);
      const bool has_prev = closed_profile || i > 0, has_next = closed_profile || i + 1 < n;
      const bool pinch = v.x == 0 && r.closed && has_prev && has_next &&
                         loops[l][(i + n - 1) % n].x != 0 && loops[l][(i + 1) % n].x != 0;
      axis_out[l].push_back(pinch ? d.vertex({0, 0, v.y}) : id);
    }
  }
  for (int j = 0; j < rings; ++j) {
    const double a = r.start + j * o.angle / r.sections;
    const double c = cos_degrees(a), s = sin_degrees(a);
    for (std::size_t l = 0; l < loops.size(); ++l) {
      ring.in[j].emplace_back();
      for (std::size_t i = 0; i < loops[l].size(); ++i) {
        const Vec2 v = loops[l][i];
        ring.in[j].back().push_back(v.x == 0 ? axis_in[l][i] : d.vertex({v.x * c, v.x * s, v.y}));
      }
    }
  }
  ring.out = ring.in;
  for (int j = 0; j < rings; ++j) {
    for (std::size_t l = 0; l < loops.size(); ++l) {
      for (std::size_t i = 0; i < loops[l].size(); ++i) {
        if (loops[l][i].x == 0) ring.out[j][l][i] = axis_out[l][i];
      }
    }
  }
  return ring;
}

void revolve_into(Draft& d, const Profile& p, const RotateExtrudeOptions& o, const Revolution& r) {
  const Rings ring = revolve_vertices(d, p.loops, o, r, p.closed);
  const int rings = static_cast<int>(ring.in.size());
  for (std::size_t l = 0; l < p.loops.size(); ++l) {
    const std::size_t n = p.loops[l].size();
    for (std::size_t i = 0; i < edge_count(p, l); ++i) {
      const std::size_t k = (i + 1) % n;
      const Vec2 v = p.loops[l][i], w = p.loops[l][k];
      if (v.x == 0 && w.x == 0) continue;  // an edge on the axis sweeps nothing
      const int surface = d.surface(Surface{.kind = "revolution",
                                            .center = {0, 0, v.y},
                                            .radius = std::fabs(v.x),
                                            .radius2 = std::fabs(w.x),
                                            .height = w.y - v.y,
                                            .segments = r.sections});
      for (int j = 0; j < r.sections; ++j) {
        const int j1 = (j + 1) % rings;
        const std::uint32_t a = ring.out[j][l][i], b = ring.in[j][l][k];
        const std::uint32_t c = ring.in[j1][l][k], e = ring.out[j1][l][i];
        d.face(without_repeats(r.standard ? Loop{a, e, c, b} : Loop{a, b, c, e}), surface);
      }
    }
  }
  if (r.closed || !p.closed) return;
  std::vector<Loop> first, last;
  for (std::size_t l = 0; l < p.loops.size(); ++l) {
    first.push_back(r.standard ? ring.in[0][l] : reversed(ring.in[0][l]));
    last.push_back(r.standard ? reversed(ring.in[rings - 1][l]) : ring.in[rings - 1][l]);
  }
  d.face(std::move(first));
  d.face(std::move(last));
}

}  // namespace

int extrude_slices(const Region& profile, const LinearExtrudeOptions& options) {
  return slices_for(Profile{profile.loops, true}, options);
}

Result<Draft> extrude_draft(const Region& region, const LinearExtrudeOptions& o) {
  if (Status s = check_extrude(o, region.loops.size() > 1); !s) return s.error();
  const Profile p{region.loops, true};
  const int slices = slices_for(p, o);
  if (Status s = check_extrude_size(p, o, slices); !s) return s.error();
  Draft d = Draft::solid("linear_extrude");
  extrude_attributes(d, o, slices);
  extrude_into(d, p, o, slices);
  return d;
}

Result<Draft> revolve_draft(const Region& region, const RotateExtrudeOptions& o) {
  auto r = plan_revolution(region.loops, o);
  if (!r) return r.error();
  Draft d = Draft::solid("rotate_extrude");
  revolve_attributes(d, o, *r);
  revolve_into(d, Profile{region.loops, true}, o, *r);
  return d;
}

Result<GroupId> linear_extrude(Model& m, const Region& profile, const LinearExtrudeOptions& o) {
  auto region = checked(profile);
  if (!region) return region.error();
  auto d = extrude_draft(*region, o);
  if (!d) return d.error();
  return commit(m, *d);
}

Result<GroupId> linear_extrude(Model& m, const Polyline& profile, const LinearExtrudeOptions& o) {
  if (Status s = check_polyline(profile); !s) return s.error();
  if (Status s = check_extrude(o, false); !s) return s.error();
  const Profile p{{profile.points}, false};
  const int slices = slices_for(p, o);
  if (Status s = check_extrude_size(p, o, slices); !s) return s.error();
  Draft d = Draft::sheet("linear_extrude");
  extrude_attributes(d, o, slices);
  extrude_into(d, p, o, slices);
  return commit(m, d);
}

Result<GroupId> linear_extrude(Model& m, Vec2 point, const LinearExtrudeOptions& o) {
  if (!std::isfinite(point.x) || !std::isfinite(point.y)) return invalid("point is not finite");
  if (Status s = check_extrude(o, false); !s) return s.error();
  const Profile p{{{point}}, false};
  const int slices = slices_for(p, o);
  if (Status s = check_extrude_size(p, o, slices); !s) return s.error();
  Draft d = Draft::sheet("linear_extrude");
  extrude_attributes(d, o, slices);
  const double z0 = o.center ? -o.height / 2 : 0, z1 = o.center ? o.height / 2 : o.height;
  for (int k = 0; k <= slices; ++k) {
    const double t = static_cast<double>(k) / slices;
    const double sx = lerp(1, o.scale_x, t), sy = lerp(1, o.scale_y, t);
    const double c = cos_degrees(-o.twist * t), s = sin_degrees(-o.twist * t);
    d.vertex({sx * (c * point.x - s * point.y), sy * (s * point.x + c * point.y), lerp(z0, z1, t)});
    if (k > 0) d.wire(k - 1, k);
  }
  return commit(m, d);
}

Result<GroupId> rotate_extrude(Model& m, const Region& profile, const RotateExtrudeOptions& o) {
  auto region = checked(profile);
  if (!region) return region.error();
  auto d = revolve_draft(*region, o);
  if (!d) return d.error();
  return commit(m, *d);
}

Result<GroupId> rotate_extrude(Model& m, const Polyline& profile, const RotateExtrudeOptions& o) {
  if (Status s = check_polyline(profile); !s) return s.error();
  auto r = plan_revolution({profile.points}, o);
  if (!r) return r.error();
  Draft d = Draft::sheet("rotate_extrude");
  revolve_attributes(d, o, *r);
  revolve_into(d, Profile{{profile.points}, false}, o, *r);
  return commit(m, d);
}

Result<GroupId> rotate_extrude(Model& m, Vec2 point, const RotateExtrudeOptions& o) {
  if (!std::isfinite(point.x) || !std::isfinite(point.y)) return invalid("point is not finite");
  if (Status s = check_faceting(o.faceting); !s) return s.error();
  Draft d = Draft::sheet("rotate_extrude");
  if (point.x == 0) {  // the sweep of a point on the axis is that point
    d.vertex({0, 0, point.y});
    d.attribute("angle", o.angle);
    return commit(m, d);
  }
  auto r = plan_revolution({{point}}, o);
  if (!r) return r.error();
  revolve_attributes(d, o, *r);
  const Rings ring = revolve_vertices(d, {{point}}, o, *r, false);
  const int rings = static_cast<int>(ring.in.size());
  for (int j = 0; j < r->sections; ++j) d.wire(ring.in[j][0][0], ring.in[(j + 1) % rings][0][0]);
  return commit(m, d);
}

}  // namespace cellforge::shape
