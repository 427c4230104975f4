// Winding number by a perturbed ray (winding.h).
//
// With N = (b - a) x (c - a): N.x = orient2d of a, b, c projected onto (y, z), and the
// ray p + t e_x meets the plane of abc at t = N.(a - p) / N.x. For the perturbed
// point p' = p + (e^3, e, e^2):
//   orient2d(a, b, p') in (y, z) = orient2d(a, b, p) + e (a.z - b.z) + e^2 (b.y - a.y),
//   N.(a - p')                   = N.(a - p) - e N.y - e^2 N.z - e^3 N.x,
// so each sign is the first non-zero term. The ray crosses the triangle when p'
// projects inside it (the three edge tests agree with the sign of N.x) and the plane
// lies ahead (N.(a - p') has the sign of N.x).
#include "cellforge/geom/winding.h"

#include <algorithm>

#include "cellforge/geom/bvh.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/predicates.h"

namespace cellforge::inline geom {

namespace {

int sign(double x) { return (x > 0) - (x < 0); }

// orient2d(a, b, p') in the (y, z) plane, p' = p + (e, e^2).
int perturbed_side(Vec3 a, Vec3 b, Vec3 p) {
  if (const int s = orient2d({a.y, a.z}, {b.y, b.z}, {p.y, p.z}); s != 0) return s;
  if (a.z != b.z) return a.z > b.z ? 1 : -1;
  return sign(b.y - a.y);
}

}  // namespace

int ray_crossing(Vec3 a, Vec3 b, Vec3 c, Vec3 p) {
  const int nx = orient2d({a.y, a.z}, {b.y, b.z}, {c.y, c.z});
  if (nx == 0) return 0;
  if (perturbed_side(a, b, p) != nx || perturbed_side(b, c, p) != nx ||
      perturbed_side(c, a, p) != nx)
    return 0;
  // The sign of N.(a - p') = -orient3d(a, b, c, p'), term by term.
  int ahead = -orient3d(a, b, c, p);
  if (ahead == 0) ahead = -orient2d({a.z, a.x}, {b.z, b.x}, {c.z, c.x});  // -N.y
  if (ahead == 0) ahead = -orient2d({a.x, a.y}, {b.x, b.y}, {c.x, c.y});  // -N.z
  if (ahead == 0) ahead = -nx;
  return ahead == nx ? nx : 0;
}

bool point_on_triangle(Vec3 a, Vec3 b, Vec3 c, Vec3 p) {
  if (orient3d(a, b, c, p) != 0) return false;
  // Project along an axis the triangle's plane is not parallel to.
  const auto in = [&](auto project) {
    const Vec2 t[3] = {project(a), project(b), project(c)};
    return point_in_triangle(t, project(p));
  };
  if (orient2d({a.y, a.z}, {b.y, b.z}, {c.y, c.z}) != 0)
    return in([](Vec3 q) { return Vec2{q.y, q.z}; });
  if (orient2d({a.z, a.x}, {b.z, b.x}, {c.z, c.x}) != 0)
    return in([](Vec3 q) { return Vec2{q.z, q.x}; });
  return in([](Vec3 q) { return Vec2{q.x, q.y}; });
}

Winding winding_number(std::span<const Vec3> points,
                       std::span<const std::array<std::uint32_t, 3>> triangles, Vec3 p) {
  Winding w;
  for (const auto& t : triangles) {
    const Vec3 a = points[t[0]], b = points[t[1]], c = points[t[2]];
    // Cheap rejections first: the ray only reaches triangles ahead of p in x whose
    // yz box holds p (the perturbation moves p by less than any gap between doubles).
    const double hi_x = std::max({a.x, b.x, c.x});
    if (hi_x < p.x) continue;
    if (std::max({a.y, b.y, c.y}) < p.y || std::min({a.y, b.y, c.y}) > p.y) continue;
    if (std::max({a.z, b.z, c.z}) < p.z || std::min({a.z, b.z, c.z}) > p.z) continue;
    w.number += ray_crossing(a, b, c, p);
    if (!w.on_surface && std::min({a.x, b.x, c.x}) <= p.x && point_on_triangle(a, b, c, p))
      w.on_surface = true;
  }
  return w;
}

Nesting nest_surfaces(std::span<const Vec3> points,
                      std::span<const std::array<std::uint32_t, 3>> triangles,
                      std::span<const std::uint32_t> surface_of, std::uint32_t surfaces,
                      const std::vector<bool>& container) {
  const auto can_contain = [&](std::uint32_t s) { return container.empty() || container[s]; };
  std::vector<Box> surface_box(surfaces), triangle_box(triangles.size());
  std::vector<std::vector<std::uint32_t>> members(surfaces);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    for (std::uint32_t v : triangles[t]) triangle_box[t].add(points[v]);
    surface_box[surface_of[t]].add(triangle_box[t]);
    members[surface_of[t]].push_back(static_cast<std::uint32_t>(t));
  }
  std::vector<Box> container_box;
  std::vector<std::uint32_t> container_id;
  for (std::uint32_t s = 0; s < surfaces; ++s) {
    if (!can_contain(s) || members[s].empty()) continue;
    container_box.push_back(surface_box[s]);
    container_id.push_back(s);
  }
  Nesting out;
  out.depth.assign(surfaces, 0);
  out.parent.assign(surfaces, Nesting::kNone);
  if (container_id.empty()) return out;
  // Only triangles of containers are ever crossed.
  std::vector<Box> ray_boxes;
  std::vector<std::uint32_t> ray_triangle;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    if (!can_contain(surface_of[t])) continue;
    ray_boxes.push_back(triangle_box[t]);
    ray_triangle.push_back(static_cast<std::uint32_t>(t));
  }
  const Bvh by_surface(container_box), by_triangle(ray_boxes);
  const auto inside_box = [](const Box& outer, const Box& inner) {
    return outer.lo.x <= inner.lo.x && outer.lo.y <= inner.lo.y && outer.lo.z <= inner.lo.z &&
           inner.hi.x <= outer.hi.x && inner.hi.y <= outer.hi.y && inner.hi.z <= outer.hi.z;
  };
  // A container's own vertices lie on it and decide nothing.
  std::vector<std::vector<std::uint32_t>> vertices(surfaces);
  for (std::uint32_t s : container_id) {
    for (std::uint32_t t : members[s])
      vertices[s].insert(vertices[s].end(), triangles[t].begin(), triangles[t].end());
    std::sort(vertices[s].begin(), vertices[s].end());
    vertices[s].erase(std::unique(vertices[s].begin(), vertices[s].end()), vertices[s].end());
  }
  std::vector<std::vector<std::uint32_t>> containers(surfaces);
  struct Open {
    std::uint32_t surface;
    bool testable = false;
    Winding w;
  };
  std::vector<Open> open;
  std::vector<bool> tried(points.size(), false);
  std::vector<std::uint32_t> touched;
  for (std::uint32_t t = 0; t < surfaces; ++t) {
    if (members[t].empty()) continue;
    open.clear();
    by_surface.query([&](const Box& b) { return inside_box(b, surface_box[t]); },
                     [&](std::uint32_t k) {
                       if (container_id[k] != t) open.push_back({container_id[k], false, {}});
                     });
    for (std::size_t i = 0; i < members[t].size() * 3 && !open.empty(); ++i) {
      const std::uint32_t v = triangles[members[t][i / 3]][i % 3];
      if (tried[v]) continue;
      tried[v] = true;
      touched.push_back(v);
      bool any = false;
      for (Open& o : open) {
        o.testable = !std::binary_search(vertices[o.surface].begin(), vertices[o.surface].end(), v);
        o.w = {};
        any = any || o.testable;
      }
      if (!any) continue;
      const Vec3 p = points[v];
      const auto ray = [&](const Box& b) {
        return b.hi.x >= p.x && b.lo.y <= p.y && p.y <= b.hi.y && b.lo.z <= p.z && p.z <= b.hi.z;
      };
      by_triangle.query(ray, [&](std::uint32_t k) {
        const std::uint32_t tri = ray_triangle[k], s = surface_of[tri];
        for (Open& o : open) {
          if (o.surface != s || !o.testable) continue;
          const Vec3 a = points[triangles[tri][0]], b = points[triangles[tri][1]],
                     c = points[triangles[tri][2]];
          o.w.number += ray_crossing(a, b, c, p);
          if (!o.w.on_surface && point_on_triangle(a, b, c, p)) o.w.on_surface = true;
        }
      });
      std::erase_if(open, [&](const Open& o) {
        if (!o.testable || o.w.on_surface) return false;
        if (o.w.number != 0) containers[t].push_back(o.surface);
        return true;
      });
    }
    for (std::uint32_t v : touched) tried[v] = false;
    touched.clear();
    out.depth[t] = static_cast<std::uint32_t>(containers[t].size());
  }
  for (std::uint32_t t = 0; t < surfaces; ++t) {
    for (std::uint32_t s : containers[t])
      if (out.parent[t] == Nesting::kNone || out.depth[s] > out.depth[out.parent[t]])
        out.parent[t] = s;
  }
  return out;
}

}  // namespace cellforge::inline geom
