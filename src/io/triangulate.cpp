// Ear clipping with hole bridging (triangulate.h). The polygon is a circular list
// of indices; holes are spliced in where they touch it or through bridges to
// visible outer vertices (nearest first, each candidate checked with exact
// orientation tests), the ring is split where it passes a point twice crossing
// itself, then ears are cut while one exists. Ears are sought along the ring from
// the last one cut, and a candidate is tested only against the vertices in the grid
// cells its box covers, so that a face with thousands of holes (a plate after a
// Boolean) costs about n log n rather than n^2; repeated points are found by hashing.
// Triangles, the common case, are returned as they are, and quadrilaterals tiled
// directly, as the ear clipping would tile them.
#include "cellforge/io/triangulate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <numeric>
#include <optional>
#include <unordered_map>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"

namespace cellforge::io {

namespace {

using Tri = std::array<std::uint32_t, 3>;

struct PointHash {
  std::size_t operator()(Vec2 p) const {
    std::uint64_t h = 0;
    for (double d : {p.x + 0.0, p.y + 0.0}) {  // -0.0 == 0.0: one key
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 29;
    }
    return static_cast<std::size_t>(h);
  }
};

// Direction p->q leaves vertex p (between prev and next, interior on the left)
// into the interior.
bool inside_cone(Vec2 prev, Vec2 p, Vec2 next, Vec2 q) {
  if (orient2d(prev, p, next) > 0) return orient2d(prev, p, q) > 0 && orient2d(p, next, q) > 0;
  return orient2d(prev, p, q) > 0 || orient2d(p, next, q) > 0;
}

class Clipper {
 public:
  explicit Clipper(std::vector<Vec2> points) : p_(std::move(points)) {}

  // Joins every hole into `outer`: a hole that shares a point with the ring is
  // spliced in there (holes touching the outer loop or a joined hole at a vertex),
  // any other through a bridge from its rightmost vertex, rightmost hole first, so
  // that the holes not yet joined lie to the left of the bridge's start.
  void bridge(std::vector<std::uint32_t>& outer, std::vector<std::vector<std::uint32_t>> holes) {
    // Whether any hole shares a point with another loop at all: usually none does,
    // and the search for touching holes is skipped.
    bool any_touch = false;
    {
      std::unordered_map<Vec2, std::size_t, PointHash> loop_of;
      const auto note = [&](const std::vector<std::uint32_t>& loop, std::size_t id) {
        for (std::uint32_t v : loop) {
          auto [it, fresh] = loop_of.try_emplace(p_[v], id);
          if (!fresh && it->second != id) any_touch = true;
        }
      };
      note(outer, 0);
      for (std::size_t h = 0; h < holes.size(); ++h) note(holes[h], h + 1);
    }
    const auto right_of = [&](std::uint32_t a, std::uint32_t b) {  // a beyond b
      return p_[a].x > p_[b].x || (p_[a].x == p_[b].x && p_[a].y < p_[b].y);
    };
    const auto rightmost = [&](const std::vector<std::uint32_t>& h) {
      return static_cast<std::size_t>(std::min_element(h.begin(), h.end(), right_of) - h.begin());
    };
    const auto splice = [&](const std::vector<std::uint32_t>& h, std::size_t mi, std::size_t at) {
      std::vector<std::uint32_t> spliced(outer.begin(), outer.begin() + at + 1);
      for (std::size_t k = 0; k <= h.size(); ++k) spliced.push_back(h[(mi + k) % h.size()]);
      spliced.insert(spliced.end(), outer.begin() + at, outer.end());
      outer = std::move(spliced);
    };
    if (!any_touch && !holes.empty()) {
      // No loop shares a point with another: the holes go in the order of their
      // rightmost vertices, found once, and the edges a bridge must clear are kept in
      // a grid (every loop's edges and the bridges so far).
      std::vector<std::size_t> order(holes.size()), right(holes.size());
      for (std::size_t i = 0; i < holes.size(); ++i) right[i] = rightmost(holes[i]);
      std::iota(order.begin(), order.end(), std::size_t{0});
      std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        return right_of(holes[a][right[a]], holes[b][right[b]]);
      });
      grid_ = std::make_unique<SegmentGrid>(p_, outer, holes);
      for (std::size_t i : order) {
        const std::vector<std::uint32_t>& h = holes[i];
        const std::size_t at = find_bridge(outer, h, right[i], {});
        grid_->add(h[right[i]], outer[at]);
        splice(h, right[i], at);
      }
      return;
    }
    while (!holes.empty()) {
      if (any_touch && join_touching(outer, holes)) continue;
      const auto hole = std::min_element(
          holes.begin(), holes.end(),
          [&](const auto& a, const auto& b) { return right_of(a[rightmost(a)], b[rightmost(b)]); });
      const std::vector<std::uint32_t> h = std::move(*hole);
      holes.erase(hole);
      const std::size_t mi = rightmost(h);
      splice(h, mi, find_bridge(outer, h, mi, holes));
    }
  }

