// Stages 5 and 6: merging and stitching (stages.h).
//
// 1. Points equal in exact arithmetic become one vertex: candidates are found in a
//    hash grid over the points' filtered positions (cells wider than twice any
//    error bound), then compared exactly.
// 2. Every edge gets every vertex of the line it lies on strictly between its ends:
//    a line's points are all those any cluster recorded on a line with its global
//    key (arrangement.h), sorted along the line exactly.
// 3. Faces on one plane with one orientation that share an edge no third face uses
//    merge; their boundary is traced, and the loop through the lexicographically
//    largest vertex is the outer one (a region whose boundary passes a vertex twice
//    stays unmerged). A vertex with two neighbours on one line goes.
// 4. Coordinates are rounded, face-connected shells found, and each shell of positive
//    volume bounds a cell; a shell of negative volume is a cavity of the innermost
//    cell around it (an exact nesting test).
#include <algorithm>
#include <span>
#include <cmath>
#include <map>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "boolean/parallel.h"
#include "boolean/stages.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/winding.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/topo/builder.h"
#include "cellforge/topo/property.h"
#include "cellforge/io/volumes.h"

namespace cellforge::boolean {

namespace {


std::uint64_t ordered(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// canon[p]: the smallest id among the `used` points at p's exact position, or, when
// that one does not round exactly, the smallest that does.
std::vector<std::uint32_t> canonical_points(const Arrangement& a, const std::vector<std::uint32_t>& used) {
  const std::uint32_t total = static_cast<std::uint32_t>(a.pos.size() + a.points.size());
  std::vector<std::uint32_t> canon(total);
  std::iota(canon.begin(), canon.end(), 0u);
  struct Item {
    std::uint32_t id;
    Vec3 x;
    double e;
  };
  std::vector<Item> items;
  items.reserve(used.size());
  double max_err = 0, scale = 0;
  for (std::uint32_t p : used) {
    double e = 0;
    const Vec3 x = a.approx3(p, &e);
    items.push_back({p, x, e});
    scale = std::max({scale, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  }
  for (const Item& it : items)
    if (it.e < scale * 1e-6) max_err = std::max(max_err, it.e);
  // Cells far wider than any error: two equal points share a cell unless one of them
  // lies within its error of a cell wall, and only those look next door.
  const double h = std::max({1e4 * max_err, scale * 1e-12, 1e-300});
  auto cell = [&](double v) { return static_cast<std::int64_t>(std::floor(v / h)); };
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull) ^
           (static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full) ^
           (static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull);
  };
  // Cell -> the last representative put there; chain[i]: the one before it there.
  std::unordered_map<std::uint64_t, std::uint32_t> grid;
  grid.reserve(items.size());
  std::vector<std::uint32_t> chain(items.size(), kInvalidIndex);
  std::vector<std::uint32_t> wide, reps;  // items whose error exceeds a cell; all representatives
  auto near = [](const Item& p, const Item& q) {
    return std::abs(p.x.x - q.x.x) <= p.e + q.e && std::abs(p.x.y - q.x.y) <= p.e + q.e &&
           std::abs(p.x.z - q.x.z) <= p.e + q.e;
  };
  auto match = [&](const Item& it, const std::vector<std::uint32_t>& list) {
    for (std::uint32_t r : list)
      if (near(it, items[r]) && (it.id == items[r].id || a.equal3(it.id, items[r].id))) return r;
    return kInvalidIndex;
  };
  for (std::uint32_t i = 0; i < items.size(); ++i) {
    const Item& it = items[i];
    std::uint32_t found = kInvalidIndex;
    if (it.e * 4 > h) {
      found = match(it, reps);
    } else {
      const std::int64_t c[3] = {cell(it.x.x), cell(it.x.y), cell(it.x.z)};
      int lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {  // a neighbour only where the error reaches a wall
        const double v = it.x[k], m = 2 * max_err + it.e;
        lo[k] = cell(v - m) < c[k] ? -1 : 0;
        hi[k] = cell(v + m) > c[k] ? 1 : 0;
      }
      for (int dx = lo[0]; dx <= hi[0] && found == kInvalidIndex; ++dx)
        for (int dy = lo[1]; dy <= hi[1] && found == kInvalidIndex; ++dy)
          for (int dz = lo[2]; dz <= hi[2] && found == kInvalidIndex; ++dz) {
            auto g = grid.find(key(c[0] + dx, c[1] + dy, c[2] + dz));
            if (g == grid.end()) continue;
            for (std::uint32_t r = g->second; r != kInvalidIndex && found == kInvalidIndex; r = chain[r])
              if (near(it, items[r]) && (it.id == items[r].id || a.equal3(it.id, items[r].id))) found = r;
          }
      if (found == kInvalidIndex) found = match(it, wide);
    }
    if (found != kInvalidIndex) {
      canon[it.id] = canon[items[found].id];
      continue;
    }
    reps.push_back(i);
    if (it.e * 4 > h) {
      wide.push_back(i);
    } else {
      auto [g, fresh] = grid.try_emplace(key(cell(it.x.x), cell(it.x.y), cell(it.x.z)), i);
      if (!fresh) {
        chain[i] = g->second;
        g->second = i;
      }
    }
  }
  // A class whose least id rounds inexactly while another of its points rounds exactly
  // (a diagonal of a face's tiling through a corner of another operand, whose point
  // is also a vertical edge's through a plane) takes that one: the result vertex is
  // then exact, and its faces stay out of the rounding repair.
  std::unordered_map<std::uint32_t, std::uint32_t> better;  // least id -> exact member
  for (const Item& it : items) {
    const std::uint32_t r = canon[it.id];
    if (r == it.id || better.count(r) || a.rounds_exactly(r) || !a.rounds_exactly(it.id)) continue;
    better.emplace(r, it.id);
  }
  if (!better.empty())
    for (const Item& it : items)
      if (auto b = better.find(canon[it.id]); b != better.end()) canon[it.id] = b->second;
  return canon;
}

// The points of each line class, sorted along the line: by root key (keys are
// dense), a range of `pts` and the axis it is sorted along (-1: fewer than 2 points).
struct LineClasses {
  std::vector<std::uint32_t> begin;  // begin[k] .. begin[k + 1]
  std::vector<std::uint32_t> pts;
  std::vector<std::int8_t> axis;
  // By entry of pts in a class of two points or more: its coordinate along the axis
  // in doubles, within +-err.
  std::vector<double> key, err;
  std::span<const std::uint32_t> points(std::uint32_t root) const {
    if (root + 1 >= begin.size()) return {};
    return {pts.data() + begin[root], pts.data() + begin[root + 1]};
  }
};

LineClasses line_classes(Arrangement& a, const std::vector<std::uint32_t>& canon) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;  // (root key, point)
  std::vector<std::uint32_t> on_line;
  for (const Cluster& c : a.clusters)
    for (const Line& l : c.lines()) {
      // A line records a point once per piece it met there: each point once here.
      on_line.clear();
      for (std::uint32_t p : l.points) on_line.push_back(canon[p]);
      std::sort(on_line.begin(), on_line.end());
      on_line.erase(std::unique(on_line.begin(), on_line.end()), on_line.end());
      const std::uint32_t root = a.line_root(l.key);
      for (std::uint32_t p : on_line) pairs.push_back({root, p});
    }
  for (auto [key, p] : a.edge_points) pairs.push_back({a.line_root(key), canon[p]});
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  LineClasses lc;
  const std::size_t keys = a.key_parent.size();
  lc.begin.assign(keys + 1, 0);
  lc.axis.assign(keys, -1);
  lc.pts.reserve(pairs.size());
  for (auto [root, p] : pairs) {
    ++lc.begin[root + 1];
    lc.pts.push_back(p);
  }
  for (std::size_t k = 0; k < keys; ++k) lc.begin[k + 1] += lc.begin[k];
  std::vector<std::pair<double, std::uint32_t>> keyed;
  for (std::size_t key = 0; key < keys; ++key) {
    const std::span<std::uint32_t> list(lc.pts.data() + lc.begin[key], lc.pts.data() + lc.begin[key + 1]);
    if (list.size() < 2) continue;
    Vec3 lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
    for (std::uint32_t p : list) {
      const Vec3 x = a.approx3(p);
      for (int i = 0; i < 3; ++i) {
        (&lo.x)[i] = std::min((&lo.x)[i], x[i]);
        (&hi.x)[i] = std::max((&hi.x)[i], x[i]);
      }
    }
    const Vec3 ext = hi - lo;
    const int ax = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    lc.axis[key] = static_cast<std::int8_t>(ax);
    // Sort by the rounded coordinate, then finish exactly with insertion (safe for
    // any comparator, and linear when the rounded order was right).
    keyed.clear();
    for (std::uint32_t p : list) keyed.push_back({a.approx3(p)[ax], p});
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < list.size(); ++i) list[i] = keyed[i].second;
    for (std::size_t i = 1; i < list.size(); ++i)
      for (std::size_t j = i; j > 0 && a.compare3(list[j], list[j - 1], ax) < 0; --j)
        std::swap(list[j], list[j - 1]);
  }
  lc.key.resize(lc.pts.size());
  lc.err.resize(lc.pts.size());
  for (std::size_t k = 0; k < keys; ++k) {
    if (lc.axis[k] < 0) continue;
    for (std::uint32_t i = lc.begin[k]; i < lc.begin[k + 1]; ++i) {
      double e = 0;
      lc.key[i] = a.approx3(lc.pts[i], &e)[lc.axis[k]];
      lc.err[i] = e;
    }
  }
  return lc;
}

// Every point of the edge's line strictly between its ends, in order from p to q.
void insert_between(const Arrangement& a, const LineClasses& lc, std::uint32_t root,
                    std::uint32_t p, std::uint32_t q, std::vector<std::uint32_t>& out) {
  const std::span<const std::uint32_t> list = lc.points(root);
  if (list.empty()) return;
  // Along the axis the class was sorted by; a class of one point takes one along
  // which the edge runs.
  int ax = lc.axis[root];
  if (ax < 0) {
    const Vec3 d = a.approx3(q) - a.approx3(p);
    ax = std::abs(d.x) >= std::abs(d.y) && std::abs(d.x) >= std::abs(d.z) ? 0 : (std::abs(d.y) >= std::abs(d.z) ? 1 : 2);
  }
  const int dir = a.compare3(p, q, ax);
  if (dir == 0) return;
  const std::uint32_t lo = dir < 0 ? p : q, hi = dir < 0 ? q : p;
  std::span<const std::uint32_t>::iterator b, e;
  if (lc.axis[root] < 0) {
    auto less = [&](std::uint32_t x, std::uint32_t y) { return a.compare3(x, y, ax) < 0; };
    b = std::upper_bound(list.begin(), list.end(), lo, less);
    e = std::lower_bound(list.begin(), list.end(), hi, less);
  } else {
    // By the doubles where the error intervals part, exactly where they meet: the
    // exact order, with compare3 only between points close together.
    struct Placed {
      std::uint32_t p;
      double key, err;
    };
    auto placed = [&](std::uint32_t x) {
      double err = 0;
      const double key = a.approx3(x, &err)[ax];
      return Placed{x, key, err};
    };
    auto at = [&](std::span<const std::uint32_t>::iterator it) {
      const std::size_t i = lc.begin[root] + static_cast<std::size_t>(it - list.begin());
      return Placed{*it, lc.key[i], lc.err[i]};
    };
    auto less = [&](const Placed& x, const Placed& y) {
      if (x.key + x.err < y.key - y.err) return true;
      if (y.key + y.err < x.key - x.err) return false;
      return a.compare3(x.p, y.p, ax) < 0;
    };
    const Placed plo = placed(lo), phi = placed(hi);
    // The first entry after lo, and the first not before hi (binary searches).
    auto search = [&](auto goes_right) {
      auto first = list.begin();
      std::size_t n = list.size();
      while (n > 0) {
        const std::size_t half = n / 2;
        if (goes_right(at(first + static_cast<std::ptrdiff_t>(half)))) {
          first += static_cast<std::ptrdiff_t>(half) + 1;
          n -= half + 1;
        } else {
          n = half;
        }
      }
      return first;
    };
    b = search([&](const Placed& x) { return !less(plo, x); });
    e = search([&](const Placed& x) { return less(x, phi); });
  }
  if (b >= e) return;
  if (dir < 0) {
    out.insert(out.end(), b, e);
  } else {
    out.insert(out.end(), std::make_reverse_iterator(e), std::make_reverse_iterator(b));
  }
}

// Non-regularized results mark each edge in or out of the set as a whole, so an edge
// must have a vertex wherever another operand's vertex (or a wire's end or point)
// lies inside it: the set may change there (a - b for boxes touching along part of an
// edge).
void split_at_vertices(const Arrangement& a, const std::vector<std::uint32_t>& canon,
                       std::vector<OutPoly>& polys) {
  std::vector<std::uint32_t> found;
  auto strictly_inside = [&](std::uint32_t x, std::uint32_t y, std::uint32_t v, int ax) {
    return v != x && v != y && a.compare3(x, v, ax) * a.compare3(v, y, ax) > 0 && a.collinear3(x, y, v);
  };
  // A face of an operand that cannot meet itself (boolean.cpp's certificate), none of
  // whose tiles another operand's triangle came near: no corner of anything lies inside
  // its edges (it would lie in a tile's box).
  auto alone = [&](const OutPoly& poly) {
    if (!a.wires.empty() || poly.tri >= a.tris.size()) return false;
    const Tri& t = a.tris[poly.tri];
    if (!a.embedded[t.operand]) return false;
    for (std::uint32_t s : a.faces[t.input_face].tris)
      if (a.near_other[s]) return false;
    return true;
  };
  for (OutPoly& poly : polys) {
    if (alone(poly)) continue;
    for (auto& loop : poly.loops) {
      std::vector<std::uint32_t> out;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t x = loop[i], y = loop[(i + 1) % loop.size()];
        out.push_back(x);
        double ex = 0, ey = 0;
        const Vec3 px = a.approx3(x, &ex), py = a.approx3(y, &ey);
        Box box;
        box.add(px - Vec3{ex, ex, ex});
        box.add(px + Vec3{ex, ex, ex});
        box.add(py - Vec3{ey, ey, ey});
        box.add(py + Vec3{ey, ey, ey});
        const Vec3 d = py - px;
        const int ax = std::abs(d.x) >= std::abs(d.y) && std::abs(d.x) >= std::abs(d.z) ? 0 : (std::abs(d.y) >= std::abs(d.z) ? 1 : 2);
        found.clear();
        auto test = [&](std::uint32_t v) {
          v = canon[v];
          const Vec3 pv = a.pos[v];
          if (pv.x < box.lo.x || pv.x > box.hi.x || pv.y < box.lo.y || pv.y > box.hi.y || pv.z < box.lo.z || pv.z > box.hi.z)
            return;
          if (strictly_inside(x, y, v, ax)) found.push_back(v);
        };
        a.bvh.query([&](const auto& b) { return b.overlaps(box); }, [&](std::uint32_t t) {
          for (std::uint32_t v : a.tris[t].v) test(v);
        });
        if (!a.wires.empty())
          a.wire_bvh.query([&](const auto& b) { return b.overlaps(box); }, [&](std::uint32_t w) {
            test(a.wires[w].p);
            test(a.wires[w].q);
          });
        if (found.empty()) continue;
        const int dir = a.compare3(x, y, ax);
        std::sort(found.begin(), found.end(), [&](std::uint32_t u, std::uint32_t v) {
          return a.compare3(u, v, ax) * dir < 0;
        });
        found.erase(std::unique(found.begin(), found.end()), found.end());
        out.insert(out.end(), found.begin(), found.end());
      }
      loop = std::move(out);
    }
  }
}

