// The Boolean's driver (boolean.h): the operands' outward faces as triangles over
// one table of exact vertices, then the stages of arrangement.cpp, classify.cpp and
// output.cpp, and the exact check of the rounded result.
#include "cellforge/boolean/boolean.h"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <cstring>
#include <numeric>
#include <span>

#include "boolean/parallel.h"
#include "boolean/stages.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/triangulate.h"

namespace cellforge::boolean {

// ---------------------------------------------------------------- expressions

Expr Expr::op(Op o, std::vector<Expr> children) {
  const Kind k = o == Op::kUnion ? Kind::kUnion
                                 : (o == Op::kIntersection ? Kind::kIntersection : Kind::kDifference);
  return Expr{k, 0, std::move(children)};
}

Expr Expr::over(Op o, int n) {
  std::vector<Expr> c;
  for (int i = 0; i < n; ++i) c.push_back(of(i));
  return op(o, std::move(c));
}

bool Expr::contains(const std::vector<bool>& inside) const {
  switch (kind) {
    case Kind::kOperand:
      return operand >= 0 && static_cast<std::size_t>(operand) < inside.size() && inside[operand];
    case Kind::kUnion:
      for (const Expr& c : children)
        if (c.contains(inside)) return true;
      return false;
    case Kind::kIntersection:
      for (const Expr& c : children)
        if (!c.contains(inside)) return false;
      return !children.empty();
    case Kind::kDifference:
      if (children.empty() || !children[0].contains(inside)) return false;
      for (std::size_t i = 1; i < children.size(); ++i)
        if (children[i].contains(inside)) return false;
      return true;
  }
  return false;
}

Expr Expr::flattened() const {
  if (kind == Kind::kOperand) return *this;
  Expr out{kind, operand, {}};
  for (std::size_t i = 0; i < children.size(); ++i) {
    Expr c = children[i].flattened();
    // What a child may be spliced as: the same operation, or for a difference its
    // first child's difference and the unions it takes away.
    const Kind splice = kind != Kind::kDifference ? kind : (i == 0 ? Kind::kDifference : Kind::kUnion);
    if (c.kind == splice && !c.children.empty()) {
      for (Expr& g : c.children) out.children.push_back(std::move(g));
    } else {
      out.children.push_back(std::move(c));
    }
  }
  return out;
}

int Expr::max_operand() const {
  int m = kind == Kind::kOperand ? operand : -1;
  for (const Expr& c : children) m = std::max(m, c.max_operand());
  return m;
}

std::string to_string(Op op) {
  switch (op) {
    case Op::kUnion:
      return "union";
    case Op::kIntersection:
      return "intersection";
    case Op::kDifference:
      return "difference";
  }
  return "?";
}

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct VecHash {
  std::size_t operator()(const Vec3& v) const {
    std::uint64_t h = 0;
    for (double d : {v.x, v.y, v.z}) {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      h = (h ^ bits) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 31;
    }
    return static_cast<std::size_t>(h);
  }
};

// The input points, one id each: open addressing over the positions' bits, at most
// half full (`n` bounds the number of points).
class PointIds {
 public:
  explicit PointIds(std::size_t n) : mask_(std::bit_ceil(2 * n + 2) - 1), slots_(mask_ + 1, kInvalidIndex) {}
  // The id of p; a new one, p pushed onto pos, when p was not seen.
  std::uint32_t get(Vec3 p, std::vector<Vec3>& pos) {
    for (std::size_t i = VecHash{}(p) & mask_;; i = (i + 1) & mask_) {
      std::uint32_t& s = slots_[i];
      if (s == kInvalidIndex) {
        s = static_cast<std::uint32_t>(pos.size());
        pos.push_back(p);
        return s;
      }
      if (pos[s] == p) return s;
    }
  }