  std::vector<Tri> clip(const std::vector<std::uint32_t>& poly) {
    std::vector<Tri> out;
    std::vector<std::vector<std::uint32_t>> rings = {poly};
    while (!rings.empty()) {
      std::vector<std::uint32_t> ring = std::move(rings.back());
      rings.pop_back();
      if (!split_at_crossing(ring, rings)) clip_ring(std::move(ring), out);
    }
    return out;
  }

 private:
  // A ring that passes a point twice with crossing interior cones, each holding an
  // edge of the other (a hole touching the ring at several points, or holes
  // touching in a cycle, cut the polygon into parts meeting there), is split there
  // into two rings by swapping the copies' successors: the cones become the two
  // overlaps, one per part.
  bool split_at_crossing(const std::vector<std::uint32_t>& ring,
                         std::vector<std::vector<std::uint32_t>>& rings) const {
    const std::size_t n = ring.size();
    const auto at = [&](std::size_t k) { return p_[ring[k % n]]; };
    const auto in_cone = [&](std::size_t k, Vec2 q) {
      return inside_cone(at(k + n - 1), at(k), at(k + 1), q);
    };
    // The positions where the ring passes a point again, as pairs (i, j), i < j,
    // tried in order.
    std::unordered_map<Vec2, std::vector<std::size_t>, PointHash> seen;
    std::vector<std::pair<std::size_t, std::size_t>> repeats;
    for (std::size_t k = 0; k < n; ++k) {
      auto& list = seen[at(k)];
      for (std::size_t i : list) repeats.push_back({i, k});
      list.push_back(k);
    }
    std::sort(repeats.begin(), repeats.end());
    for (auto [i, j] : repeats) {
      if (!(in_cone(i, at(j + n - 1)) || in_cone(i, at(j + 1))) ||
          !(in_cone(j, at(i + n - 1)) || in_cone(j, at(i + 1))))
        continue;
      rings.emplace_back(ring.begin() + i + 1, ring.begin() + j + 1);
      rings.emplace_back(ring.begin() + j + 1, ring.end());
      rings.back().insert(rings.back().end(), ring.begin(), ring.begin() + i + 1);
      return true;
    }
    return false;
  }