// The sites (indices into `sites`, with their verdicts) whose verdict differs from
// the points' next to them and that lie on no face between points in and out of the
// set: no face of the result holds them, so they stand alone. A site on such a face
// (a corner of a dropped face touching a kept face that nothing split there) is the
// face's: the points next to it along one axis differ only because the ray's start
// was shifted off the face. The five more rays of that test only for the few that
// differ.
std::vector<std::pair<std::uint32_t, bool>> alone_sites(
    const Arrangement& a, const Expr& expr, const std::vector<std::array<std::uint32_t, 2>>& sites,
    int threads) {
  const std::vector<SiteVerdict> v = classify_sites(a, expr, sites, threads);
  std::vector<std::uint32_t> differ;
  std::vector<std::array<std::uint32_t, 2>> again;
  std::vector<std::int8_t> axes;  // each one's first ray again
  for (std::uint32_t i = 0; i < sites.size(); ++i)
    if (v[i].in != v[i].around) {
      differ.push_back(i);
      again.push_back(sites[i]);
      axes.push_back(v[i].axis);
    }
  const std::vector<SiteVerdict> w = classify_sites(a, expr, again, threads, true, axes);
  std::vector<std::pair<std::uint32_t, bool>> out;
  for (std::size_t k = 0; k < differ.size(); ++k)
    if (!w[k].on_face) out.push_back({differ[k], v[differ[k]].in});
  return out;
}