 private:
  std::size_t mask_;
  std::vector<std::uint32_t> slots_;
};

std::vector<FaceId> face_list(const Model& m) {
  std::vector<FaceId> out;
  out.reserve(m.num_faces());
  for (FaceId f : m.faces()) out.push_back(f);
  return out;
}

// The triangles of each face that `wanted` accepts (none for the others), in the
// order given, computed on threads: face i's are tiles[begin[i]] .. tiles[begin[i + 1]].
struct FaceTiles {
  std::vector<std::array<VertexId, 3>> tiles;
  std::vector<std::uint32_t> begin;
  std::span<const std::array<VertexId, 3>> operator[](std::size_t i) const {
    return {tiles.data() + begin[i], tiles.data() + begin[i + 1]};
  }
};
template <class Wanted>
FaceTiles triangulate_faces(const Model& m, const std::vector<FaceId>& faces, int threads, Wanted wanted) {
  std::vector<FaceTiles> parts =
      parallel_ranges<FaceTiles>(faces.size(), threads, [&](std::size_t lo, std::size_t hi, FaceTiles& out) {
        for (std::size_t i = lo; i < hi; ++i) {
          out.begin.push_back(static_cast<std::uint32_t>(out.tiles.size()));
          if (wanted(faces[i])) io::triangulate_face(m, faces[i], out.tiles);
        }
      });
  FaceTiles all;
  std::size_t n = 0;
  for (const FaceTiles& p : parts) n += p.tiles.size();
  all.tiles.reserve(n);
  all.begin.reserve(faces.size() + 1);
  for (const FaceTiles& p : parts) {
    const auto base = static_cast<std::uint32_t>(all.tiles.size());
    for (std::uint32_t b : p.begin) all.begin.push_back(base + b);
    all.tiles.insert(all.tiles.end(), p.tiles.begin(), p.tiles.end());
  }
  all.begin.push_back(static_cast<std::uint32_t>(all.tiles.size()));
  return all;
}

// Whether every edge of every loop is an edge of one of the triangles.
bool covers_loops(const FaceLoops& loops,
                  const std::vector<std::array<std::uint32_t, 3>>& tiles) {
  if (loops.size() == 1 && loops[0].size() == 3 && tiles.size() == 1) return true;
  const auto has_edge = [&](std::uint32_t p, std::uint32_t q) {
    for (const auto& t : tiles)
      for (int e = 0; e < 3; ++e)
        if ((t[e] == p && t[(e + 1) % 3] == q) || (t[e] == q && t[(e + 1) % 3] == p)) return true;
    return false;
  };
  if (tiles.size() <= 4) {  // a quad, the common case: no sorting
    for (const auto& loop : loops)
      for (std::size_t i = 0; i < loop.size(); ++i)
        if (!has_edge(loop[i], loop[(i + 1) % loop.size()])) return false;
    return true;
  }
  std::vector<std::uint64_t> edges;
  for (const auto& t : tiles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = t[e], q = t[(e + 1) % 3];
      edges.push_back((static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q));
    }
  std::sort(edges.begin(), edges.end());
  for (const auto& loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t p = loop[i], q = loop[(i + 1) % loop.size()];
      if (!std::binary_search(edges.begin(), edges.end(),
                              (static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q)))
        return false;
    }
  return true;
}

// Each loop as a fan from its first vertex (holes turn the other way, so they count
// negatively).
std::vector<std::array<std::uint32_t, 3>> fan_tiles(const FaceLoops& loops) {
  std::vector<std::array<std::uint32_t, 3>> out;
  for (const auto& loop : loops)
    for (std::size_t i = 1; i + 1 < loop.size(); ++i) out.push_back({loop[0], loop[i], loop[i + 1]});
  return out;
}

// Whether the planar loop turns the same way, strictly, at every corner and winds
// once, in the projection where its first tile t0 has area: the direction of its edges
// then turns through one revolution, so their component along the projection's
// second axis changes sign exactly twice (k revolutions: 2k times).
bool strictly_convex(const std::vector<Vec3>& pos, std::span<const std::uint32_t> loop, const Tri& t0) {
  int k = 0;
  while (k < 3 && orient2d_projected(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], k) == 0) ++k;
  if (k == 3) return false;
  const int turn = orient2d_projected(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], k);
  const int axis = (k + 2) % 3;  // the projection's second axis (predicates.h)
  const std::size_t n = loop.size();
  int changes = 0, last = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = pos[loop[i]], q = pos[loop[(i + 1) % n]], r = pos[loop[(i + 2) % n]];
    if (orient2d_projected(p, q, r, k) != turn) return false;
    const int d = (q[axis] > p[axis]) - (q[axis] < p[axis]);
    if (d == 0) continue;
    if (last != 0 && d != last) ++changes;
    last = d;
  }
  // The change from the last edge back to the first.
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p = pos[loop[i]], q = pos[loop[(i + 1) % n]];
    const int d = (q[axis] > p[axis]) - (q[axis] < p[axis]);
    if (d == 0) continue;
    changes += d != last;
    break;
  }
  return changes == 2;
}

}  // namespace

// ---------------------------------------------------------------- simple faces