  // Cuts ears off the ring: the next strict ear along the ring from the last one
  // cut (no ring vertex inside or on the triangle but its corners' points); when a
  // whole round finds none, any convex corner; when there is none, the current
  // corner (all on a line: zero-area triangles keep the edges).
  void clip_ring(const std::vector<std::uint32_t>& ring, std::vector<Tri>& out) const {
    std::size_t count = ring.size();
    if (count < 3) return;
    std::vector<std::uint32_t> prev(count), next(count);
    std::vector<char> alive(count, 1);
    for (std::size_t k = 0; k < count; ++k) {
      prev[k] = static_cast<std::uint32_t>((k + count - 1) % count);
      next[k] = static_cast<std::uint32_t>((k + 1) % count);
    }
    // A grid of about one ring vertex a cell over the ring's box.
    double lo[2] = {1e308, 1e308}, hi[2] = {-1e308, -1e308};
    for (std::uint32_t v : ring) {
      lo[0] = std::min(lo[0], p_[v].x), hi[0] = std::max(hi[0], p_[v].x);
      lo[1] = std::min(lo[1], p_[v].y), hi[1] = std::max(hi[1], p_[v].y);
    }
    const int g = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(count))));
    const double w[2] = {(hi[0] - lo[0]) / g, (hi[1] - lo[1]) / g};
    const auto cell = [&](double x, int axis) {
      if (!(w[axis] > 0)) return 0;
      const double c = std::floor((x - lo[axis]) / w[axis]);
      return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(g - 1)));
    };
    std::vector<std::vector<std::uint32_t>> grid(static_cast<std::size_t>(g) * g);
    for (std::size_t k = 0; k < count; ++k) {
      const Vec2 q = p_[ring[k]];
      grid[static_cast<std::size_t>(cell(q.y, 1)) * g + cell(q.x, 0)].push_back(static_cast<std::uint32_t>(k));
    }
    const auto is_ear = [&](std::uint32_t k, bool strict) {
      const Vec2 a = p_[ring[prev[k]]], b = p_[ring[k]], c = p_[ring[next[k]]];
      if (orient2d(a, b, c) <= 0) return false;
      if (!strict) return true;
      const int x0 = cell(std::min({a.x, b.x, c.x}), 0), x1 = cell(std::max({a.x, b.x, c.x}), 0);
      const int y0 = cell(std::min({a.y, b.y, c.y}), 1), y1 = cell(std::max({a.y, b.y, c.y}), 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          for (std::uint32_t m : grid[static_cast<std::size_t>(y) * g + x]) {
            if (!alive[m]) continue;
            const Vec2 q = p_[ring[m]];
            if (q == a || q == b || q == c) continue;
            if (orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 && orient2d(c, a, q) >= 0) return false;
          }
      return true;
    };
    const auto cut = [&](std::uint32_t k) {
      out.push_back({ring[prev[k]], ring[k], ring[next[k]]});
      next[prev[k]] = next[k];
      prev[next[k]] = prev[k];
      alive[k] = 0;
      --count;
    };
    std::uint32_t cur = 0;
    while (count > 3) {
      std::uint32_t pick = cur;
      bool found = false;
      for (std::size_t s = 0; s < count && !found; ++s, pick = next[pick]) found = is_ear(pick, true);
      if (found) {
        pick = prev[pick];  // the loop stepped past it
      } else {
        pick = cur;
        for (std::size_t s = 0; s < count && !found; ++s, pick = next[pick]) found = is_ear(pick, false);
        pick = found ? prev[pick] : cur;
      }
      cur = next[pick];
      cut(pick);
    }
    out.push_back({ring[prev[cur]], ring[cur], ring[next[cur]]});
  }

  // Splices in a hole with a vertex at a point of the ring, at the copy of that
  // point whose interior cone holds the hole; the ring then passes the point twice.
  bool join_touching(std::vector<std::uint32_t>& outer,
                     std::vector<std::vector<std::uint32_t>>& holes) {
    const std::size_t n = outer.size();
    for (auto h = holes.begin(); h != holes.end(); ++h) {
      for (std::size_t j = 0; j < h->size(); ++j) {
        const Vec2 next = p_[(*h)[(j + 1) % h->size()]];
        for (std::size_t k = 0; k < n; ++k) {
          if (p_[outer[k]] != p_[(*h)[j]] ||
              !inside_cone(p_[outer[(k + n - 1) % n]], p_[outer[k]], p_[outer[(k + 1) % n]], next))
            continue;
          std::vector<std::uint32_t> spliced(outer.begin(), outer.begin() + k + 1);
          for (std::size_t i = 1; i <= h->size(); ++i) spliced.push_back((*h)[(j + i) % h->size()]);
          spliced.insert(spliced.end(), outer.begin() + k + 1, outer.end());
          outer = std::move(spliced);
          holes.erase(h);
          return true;
        }
      }
    }
    return false;
  }

  // The ring position to bridge hole vertex mi to: the nearest ring vertex q such
  // that segment mq leaves q into the ring's interior, leaves m outside the hole
  // (and outside every other hole with a vertex at m), and meets no edge elsewhere.
  std::size_t find_bridge(const std::vector<std::uint32_t>& outer,
                          const std::vector<std::uint32_t>& hole, std::size_t mi,
                          const std::vector<std::vector<std::uint32_t>>& others) {
    const Vec2 m = p_[hole[mi]];
    const auto dist = [&](std::size_t k) {
      const Vec2 q = p_[outer[k]];
      return (q.x - m.x) * (q.x - m.x) + (q.y - m.y) * (q.y - m.y);
    };
    // Nearest first: usually one of the first few is visible, so the 16 nearest are
    // picked in one pass and tried in order; only when none will do, all of them,
    // from a heap (the same order: by distance, then by position).
    const auto fits = [&](std::size_t k) {
      const Vec2 q = p_[outer[k]];
      const Vec2 q_prev = p_[outer[(k + outer.size() - 1) % outer.size()]];
      const Vec2 q_next = p_[outer[(k + 1) % outer.size()]];
      if (!inside_cone(q_prev, q, q_next, m)) return false;
      if (grid_) return !grid_->crosses(p_, m, q) && cones_clear(hole, m, q);
      if (crosses(outer, m, q) || !clear(hole, m, q)) return false;
      return std::all_of(others.begin(), others.end(), [&](const auto& other) { return clear(other, m, q); });
    };
    {
      constexpr std::size_t kFirst = 16;
      std::array<std::pair<double, std::size_t>, kFirst> best;
      std::size_t n = 0;
      for (std::size_t k = 0; k < outer.size(); ++k) {
        const std::pair<double, std::size_t> c{dist(k), k};
        if (n < kFirst) {
          best[n++] = c;
          std::push_heap(best.begin(), best.begin() + n);
        } else if (c < best[0]) {
          std::pop_heap(best.begin(), best.begin() + n);
          best[n - 1] = c;
          std::push_heap(best.begin(), best.begin() + n);
        }
      }
      std::sort_heap(best.begin(), best.begin() + n);
      for (std::size_t i = 0; i < n; ++i)
        if (fits(best[i].second)) return best[i].second;
      if (n == outer.size()) return n ? best[0].second : 0;
    }
    std::vector<std::pair<double, std::size_t>> heap;
    heap.reserve(outer.size());
    for (std::size_t k = 0; k < outer.size(); ++k) heap.push_back({dist(k), k});
    const auto farther = [](const auto& a, const auto& b) { return a > b; };
    std::make_heap(heap.begin(), heap.end(), farther);
    std::size_t nearest = heap.empty() ? 0 : heap.front().second;
    while (!heap.empty()) {
      std::pop_heap(heap.begin(), heap.end(), farther);
      const std::size_t k = heap.back().second;
      heap.pop_back();
      if (fits(k)) return k;
    }
    return nearest;  // nothing visible (a degenerate face): the nearest vertex
  }

  // Segment mq leaves each vertex of `loop` at m on the interior side of the loop.
  bool cones_clear(const std::vector<std::uint32_t>& loop, Vec2 m, Vec2 q) const {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (p_[loop[i]] != m) continue;
      const Vec2 prev = p_[loop[(i + loop.size() - 1) % loop.size()]];
      if (!inside_cone(prev, m, p_[loop[(i + 1) % loop.size()]], q)) return false;
    }
    return true;
  }

  // Segment mq, from a point m of hole loop `loop` or beside it, meets none of its
  // edges away from m and q, and leaves m on the interior side of the loop (which is
  // clockwise: the polygon's interior is on its left).
  bool clear(const std::vector<std::uint32_t>& loop, Vec2 m, Vec2 q) const {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (p_[loop[i]] != m) continue;
      const Vec2 prev = p_[loop[(i + loop.size() - 1) % loop.size()]];
      if (!inside_cone(prev, m, p_[loop[(i + 1) % loop.size()]], q)) return false;
    }
    return !crosses(loop, m, q);
  }

  // Segment mq meets an edge of `loop` that has neither m nor q as an end.
  bool crosses(const std::vector<std::uint32_t>& loop, Vec2 m, Vec2 q) const {
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec2 c = p_[loop[i]], d = p_[loop[(i + 1) % loop.size()]];
      if (c == m || c == q || d == m || d == q) continue;
      if (segments_meet(m, q, c, d)) return true;
    }
    return false;
  }

  bool is_ear(const std::vector<std::uint32_t>& ring, std::size_t i, bool strict) const {
    const std::size_t n = ring.size();
    const Vec2 a = p_[ring[(i + n - 1) % n]], b = p_[ring[i]], c = p_[ring[(i + 1) % n]];
    if (orient2d(a, b, c) <= 0) return false;
    if (!strict) return true;
    for (std::size_t k = 0; k < n; ++k) {
      const Vec2 q = p_[ring[k]];
      if (q == a || q == b || q == c) continue;
      if (orient2d(a, b, q) >= 0 && orient2d(b, c, q) >= 0 && orient2d(c, a, q) >= 0) return false;
    }
    return true;
  }

  // Every edge of the loops and every bridge made so far, in a uniform grid over
  // their box, so that a bridge candidate is tested against the edges near it rather
  // than all of them (a face with a thousand holes).
  class SegmentGrid {
   public:
    SegmentGrid(const std::vector<Vec2>& p, const std::vector<std::uint32_t>& outer,
                const std::vector<std::vector<std::uint32_t>>& holes) {
      std::size_t edges = outer.size();
      for (const auto& h : holes) edges += h.size();
      lo_ = {1e308, 1e308};
      Vec2 hi{-1e308, -1e308};
      for (const Vec2& q : p) {
        lo_ = {std::min(lo_.x, q.x), std::min(lo_.y, q.y)};
        hi = {std::max(hi.x, q.x), std::max(hi.y, q.y)};
      }
      g_ = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(edges))));
      w_ = {(hi.x - lo_.x) / g_, (hi.y - lo_.y) / g_};
      cells_.resize(static_cast<std::size_t>(g_) * g_);
      const auto loop = [&](const std::vector<std::uint32_t>& l) {
        for (std::size_t i = 0; i < l.size(); ++i) add_edge(p, l[i], l[(i + 1) % l.size()]);
      };
      loop(outer);
      for (const auto& h : holes) loop(h);
    }
    void add(std::uint32_t a, std::uint32_t b) { pending_.push_back({a, b}); }
    // Whether mq meets an edge that has neither m nor q as an end.
    bool crosses(const std::vector<Vec2>& p, Vec2 m, Vec2 q) {
      for (auto [a, b] : pending_) add_edge(p, a, b);
      pending_.clear();
      ++tick_;
      const auto [x0, x1] = span(std::min(m.x, q.x), std::max(m.x, q.x), 0);
      const auto [y0, y1] = span(std::min(m.y, q.y), std::max(m.y, q.y), 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x)
          for (std::uint32_t s : cells_[static_cast<std::size_t>(y) * g_ + x]) {
            if (stamp_[s] == tick_) continue;
            stamp_[s] = tick_;
            const Vec2 c = p[segs_[s][0]], d = p[segs_[s][1]];
            if (c == m || c == q || d == m || d == q) continue;
            if (segments_meet(m, q, c, d)) return true;
          }
      return false;
    }

   private:
    int cell(double v, int axis) const {
      const double w = axis == 0 ? w_.x : w_.y, o = axis == 0 ? lo_.x : lo_.y;
      if (!(w > 0)) return 0;
      return static_cast<int>(std::clamp(std::floor((v - o) / w), 0.0, static_cast<double>(g_ - 1)));
    }
    // Cells one beyond on each side: a point on a cell wall may round into either.
    std::pair<int, int> span(double a, double b, int axis) const {
      return {std::max(0, cell(a, axis) - 1), std::min(g_ - 1, cell(b, axis) + 1)};
    }
    void add_edge(const std::vector<Vec2>& p, std::uint32_t a, std::uint32_t b) {
      const auto s = static_cast<std::uint32_t>(segs_.size());
      segs_.push_back({a, b});
      stamp_.push_back(0);
      const auto [x0, x1] = span(std::min(p[a].x, p[b].x), std::max(p[a].x, p[b].x), 0);
      const auto [y0, y1] = span(std::min(p[a].y, p[b].y), std::max(p[a].y, p[b].y), 1);
      for (int y = y0; y <= y1; ++y)
        for (int x = x0; x <= x1; ++x) cells_[static_cast<std::size_t>(y) * g_ + x].push_back(s);
    }
    Vec2 lo_, w_;
    int g_ = 1;
    std::vector<std::vector<std::uint32_t>> cells_;
    std::vector<std::array<std::uint32_t, 2>> segs_;
    std::vector<std::uint32_t> stamp_;
    std::uint32_t tick_ = 0;
    std::vector<std::array<std::uint32_t, 2>> pending_;
  };

  std::vector<Vec2> p_;
  std::unique_ptr<SegmentGrid> grid_;
};

}  // namespace

