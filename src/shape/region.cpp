// 2D regions: constructors, and the exact checks of polygon() (region.h).
#include "cellforge/shape/region.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"
#include "shape/draft.h"

namespace cellforge::shape {

namespace {

std::string point_text(Vec2 p) {
  return "(" + format_number(p.x) + ", " + format_number(p.y) + ")";
}

std::string loop_name(std::size_t loop) {
  return loop == 0 ? std::string("outer loop") : "hole " + std::to_string(loop - 1);
}

// +1 counterclockwise, -1 clockwise, 0 degenerate; for a loop without crossings the
// turn at its lexicographically smallest vertex decides.
int orientation(const std::vector<Vec2>& loop) {
  std::size_t k = 0;
  for (std::size_t i = 1; i < loop.size(); ++i) {
    if (loop[i].x < loop[k].x || (loop[i].x == loop[k].x && loop[i].y < loop[k].y)) k = i;
  }
  const std::size_t n = loop.size();
  return orient2d(loop[(k + n - 1) % n], loop[k], loop[(k + 1) % n]);
}

Status check_loop(const std::vector<Vec2>& loop, std::size_t li) {
  const std::string name = loop_name(li);
  if (loop.size() < 3) {
    return invalid(name + " has " + std::to_string(loop.size()) + " vertices (at least 3)");
  }
  for (std::size_t i = 0; i < loop.size(); ++i) {
    if (!std::isfinite(loop[i].x) || !std::isfinite(loop[i].y)) {
      return invalid(name + " vertex " + std::to_string(i) + " is not finite");
    }
  }
  std::vector<std::size_t> order(loop.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  auto less = [&](std::size_t i, std::size_t j) {
    return loop[i].x < loop[j].x || (loop[i].x == loop[j].x && loop[i].y < loop[j].y);
  };
  std::sort(order.begin(), order.end(), less);
  for (std::size_t i = 1; i < order.size(); ++i) {
    if (loop[order[i]] == loop[order[i - 1]]) {
      return invalid(name + " repeats the point " + point_text(loop[order[i]]) + " (vertices " +
                     std::to_string(std::min(order[i], order[i - 1])) + " and " +
                     std::to_string(std::max(order[i], order[i - 1])) + ")");
    }
  }
  return Status::Ok();
}

// Every pair of edges of all loops: only neighbours in one loop may meet, at their
// common vertex. Pairs whose boxes meet, by a sweep along x; of the pairs at fault,
// the first in the loops' order is reported.
Status check_crossings(const std::vector<std::vector<Vec2>>& loops) {
  struct Edge {
    std::size_t loop, index;
    Vec2 a, b;
    double x0, x1, y0, y1;
  };
  std::vector<Edge> edges;
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (std::size_t i = 0; i < loops[l].size(); ++i) {
      const Vec2 a = loops[l][i], b = loops[l][(i + 1) % loops[l].size()];
      edges.push_back({l, i, a, b, std::min(a.x, b.x), std::max(a.x, b.x), std::min(a.y, b.y), std::max(a.y, b.y)});
    }
  }
  std::vector<std::size_t> order(edges.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return edges[i].x0 < edges[j].x0; });
  std::pair<std::size_t, std::size_t> fault{edges.size(), edges.size()};
  for (std::size_t oi = 0; oi < order.size(); ++oi) {
    for (std::size_t oj = oi + 1; oj < order.size() && edges[order[oj]].x0 <= edges[order[oi]].x1; ++oj) {
      const std::size_t i = std::min(order[oi], order[oj]), j = std::max(order[oi], order[oj]);
      const Edge& e = edges[i];
      const Edge& f = edges[j];
      if (e.y0 > f.y1 || f.y0 > e.y1) continue;
      bool bad;
      const std::size_t n = loops[e.loop].size();
      if (e.loop == f.loop && (e.index + 1) % n == f.index) {
        bad = edges_fold_back(e.a, e.b, f.b);
      } else if (e.loop == f.loop && (f.index + 1) % n == e.index) {
        bad = edges_fold_back(f.a, f.b, e.b);
      } else {
        bad = segments_meet(e.a, e.b, f.a, f.b);
      }
      if (bad) fault = std::min(fault, std::pair{i, j});
    }
  }
  if (fault.first == edges.size()) return Status::Ok();
  const Edge& e = edges[fault.first];
  const Edge& f = edges[fault.second];
  return invalid(loop_name(e.loop) + " edge " + std::to_string(e.index) + " " + point_text(e.a) + "-" +
                 point_text(e.b) + " meets " + loop_name(f.loop) + " edge " + std::to_string(f.index) + " " +
                 point_text(f.a) + "-" + point_text(f.b));
}

}  // namespace