namespace {

// Whether planar tiles (`tiles`, ids into `tris`) with boundary loops `loops` meet only
// in the corners and edges they share. Decided exactly in the projection along k, an
// axis where the tiles have area:
//  1. every tile turns the same way, strictly;
//  2. every tile edge is used by two tiles in opposite directions, or by one tile and
//     is an edge of a loop, and every loop edge is such an edge once;
//  3. the loops' vertices are distinct and no two loop edges meet but consecutive ones
//     at their common corner (the loops are simple and apart);
//  4. at the lowest corner of each loop that turns the tiles' way (counted the way the
//     tiles run it), the other loops wind 0 times.
// By 1 and 2 the number of tiles over a point off their edges is the winding number of
// the loops about it (each loop counted the way the tiles run it), so never negative.
// By 3 and 4 it is at most 1: the region where it is greatest is bounded, and just
// outside the loop around it the number is one less, so that loop turns the tiles' way
// and the others wind that one-less number about its corner. So tile interiors never
// overlap, and a corner of one tile inside another's edge, or edges crossing, would
// cover some point twice. With one loop turning the tiles' way (a face: one outer
// loop, holes) 4 holds by itself: the holes alone wind 0 or less about any point, and
// the number just outside the outer loop is not negative. Tilings whose loop edges'
// boxes meet too often (more than 32 candidate pairs an edge), or with many outer
// loops far from apart, are not certified: their pairs are tested as before.
// `axis`: the projection to decide in (-1: the first where the first tile has area).
template <class Loops, class Tiles>
bool simple_tiling(const std::vector<Vec3>& pos, const Loops& loops, std::span<const Tri> tris,
                   const Tiles& tiles, int axis = -1) {
  if (tiles.empty()) return false;
  const Tri& t0 = tris[tiles[0]];
  int k = std::max(axis, 0);
  while (axis < 0 && k < 3 && orient2d_projected(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], k) == 0) ++k;
  if (k == 3 || orient2d_projected(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], k) == 0) return false;
  const int turn = orient2d_projected(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], k);
  // 1.
  for (std::uint32_t t : tiles)
    if (orient2d_projected(pos[tris[t].v[0]], pos[tris[t].v[1]], pos[tris[t].v[2]], k) != turn) return false;
  // 2: tile edges (smaller end, larger end, +1 if drawn from the smaller) against the
  // loop edges (smaller, larger).
  struct Use {
    std::uint64_t edge;
    int dir;
    bool operator<(const Use& o) const { return edge < o.edge || (edge == o.edge && dir < o.dir); }
  };
  const auto key = [](std::uint32_t p, std::uint32_t q) {
    return (static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q);
  };
  std::vector<Use> uses;
  uses.reserve(tiles.size() * 3);
  for (std::uint32_t t : tiles)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = tris[t].v[e], q = tris[t].v[(e + 1) % 3];
      uses.push_back({key(p, q), p < q ? 1 : -1});
    }
  std::sort(uses.begin(), uses.end());
  std::vector<Use> boundary;  // used once: the direction the tiles run it
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].edge == uses[i].edge) ++j;
    if (j - i == 1) {
      boundary.push_back(uses[i]);
    } else if (j - i != 2 || uses[i].dir == uses[i + 1].dir) {
      return false;
    }
    i = j;
  }
  std::vector<std::uint64_t> loop_edges;
  std::vector<std::uint32_t> corners;
  for (const auto loop : loops) {
    if (loop.size() < 3) return false;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      loop_edges.push_back(key(loop[i], loop[(i + 1) % loop.size()]));
      corners.push_back(loop[i]);
    }
  }
  std::sort(loop_edges.begin(), loop_edges.end());
  if (loop_edges.size() != boundary.size()) return false;
  for (std::size_t i = 0; i < boundary.size(); ++i)
    if (boundary[i].edge != loop_edges[i]) return false;
  // 3. Corners distinct; then pairs of loop edges by a sweep along the first axis.
  std::sort(corners.begin(), corners.end());
  if (std::adjacent_find(corners.begin(), corners.end()) != corners.end()) return false;
  const int iu = (k + 1) % 3, iv = (k + 2) % 3;
  struct Seg {
    double lo, hi, vlo, vhi;
    std::uint32_t p, q;
  };
  std::vector<Seg> segs;
  segs.reserve(loop_edges.size());
  for (const auto loop : loops)
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t p = loop[i], q = loop[(i + 1) % loop.size()];
      segs.push_back({std::min(pos[p][iu], pos[q][iu]), std::max(pos[p][iu], pos[q][iu]),
                      std::min(pos[p][iv], pos[q][iv]), std::max(pos[p][iv], pos[q][iv]), p, q});
    }
  std::sort(segs.begin(), segs.end(), [](const Seg& x, const Seg& y) { return x.lo < y.lo; });
  const auto o2 = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    return orient2d_projected(pos[a], pos[b], pos[c], k);
  };
  // Collinear a, b, c with b on the segment's line: whether c lies on a's side of b.
  const auto same_side = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const int ax = pos[a][iu] != pos[b][iu] ? iu : iv;
    return (pos[a][ax] > pos[b][ax]) == (pos[c][ax] > pos[b][ax]);
  };
  std::size_t budget = 32 * segs.size();
  for (std::size_t i = 0; i < segs.size(); ++i)
    for (std::size_t j = i + 1; j < segs.size() && segs[j].lo <= segs[i].hi; ++j) {
      const Seg &x = segs[i], &y = segs[j];
      if (x.vlo > y.vhi || y.vlo > x.vhi) continue;
      if (budget-- == 0) return false;
      // Consecutive edges: they meet beyond their corner only folding back on one line.
      std::uint32_t c = kInvalidIndex, a = 0, b = 0;
      if (x.q == y.p) c = x.q, a = x.p, b = y.q;
      if (x.p == y.q) c = x.p, a = x.q, b = y.p;
      if (x.p == y.p) c = x.p, a = x.q, b = y.q;  // (not in consistently oriented loops)
      if (x.q == y.q) c = x.q, a = x.p, b = y.p;
      if (c != kInvalidIndex) {
        if (o2(a, c, b) == 0 && same_side(a, c, b)) return false;
        continue;
      }
      const int s1 = o2(x.p, x.q, y.p), s2 = o2(x.p, x.q, y.q);
      if (s1 * s2 > 0) continue;
      const int s3 = o2(y.p, y.q, x.p), s4 = o2(y.p, y.q, x.q);
      if (s3 * s4 > 0) continue;
      if (s1 != 0 || s2 != 0 || s3 != 0 || s4 != 0) return false;  // they cross or touch
      // On one line: apart only if their spans along it do not meet.
      const int ax = pos[x.p][iu] != pos[x.q][iu] ? iu : iv;
      const double xlo = std::min(pos[x.p][ax], pos[x.q][ax]), xhi = std::max(pos[x.p][ax], pos[x.q][ax]);
      const double ylo = std::min(pos[y.p][ax], pos[y.q][ax]), yhi = std::max(pos[y.p][ax], pos[y.q][ax]);
      if (!(xhi < ylo || yhi < xlo)) return false;
    }
  // 4. A simple loop turns as its lowest corner does; the tiles' direction along the
  // loop is the loop's own where they run its first edge so.
  struct LoopSeen {
    std::size_t lowest = 0;  // its lowest corner's place in it
    int along = 1;           // +1: the tiles run it as it is listed
    bool outer = false;      // it turns the tiles' way
  };
  std::vector<LoopSeen> seen;
  std::size_t outer = 0;
  for (const auto loop : loops) {
    const std::size_t n = loop.size();
    std::size_t m = 0;
    for (std::size_t i = 1; i < n; ++i) {
      const Vec3 &a = pos[loop[i]], &b = pos[loop[m]];
      if (a[iu] < b[iu] || (a[iu] == b[iu] && a[iv] < b[iv])) m = i;
    }
    const int loop_turn = o2(loop[(m + n - 1) % n], loop[m], loop[(m + 1) % n]);
    const std::uint32_t p = loop[0], q = loop[1];
    const auto it = std::lower_bound(boundary.begin(), boundary.end(), Use{key(p, q), -2});
    const int along = it->dir == (p < q ? 1 : -1) ? 1 : -1;  // the tiles run p -> q
    seen.push_back({m, along, loop_turn * along == turn});
    outer += seen.back().outer;
  }
  if (outer <= 1) return outer == 1;
  // The winding of the other loops about each outer loop's lowest corner, which lies on
  // none of them (3): a loop's edges crossing the ray from it along +u, upward with the
  // corner on their left (+1) or downward with it on their right (-1), each edge taken
  // with its lower end and without its upper one. Loops whose boxes miss the ray are
  // passed over; the edges visited are bounded as the sweep's pairs were.
  struct LoopBox {
    double umax, vmin, vmax;
  };
  std::vector<LoopBox> boxes;
  for (const auto loop : loops) {
    LoopBox b{-HUGE_VAL, HUGE_VAL, -HUGE_VAL};
    for (std::uint32_t v : loop) {
      b.umax = std::max(b.umax, pos[v][iu]);
      b.vmin = std::min(b.vmin, pos[v][iv]);
      b.vmax = std::max(b.vmax, pos[v][iv]);
    }
    boxes.push_back(b);
  }
  std::size_t visits = 32 * segs.size();
  std::size_t li = 0;
  for (const auto loop : loops) {
    const LoopSeen& s = seen[li++];
    if (!s.outer) continue;
    const std::uint32_t c = loop[s.lowest];
    const double cu = pos[c][iu], cv = pos[c][iv];
    int winding = 0;
    std::size_t lj = 0;
    for (const auto other : loops) {
      const std::size_t j = lj++;
      if (j + 1 == li) continue;
      const LoopBox& b = boxes[j];
      if (cu > b.umax || cv < b.vmin || cv >= b.vmax) continue;
      if (visits < other.size()) return false;
      visits -= other.size();
      int w = 0;
      for (std::size_t i = 0; i < other.size(); ++i) {
        const std::uint32_t a = other[i], e = other[(i + 1) % other.size()];
        if (pos[a][iv] <= cv) {
          if (pos[e][iv] > cv && o2(a, e, c) > 0) ++w;
        } else if (pos[e][iv] <= cv && o2(a, e, c) < 0) {
          --w;
        }
      }
      winding += w * seen[j].along;
    }
    if (winding != 0) return false;
  }
  return true;
}

}  // namespace