// A box around the point p (q == p), or around the middle third of the open edge pq
// (an edge has one verdict along its inside, sampled at (p + 2q) / 3): the points'
// approximations grown by their error bounds, and by a unit in the last place for the
// thirds' rounding.
// With `whole`, around the closed edge.
Box site_box(const Arrangement& a, std::uint32_t p, std::uint32_t q, bool whole) {
  double ep = 0, eq = 0;
  const Vec3 x = a.approx3(p, &ep), y = a.approx3(q, &eq);
  Box box;
  if (p == q || whole) {
    box.add(x - Vec3{ep, ep, ep});
    box.add(x + Vec3{ep, ep, ep});
    box.add(y - Vec3{eq, eq, eq});
    box.add(y + Vec3{eq, eq, eq});
    return box;
  }
  const double e = std::max(ep, eq);
  for (const Vec3 m : {x + (y - x) * (1.0 / 3), x + (y - x) * (2.0 / 3)}) {
    const double r = e + 4 * kUnit * std::max({std::abs(m.x), std::abs(m.y), std::abs(m.z), std::abs(x.x),
                                               std::abs(x.y), std::abs(x.z), std::abs(y.x), std::abs(y.y),
                                               std::abs(y.z)});
    box.add(m - Vec3{r, r, r});
    box.add(m + Vec3{r, r, r});
  }
  return box;
}

// Whether only operand x has anything near the point p (q == p) or near the middle of
// the edge pq: no triangle of another operand has a box meeting the site's, and no
// operand has wires or points. Then every other operand's winding number is one
// constant there, the one on each side of x's faces.
// kAnyOperand for x: whether a single operand, whichever it is, has all there is near
// the site (then a face through the site is that operand's).
constexpr std::uint32_t kAnyOperand = kInvalidIndex - 1;
bool only_operand_near(const Arrangement& a, std::uint32_t x, std::uint32_t p, std::uint32_t q,
                       bool whole = false) {
  if (x == kInvalidIndex || !a.wires.empty()) return false;
  // An input vertex, or a triangle's edge between two, of triangles that nothing of
  // another operand came near (their boxes hold the site, and the pair tests saw every
  // box of another operand's that met theirs): that operand's alone.
  if (p < a.alone_in.size() && q < a.alone_in.size()) {
    const std::uint32_t o = a.alone_in[p];
    if (o != kInvalidIndex && a.alone_in[q] == o && (p == q || a.is_triangle_edge(p, q)))
      return x == kAnyOperand || x == o;
  }
  const Box box = site_box(a, p, q, whole);
  bool alone = true;
  a.bvh.query([&](const auto& b) { return alone && b.overlaps(box); },
              [&](std::uint32_t t) {
                if (x == kAnyOperand) x = a.tris[t].operand;
                alone &= a.tris[t].operand == x;
              });
  return alone;
}

// The lower-dimensional parts of a non-regularized result: the edges of the
// arrangement's faces and the operands' wire pieces that no kept face holds, in the
// set with the points around them not, or out of it inside a volume (a cut), as
// wires; and the points no kept face or wire holds that are likewise alone (isolated
// points). All in canonical ids.
struct LowerParts {
  std::vector<std::array<std::uint32_t, 2>> wires;
  std::vector<std::uint32_t> points;
  std::unordered_set<std::uint32_t> ends;  // the wires' ends: no face loop drops them
};

LowerParts lower_parts(Arrangement& a, const LineClasses& lc, const std::vector<std::uint32_t>& canon,
                       const std::vector<OutPoly>& polys, const std::vector<OutSide>& sides,
                       const Expr& expr, int threads) {
  std::unordered_set<std::uint64_t> held_edges, seen;
  std::unordered_set<std::uint32_t> held_points;
  for (const OutPoly& p : polys)
    for (const auto& loop : p.loops)
      for (std::size_t i = 0; i < loop.size(); ++i) {
        held_edges.insert(ordered(loop[i], loop[(i + 1) % loop.size()]));
        held_points.insert(loop[i]);
      }
  // only_operand_near, asked once per site and operand (a point is a corner of many
  // sides, an edge the side of two pieces).
  struct NearKey {
    std::uint32_t x, p, q, whole;
    bool operator==(const NearKey&) const = default;
  };
  struct NearHash {
    std::size_t operator()(const NearKey& k) const {
      const std::uint64_t h = (static_cast<std::uint64_t>(k.p) << 32 | k.q) * 0x9E3779B97F4A7C15ull;
      return static_cast<std::size_t>(h ^ (static_cast<std::uint64_t>(k.x) << 1 | k.whole) * 0xff51afd7ed558ccdull);
    }
  };
  std::unordered_map<NearKey, bool, NearHash> near_memo;
  const auto near_alone = [&](std::uint32_t x, std::uint32_t p, std::uint32_t q, bool whole = false) {
    if (x == kInvalidIndex) return false;
    const auto [it, fresh] = near_memo.try_emplace({x, std::min(p, q), std::max(p, q), whole}, false);
    if (fresh) it->second = only_operand_near(a, x, p, q, whole);
    return it->second;
  };
  std::vector<std::array<std::uint32_t, 2>> raw, edges;
  std::vector<std::uint32_t> raw_settled_by, corners, chain;
  // The corners and edges of settled sides (OutSide::settled) with nothing of another
  // operand near them: neither can stand alone.
  std::unordered_set<std::uint32_t> settled_corners;
  for (const OutSide& side : sides) {
    const std::uint32_t p = canon[side.p], q = canon[side.q];
    if (p == q) continue;
    chain.assign(1, p);
    if (side.key != kInvalidIndex) insert_between(a, lc, a.line_root(side.key), p, q, chain);
    chain.push_back(q);
    for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
      corners.push_back(chain[i]);
      if (chain[i] != chain[i + 1]) {
        raw.push_back({chain[i], chain[i + 1]});
        raw_settled_by.push_back(side.settled);
      }
    }
    corners.push_back(q);
    for (std::uint32_t v : chain)
      if (!settled_corners.count(v) && near_alone(side.settled, v, v)) settled_corners.insert(v);
  }
  // Two sides along one line may be cut at different points (the line known under
  // two keys whose classes hold different points): an edge that another edge or a
  // kept face's side from the same end overlaps is cut back to where that one ends,
  // so that the pieces classified never overlap.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> next_to;
  for (const auto& [x, y] : raw) {
    next_to[x].push_back(y);
    next_to[y].push_back(x);
  }
  for (std::uint64_t key : held_edges) {
    const auto x = static_cast<std::uint32_t>(key >> 32), y = static_cast<std::uint32_t>(key);
    next_to[x].push_back(y);
    next_to[y].push_back(x);
  }
  // Between the two along an axis first: collinear neighbours beyond an end (the next
  // piece of a chain) are the common case, and only arithmetic tells them collinear.
  const auto inside = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    for (int ax = 0; ax < 3; ++ax)
      if (const int d = a.compare3(x, y, ax); d != 0)
        return a.compare3(x, z, ax) == d && a.compare3(z, y, ax) == d && a.collinear3(x, y, z);
    return false;
  };
  const auto cut_back = [&](std::uint32_t& from, std::uint32_t to) {
    for (bool moved = true; moved && from != to;) {
      moved = false;
      // A point of the segment has every coordinate between its ends': outside their
      // box, grown by the approximations' error bounds, a neighbour is not on it.
      const Box segment = site_box(a, from, to, /*whole=*/true);
      for (std::uint32_t z : next_to[from]) {
        if (z == from || z == to || !segment.overlaps(site_box(a, z, z, true))) continue;
        if (inside(from, to, z)) {
          from = z;
          moved = true;
          break;
        }
      }
    }
  };
  std::unordered_set<std::uint64_t> settled_edges;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    auto [x, y] = raw[i];
    // Nothing of another operand near the whole of a settled edge: neither it nor a
    // part of it stands alone, and it need not be cut back.
    if (near_alone(raw_settled_by[i], x, y, /*whole=*/true)) {
      seen.insert(ordered(x, y));
      continue;
    }
    cut_back(x, y);
    cut_back(y, x);
    if (x == y || held_edges.count(ordered(x, y))) continue;
    if (near_alone(raw_settled_by[i], x, y)) settled_edges.insert(ordered(x, y));
    if (seen.insert(ordered(x, y)).second) edges.push_back({x, y});
  }
  // An edge inside the pieces of a settled side has the verdict of all around it.
  edges.erase(std::remove_if(edges.begin(), edges.end(),
                             [&](const auto& e) { return settled_edges.count(ordered(e[0], e[1])) > 0; }),
              edges.end());
  // The operands' wires, cut at every crossing, and their isolated points: these may
  // also lie on a kept face (held by it).
  std::vector<std::array<std::uint32_t, 2>> wire_edges;
  for (const WireSeg& w : a.wire_pieces) {
    const std::uint32_t p = canon[w.p], q = canon[w.q];
    if (p == q || held_edges.count(ordered(p, q)) || !seen.insert(ordered(p, q)).second) continue;
    wire_edges.push_back({p, q});
  }
  LowerParts out;
  std::vector<char> kept_in;  // by out.wires: in the set (else a cut)
  auto keep = [&](const std::vector<std::array<std::uint32_t, 2>>& list) {
    for (auto [i, in] : alone_sites(a, expr, list, threads)) {
      out.wires.push_back(list[i]);
      kept_in.push_back(in);
    }
  };
  keep(edges);
  keep(wire_edges);
  // A vertex between two collinear wires of one verdict, and on nothing else, goes.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> at;  // point -> wires
  for (std::uint32_t i = 0; i < out.wires.size(); ++i)
    for (std::uint32_t e : out.wires[i]) at[e].push_back(i);
  std::vector<char> gone(out.wires.size(), 0);
  std::unordered_set<std::uint32_t> inside_wires;  // the vertices merged away
  for (auto& [v, list] : at) {
    if (list.size() != 2 || held_points.count(v)) continue;
    const std::uint32_t i = list[0], j = list[1];
    if (i == j || gone[i] || gone[j] || kept_in[i] != kept_in[j]) continue;
    const std::uint32_t x = out.wires[i][0] == v ? out.wires[i][1] : out.wires[i][0];
    const std::uint32_t y = out.wires[j][0] == v ? out.wires[j][1] : out.wires[j][0];
    if (x == y || !a.collinear3(x, v, y)) continue;
    out.wires[i] = {x, y};
    gone[j] = 1;
    inside_wires.insert(v);
    for (std::uint32_t end : {y}) std::replace(at[end].begin(), at[end].end(), j, i);
  }
  std::vector<std::array<std::uint32_t, 2>> merged;
  for (std::size_t i = 0; i < out.wires.size(); ++i)
    if (!gone[i]) merged.push_back(out.wires[i]);
  out.wires = std::move(merged);
  for (const auto& w : out.wires) {
    out.ends.insert(w[0]);
    out.ends.insert(w[1]);
  }
  // Corners of dropped faces, then the operands' points and wire ends (which, like
  // their wires, may lie on a kept face).
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  std::vector<std::uint32_t> loose;
  for (const WireSeg& w : a.wire_pieces) {
    loose.push_back(canon[w.p]);
    loose.push_back(canon[w.q]);
  }
  std::sort(loose.begin(), loose.end());
  loose.erase(std::unique(loose.begin(), loose.end()), loose.end());
  std::vector<std::array<std::uint32_t, 2>> sites;
  for (const std::vector<std::uint32_t>* list : {&corners, &loose})
    for (std::uint32_t p : *list)
      if (!held_points.count(p) && !out.ends.count(p) && !inside_wires.count(p) &&
          (list == &loose || (!std::binary_search(loose.begin(), loose.end(), p) && !settled_corners.count(p))))
        sites.push_back({p, p});
  for (auto [i, in] : alone_sites(a, expr, sites, threads)) out.points.push_back(sites[i][0]);
  return out;
}