Result<Region> rectangle(Vec2 size, bool center) {
  if (!(size.x > 0) || !(size.y > 0) || !std::isfinite(size.x) || !std::isfinite(size.y)) {
    return invalid("rectangle size must be positive and finite, got " + point_text(size));
  }
  const double x0 = center ? -size.x / 2 : 0, y0 = center ? -size.y / 2 : 0;
  const double x1 = center ? size.x / 2 : size.x, y1 = center ? size.y / 2 : size.y;
  return Region{{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}};
}

Result<Region> circle(double r, const Faceting& faceting) {
  if (!(r > 0) || !std::isfinite(r))
    return invalid("circle r must be positive, got " + format_number(r));
  if (Status s = check_faceting(faceting); !s) return s.error();
  const int n = fragments(r, faceting);
  if (Status s = check_vertex_count(static_cast<std::uint64_t>(n), faceting.max_vertices,
                                    "a circle of " + std::to_string(n) + " segments");
      !s)
    return s.error();
  Region region;
  region.loops.emplace_back();
  for (int i = 0; i < n; ++i) {
    const double phi = (360.0 * i) / n;
    region.loops[0].push_back({r * cos_degrees(phi), r * sin_degrees(phi)});
  }
  return region;
}

Result<Region> regular_polygon(int sides, double r) {
  if (sides < 3)
    return invalid("a regular polygon needs at least 3 sides, got " + std::to_string(sides));
  return circle(r, Faceting{.fn = static_cast<double>(sides)});
}

Result<Region> polygon(std::vector<Vec2> outer, std::vector<std::vector<Vec2>> holes) {
  Region region;
  region.loops.push_back(std::move(outer));
  for (auto& h : holes) region.loops.push_back(std::move(h));
  for (std::size_t l = 0; l < region.loops.size(); ++l) {
    if (Status s = check_loop(region.loops[l], l); !s) return s.error();
  }
  if (Status s = check_crossings(region.loops); !s) return s.error();
  for (std::size_t l = 0; l < region.loops.size(); ++l) {
    const int o = orientation(region.loops[l]);
    if (o == 0) return invalid(loop_name(l) + " has zero area (its vertices are collinear)");
    if ((l == 0) != (o > 0)) std::reverse(region.loops[l].begin(), region.loops[l].end());
  }
  for (std::size_t l = 1; l < region.loops.size(); ++l) {
    if (winding_number(region.loops[0], region.loops[l][0]) == 0) {
      return invalid(loop_name(l) + " lies outside the outer loop");
    }
    for (std::size_t k = 1; k < region.loops.size(); ++k) {
      if (k != l && winding_number(region.loops[k], region.loops[l][0]) != 0) {
        return invalid(loop_name(l) + " lies inside " + loop_name(k));
      }
    }
  }
  return region;
}

double area(const Region& region) {
  double a = 0;
  for (const auto& loop : region.loops) a += signed_area2(loop);
  return a / 2;
}

Result<Region> checked(const Region& region) {
  if (region.loops.empty()) return invalid("the region has no loops");
  return polygon(region.loops[0],
                 std::vector<std::vector<Vec2>>(region.loops.begin() + 1, region.loops.end()));
}

Result<GroupId> make_region_face(Model& m, const Region& region) {
  auto ok = checked(region);
  if (!ok) return ok.error();
  Draft d = Draft::sheet("region");
  std::vector<Loop> loops;
  for (const auto& loop : ok->loops) {
    loops.emplace_back();
    for (Vec2 p : loop) loops.back().push_back(d.vertex({p.x, p.y, 0}));
  }
  d.face(std::move(loops));
  d.attribute("area", area(*ok));
  return commit(m, d);
}

}  // namespace cellforge::shape