// stages.h: a face's tiles and loops (simple_tiling above).
bool simple_face(const std::vector<Vec3>& pos, const FaceLoops& loops, std::span<const Tri> tris,
                 const TileRange& tiles) {
  return simple_tiling(pos, loops, tris, tiles);
}

// ---------------------------------------------------------------- embedded operands

// arrangement.h.
EdgeUseTable::EdgeUseTable(std::span<const Tri> tris, std::size_t n_points, int threads)
    : EdgeUseTable(
          n_points, tris.size(),
          [&](std::size_t lo, std::size_t hi, auto&& emit) {
            for (auto i = static_cast<std::uint32_t>(lo); i < hi; ++i)
              for (int e = 0; e < 3; ++e) emit(tris[i].v[e], tris[i].v[(e + 1) % 3], i);
          },
          threads) {}

// Rows are short (a vertex's edges to larger ends): insertion sort, stable, but for
// the few long ones. Ranges of rows on threads.
void EdgeUseTable::sort_rows(int threads) {
  const auto by_q = [](const Use& x, const Use& y) { return x.q < y.q; };
  parallel_ranges<char>(rows(), threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t v = lo; v < hi; ++v) {
      if (start_[v + 1] - start_[v] < 2) continue;
      Use* b = uses_.data() + start_[v];
      Use* e = uses_.data() + start_[v + 1];
      if (e - b > 32) {
        std::stable_sort(b, e, by_q);
        continue;
      }
      for (Use* x = b + 1; x < e; ++x)
        for (Use* y = x; y > b && by_q(*y, *(y - 1)); --y) std::swap(*y, *(y - 1));
    }
  });
}

std::span<const EdgeUseTable::Use> EdgeUseTable::uses(std::uint32_t p, std::uint32_t q) const {
  if (p > q) std::swap(p, q);
  if (p + 1 >= start_.size()) return {};
  const Use* b = uses_.data() + start_[p];
  const Use* e = uses_.data() + start_[p + 1];
  const Use* lo = std::lower_bound(b, e, q, [](const Use& u, std::uint32_t x) { return u.q < x; });
  const Use* hi = lo;
  while (hi < e && hi->q == q) ++hi;
  return {lo, static_cast<std::size_t>(hi - lo)};
}

namespace {

// Conditions 2 and 3 of embedded_operands' first argument, for an operand's own
// triangles (1, closed and oriented, holds).
bool star_shaped(const std::vector<Vec3>& pos, std::span<const Tri> own) {
  Vec3 o{0, 0, 0};
  for (const Tri& t : own)
    for (std::uint32_t v : t.v) o = o + pos[v];
  o = o * (1.0 / static_cast<double>(3 * own.size()));
  const Tri& t0 = own[0];
  const int side = orient3d(o, pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]]);
  if (side == 0) return false;
  const Vec3 through = (pos[t0.v[0]] + pos[t0.v[1]] + pos[t0.v[2]]) * (1.0 / 3.0);
  for (int e = 0; e < 3; ++e)
    if (orient3d(o, pos[t0.v[e]], pos[t0.v[(e + 1) % 3]], through) != side) return false;
  for (std::size_t i = 1; i < own.size(); ++i) {
    const Tri& t = own[i];
    if (orient3d(o, pos[t.v[0]], pos[t.v[1]], pos[t.v[2]]) != side) return false;
    bool outside = false;
    for (int e = 0; e < 3 && !outside; ++e)
      outside = orient3d(o, pos[t.v[e]], pos[t.v[(e + 1) % 3]], through) == -side;
    if (!outside) return false;
  }
  return true;
}

constexpr std::array<int, 3> kAxes{2, 0, 1};  // z first: extrusions are made along it

