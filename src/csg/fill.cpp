#include "fill.h"

#include <algorithm>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"

namespace cellforge::csg {

namespace {

struct Box {
  Vec2 lo, hi;
  bool overlaps(const Box& o) const {
    return lo.x <= o.hi.x && o.lo.x <= hi.x && lo.y <= o.hi.y && o.lo.y <= hi.y;
  }
};

Box box_of(const std::vector<Vec2>& loop) {
  Box b{loop[0], loop[0]};
  for (Vec2 p : loop) {
    b.lo = Vec2{std::min(b.lo.x, p.x), std::min(b.lo.y, p.y)};
    b.hi = Vec2{std::max(b.hi.x, p.x), std::max(b.hi.y, p.y)};
  }
  return b;
}

// Some edge of a meets some edge of b (closed segments). The edges of each inside the
// other's box, swept by their smallest x.
bool loops_meet(const std::vector<Vec2>& a, const Box& ba, const std::vector<Vec2>& b,
                const Box& bb) {
  struct Edge {
    Vec2 p, q;
    Box box;
    int side;
  };
  const Box common{Vec2{std::max(ba.lo.x, bb.lo.x), std::max(ba.lo.y, bb.lo.y)},
                   Vec2{std::min(ba.hi.x, bb.hi.x), std::min(ba.hi.y, bb.hi.y)}};
  std::vector<Edge> edges;
  auto add = [&](const std::vector<Vec2>& l, int side) {
    for (std::size_t i = 0; i < l.size(); ++i) {
      const Vec2 p = l[i], q = l[(i + 1) % l.size()];
      const Box e{Vec2{std::min(p.x, q.x), std::min(p.y, q.y)},
                  Vec2{std::max(p.x, q.x), std::max(p.y, q.y)}};
      if (e.overlaps(common)) edges.push_back(Edge{p, q, e, side});
    }
  };
  add(a, 0);
  add(b, 1);
  std::sort(edges.begin(), edges.end(),
            [](const Edge& x, const Edge& y) { return x.box.lo.x < y.box.lo.x; });
  for (std::size_t i = 0; i < edges.size(); ++i) {
    for (std::size_t j = i + 1; j < edges.size() && edges[j].box.lo.x <= edges[i].box.hi.x; ++j) {
      if (edges[i].side == edges[j].side || !edges[i].box.overlaps(edges[j].box)) continue;
      if (segments_meet(edges[i].p, edges[i].q, edges[j].p, edges[j].q)) return true;
    }
  }
  return false;
}

}  // namespace

std::optional<std::vector<shape::Region>> fill_nested(const std::vector<std::vector<Vec2>>& paths) {
  std::vector<std::vector<Vec2>> loops;
  for (const auto& p : paths) {
    if (p.size() < 3) continue;
    auto simple = shape::polygon(p);  // checks the path is a simple polygon
    if (!simple) return std::nullopt;
    loops.push_back(std::move(simple->loops[0]));
  }
  const std::size_t n = loops.size();
  std::vector<Box> boxes;
  for (const auto& l : loops) boxes.push_back(box_of(l));
  // contains[i]: the loops that hold loop i (its first vertex is on none of them).
  std::vector<std::vector<std::size_t>> holders(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (!boxes[i].overlaps(boxes[j])) continue;
      if (loops_meet(loops[i], boxes[i], loops[j], boxes[j])) return std::nullopt;
      if (point_in_polygon(loops[j], loops[i][0])) holders[i].push_back(j);
      if (point_in_polygon(loops[i], loops[j][0])) holders[j].push_back(i);
    }
  }
  std::vector<std::size_t> depth(n);
  std::vector<long> parent(n, -1);
  for (std::size_t i = 0; i < n; ++i) depth[i] = holders[i].size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j : holders[i]) {
      if (depth[j] + 1 == depth[i]) parent[i] = static_cast<long>(j);
    }
  }
  std::vector<shape::Region> out;
  std::vector<long> region_of(n, -1);
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 != 0) continue;
    region_of[i] = static_cast<long>(out.size());
    out.push_back(shape::Region{{loops[i]}});
  }
  std::vector<std::vector<std::vector<Vec2>>> holes(out.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (depth[i] % 2 == 0) continue;
    holes[static_cast<std::size_t>(region_of[static_cast<std::size_t>(parent[i])])].push_back(
        loops[i]);
  }
  for (std::size_t r = 0; r < out.size(); ++r) {
    if (holes[r].empty()) continue;
    auto region = shape::polygon(out[r].loops[0], std::move(holes[r]));
    if (!region) return std::nullopt;
    out[r] = std::move(*region);
  }
  return out;
}

}  // namespace cellforge::csg