bool lex_greater(const Arrangement& a, std::uint32_t p, std::uint32_t q) {
  for (int ax = 0; ax < 3; ++ax) {
    const int c = a.compare3(p, q, ax);
    if (c != 0) return c > 0;
  }
  return false;
}

// Whether two faces' planes and orientations agree (they share an edge).
bool same_plane(const Arrangement& a, const OutPoly& x, const OutPoly& y) {
  if (x.cluster == kInvalidIndex || y.cluster == kInvalidIndex) return false;
  if (x.kind != y.kind || x.mark != y.mark) return false;
  if (x.cluster == y.cluster) return x.normal_sign == y.normal_sign;
  Cluster lone;
  const Cluster& cx = a.cluster(x.cluster, lone);
  const Tri& rx = a.tris[cx.ref];
  const Tri& ry = a.tris[a.cluster_ref(y.cluster)];
  // Tiles of one planar face are coplanar without a test (SoupFace::planar), the two
  // tiles of a quad that is not are not.
  const SoupFace& fx = a.faces[rx.input_face];
  const bool one_face = rx.input_face == ry.input_face;
  if (one_face && !fx.planar && fx.quad) return false;
  if (!one_face || !fx.planar) {
    const Vec3 p0 = a.pos[rx.v[0]], p1 = a.pos[rx.v[1]], p2 = a.pos[rx.v[2]];
    for (std::uint32_t v : ry.v)
      if (orient3d(p0, p1, p2, a.pos[v]) != 0) return false;
  }
  const int rel =
      orient2d_projected(a.pos[ry.v[0]], a.pos[ry.v[1]], a.pos[ry.v[2]], cx.k) * cx.nk_sign;
  return x.normal_sign == y.normal_sign * rel;
}

// The loops bounding the union of faces (directed edges used once), the outer first.
std::vector<std::vector<std::uint32_t>> boundary(const Arrangement& a,
                                                 const std::vector<const OutPoly*>& region) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (const OutPoly* p : region)
    for (const auto& loop : p->loops)
      for (std::size_t i = 0; i < loop.size(); ++i) edges.push_back({loop[i], loop[(i + 1) % loop.size()]});
  std::sort(edges.begin(), edges.end());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> kept;
  for (auto e : edges)
    if (!std::binary_search(edges.begin(), edges.end(), std::make_pair(e.second, e.first))) kept.push_back(e);
  std::multimap<std::uint32_t, std::uint32_t> next;
  for (auto e : kept) next.insert(e);
  std::vector<std::vector<std::uint32_t>> loops;
  while (!next.empty()) {
    auto it = next.begin();
    const std::uint32_t start = it->first;
    std::vector<std::uint32_t> loop{start};
    std::uint32_t cur = it->second;
    next.erase(it);
    while (cur != start) {
      loop.push_back(cur);
      auto n = next.find(cur);
      if (n == next.end()) break;  // not closed: keep what was traced
      cur = n->second;
      next.erase(n);
    }
    if (loop.size() >= 3) loops.push_back(std::move(loop));
  }
  std::size_t outer = 0;
  std::uint32_t best = kInvalidIndex;
  for (std::size_t l = 0; l < loops.size(); ++l)
    for (std::uint32_t v : loops[l])
      if (best == kInvalidIndex || lex_greater(a, v, best)) {
        best = v;
        outer = l;
      }
  if (outer != 0) std::swap(loops[0], loops[outer]);
  return loops;
}