// The second argument of embedded_operands, for the triangles tris[lo, hi) of one
// operand along axis d, turned by `s` = +1 or -1 (condition 1, closed and oriented,
// holds). Writing a vertex as (x, z) with z = s times its coordinate along d and x its
// projection across, z0 the least z:
//  P1. the triangles with every corner at z0 (the floor) and those with none there
//      (the top) each pass simple_tiling, in the projection along d, with their
//      boundary (the edges one of their own triangles uses) as loops;
//  P2. every other triangle, a wall, has two corners p, q of one kind (at z0, or
//      above it) and the third, r, of the other kind with x(r) = x(p) or x(q), and
//      its edge p q is on the boundary of the floor or the top, the one of its kind.
// Then the walls come in pairs that make a trapezoid over a floor boundary edge
// e = a0 b0, with a1, b1 the top's vertices over a0, b0 (the top's projection is one
// to one, and vertices are one per point): if a wall is a0 b0 b1, the triangle across
// its edge b1 a0 holds a0 and b1, so it is a wall; by P2 it is a0 b1 a1 with b1 a1 on
// the top's boundary (its third corner at z0 would have to be b0, which would use a0
// b0 a second time in turn, against 1). Likewise from a0 b0 a1, and from a top edge.
// So every boundary edge of the floor has one trapezoid over it, whose top is a
// boundary edge of the top over the same segment. Two triangles then meet only in
// corners and edges they share: in the floor, and in the top (a graph over the
// floor's region), by P1; the floor and the top never (the top is above z0); a wall
// and the floor or the top only on the trapezoid's edge over e, a boundary edge that
// tiles touch only as their edge or at its ends (a tile reaching it elsewhere would
// cover a point next to it twice); two walls of one trapezoid in its diagonal; walls
// over boundary edges e != f within the vertical line over the corner c that e and f
// may have (the loops are simple and apart), where each wall meets the segment c0 c1
// in all of it or one of its ends. An outline's extrusion (linear_extrude without
// twist or scale; the top a second flat cap) is such a prism, letters and outlines
// with holes and several pieces among them, turned by quarter turns too, and so is
// surface()'s heightfield over its flat base; most are not star-shaped.
bool prism(const std::vector<Vec3>& pos, std::span<const Tri> tris, std::uint32_t lo, std::uint32_t hi, int d,
           double s) {
  double z0 = HUGE_VAL;
  for (std::uint32_t t = lo; t < hi; ++t)
    for (std::uint32_t v : tris[t].v) z0 = std::min(z0, s * pos[v][d]);
  const auto floor = [&](std::uint32_t v) { return s * pos[v][d] == z0; };
  // First what one triangle at a time tells, which most surfaces that are no prism
  // fail at once (a Menger sponge's walls inside it, in the top): the floor's and the
  // top's triangles each turn one way in the projection along d (P1's first
  // condition), a wall's corner alone of its kind is over another (P2).
  std::array<std::vector<std::uint32_t>, 2> cap;
  std::array<int, 2> turn{0, 0};
  std::vector<std::uint32_t> walls;
  const int du = (d + 1) % 3, dv = (d + 2) % 3;
  for (std::uint32_t t = lo; t < hi; ++t) {
    const auto& v = tris[t].v;
    const int low = floor(v[0]) + floor(v[1]) + floor(v[2]);
    if (low == 1 || low == 2) {
      int i = 0;  // the corner alone of its kind
      while (floor(v[i]) == floor(v[(i + 1) % 3]) || floor(v[i]) == floor(v[(i + 2) % 3])) ++i;
      const std::uint32_t r = v[i];
      const auto over = [&](std::uint32_t a) { return pos[r][du] == pos[a][du] && pos[r][dv] == pos[a][dv]; };
      if (!over(v[(i + 1) % 3]) && !over(v[(i + 2) % 3])) return false;
      walls.push_back(t);
      continue;
    }
    const int c = low == 3 ? 0 : 1;
    const int o = orient2d_projected(pos[v[0]], pos[v[1]], pos[v[2]], d);
    if (o == 0 || (turn[c] != 0 && o != turn[c])) return false;
    turn[c] = o;
    cap[c].push_back(t);
  }
  // P1. The floor's and the top's boundaries as sorted directed edges (from << 32 |
  // to), then chained into loops (a corner where a boundary leaves twice is not simple).
  std::array<std::vector<std::uint64_t>, 2> rim;
  for (int c = 0; c < 2; ++c) {
    if (cap[c].empty()) return false;
    std::vector<std::uint64_t> uses;
    for (std::uint32_t t : cap[c])
      for (int e = 0; e < 3; ++e)
        uses.push_back(static_cast<std::uint64_t>(tris[t].v[e]) << 32 | tris[t].v[(e + 1) % 3]);
    std::sort(uses.begin(), uses.end());
    for (std::uint64_t u : uses) {
      const std::uint64_t back = (u << 32) | (u >> 32);
      if (!std::binary_search(uses.begin(), uses.end(), back)) rim[c].push_back(u);
    }
    // Each corner of the boundary left once and reached once: then the chains below
    // close into loops.
    std::vector<std::uint64_t>& r = rim[c];
    std::vector<std::uint32_t> ends;
    for (std::uint64_t u : r) ends.push_back(static_cast<std::uint32_t>(u));
    std::sort(ends.begin(), ends.end());
    const auto same_start = [](std::uint64_t x, std::uint64_t y) { return x >> 32 == y >> 32; };
    if (std::adjacent_find(r.begin(), r.end(), same_start) != r.end() ||
        std::adjacent_find(ends.begin(), ends.end()) != ends.end())
      return false;
    LoopTable loops;
    std::vector<char> used(r.size(), 0);
    std::vector<std::uint32_t> loop;
    for (std::size_t i = 0; i < r.size(); ++i) {
      if (used[i]) continue;
      loop.clear();
      for (std::size_t j = i; !used[j];) {
        used[j] = 1;
        loop.push_back(static_cast<std::uint32_t>(r[j] >> 32));
        const auto to = static_cast<std::uint32_t>(r[j]);
        const auto next = std::lower_bound(r.begin(), r.end(), static_cast<std::uint64_t>(to) << 32);
        if (next == r.end() || *next >> 32 != to) return false;
        j = static_cast<std::size_t>(next - r.begin());
      }
      loops.add(loop);
    }
    if (!simple_tiling(pos, FaceLoops{&loops, 0, loops.size()}, tris, cap[c], d)) return false;
  }
  // P2, the rest: a wall's edge of one kind on that kind's boundary.
  for (std::uint32_t t : walls) {
    const auto& v = tris[t].v;
    int i = 0;
    while (floor(v[i]) == floor(v[(i + 1) % 3]) || floor(v[i]) == floor(v[(i + 2) % 3])) ++i;
    const std::uint32_t p = v[(i + 1) % 3], q = v[(i + 2) % 3];
    const std::vector<std::uint64_t>& level = rim[floor(p) ? 0 : 1];
    if (!std::binary_search(level.begin(), level.end(), static_cast<std::uint64_t>(q) << 32 | p)) return false;
  }
  return true;
}

}  // namespace

