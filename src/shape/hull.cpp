// Convex hulls (hull.h).
//
// 2D: Andrew's monotone chain over the lexicographically sorted points, popping while
// the turn is not strictly counterclockwise, so collinear points never become
// vertices.
//
// 3D: Quickhull (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for Convex
// Hulls", ACM TOMS 1996) on triangles, with every visibility decided by exact orient3d:
// a point is outside a facet when orient3d(facet, point) > 0. Each point not yet on the
// hull waits in the outside set of one facet it sees; the facet's farthest point (a
// double estimate: it only orders the work) is added by removing every facet it sees
// (a connected set, found by walking neighbours) and coning the horizon to it. The
// points of removed facets go to a new facet they see. Quickhull's lemma (a point that
// sees a removed facet and no new one is inside the new hull) assumes no point lies on
// a new facet's plane; a point that does is checked against every facet instead.
// Finally adjacent coplanar triangles merge into one polygon and vertices strictly
// inside a hull edge go (collinear3d), so faces are maximal convex polygons.
#include "cellforge/shape/hull.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>

#include "cellforge/geom/plane.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"
#include "shape/draft.h"

namespace cellforge::shape {

namespace {

template <class P>
bool lex_less(const P& a, const P& b) {
  if (a.x != b.x) return a.x < b.x;
  return a.y < b.y;
}

bool lex_less3(Vec3 a, Vec3 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

// Indices of the strict 2D hull of distinct points, counterclockwise, by monotone chain.
// `sorted` lists the point indices in lexicographic order of `at(i)`.
template <class At>
std::vector<std::uint32_t> monotone_chain(const std::vector<std::uint32_t>& sorted, At at) {
  const std::size_t n = sorted.size();
  if (n < 3) return {};
  std::vector<std::uint32_t> h(2 * n);
  std::size_t k = 0;
  for (std::size_t i = 0; i < n; ++i) {  // lower chain
    while (k >= 2 && orient2d(at(h[k - 2]), at(h[k - 1]), at(sorted[i])) <= 0) --k;
    h[k++] = sorted[i];
  }
  for (std::size_t i = n - 1, t = k + 1; i-- > 0;) {  // upper chain
    while (k >= t && orient2d(at(h[k - 2]), at(h[k - 1]), at(sorted[i])) <= 0) --k;
    h[k++] = sorted[i];
  }
  h.resize(k - 1);  // the last point repeats the first
  return h.size() >= 3 ? h : std::vector<std::uint32_t>{};
}

Error invalid_points(std::string what) { return invalid("convex_hull: " + std::move(what)); }

// ---- 3D

struct Facet {
  std::array<std::uint32_t, 3> v;   // counterclockwise seen from outside
  std::array<std::uint32_t, 3> nb;  // neighbour across edge v[i] -> v[i + 1]
  std::vector<std::uint32_t> outside;
  bool alive = true;
  std::uint32_t visit = 0;
};

class Quickhull {
 public:
  explicit Quickhull(const std::vector<Vec3>& p) : p_(p) {}

  // a, b, c, d: a tetrahedron (orient3d(a, b, c, d) != 0).
  void run(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    if (orient3d(p_[a], p_[b], p_[c], p_[d]) > 0) std::swap(b, c);  // d behind abc
    // Faces abc, adb, bdc, cda, each seen counterclockwise from outside.
    const std::array<std::array<std::uint32_t, 3>, 4> tris = {
        {{a, b, c}, {a, d, b}, {b, d, c}, {c, d, a}}};
    for (const auto& t : tris) add_facet(t);
    link_all();
    std::vector<std::uint32_t> rest;
    for (std::uint32_t i = 0; i < p_.size(); ++i)
      if (i != a && i != b && i != c && i != d) rest.push_back(i);
    assign(rest, 0, static_cast<std::uint32_t>(f_.size()));
    for (std::uint32_t f = 0; f < f_.size(); ++f) {  // facets made later come after
      while (f_[f].alive && !f_[f].outside.empty()) add_point(farthest(f), f);
    }
  }

  const std::vector<Facet>& facets() const { return f_; }

 private:
  void add_facet(std::array<std::uint32_t, 3> v) {
    f_.push_back(Facet{v, {kInvalidIndex, kInvalidIndex, kInvalidIndex}, {}, true, 0});
  }
  static std::uint64_t key(std::uint32_t a, std::uint32_t b) {
    return (static_cast<std::uint64_t>(a) << 32) | b;
  }
  // Links the neighbours of the first four facets through their directed edges.
  void link_all() {
    std::unordered_map<std::uint64_t, std::pair<std::uint32_t, int>> edge;
    for (std::uint32_t f = 0; f < f_.size(); ++f)
      for (int i = 0; i < 3; ++i) edge[key(f_[f].v[i], f_[f].v[(i + 1) % 3])] = {f, i};
    for (std::uint32_t f = 0; f < f_.size(); ++f)
      for (int i = 0; i < 3; ++i) f_[f].nb[i] = edge.at(key(f_[f].v[(i + 1) % 3], f_[f].v[i])).first;
  }
  int side(std::uint32_t f, std::uint32_t q) const {
    const auto& v = f_[f].v;
    return orient3d(p_[v[0]], p_[v[1]], p_[v[2]], p_[q]);
  }
  // Gives each point to a facet in [first, last) it lies strictly outside of; a point
  // on a new facet's plane and outside none of them is checked against every facet.
  void assign(const std::vector<std::uint32_t>& points, std::uint32_t first, std::uint32_t last) {
    for (std::uint32_t q : points) {
      bool on_plane = false, placed = false;
      for (std::uint32_t f = first; f < last && !placed; ++f) {
        if (!f_[f].alive) continue;
        const int s = side(f, q);
        if (s > 0) {
          f_[f].outside.push_back(q);
          placed = true;
        }
        on_plane |= s == 0;
      }
      for (std::uint32_t f = 0; f < f_.size() && on_plane && !placed; ++f) {
        if (f_[f].alive && side(f, q) > 0) {
          f_[f].outside.push_back(q);
          placed = true;
        }
      }
    }
  }
  std::uint32_t farthest(std::uint32_t f) const {
    const auto& v = f_[f].v;
    const Vec3 n = cross(p_[v[1]] - p_[v[0]], p_[v[2]] - p_[v[0]]);
    std::uint32_t best = f_[f].outside[0];
    double best_d = -1;
    for (std::uint32_t q : f_[f].outside) {
      const double d = dot(n, p_[q] - p_[v[0]]);
      if (d > best_d) best_d = d, best = q;
    }
    return best;
  }
  // Adds q, which lies outside facet `seed`.
  void add_point(std::uint32_t q, std::uint32_t seed) {
    ++stamp_;
    std::vector<std::uint32_t> visible{seed}, stack{seed};
    f_[seed].visit = stamp_;
    struct Horizon {
      std::uint32_t a, b, outer;  // edge a -> b of a visible facet; outer: the facet beyond
    };
    std::vector<Horizon> horizon;
    while (!stack.empty()) {
      const std::uint32_t f = stack.back();
      stack.pop_back();
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t g = f_[f].nb[i];
        if (f_[g].visit == stamp_) continue;
        if (side(g, q) > 0) {
          f_[g].visit = stamp_;
          visible.push_back(g);
          stack.push_back(g);
        } else {
          horizon.push_back({f_[f].v[i], f_[f].v[(i + 1) % 3], g});
        }
      }
    }
    // Facets seen twice through the stack are marked on the first visit, so an edge
    // between two visible facets is never a horizon edge; a horizon edge may appear
    // once only (the visible set is a disc).
    std::vector<std::uint32_t> orphans;
    for (std::uint32_t f : visible) {
      f_[f].alive = false;
      for (std::uint32_t o : f_[f].outside)
        if (o != q) orphans.push_back(o);
      f_[f].outside.clear();
      f_[f].outside.shrink_to_fit();
    }
    const std::uint32_t first = static_cast<std::uint32_t>(f_.size());
    std::unordered_map<std::uint32_t, std::uint32_t> by_start;  // horizon a -> new facet
    for (const Horizon& h : horizon) {
      const std::uint32_t nf = static_cast<std::uint32_t>(f_.size());
      add_facet({h.a, h.b, q});
      f_[nf].nb[0] = h.outer;
      for (int i = 0; i < 3; ++i)  // the outer facet's edge b -> a now borders nf
        if (f_[h.outer].v[i] == h.b && f_[h.outer].v[(i + 1) % 3] == h.a) f_[h.outer].nb[i] = nf;
      by_start[h.a] = nf;
    }
    for (std::uint32_t nf = first; nf < f_.size(); ++nf) {
      // Edge b -> q borders the new facet starting at b; edge q -> a the one ending at a.
      f_[nf].nb[1] = by_start.at(f_[nf].v[1]);
      const std::uint32_t next = f_[nf].nb[1];
      f_[next].nb[2] = nf;
    }
    assign(orphans, first, static_cast<std::uint32_t>(f_.size()));
  }

  const std::vector<Vec3>& p_;
  std::vector<Facet> f_;
  std::uint32_t stamp_ = 0;
};

// The polygon faces of the triangulated hull: coplanar neighbours merged, vertices
// inside a straight run of a face's boundary dropped. Each face's loop is
// counterclockwise seen from outside.
std::vector<std::vector<std::uint32_t>> merged_faces(const std::vector<Vec3>& p,
                                                     const std::vector<Facet>& f) {
  UnionFind sets(f.size());
  for (std::uint32_t i = 0; i < f.size(); ++i) {
    if (!f[i].alive) continue;
    for (int k = 0; k < 3; ++k) {
      const Facet& g = f[f[i].nb[k]];
      std::uint32_t far = g.v[0];
      for (std::uint32_t w : g.v)
        if (w != f[i].v[k] && w != f[i].v[(k + 1) % 3]) far = w;
      if (orient3d(p[f[i].v[0]], p[f[i].v[1]], p[f[i].v[2]], p[far]) == 0) sets.unite(i, f[i].nb[k]);
    }
  }
  // Boundary edges of each merged set, as start -> end.
  std::unordered_map<std::uint32_t, std::unordered_map<std::uint32_t, std::uint32_t>> next;
  for (std::uint32_t i = 0; i < f.size(); ++i) {
    if (!f[i].alive) continue;
    for (int k = 0; k < 3; ++k)
      if (sets.find(f[i].nb[k]) != sets.find(i)) next[sets.find(i)][f[i].v[k]] = f[i].v[(k + 1) % 3];
  }
  std::vector<std::vector<std::uint32_t>> faces;
  for (auto& [root, edges] : next) {
    (void)root;
    std::vector<std::uint32_t> loop;
    const std::uint32_t start = edges.begin()->first;
    std::uint32_t v = start;
    do {
      loop.push_back(v);
      v = edges.at(v);
    } while (v != start && loop.size() <= edges.size());
    std::vector<std::uint32_t> kept;
    for (std::size_t i = 0; i < loop.size(); ++i) {
      const Vec3 a = p[loop[(i + loop.size() - 1) % loop.size()]], b = p[loop[i]],
                 c = p[loop[(i + 1) % loop.size()]];
      if (!collinear3d(a, b, c)) kept.push_back(loop[i]);
    }
    faces.push_back(std::move(kept));
  }
  // A deterministic face order: by the smallest vertex index, the loop starting there.
  for (auto& loop : faces) std::rotate(loop.begin(), std::min_element(loop.begin(), loop.end()), loop.end());
  std::sort(faces.begin(), faces.end());
  return faces;
}

Result<GroupId> flat_hull(Model& m, const std::vector<Vec3>& p, std::uint32_t a, std::uint32_t b,
                          std::uint32_t c) {
  const Projection proj = Plane::through(p[a], p[b], p[c]).projection();
  std::vector<std::uint32_t> order(p.size());
  for (std::uint32_t i = 0; i < p.size(); ++i) order[i] = i;
  auto at = [&](std::uint32_t i) { return proj(p[i]); };
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t i, std::uint32_t j) { return lex_less(at(i), at(j)); });
  const std::vector<std::uint32_t> loop = monotone_chain(order, at);
  Draft d = Draft::sheet("hull");
  Loop l;
  for (std::uint32_t i : loop) l.push_back(d.vertex(p[i]));
  d.face(std::move(l));
  d.attribute("points", static_cast<int>(p.size()));
  return commit(m, d);
}

}  // namespace