// A region that cannot become one face (its boundary would pass a vertex twice, or
// swallow a vertex another face uses, a pinned vertex or a cut) merges as far as it
// can: one shared edge at a time, keeping each union whose boundary passes no vertex
// twice and swallows no vertex of a face outside it, no pinned vertex and no cut.
// Edges with an end that does not round exactly go first, so that what stays apart is
// cut along exact edges where it can be: a vertex left on a cut that the faces would
// otherwise have dropped is rounded, and may move off the line it lies on.
std::vector<OutPoly> merge_greedily(
    const Arrangement& a, const std::vector<const OutPoly*>& members,
    const std::vector<OutPoly>& all,
    const std::unordered_map<std::uint32_t, std::vector<std::uint32_t>>& users,
    const std::unordered_set<std::uint32_t>& pinned,
    const std::unordered_set<std::uint64_t>& cuts) {
  const std::size_t n = members.size();
  // The region's pieces in `all`, and the group each is in.
  std::vector<std::uint32_t> index(n), group(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    index[i] = static_cast<std::uint32_t>(members[i] - all.data());
    group[i] = i;
  }
  std::unordered_map<std::uint32_t, char> inside;  // pieces of the union being tried
  std::vector<std::vector<std::uint32_t>> parts(n);  // group -> members
  for (std::uint32_t i = 0; i < n; ++i) parts[i] = {i};
  std::vector<std::vector<std::vector<std::uint32_t>>> loops(n);
  for (std::uint32_t i = 0; i < n; ++i) loops[i] = members[i]->loops;
  // Edges between two pieces of the region.
  struct Shared {
    bool exact;
    std::uint64_t key;
    std::uint32_t x, y;
    bool operator<(const Shared& o) const { return exact != o.exact ? !exact : key < o.key; }
  };
  std::map<std::uint64_t, std::vector<std::uint32_t>> by_edge;
  for (std::uint32_t i = 0; i < n; ++i)
    for (const auto& loop : members[i]->loops)
      for (std::size_t k = 0; k < loop.size(); ++k) by_edge[ordered(loop[k], loop[(k + 1) % loop.size()])].push_back(i);
  std::vector<Shared> edges;
  std::vector<std::array<std::uint32_t, 2>> kept_cuts;  // pieces on either side of a cut
  for (const auto& [key, who] : by_edge) {
    if (who.size() != 2 || who[0] == who[1]) continue;
    if (cuts.count(key)) {
      kept_cuts.push_back({who[0], who[1]});
      continue;
    }
    const auto p = static_cast<std::uint32_t>(key >> 32), q = static_cast<std::uint32_t>(key);
    edges.push_back({a.rounds_exactly(p) && a.rounds_exactly(q), key, who[0], who[1]});
  }
  std::sort(edges.begin(), edges.end());
  for (bool changed = true; changed;) {
    changed = false;
    for (const Shared& e : edges) {
      const std::uint32_t gx = group[e.x], gy = group[e.y];
      if (gx == gy) continue;
      std::vector<const OutPoly*> both;
      inside.clear();
      for (std::uint32_t g : {gx, gy})
        for (std::uint32_t i : parts[g]) {
          both.push_back(members[i]);
          inside[index[i]] = 1;
        }
      std::vector<std::vector<std::uint32_t>> b = boundary(a, both);
      std::vector<std::uint32_t> seen;
      for (const auto& loop : b) seen.insert(seen.end(), loop.begin(), loop.end());
      std::sort(seen.begin(), seen.end());
      bool ok = !b.empty() && std::adjacent_find(seen.begin(), seen.end()) == seen.end();
      for (const auto& [x, y] : kept_cuts)
        ok &= !((group[x] == gx || group[x] == gy) && (group[y] == gx || group[y] == gy));
      for (const OutPoly* q : both)
        for (const auto& loop : q->loops)
          for (std::uint32_t v : loop)
            if (ok && !std::binary_search(seen.begin(), seen.end(), v)) {
              ok = !pinned.count(v);
              for (std::uint32_t u : users.at(v)) ok &= inside.count(u) != 0;
            }
      if (!ok) continue;
      for (std::uint32_t i : parts[gy]) group[i] = gx;
      parts[gx].insert(parts[gx].end(), parts[gy].begin(), parts[gy].end());
      parts[gy].clear();
      loops[gx] = std::move(b);
      changed = true;
    }
  }
  std::vector<OutPoly> out;
  for (std::uint32_t g = 0; g < n; ++g) {
    if (parts[g].empty()) continue;
    OutPoly m = *members[parts[g][0]];
    if (parts[g].size() > 1) {
      m.loops = std::move(loops[g]);
      m.keys.clear();
    }
    out.push_back(std::move(m));
  }
  return out;
}

// A region of faces on one plane, joined across edges, that may merge into one face:
// its faces (the first the smallest), its boundary, and the vertices that merging would
// leave inside it (kInvalidIndex: a reason to keep the faces apart).
struct MergeRegion {
  std::uint32_t root;
  std::vector<const OutPoly*> members;
  std::vector<std::vector<std::uint32_t>> outline;
  std::vector<std::uint32_t> swallowed;
};

// The vertices that merging would leave inside a face whose own points are in the set
// while the face's are not, or the other way round.
std::unordered_set<std::uint32_t> pinned_vertices(const Arrangement& a, const Expr& expr,
                                                  const std::vector<OutPoly>& polys,
                                                  const std::vector<MergeRegion>& regions, int threads) {
  std::vector<std::array<std::uint32_t, 2>> sites;
  std::vector<bool> face_mark;
  // A vertex near one operand's elements alone lies on its face and has its verdict.
  for (const MergeRegion& r : regions)
    for (std::uint32_t v : r.swallowed)
      if (v != kInvalidIndex && !only_operand_near(a, kAnyOperand, v, v)) {
        sites.push_back({v, v});
        face_mark.push_back(polys[r.root].mark);
      }
  const std::vector<SiteVerdict> v = classify_sites(a, expr, sites, threads);
  std::unordered_set<std::uint32_t> out;
  for (std::size_t k = 0; k < sites.size(); ++k)
    if (v[k].in != face_mark[k]) out.insert(sites[k][0]);
  return out;
}

double loop_volume6(const std::vector<Vec3>& pos, const std::vector<std::uint32_t>& loop) {
  double v = 0;
  const Vec3 o = pos[loop[0]];
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) v += dot(o, cross(pos[loop[i]], pos[loop[i + 1]]));
  return v;
}

// BooleanResult::face_in, edge_in and vertex_in as the model's kInSetProperty columns.
void mark_in_set(BooleanResult& r) {
  Model& m = r.model;
  auto faces = add_property<FaceProperty<std::uint8_t>>(m, kInSetProperty, 1);
  auto edges = add_property<EdgeProperty<std::uint8_t>>(m, kInSetProperty, 1);
  auto vertices = add_property<VertexProperty<std::uint8_t>>(m, kInSetProperty, 1);
  if (!faces || !edges || !vertices) return;  // the name taken by another type: none on a result
  for (FaceId f : m.faces()) faces->set(f, r.face_in[f.value] ? 1 : 0);
  for (EdgeId e : m.edges()) edges->set(e, r.edge_in[e.value] ? 1 : 0);
  for (VertexId v : m.vertices()) vertices->set(v, r.vertex_in[v.value] ? 1 : 0);
}

}  // namespace