// arrangement.h. Two arguments, for one operand's triangles. The first:
//  1. every edge is used by two of them, once each way: a closed oriented surface;
//  2. a point o is strictly on one side of every triangle's plane, the same side for
//     all: seen from o, every triangle turns the same way, so the surface's projection
//     onto a sphere around o covers every direction the same number of times (its
//     degree);
//  3. the ray from o through a point inside the first triangle's cone lies in no other
//     triangle's closed cone: the degree is 1.
// Covering the sphere once, the projection is one to one, so two triangles meet only
// in the corners and edges they share: the surface is embedded (and star-shaped from o).
// The second, for surfaces that pass 1 but not 2 and 3: the surface is a prism over
// an outline along an axis (prism, above).
std::vector<char> embedded_operands(const std::vector<Vec3>& pos, std::span<const Tri> tris,
                                    const EdgeUseTable& edges, const std::vector<char>& candidates,
                                    int threads, std::vector<std::array<std::uint32_t, 2>>& joins) {
  const std::size_t operands = candidates.size();
  std::vector<char> ok(candidates);
  // 1, for all operands at once: in each edge's uses, an operand's are one each way.
  // Ranges of edges on threads, each with its own verdicts, joined after.
  const std::vector<std::vector<char>> open_in =
      parallel_ranges<std::vector<char>>(edges.rows(), threads, [&](std::size_t lo, std::size_t hi, std::vector<char>& open) {
        open.assign(operands, 0);
        edges.each_edge_from(lo, hi, [&](std::uint32_t, std::uint32_t, std::span<const EdgeUseTable::Use> uses) {
          for (const EdgeUseTable::Use& x : uses) {
            const std::uint32_t k = tris[x.tri()].operand;
            if (!ok[k] || open[k]) continue;
            int forward = 0, backward = 0;
            for (const EdgeUseTable::Use& y : uses)
              if (tris[y.tri()].operand == k) (y.forward() ? forward : backward) += 1;
            if (forward != 1 || backward != 1) open[k] = 1;
          }
        });
      });
  for (const std::vector<char>& open : open_in)
    for (std::size_t k = 0; k < operands; ++k)
      if (open[k]) ok[k] = 0;
  // 2 and 3, an operand at a time (its triangles are consecutive).
  std::vector<std::uint32_t> begin(operands + 1, static_cast<std::uint32_t>(tris.size()));
  for (std::size_t t = tris.size(); t-- > 0;) begin[tris[t].operand] = static_cast<std::uint32_t>(t);
  for (std::size_t k = operands; k-- > 0;) begin[k] = std::min(begin[k], begin[k + 1]);
  const std::vector<char> star = parallel_jobs<char>(operands, threads, [&](std::size_t k, char& out) {
    if (!ok[k] || begin[k + 1] - begin[k] < 4) return;
    out = star_shaped(pos, tris.subspan(begin[k], begin[k + 1] - begin[k])) ||
          std::any_of(kAxes.begin(), kAxes.end(), [&](int d) {
            return prism(pos, tris, begin[k], begin[k + 1], d, 1) || prism(pos, tris, begin[k], begin[k + 1], d, -1);
          });
  });
  for (std::size_t k = 0; k < operands; ++k) ok[k] = ok[k] && star[k];
  // The certified operands' neighbours in one plane, from different faces (a planar
  // face's tiles are joined whole): ranges of edges on threads, their lists in order.
  if (std::none_of(ok.begin(), ok.end(), [](char x) { return x != 0; })) return ok;
  const auto found = edges.gather<std::array<std::uint32_t, 2>>(
      threads, [&](std::uint32_t, std::uint32_t, std::span<const EdgeUseTable::Use> uses, auto& out) {
        for (std::size_t i = 0; i < uses.size(); ++i)
          for (std::size_t j = i + 1; j < uses.size(); ++j) {
            const Tri& a = tris[uses[i].tri()];
            const Tri& b = tris[uses[j].tri()];
            if (a.operand != b.operand || !ok[a.operand] || a.input_face == b.input_face) continue;
            std::uint32_t w = b.v[0];
            for (std::uint32_t v : b.v)
              if (v != a.v[0] && v != a.v[1] && v != a.v[2]) w = v;
            if (orient3d(pos[a.v[0]], pos[a.v[1]], pos[a.v[2]], pos[w]) == 0) out.push_back({uses[i].tri(), uses[j].tri()});
          }
      });
  joins.insert(joins.end(), found.begin(), found.end());
  return ok;
}