namespace {

// A quadrilateral of four distinct projected points, tiled as Clipper::clip_ring
// tiles it (the first strict ear from corner 0, else the first convex corner, else
// corner 0), without the general path's allocations: most faces of a mesh are
// triangles or quads.
std::array<Tri, 2> clip_quad(const std::array<Vec2, 4>& q, bool reversed) {
  std::array<std::uint32_t, 4> r{0, 1, 2, 3};
  if (reversed) r = {3, 2, 1, 0};
  const auto at = [&](int k) { return q[r[(k + 4) % 4]]; };
  const auto strict_ear = [&](int k) {
    const Vec2 a = at(k - 1), b = at(k), c = at(k + 1), other = at(k + 2);
    if (orient2d(a, b, c) <= 0) return false;
    return !(orient2d(a, b, other) >= 0 && orient2d(b, c, other) >= 0 && orient2d(c, a, other) >= 0);
  };
  int pick = -1;
  for (int k = 0; k < 4 && pick < 0; ++k)
    if (strict_ear(k)) pick = k;
  for (int k = 0; k < 4 && pick < 0; ++k)
    if (orient2d(at(k - 1), at(k), at(k + 1)) > 0) pick = k;
  if (pick < 0) pick = 0;
  const auto id = [&](int k) { return r[(k + 4) % 4]; };
  return {Tri{id(pick - 1), id(pick), id(pick + 1)}, Tri{id(pick - 1), id(pick + 1), id(pick + 2)}};
}

// A quadrilateral's two tiles, unless two of its corners project to one point.
std::optional<std::array<Tri, 2>> quad_tiles(const std::array<Vec3, 4>& p, const Projection& proj) {
  const std::array<Vec2, 4> q{proj(p[0]), proj(p[1]), proj(p[2]), proj(p[3])};
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j)
      if (q[i] == q[j]) return std::nullopt;
  return clip_quad(q, area_sign(q) < 0);
}

}  // namespace