Result<Region> convex_hull(std::span<const Vec2> points) {
  std::vector<Vec2> p(points.begin(), points.end());
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y))
      return invalid_points("point " + std::to_string(i) + " is not finite");
  std::sort(p.begin(), p.end(), lex_less<Vec2>);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3)
    return invalid_points(std::to_string(p.size()) + " distinct points (at least 3)");
  std::vector<std::uint32_t> order(p.size());
  for (std::uint32_t i = 0; i < p.size(); ++i) order[i] = i;
  const std::vector<std::uint32_t> h = monotone_chain(order, [&](std::uint32_t i) { return p[i]; });
  if (h.empty()) return invalid_points("all points are collinear");
  Region r;
  r.loops.emplace_back();
  for (std::uint32_t i : h) r.loops[0].push_back(p[i]);
  return r;
}

Result<GroupId> convex_hull(Model& m, std::span<const Vec3> points, const HullOptions& options) {
  std::vector<Vec3> p(points.begin(), points.end());
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!std::isfinite(p[i].x) || !std::isfinite(p[i].y) || !std::isfinite(p[i].z))
      return invalid_points("point " + std::to_string(i) + " is not finite");
  std::sort(p.begin(), p.end(), lex_less3);
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3)
    return invalid_points(std::to_string(p.size()) + " distinct points (at least 4)");
  const std::uint32_t n = static_cast<std::uint32_t>(p.size());
  std::uint32_t c = 2;
  while (c < n && collinear3d(p[0], p[1], p[c])) ++c;
  if (c == n) return invalid_points("all points are collinear");
  std::uint32_t d = 2;
  while (d < n && (d == c || orient3d(p[0], p[1], p[c], p[d]) == 0)) ++d;
  if (d == n) {
    if (options.allow_flat) return flat_hull(m, p, 0, 1, c);
    return invalid_points("all " + std::to_string(n) + " distinct points lie in one plane");
  }
  Quickhull qh(p);
  qh.run(0, 1, c, d);
  const std::vector<std::vector<std::uint32_t>> faces = merged_faces(p, qh.facets());
  Draft dr = Draft::solid("hull");
  std::vector<std::uint32_t> id(n, kInvalidIndex);
  for (const auto& loop : faces) {
    Loop l;
    for (std::uint32_t v : loop) {
      if (id[v] == kInvalidIndex) id[v] = dr.vertex(p[v]);
      l.push_back(id[v]);
    }
    dr.face(std::move(l));
  }
  dr.attribute("points", static_cast<int>(points.size()));
  return commit(m, dr);
}

std::vector<Vec3> vertex_positions(const Model& m) {
  std::vector<Vec3> out;
  out.reserve(m.num_vertices());
  for (VertexId v : m.vertices()) out.push_back(m.position(v));
  return out;
}

}  // namespace cellforge::shape