namespace {

// The operands' faces that bound a cell on one side, as outward triangles, and their
// sheets (faces with no cell on either side) as they are.
Result<Arrangement> make_soup(std::span<const Model* const> operands, int threads) {
  std::vector<Vec3> pos;
  std::size_t vertices = 0;
  for (const Model* m : operands) vertices += m->num_vertices();
  PointIds ids(vertices);
  pos.reserve(vertices);
  std::vector<Tri> tris;
  std::vector<SoupFace> faces;
  std::vector<WireSeg> wires;
  LoopTable loops;  // the faces' loops
  std::size_t face_count = 0;
  for (const Model* m : operands) face_count += m->num_faces();
  faces.reserve(face_count);
  std::vector<char> closed_only;  // no sheet, wire or point, by operand
  for (std::uint32_t k = 0; k < operands.size(); ++k) {
    const Model& m = *operands[k];
    std::vector<std::uint32_t> vmap(m.vertex_slots(), kInvalidIndex);  // by vertex slot
    auto vid = [&](VertexId v) {
      std::uint32_t& id = vmap[v.value];
      if (id == kInvalidIndex) {
        Vec3 p = m.position(v);
        p = {p.x + 0.0, p.y + 0.0, p.z + 0.0};  // -0.0 and 0.0 are one point
        id = ids.get(p, pos);
      }
      return id;
    };
    // The vertices numbered in the model's order first: read in that order, positions
    // and the id table are met in sequence, where the faces' order jumps about them (a
    // third of the soup of two spheres of 10^6 triangles). A vertex only on a face's
    // point loop gets no id; one on nothing gets its id with the wires below.
    for (VertexId v : m.vertices())
      if (m.first_end(v).edge.is_valid()) vid(v);
    const std::size_t before = tris.size();
    const std::vector<FaceId> face_ids = face_list(m);
    // Its tiles, about: a face of loops of n_1 ... n_k corners has n_1 + ... + n_k +
    // 2k - 4 (each face is tiled where it is read, below, not in a pass before it that
    // kept every tile in an array of its own: 16 MB a sphere of 10^6 triangles).
    const std::size_t tile_estimate = static_cast<std::size_t>(std::max<std::int64_t>(
        0, static_cast<std::int64_t>(m.num_edge_uses() + 2 * m.num_loops()) - 4 * static_cast<std::int64_t>(m.num_faces())));
    // Room for this operand's tiles, growing geometrically: an exact reserve per
    // operand copies the whole soup once per operand (a plate and 1,000 cylinders).
    if (tris.capacity() < tris.size() + tile_estimate)
      tris.reserve(std::max(tris.size() + tile_estimate, 2 * tris.capacity()));
    // The faces on threads: the first range of them writes the soup's own lists, each
    // later range lists of its own, appended in order after it (their indices shifted),
    // so that the lists are the ones one thread makes and one thread copies nothing.
    // Every vertex a face's loops or tiles hold has an edge: numbered above, and only
    // read here.
    struct FacePart {
      std::vector<SoupFace> faces;
      std::vector<Tri> tris;
      LoopTable loops;
      bool sheets = false;
    };
    auto read_faces = [&](std::size_t lo, std::size_t hi, FacePart& out) {
      std::vector<std::uint32_t> scratch;                // a loop being read
      std::vector<std::array<VertexId, 3>> triangles;    // a face's tiling
      std::vector<std::array<std::uint32_t, 3>> tiles;  // a face's triangles
      for (std::size_t fi = lo; fi < hi; ++fi) {
        const FaceId f = face_ids[fi];
        const bool front = m.front_volume(f).is_valid(), back = m.back_volume(f).is_valid();
        if (front && back) continue;  // a face between two of its cells: inside it
        triangles.clear();
        io::triangulate_face(m, f, triangles);
        SoupFace sf;
        sf.operand = k;
        sf.face = f.value;
        sf.flipped = front;
        sf.sheet = !front && !back;
        out.sheets |= sf.sheet;
        for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
          if (m.is_point_loop(l)) continue;
          scratch.clear();
          for (EdgeUseId u : m.uses_of(l)) scratch.push_back(vmap[m.use_start(u).value]);
          if (front) std::reverse(scratch.begin(), scratch.end());
          const std::uint32_t li = out.loops.add(scratch);
          if (sf.loop_count++ == 0) sf.first_loop = li;
        }
        const auto sfi = static_cast<std::uint32_t>(out.faces.size());
        tiles.clear();
        for (const auto& t : triangles) {
          std::array<std::uint32_t, 3> tri{vmap[t[0].value], vmap[t[1].value], vmap[t[2].value]};
          if (front) std::swap(tri[1], tri[2]);
          tiles.push_back(tri);
        }
        // A face that is not planar (a rounded result read back) may have two vertices
        // that one projection makes one point, and its tiling then misses a sliver along
        // its boundary. Then each loop is tiled as a fan instead: the fans' triangles,
        // signed, have the face's winding number everywhere, which is all the
        // classification reads, and they take every edge of every loop.
        const FaceLoops face_loops{&out.loops, sf.first_loop, sf.loop_count};
        if (!covers_loops(face_loops, tiles)) tiles = fan_tiles(face_loops);
        for (const auto& t : tiles) {
          const Tri tri{t, k, sfi};
          if (collinear3d(pos[tri.v[0]], pos[tri.v[1]], pos[tri.v[2]])) continue;
          sf.tris.push_back(static_cast<std::uint32_t>(out.tris.size()));
          out.tris.push_back(tri);
        }
        out.faces.push_back(sf);
      }
    };
    FacePart soup_lists{std::move(faces), std::move(tris), std::move(loops), false};
    std::vector<FacePart> parts =
        parallel_ranges<FacePart>(face_ids.size(), threads, [&](std::size_t lo, std::size_t hi, FacePart& part) {
          if (lo > 0) {
            part.faces.reserve(hi - lo);
            part.tris.reserve(tile_estimate * (hi - lo) / face_ids.size() + 16);
          }
          read_faces(lo, hi, lo == 0 ? soup_lists : part);
        });
    faces = std::move(soup_lists.faces);
    tris = std::move(soup_lists.tris);
    loops = std::move(soup_lists.loops);
    bool sheets = soup_lists.sheets;
    for (std::size_t r = 1; r < parts.size(); ++r) {
      FacePart& part = parts[r];
      const auto face_base = static_cast<std::uint32_t>(faces.size());
      const auto tri_base = static_cast<std::uint32_t>(tris.size());
      const std::uint32_t loop_base = loops.size();
      for (SoupFace sf : part.faces) {
        sf.first_loop += loop_base;
        sf.tris.shift(tri_base);
        faces.push_back(sf);
      }
      for (Tri t : part.tris) {
        t.input_face += face_base;
        tris.push_back(t);
      }
      loops.append(part.loops);
      sheets |= part.sheets;
      part = FacePart{};
    }
    // Wire edges, and vertices on nothing (not a face's point loop either).
    const std::size_t wires_before = wires.size();
    for (EdgeId e : m.edges())
      if (m.is_wire(e)) wires.push_back({vid(m.start_of(e)), vid(m.end_of(e)), k});
    for (VertexId v : m.vertices())
      if (!m.first_end(v).edge.is_valid() && !m.point_loop(v).is_valid()) wires.push_back({vid(v), vid(v), k});
    if (tris.size() == before && wires.size() == wires_before)
      return Error{ErrorCode::kInvalidInput,
                   "boolean: operand " + std::to_string(k) + " is empty (no face, edge or point)"};
    closed_only.push_back(!sheets && wires.size() == wires_before);
  }
  parallel_ranges<char>(faces.size(), threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t i = lo; i < hi; ++i) {
      SoupFace& f = faces[i];
      if (f.tris.empty()) continue;
      const FaceLoops f_loops{&loops, f.first_loop, f.loop_count};
      if (f_loops.size() == 1 && f_loops[0].size() == 4) {
        const auto q = f_loops[0];
        f.quad = true;
        f.fold = static_cast<std::int8_t>(orient3d(pos[q[0]], pos[q[1]], pos[q[2]], pos[q[3]]));
        f.planar = f.fold == 0;
        f.convex = f.planar && f.tris.size() == 2 && strictly_convex(pos, q, tris[f.tris[0]]);
        f.simple = f.convex;
        continue;
      }
      const Tri& t0 = tris[f.tris[0]];
      for (const auto loop : f_loops)
        for (std::uint32_t v : loop)
          if (f.planar && v != t0.v[0] && v != t0.v[1] && v != t0.v[2])
            f.planar = orient3d(pos[t0.v[0]], pos[t0.v[1]], pos[t0.v[2]], pos[v]) == 0;
      f.convex = f.planar && f_loops.size() == 1 && f.tris.size() + 2 == f_loops[0].size() &&
                 strictly_convex(pos, f_loops[0], t0);
      f.simple = f.convex || (f.planar && f.tris.size() > 2 &&
                              simple_face(pos, f_loops, tris, f.tris));
    }
  });
  // Triangle ids, and a lone triangle's cluster id kLoneCluster | t, fit 31 bits.
  if (tris.size() >= Arrangement::kLoneCluster - 1)
    return Error{ErrorCode::kInvalidInput, "boolean: the operands have " + std::to_string(tris.size()) +
                                               " triangles; at most 2^31 - 2 can be combined"};
  // The operands whose own tiles need not be tested against each other.
  EdgeUseTable edges(tris, pos.size(), threads);
  std::vector<std::array<std::uint32_t, 2>> plane_joins;
  std::vector<char> embedded = embedded_operands(pos, tris, edges, closed_only, threads, plane_joins);
  return Arrangement(std::move(pos), std::move(tris), std::move(faces), std::move(loops),
                     static_cast<std::uint32_t>(operands.size()), std::move(wires),
                     std::move(embedded), std::move(plane_joins), std::move(edges), thread_count(threads));
}