std::vector<Tri> triangulate_polygon(const std::vector<std::vector<Vec3>>& loops, Vec3 normal) {
  if (loops.empty()) return {};
  if (loops.size() == 1 && loops[0].size() == 3) return {{0, 1, 2}};
  const Projection proj(normal);
  if (loops.size() == 1 && loops[0].size() == 4) {
    const auto& l = loops[0];
    if (const auto t = quad_tiles({l[0], l[1], l[2], l[3]}, proj)) return {(*t)[0], (*t)[1]};
  }
  std::vector<Vec2> points;
  std::vector<std::vector<std::uint32_t>> index(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    for (const Vec3& p : loops[l]) {
      index[l].push_back(static_cast<std::uint32_t>(points.size()));
      points.push_back(proj(p));
    }
  }
  // Outer counterclockwise, holes clockwise, whatever the input said.
  const auto area_sign_of = [&](const std::vector<std::uint32_t>& loop) {
    std::vector<Vec2> p;
    p.reserve(loop.size());
    for (std::uint32_t i : loop) p.push_back(points[i]);
    return area_sign(p);
  };
  if (area_sign_of(index[0]) < 0) std::reverse(index[0].begin(), index[0].end());
  for (std::size_t l = 1; l < index.size(); ++l)
    if (area_sign_of(index[l]) > 0) std::reverse(index[l].begin(), index[l].end());
  Clipper clipper(std::move(points));
  std::vector<std::uint32_t> outer = index[0];
  clipper.bridge(outer, {index.begin() + 1, index.end()});
  return clipper.clip(outer);
}