Result<BooleanResult> build_result(Arrangement& a, Selection selection, const Expr& expr,
                                   const Options& options, Report& report) {
  const int threads = options.threads;
  std::vector<OutPoly>& polys = selection.polys;
  if (options.keep_lower_dim) a.find_alone_vertices();  // for only_operand_near
  // 0. The loops of the faces nothing cut, copied from the input now that the pieces
  // are freed (LoopSource).
  // On threads: each face's own lists.
  parallel_ranges<char>(polys.size(), threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t i = lo; i < hi; ++i) {
      OutPoly& p = polys[i];
      if (p.source == LoopSource::kFace) {
        for (const auto l : a.loops_of(a.faces[a.tris[p.tri].input_face])) p.loops.emplace_back(l.begin(), l.end());
      } else if (p.source == LoopSource::kTriangle) {
        p.loops.emplace_back(a.tris[p.tri].v.begin(), a.tris[p.tri].v.end());
      } else {
        continue;
      }
      if (p.normal_sign < 0)
        for (auto& loop : p.loops) std::reverse(loop.begin(), loop.end());
      p.source = LoopSource::kMade;
    }
  });
  // A non-regularized result casts rays below, which read the planar quads' loops
  // (Arrangement::plane_vertices).
  if (!options.keep_lower_dim) a.release_loops();
  // 1. One id per exact position, among the points a face or a line holds. An input
  // vertex whose triangles are all in clusters nothing cut, came near no other
  // operand's and belong to operands known to be embedded equals no other point: an
  // implicit point there would lie on a triangle whose box holds the vertex, one of
  // another operand (then a pair, and near_other) or, the surface being embedded, one
  // at the vertex (then cut). It is its own representative, not looked up.
  const std::size_t total = a.pos.size() + a.points.size();
  std::vector<char> held(total, 0);
  for (const OutPoly& p : polys)
    for (const auto& loop : p.loops)
      for (std::uint32_t v : loop) held[v] = 1;
  for (const OutSide& side : selection.sides) held[side.p] = held[side.q] = 1;
  for (const WireSeg& w : a.wire_pieces) held[w.p] = held[w.q] = 1;
  for (const Cluster& c : a.clusters)
    for (const Line& l : c.lines())
      for (std::uint32_t v : l.points) held[v] = 1;
  for (auto [key, p] : a.edge_points) held[p] = 1;
  {
    std::vector<char> safe(a.pos.size(), 2);  // 2: no triangle seen at it yet
    for (std::uint32_t t = 0; t < a.tris.size(); ++t) {
      const bool ok = !a.cluster_touched(a.cluster_of[t]) && !a.near_other[t] && a.embedded[a.tris[t].operand];
      for (std::uint32_t v : a.tris[t].v) safe[v] = static_cast<char>(ok && safe[v] != 0);
    }
    for (std::size_t v = 0; v < a.pos.size(); ++v)
      if (safe[v] == 1) held[v] = 0;
  }
  std::vector<std::uint32_t> used;  // increasing
  for (std::uint32_t v = 0; v < total; ++v)
    if (held[v]) used.push_back(v);
  std::vector<char>().swap(held);
  const std::vector<std::uint32_t> canon = canonical_points(a, used);
  // In place (a face's loops and keys are rewritten, never copied: most faces go
  // through every step below unchanged).
  for (OutPoly& p : polys) {
    if (p.keys.empty()) continue;  // input vertices: their own representatives
    for (std::size_t l = 0; l < p.loops.size(); ++l) {
      auto& loop = p.loops[l];
      auto& keys = p.keys[l];
      std::size_t n = 0;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const std::uint32_t c = canon[loop[i]];
        if (n > 0 && loop[n - 1] == c) {
          keys[n - 1] = keys[i];
          continue;
        }
        loop[n] = c;
        keys[n] = keys[i];
        ++n;
      }
      while (n > 1 && loop[n - 1] == loop[0]) --n;
      loop.resize(n);
      keys.resize(n);
    }
  }

  // 2. No T-junctions.
  const LineClasses lc = line_classes(a, canon);
  std::vector<std::uint32_t> derived;  // a loop's keys, where the poly keeps none
  for (OutPoly& p : polys) {
    for (std::size_t l = 0; l < p.loops.size(); ++l) {
      const auto& loop = p.loops[l];
      if (p.keys.empty()) {
        derived.resize(loop.size());
        for (std::size_t i = 0; i < loop.size(); ++i)
          derived[i] = a.find_edge_key(loop[i], loop[(i + 1) % loop.size()]);
      }
      const std::vector<std::uint32_t>& keys = p.keys.empty() ? derived : p.keys[l];
      if (std::all_of(keys.begin(), keys.end(), [](std::uint32_t k) { return k == kInvalidIndex; }))
        continue;  // on no line of the arrangement: nothing to insert
      std::vector<std::uint32_t> out;
      for (std::size_t i = 0; i < loop.size(); ++i) {
        out.push_back(loop[i]);
        if (keys[i] != kInvalidIndex)
          insert_between(a, lc, a.line_root(keys[i]), loop[i], loop[(i + 1) % loop.size()], out);
      }
      p.loops[l] = std::move(out);
    }
    p.keys.clear();  // read no more
  }

  // 2b. Non-regularized: the edges and points of the arrangement that are in the set
  // while no face holds them and the points around them are not: wires and points.
  LowerParts lower;
  if (options.keep_lower_dim) {
    split_at_vertices(a, canon, polys);
    lower = lower_parts(a, lc, canon, polys, selection.sides, expr, threads);
  }

  // 3. Merge coplanar neighbours.
  // Every edge use of the faces' loops (OutPolys, or MeshFaces: anything with loops),
  // by edge, then face.
  auto edge_uses = [&](const auto& ps, std::size_t n_points) {
    return EdgeUseTable(
        n_points, ps.size(),
        [&](std::size_t lo, std::size_t hi, auto&& emit) {
          for (auto f = static_cast<std::uint32_t>(lo); f < hi; ++f)
            for (const auto& loop : ps[f].loops)
              for (std::size_t i = 0; i < loop.size(); ++i) emit(loop[i], loop[(i + 1) % loop.size()], f);
        },
        threads);
  };
  {
    struct Join {  // an edge of two faces that may merge
      std::uint64_t key;
      std::uint32_t f, g;
    };
    // Found on threads.
    const std::vector<Join> joins = edge_uses(polys, a.pos.size() + a.points.size())
        .gather<Join>(threads, [&](std::uint32_t p, std::uint32_t q, std::span<const EdgeUseTable::Use> at, auto& out) {
          if (at.size() == 2 && at[0].tri() != at[1].tri() && at[0].forward() != at[1].forward() &&
              same_plane(a, polys[at[0].tri()], polys[at[1].tri()]))
            out.push_back({ordered(p, q), at[0].tri(), at[1].tri()});
        });
    // Non-regularized: not across an edge whose verdict differs from the faces' (a cut
    // in a face of the set: a wire of the subtrahend lying on it).
    std::vector<char> joined(joins.size(), 1);
    if (options.keep_lower_dim) {
      // An edge with one operand's elements alone near it has its faces' verdict.
      std::vector<std::array<std::uint32_t, 2>> sites;
      std::vector<std::size_t> asked;
      for (std::size_t k = 0; k < joins.size(); ++k) {
        const std::uint64_t key = joins[k].key;
        const auto p = static_cast<std::uint32_t>(key >> 32), q = static_cast<std::uint32_t>(key);
        if (only_operand_near(a, kAnyOperand, p, q)) continue;
        sites.push_back({p, q});
        asked.push_back(k);
      }
      const std::vector<SiteVerdict> v = classify_sites(a, expr, sites, threads);
      for (std::size_t i = 0; i < asked.size(); ++i)
        joined[asked[i]] = v[i].in == polys[joins[asked[i]].f].mark;
    }
    UnionFind regions(polys.size());
    std::unordered_set<std::uint64_t> cuts;
    for (std::size_t k = 0; k < joins.size(); ++k) {
      if (joined[k]) regions.unite(joins[k].f, joins[k].g);
      if (!joined[k]) cuts.insert(joins[k].key);
    }
    // The regions of several faces, in the order of their roots (a region of one face
    // stays as it is: no lists made for it).
    std::vector<std::uint32_t> root_of(polys.size()), region_of(polys.size(), 0);
    for (std::uint32_t f = 0; f < polys.size(); ++f) ++region_of[root_of[f] = regions.find(f)];
    std::vector<MergeRegion> multi;
    for (std::uint32_t r = 0; r < polys.size(); ++r) {
      const std::uint32_t size = region_of[r];
      region_of[r] = kInvalidIndex;
      if (size < 2) continue;
      region_of[r] = static_cast<std::uint32_t>(multi.size());
      multi.push_back({r, {}, {}, {}});
      multi.back().members.reserve(size);
    }
    auto region = [&](std::uint32_t f) { return region_of[root_of[f]]; };  // kInvalidIndex: alone
    for (std::uint32_t f = 0; f < polys.size(); ++f)
      if (region(f) != kInvalidIndex) multi[region(f)].members.push_back(&polys[f]);
    // Faces using each vertex of a region of several faces: a merge may not swallow a
    // vertex another face needs.
    std::vector<char> in_region(a.pos.size() + a.points.size(), 0);
    for (std::uint32_t f = 0; f < polys.size(); ++f)
      if (region(f) != kInvalidIndex)
        for (const auto& loop : polys[f].loops)
          for (std::uint32_t v : loop) in_region[v] = 1;
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> users;
    for (std::uint32_t f = 0; f < polys.size(); ++f)
      for (const auto& loop : polys[f].loops)
        for (std::uint32_t v : loop)
          if (in_region[v]) users[v].push_back(f);
    // The boundary of each region of several faces, and the vertices it leaves inside.
    for (MergeRegion& r : multi) {
      r.outline = boundary(a, r.members);
      std::vector<std::uint32_t> seen;
      for (const auto& loop : r.outline) seen.insert(seen.end(), loop.begin(), loop.end());
      std::sort(seen.begin(), seen.end());
      for (const OutPoly* q : r.members)
        for (const auto& loop : q->loops)
          for (std::uint32_t v : loop)
            if (!std::binary_search(seen.begin(), seen.end(), v)) r.swallowed.push_back(v);
      if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) r.swallowed.push_back(kInvalidIndex);
    }
    // A cut between two faces that merge by other edges is kept by merging greedily.
    for (std::size_t k = 0; k < joins.size(); ++k)
      if (!joined[k] && root_of[joins[k].f] == root_of[joins[k].g])
        multi[region(joins[k].f)].swallowed.push_back(kInvalidIndex);
    // Non-regularized: a vertex whose verdict differs from its faces' (a closed
    // operand's corner touching a face of the set from outside it) stays a vertex.
    const std::unordered_set<std::uint32_t> pinned =
        options.keep_lower_dim ? pinned_vertices(a, expr, polys, multi, threads)
                               : std::unordered_set<std::uint32_t>{};
    std::vector<OutPoly> merged;
    merged.reserve(polys.size());  // no more: a region gives at most its faces
    for (std::uint32_t f = 0; f < polys.size(); ++f) {
      if (root_of[f] != f) continue;
      if (region_of[f] == kInvalidIndex) {  // no other region reads it: moved
        merged.push_back(std::move(polys[f]));
        continue;
      }
      MergeRegion& r = multi[region_of[f]];
      // A boundary through a vertex twice (two holes touching at a corner), or a merge
      // that would leave inside the face a vertex other faces use (a corner touching
      // it) or a pinned one, is left as the pieces it came from.
      bool keep_apart = false;
      for (std::uint32_t v : r.swallowed) {
        keep_apart |= v == kInvalidIndex || pinned.count(v);
        if (keep_apart) break;
        for (std::uint32_t u : users[v]) keep_apart |= root_of[u] != f;
      }
      if (keep_apart) {
        for (OutPoly& q : merge_greedily(a, r.members, polys, users, pinned, cuts)) merged.push_back(std::move(q));
      } else if (!r.outline.empty()) {
        OutPoly m = std::move(polys[static_cast<std::size_t>(r.members[0] - polys.data())]);
        m.loops = std::move(r.outline);
        m.keys.clear();
        merged.push_back(std::move(m));
      }
    }
    polys = std::move(merged);
  }

  // Collinear edges at a vertex of two neighbours merge.
  {
    // Each point's neighbours along the faces' edges, both ways: rows of one array,
    // counted into place (a row is a vertex's few edges; sorted where read).
    const std::size_t total = a.pos.size() + a.points.size();
    std::vector<std::uint32_t> nb_begin(total + 1, 0), nb;
    auto each_side = [&](auto&& f) {
      for (const OutPoly& p : polys)
        for (const auto& loop : p.loops)
          for (std::size_t i = 0; i < loop.size(); ++i) f(loop[i], loop[(i + 1) % loop.size()]);
    };
    each_side([&](std::uint32_t x, std::uint32_t y) {
      ++nb_begin[x + 1];
      ++nb_begin[y + 1];
    });
    for (std::size_t i = 0; i < total; ++i) nb_begin[i + 1] += nb_begin[i];
    nb.resize(nb_begin[total]);
    {
      std::vector<std::uint32_t> at(nb_begin.begin(), nb_begin.end() - 1);
      each_side([&](std::uint32_t x, std::uint32_t y) {
        nb[at[x]++] = y;
        nb[at[y]++] = x;
      });
    }
    // Three points of one recorded line are collinear without arithmetic.
    // Point -> line roots, as ranges of one array (roots ascending).
    std::vector<std::uint32_t> at_begin(total + 1, 0), at_roots(lc.pts.size());
    for (std::uint32_t q : lc.pts) ++at_begin[q + 1];
    for (std::size_t i = 0; i < total; ++i) at_begin[i + 1] += at_begin[i];
    {
      std::vector<std::uint32_t> fill(at_begin.begin(), at_begin.end() - 1);
      for (std::uint32_t root = 0; root < lc.axis.size(); ++root)
        for (std::uint32_t q : lc.points(root)) at_roots[fill[q]++] = root;
    }
    auto lines_at = [&](std::uint32_t x) {
      return std::span<const std::uint32_t>(at_roots.data() + at_begin[x], at_roots.data() + at_begin[x + 1]);
    };
    auto on_one_line = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
      const auto fx = lines_at(x), fy = lines_at(y), fz = lines_at(z);
      for (std::uint32_t r : fy)
        if (std::binary_search(fx.begin(), fx.end(), r) && std::binary_search(fz.begin(), fz.end(), r))
          return true;
      return false;
    };
    // A point with two neighbours, all three on one line, is dropped: (point, its
    // neighbours).
    std::vector<char> drop(total, 0);
    std::vector<std::array<std::uint32_t, 3>> dropped;
    for (std::uint32_t v = 0; v < total; ++v) {
      std::uint32_t* b = nb.data() + nb_begin[v];
      std::uint32_t* e = nb.data() + nb_begin[v + 1];
      if (e - b < 2) continue;
      std::sort(b, e);
      e = std::unique(b, e);
      if (e - b == 2 && !lower.ends.count(v) && (on_one_line(b[0], v, b[1]) || a.collinear3(b[0], v, b[1]))) {
        drop[v] = 1;
        dropped.push_back({v, b[0], b[1]});
      }
    }
    // Non-regularized: only where the set is the same on both edges and the vertex.
    if (options.keep_lower_dim && !dropped.empty()) {
      std::vector<std::uint32_t> candidates;
      std::vector<std::array<std::uint32_t, 2>> sites;
      for (const auto& [v, x, y] : dropped) {
        // The vertex and both edges with one operand's elements alone near each: all
        // three have the verdict of the faces between them.
        if (!(only_operand_near(a, kAnyOperand, v, v) && only_operand_near(a, kAnyOperand, x, v) &&
              only_operand_near(a, kAnyOperand, v, y))) {
          candidates.push_back(v);
          sites.push_back({x, v});
          sites.push_back({v, y});
          sites.push_back({v, v});
        }
      }
      const std::vector<SiteVerdict> v = classify_sites(a, expr, sites, threads);
      for (std::size_t k = 0; k < candidates.size(); ++k)
        if (v[3 * k].in != v[3 * k + 1].in || v[3 * k].in != v[3 * k + 2].in) drop[candidates[k]] = 0;
    }
    std::size_t n = 0;  // faces kept, compacted in place
    for (OutPoly& p : polys) {
      std::size_t loops = 0;
      for (auto& loop : p.loops) {
        std::erase_if(loop, [&](std::uint32_t v) { return drop[v] != 0; });
        if (loop.size() >= 3) {
          if (&loop != &p.loops[loops]) p.loops[loops] = std::move(loop);
          ++loops;
        } else if (loops == 0) {
          break;  // the outer loop vanished: the face was degenerate
        }
      }
      if (loops == 0) continue;
      p.loops.resize(loops);
      if (&p != &polys[n]) polys[n] = std::move(p);
      ++n;
    }
    polys.resize(n);
  }

  // Face-connected shells (across edges two faces use), each of positive volume a
  // cell, each of negative volume a cavity of the innermost cell around it, by the
  // exact nesting of the shells (geom/winding.h) on their rounded triangles.
  auto assign_shell_cells = [&](MeshInput& in, const std::vector<OutPoly>& polys) {
    UnionFind shells(polys.size());
    edge_uses(in.faces, in.positions.size())
        .each_edge([&](std::uint32_t, std::uint32_t, std::span<const EdgeUseTable::Use> at) {
          if (at.size() == 2) shells.unite(at[0].tri(), at[1].tri());
        });
    // Each face's share on threads (its loops' in order), summed by shell in face order.
    std::vector<double> share(polys.size(), 0);
    parallel_ranges<char>(polys.size(), threads, [&](std::size_t lo, std::size_t hi, char&) {
      for (std::size_t f = lo; f < hi; ++f)
        for (const auto& loop : in.faces[f].loops) share[f] += loop_volume6(in.positions, loop);
    });
    std::vector<double> volume(polys.size(), 0);
    for (std::uint32_t f = 0; f < polys.size(); ++f) volume[shells.find(f)] += share[f];
    std::vector<int> cell(polys.size(), -1);
    for (std::uint32_t s = 0; s < polys.size(); ++s)
      if (shells.find(s) == s && volume[s] > 0) cell[s] = in.volumes++;
    std::vector<std::uint32_t> surface(polys.size(), kInvalidIndex), root_of;
    bool any_cavity = false;
    for (std::uint32_t s = 0; s < polys.size(); ++s) {
      if (shells.find(s) != s) continue;
      surface[s] = static_cast<std::uint32_t>(root_of.size());
      root_of.push_back(s);
      any_cavity |= volume[s] < 0;
    }
    if (any_cavity) {
      std::vector<std::array<std::uint32_t, 3>> tris;
      std::vector<std::uint32_t> surface_of;
      for (std::uint32_t f = 0; f < polys.size(); ++f)
        for (const auto& t : tile_face(in, in.faces[f])) {
          tris.push_back(t);
          surface_of.push_back(surface[shells.find(f)]);
        }
      std::vector<bool> container(root_of.size());
      for (std::size_t k = 0; k < root_of.size(); ++k) container[k] = volume[root_of[k]] > 0;
      const Nesting nest = nest_surfaces(in.positions, tris, surface_of,
                                         static_cast<std::uint32_t>(root_of.size()), container);
      for (std::size_t k = 0; k < root_of.size(); ++k)
        if (volume[root_of[k]] < 0 && nest.parent[k] != Nesting::kNone)
          cell[root_of[k]] = cell[root_of[nest.parent[k]]];
    }
    for (std::uint32_t f = 0; f < polys.size(); ++f) in.faces[f].back = cell[shells.find(f)];
  };

  // 4. Round, find shells and cells, build.
  const bool closed = options.keep_lower_dim || options.cells;
  BooleanResult result;
  MeshInput in;
  in.group_name = "boolean";
  // Arrangement point -> result vertex, and back.
  std::vector<std::uint32_t> index(a.pos.size() + a.points.size(), kInvalidIndex), point_of;
  auto add_point = [&](std::uint32_t v) {
    if (index[v] != kInvalidIndex) return;
    index[v] = static_cast<std::uint32_t>(in.positions.size());
    // The approximation, but a coordinate known from how the point was made (on an
    // axis-perpendicular plane, on a segment along which it is constant) exactly:
    // the quotient of filtered coordinates can miss it by a unit in the last place,
    // and a chain that rounds between steps would then carry a plate's top face as
    // slivers at 5 and 5.000000000000001.
    const Vec3 x = a.approx3(v);
    double c[3] = {x.x, x.y, x.z};
    for (int axis = 0; axis < 3; ++axis)
      if (double known = 0; a.known_coordinate(v, axis, known)) c[axis] = known;
    in.positions.push_back({c[0], c[1], c[2]});
    point_of.push_back(v);
  };
  for (const OutPoly& p : polys)
    for (const auto& loop : p.loops)
      for (std::uint32_t v : loop) add_point(v);
  for (const auto& w : lower.wires) {
    add_point(w[0]);
    add_point(w[1]);
    in.wires.push_back({index[w[0]], index[w[1]]});
  }
  for (std::uint32_t v : lower.points) add_point(v);
  // The faces' loops, renumbered in place, become the mesh's (polys keeps the rest).
  in.faces.reserve(polys.size());
  for (OutPoly& p : polys) {
    for (auto& loop : p.loops)
      for (std::uint32_t& v : loop) v = index[v];
    MeshFace mf;
    mf.loops = std::move(p.loops);
    in.faces.push_back(std::move(mf));
  }
  // Regularized: face-connected shells, each of positive volume a cell, each of
  // negative volume a cavity. Otherwise the cells come from the built model's regions
  // (io/volumes.h), where the radial order at every edge is known.
  if (!closed) assign_shell_cells(in, polys);
  std::vector<char> inexact(in.positions.size(), 0);
  for (std::uint32_t i = 0; i < point_of.size(); ++i) inexact[i] = !a.rounds_exactly(point_of[i]);
  // The repair's last check tiles each face as the exporters tile the face it becomes
  // (tile_face), so a clean check there is the count on the built model.
  const bool clean = options.check_rounding &&
                     nudge_rounding(
                         in, inexact,
                         [&](std::uint32_t i, int axis) { return a.coordinate_is(point_of[i], axis, in.positions[i][axis]); },
                         threads);
  if (clean) report.rounding_self_intersections = 0;  // else kRoundingUnchecked (evaluate)
  // Provenance, by face as given to the builder.
  auto source_of = [&](const OutPoly& p) {
    const Tri& t = a.tris[p.tri];
    Cluster lone;
    const Cluster& c = a.cluster(a.cluster_of[p.tri], lone);
    const Tri& ref = a.tris[c.ref];
    FaceSource s;
    s.operand = static_cast<int>(t.operand);
    s.face = a.faces[t.input_face].face;
    s.reversed = (p.normal_sign * a.tri_sign(c, p.tri) < 0) != a.faces[t.input_face].flipped;
    s.plane = {a.pos[ref.v[0]], a.pos[ref.v[1]], a.pos[ref.v[2]]};
    return s;
  };
  std::vector<FaceSource> sources(polys.size());
  parallel_ranges<char>(polys.size(), threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t f = lo; f < hi; ++f) sources[f] = source_of(polys[f]);
  });
  if (!closed) {
    // A regularized result reads nothing of the arrangement or the selection from
    // here on: both go before the model is built, which is when the memory peaks
    // (the arrangement held 110 MB, the selection 34, for two spheres of 10^6
    // triangles).
    a.release_all();
    std::vector<OutPoly>().swap(polys);
  }
  auto built = build_mesh(result.model, in);
  if (!built) return Error{ErrorCode::kUnsupported, "boolean: the result could not be built: " + built.error().message};
  if (closed) {
    Model& m = result.model;
    std::vector<FaceKind> kind_of(m.face_slots(), FaceKind::kBoundary);
    result.face_in.assign(m.face_slots(), true);
    for (std::uint32_t f = 0; f < polys.size(); ++f) {
      kind_of[built->faces[f].value] = polys[f].kind;
      result.face_in[built->faces[f].value] = polys[f].mark;
    }
    auto cells = io::make_region_volumes(m, built->group, [&](FaceId f, bool front) {
      const FaceKind k = kind_of[f.value];
      return front ? k == FaceKind::kInner : k != FaceKind::kSheet;
    });
    if (!cells) return Error{ErrorCode::kUnsupported, "boolean: the result's cells: " + cells.error().message};
    if (options.keep_lower_dim) {
      // Edges and vertices: in the set or not, at a point of each.
      // Where only one operand has anything near an edge or a vertex of one of its
      // faces, the other operands' windings are those beside the face, so the edge's
      // or vertex's verdict is the face's own (its mark): no ray.
      struct FaceMark {
        std::uint32_t operand;
        bool mark;
      };
      std::unordered_map<std::uint64_t, FaceMark> edge_face;
      std::vector<FaceMark> vertex_face(in.positions.size(), FaceMark{kInvalidIndex, true});
      for (std::uint32_t f = 0; f < polys.size(); ++f) {
        const FaceMark fm{a.tris[polys[f].tri].operand, polys[f].mark};
        for (const auto& loop : in.faces[f].loops)
          for (std::size_t i = 0; i < loop.size(); ++i) {
            edge_face.try_emplace(ordered(loop[i], loop[(i + 1) % loop.size()]), fm);
            if (vertex_face[loop[i]].operand == kInvalidIndex) vertex_face[loop[i]] = fm;
          }
      }
      std::vector<std::uint32_t> input_of(m.vertex_slots(), kInvalidIndex);
      for (std::uint32_t i = 0; i < in.positions.size(); ++i) input_of[built->vertices[i].value] = i;
      result.edge_in.assign(m.edge_slots(), true);
      result.vertex_in.assign(m.vertex_slots(), true);
      std::vector<std::array<std::uint32_t, 2>> sites;
      std::vector<EdgeId> edges;
      std::vector<VertexId> vertices;
      for (EdgeId e : m.edges()) {
        const std::uint32_t u = input_of[m.start_of(e).value], v = input_of[m.end_of(e).value];
        const auto it = edge_face.find(ordered(u, v));
        if (it != edge_face.end() && only_operand_near(a, it->second.operand, point_of[u], point_of[v])) {
          result.edge_in[e.value] = it->second.mark;
          continue;
        }
        edges.push_back(e);
        sites.push_back({point_of[u], point_of[v]});
      }
      for (VertexId v : m.vertices()) {
        const std::uint32_t u = input_of[v.value];
        const FaceMark fm = vertex_face[u];
        if (fm.operand != kInvalidIndex && only_operand_near(a, fm.operand, point_of[u], point_of[u])) {
          result.vertex_in[v.value] = fm.mark;
          continue;
        }
        vertices.push_back(v);
        sites.push_back({point_of[u], point_of[u]});
      }
      const std::vector<SiteVerdict> in_set = classify_sites(a, expr, sites, threads);
      for (std::size_t k = 0; k < edges.size(); ++k) result.edge_in[edges[k].value] = in_set[k].in;
      for (std::size_t k = 0; k < vertices.size(); ++k)
        result.vertex_in[vertices[k].value] = in_set[edges.size() + k].in;
    } else {
      result.edge_in.assign(m.edge_slots(), true);
      result.vertex_in.assign(m.vertex_slots(), true);
    }
    for (FaceId f : m.faces()) {
      const bool front = m.front_volume(f).is_valid(), back = m.back_volume(f).is_valid();
      report.sheet_faces += !front && !back;
      report.inner_faces += front && back;
      report.excluded += !result.face_in[f.value];
    }
    for (EdgeId e : m.edges()) {
      report.wire_edges += m.is_wire(e);
      report.excluded += !result.edge_in[e.value];
    }
    for (VertexId v : m.vertices()) {
      report.isolated_points += !m.first_end(v).edge.is_valid() && !m.point_loop(v).is_valid();
      report.excluded += !result.vertex_in[v.value];
    }
    if (report.excluded > 0) mark_in_set(result);
  }
  std::vector<FaceSource> by_id(result.model.face_slots());
  for (std::uint32_t f = 0; f < sources.size(); ++f) by_id[built->faces[f].value] = sources[f];
  result.sources = std::move(by_id);
  result.rounded.assign(result.model.num_vertices(), false);
  for (std::uint32_t i = 0; i < point_of.size(); ++i) {
    const VertexId v = built->vertices[i];
    if (v.value >= result.rounded.size()) result.rounded.resize(v.value + 1, false);
    result.rounded[v.value] = inexact[i];
  }
  return result;
}

}  // namespace cellforge::boolean