// ---------------------------------------------------------------- the rounding check

// Pairs of result triangles, from different faces and with no common vertex, that
// meet; only pairs with a vertex rounding may have moved can have come to meet.
std::size_t rounding_crossings(const Model& m, const std::vector<bool>& rounded, int threads) {
  std::vector<std::array<VertexId, 3>> tris;
  std::vector<std::uint32_t> face;  // of each triangle
  const std::vector<FaceId> face_ids = face_list(m);
  const auto tiled = triangulate_faces(m, face_ids, threads, [](FaceId) { return true; });
  for (std::size_t fi = 0; fi < face_ids.size(); ++fi)
    for (const auto& t : tiled[fi]) {
      tris.push_back(t);
      face.push_back(face_ids[fi].value);
    }
  std::vector<std::array<Vec3, 3>> corners(tris.size());
  std::vector<char> moved(tris.size(), 0);
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) {
      const VertexId v = tris[i][k];
      corners[i][k] = m.position(v);
      moved[i] |= v.value < rounded.size() && rounded[v.value];
    }
  // Each triangle with a moved vertex against every triangle its boxes meet (a pair of
  // two moved ones once), so that a part whose vertices are all doubles costs nothing.
  const TriangleBoxes index(corners, thread_count(threads));
  // One face: its tiling; neighbours: what they share is theirs.
  const std::vector<std::uint64_t> near_pairs =
      index.pairs_with(moved, thread_count(threads), [&](std::uint32_t i, std::uint32_t j) {
        if (face[i] == face[j]) return false;
        for (VertexId u : tris[i])
          for (VertexId v : tris[j])
            if (u == v) return false;
        return true;
      });
  std::vector<std::size_t> counts = parallel_ranges<std::size_t>(
      near_pairs.size(), threads, [&](std::size_t lo, std::size_t hi, std::size_t& count) {
        for (std::size_t k = lo; k < hi; ++k) {
          const auto i = static_cast<std::uint32_t>(near_pairs[k] >> 32), j = static_cast<std::uint32_t>(near_pairs[k]);
          const Vec3 a[3] = {m.position(tris[i][0]), m.position(tris[i][1]), m.position(tris[i][2])};
          const Vec3 b[3] = {m.position(tris[j][0]), m.position(tris[j][1]), m.position(tris[j][2])};
          if (triangles_meet(a, b)) ++count;
        }
      });
  return std::accumulate(counts.begin(), counts.end(), std::size_t{0});
}

}  // namespace

// ---------------------------------------------------------------- evaluate

Result<BooleanResult> evaluate(std::span<const Model* const> operands, const Expr& expr,
                               const Options& options) {
  if (operands.empty()) return Error{ErrorCode::kInvalidInput, "boolean: no operands"};
  if (expr.max_operand() >= static_cast<int>(operands.size()))
    return Error{ErrorCode::kInvalidInput, "boolean: the expression names operand " +
                                               std::to_string(expr.max_operand()) + " of " +
                                               std::to_string(operands.size())};
  Report report;
  const std::size_t exact_before = exact_evaluations();
  auto t = Clock::now();
  auto soup = make_soup(operands, options.threads);
  if (!soup) return soup.error();
  Arrangement& a = *soup;
  report.input_triangles = a.tris.size();
  report.seconds.soup = seconds_since(t);

  t = Clock::now();
  a.intersect(options.threads);
  report.candidate_pairs = a.pairs_tested;
  report.intersecting_pairs = a.pairs_hit;
  report.seconds.intersect = seconds_since(t);

  t = Clock::now();
  a.segment_split = !options.convex_split;
  a.split();
  a.split_wires();
  report.seconds.split = seconds_since(t);

  t = Clock::now();
  Selection selection = classify_and_select(a, expr, options, report);
  report.seconds.classify = seconds_since(t);
  // A non-regularized result classifies points and edges after merging: the tree stays.
  a.release_pieces(/*keep_tree=*/options.keep_lower_dim);
  report.implicit_points = a.points.size();
  report.convex_split_clusters = a.convex_splits;

  t = Clock::now();
  report.rounding_self_intersections = kRoundingUnchecked;  // unless the repair vouches
  auto result = build_result(a, std::move(selection), expr, options, report);
  report.seconds.output = seconds_since(t);
  if (!result) return result.error();

  t = Clock::now();
  if (report.rounding_self_intersections == kRoundingUnchecked && options.check_rounding)
    report.rounding_self_intersections = rounding_crossings(result->model, result->rounded, options.threads);
  report.seconds.check = seconds_since(t);
  report.exact_fallbacks = exact_evaluations() - exact_before;
  result->report = report;
  return result;
}

Result<BooleanResult> apply(Op op, std::span<const Model* const> operands, const Options& options) {
  return evaluate(operands, Expr::over(op, static_cast<int>(operands.size())), options);
}

}  // namespace cellforge::boolean