void triangulate_face(const Model& m, FaceId f, std::vector<std::array<VertexId, 3>>& out) {
  // One loop of three or four corners, most faces of a mesh, without the general
  // path's copies.
  LoopId only;
  int rings = 0;
  for (LoopId l : m.loops_of(f))
    if (!m.is_point_loop(l)) {
      only = l;
      ++rings;
    }
  if (rings == 1) {
    std::array<VertexId, 4> v;
    std::array<Vec3, 4> p;
    int n = 0;
    for (EdgeUseId u : m.uses_of(only)) {
      if (n == 4) {
        n = 5;
        break;
      }
      v[n] = m.use_start(u);
      p[n] = m.position(v[n]);
      ++n;
    }
    if (n == 3) {
      out.push_back({v[0], v[1], v[2]});
      return;
    }
    if (n == 4 && only == m.outer_loop(f)) {
      if (const auto t = quad_tiles(p, Projection(newell_normal(p)))) {
        out.push_back({v[(*t)[0][0]], v[(*t)[0][1]], v[(*t)[0][2]]});
        out.push_back({v[(*t)[1][0]], v[(*t)[1][1]], v[(*t)[1][2]]});
        return;
      }
    }
  }
  std::vector<VertexId> ids;
  std::vector<std::vector<Vec3>> loops;
  for (LoopId l : m.loops_of(f)) {
    if (m.is_point_loop(l)) continue;
    const std::vector<VertexId> vs = m.loop_vertices(l);
    ids.insert(ids.end(), vs.begin(), vs.end());
    loops.push_back(m.loop_points(l));
  }
  for (const Tri& t : triangulate_polygon(loops, m.face_normal(f)))
    out.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
}

std::vector<std::array<VertexId, 3>> triangulate_face(const Model& m, FaceId f) {
  std::vector<std::array<VertexId, 3>> out;
  triangulate_face(m, f, out);
  return out;
}

}  // namespace cellforge::io
