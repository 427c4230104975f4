// The exact 2D Boolean (planar.h): one arrangement of every operand's loop edges in the
// plane, a winding number per operand on each face, the faces the expression keeps,
// and their boundary as outer loops with holes.
//
// Notation. A *segment* is one input loop edge a -> b with the interior of its loop on
// the left (outer loops counterclockwise, holes clockwise). Points are explicit (an
// input vertex, doubles) or a *crossing* of two segments s and u that cross properly,
// kept as homogeneous coordinates over the four input points:
//   e_s = b_s - a_s, e_u = b_u - a_u, D = e_s x e_u, N = (a_u - a_s) x e_u,
//   (X, Y, W) = (a_s D + e_s N, W = D)           (degree 3 over degree 2)
// Every decision is the sign of a polynomial in input doubles, evaluated on Fp, then Dd,
// then Dyadic only when the filters cannot tell (filtered.h's decide). Crossings are
// rounded to doubles once, when the result is built, and the rounded result is then
// checked exactly for crossings and flipped loops that the rounding made.
//
// Stages:
//  1. Pairs of segments whose boxes overlap (bvh.h) are tested by orient2d: a proper
//     crossing makes a crossing point on both; an endpoint on the other segment (also
//     for collinear overlaps) is recorded on it.
//  2. Each segment's points are sorted along it (exactly) and equal ones identified
//     (a union-find over point ids; the smallest id, an input vertex when there is one,
//     names the point). Consecutive points give the arrangement's edges; pieces of
//     different segments between the same two points are one edge, which keeps the
//     change of every operand's winding number across it.
//  3. Half-edges around each vertex are sorted by angle (their directions are input
//     segments' directions, explicit); next(h) is the half-edge clockwise after h's twin,
//     so each cycle of next bounds the face on its left.
//  4. Connected components are taken in lexicographic order of their least vertex v
//     (always an input vertex: the least point of a union of segments is an endpoint).
//     The face left of v is found by a ray from v towards -x, perturbed to run an
//     infinitesimal above v (simulation of simplicity, so a ray through a vertex or
//     along an edge has one answer): the nearest segment it meets bounds that face,
//     and that segment belongs to a component already done (it reaches further left).
//     The unbounded face has every winding number 0; winding numbers then spread
//     across edges within the component.
//  5. A face is kept when the expression holds on its operands (winding > 0). Kept
//     half-edges with a dropped twin are walked into loops (at a vertex, the first
//     boundary half-edge clockwise after the incoming twin), a loop passing a vertex
//     twice is cut there, and straight vertices where nothing else meets are dropped.
//     A loop is an outer loop when it turns left at its least vertex. Kept faces joined
//     across kept-kept edges, or nested in one another's face, are one region; its one
//     outer loop takes the region's holes.
#include "boolean/planar.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <string>
#include <unordered_map>

#include "cellforge/geom/bvh.h"
#include "cellforge/geom/implicit.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"

namespace cellforge::boolean {

using shape::Region;
using shape::Shape2D;

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;

Error invalid(std::string message) { return Error{ErrorCode::kInvalidInput, std::move(message)}; }

struct Seg {
  Vec2 a, b;
  std::uint32_t va = 0, vb = 0;  // explicit point ids of a and b
  std::uint32_t operand = 0;
};

struct Pt {
  Vec2 p;                          // explicit: the position
  std::uint32_t s = kNone, u = 0;  // crossing: the two segments (s == kNone: explicit)
  int wsign = 1;                   // sign of W
};

using Winding = std::vector<std::pair<std::uint32_t, int>>;  // (operand, number), sorted

void add_to(Winding& w, std::uint32_t operand, int d) {
  auto it = std::lower_bound(w.begin(), w.end(), std::pair<std::uint32_t, int>{operand, INT32_MIN});
  if (it != w.end() && it->first == operand) {
    it->second += d;
    if (it->second == 0) w.erase(it);
  } else if (d != 0) {
    w.insert(it, {operand, d});
  }
}

struct Edge {
  std::uint32_t u = 0, v = 0;  // point roots, u < v
  std::uint32_t seg = 0;       // a segment it lies on
  int sg = 1;                  // +1 when seg runs u -> v
  Winding delta;               // winding left of u -> v minus winding right of it
};

// The expression evaluated on a set of inside operands given as a short list, in time
// proportional to the list and the expression's inner nodes (not its leaves): an n-ary
// union of a thousand operands is asked once per face of the arrangement.
class SparseExpr {
 public:
  SparseExpr(const Expr& e, std::uint32_t operands) : leaf_of_(operands) { add(e); }

  bool contains(const Winding& w) {
    for (const auto& [o, n] : w)
      if (n > 0) {
        inside_.push_back(o);
        for (std::uint32_t node : leaf_of_[o]) ++count_[node];
      }
    const bool r = eval(0);
    for (std::uint32_t o : inside_)
      for (std::uint32_t node : leaf_of_[o]) --count_[node];
    inside_.clear();
    return r;
  }

 private:
  struct Node {
    Expr::Kind kind = Expr::Kind::kOperand;
    std::uint32_t leaves = 0;           // operand children
    int first = -1;                     // difference: the first child as an operand, or
    std::uint32_t first_node = 0;       // as a node (first < 0)
    std::vector<std::uint32_t> kids;    // inner-node children, the first excluded
  };

  std::uint32_t add(const Expr& e) {
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    Node fresh;
    fresh.kind = e.kind;
    nodes_.push_back(std::move(fresh));
    count_.push_back(0);
    if (e.kind == Expr::Kind::kOperand) {
      leaf_of_[static_cast<std::size_t>(e.operand)].push_back(id);
      nodes_[id].leaves = 1;
      return id;
    }
    for (std::size_t i = 0; i < e.children.size(); ++i) {
      const Expr& c = e.children[i];
      if (e.kind == Expr::Kind::kDifference && i == 0) {
        if (c.kind == Expr::Kind::kOperand) {
          nodes_[id].first = c.operand;
        } else {
          nodes_[id].first_node = add(c);
        }
        continue;
      }
      if (c.kind == Expr::Kind::kOperand) {
        leaf_of_[static_cast<std::size_t>(c.operand)].push_back(id);
        ++nodes_[id].leaves;
      } else {
        const std::uint32_t k = add(c);
        nodes_[id].kids.push_back(k);
      }
    }
    return id;
  }

  bool is_inside(int operand) const {
    return std::find(inside_.begin(), inside_.end(), static_cast<std::uint32_t>(operand)) !=
           inside_.end();
  }

  bool eval(std::uint32_t id) const {
    const Node& n = nodes_[id];
    switch (n.kind) {
      case Expr::Kind::kOperand:
        return count_[id] > 0;
      case Expr::Kind::kUnion:
        if (count_[id] > 0) return true;
        for (std::uint32_t k : n.kids)
          if (eval(k)) return true;
        return false;
      case Expr::Kind::kIntersection:
        if (n.leaves + n.kids.size() == 0 || count_[id] < n.leaves) return false;
        for (std::uint32_t k : n.kids)
          if (!eval(k)) return false;
        return true;
      case Expr::Kind::kDifference:
        if (!(n.first >= 0 ? is_inside(n.first) : eval(n.first_node))) return false;
        if (count_[id] > 0) return false;
        for (std::uint32_t k : n.kids)
          if (eval(k)) return false;
        return true;
    }
    return false;
  }

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> count_;                    // by node: inside operand children
  std::vector<std::vector<std::uint32_t>> leaf_of_;     // by operand: nodes it is a child of
  std::vector<std::uint32_t> inside_;
};

class Planar {
 public:
  Planar(std::span<const Shape2D> operands, const Expr& expr) : ops_(operands), expr_(expr) {}

  Result<Evaluated2D> run() {
    if (Status s = collect(); !s) return s.error();
    Evaluated2D out;
    if (segs_.empty()) return out;
    intersect();
    build_edges();
    if (edges_.empty()) return out;
    build_half_edges();
    if (Status s = classify(); !s) return s.error();
    return emit();
  }

 private:
  // ------------------------------------------------------------------ exact helpers

  template <class T>
  H2<T> hom(std::uint32_t id) const {
    const Pt& q = pts_[id];
    if (q.s == kNone) return {T(q.p.x), T(q.p.y), T(1.0)};
    const Seg &s = segs_[q.s], &u = segs_[q.u];
    return lli<T>(s.a, s.b, u.a, u.b);
  }

  // sign(coordinate axis of p - that of q).
  int compare(std::uint32_t p, std::uint32_t q, int axis) const {
    if (p == q) return 0;
    const Pt &a = pts_[p], &b = pts_[q];
    if (a.s == kNone && b.s == kNone) {
      const double x = axis == 0 ? a.p.x : a.p.y, y = axis == 0 ? b.p.x : b.p.y;
      return (x > y) - (x < y);
    }
    return a.wsign * b.wsign * decide([&]<class T>() {
             const H2<T> hp = hom<T>(p), hq = hom<T>(q);
             return axis == 0 ? hp.u * hq.w - hq.u * hp.w : hp.v * hq.w - hq.v * hp.w;
           });
  }

  // The segment other than `seg` that crossing p lies on.
  std::uint32_t other(const Pt& p, std::uint32_t seg) const { return p.s == seg ? p.u : p.s; }

  // Side of line (a, b) of segment w that point p lies on (orient2d(a, b, p)).
  int side(std::uint32_t w, std::uint32_t p) const {
    const Seg& l = segs_[w];
    const Pt& q = pts_[p];
    if (q.s == kNone) return orient2d(l.a, l.b, q.p);
    for (std::uint32_t t : {q.s, q.u})  // on a line through one of q's segments
      if (t == w || (orient2d(l.a, l.b, segs_[t].a) == 0 && orient2d(l.a, l.b, segs_[t].b) == 0))
        return 0;
    return q.wsign * decide([&]<class T>() {
             const H2<T> h = hom<T>(p);
             return (T(l.b.x) - T(l.a.x)) * (h.v - T(l.a.y) * h.w) -
                    (T(l.b.y) - T(l.a.y)) * (h.u - T(l.a.x) * h.w);
           });
  }

  // Order along segment seg (a -> b) of two points on it: -1 when p comes first. A
  // crossing of seg with u comes before a point q exactly when q lies on the side of u
  // that b lies on: an orientation test on q, of low degree, and orient2d itself when q
  // is explicit (so that an input vertex at a crossing is found equal cheaply).
  int along(std::uint32_t seg, std::uint32_t p, std::uint32_t q) const {
    if (p == q) return 0;
    const Seg& s = segs_[seg];
    const Pt &a = pts_[p], &b = pts_[q];
    if (a.s == kNone && b.s == kNone) {
      const int axis = std::fabs(s.b.x - s.a.x) >= std::fabs(s.b.y - s.a.y) ? 0 : 1;
      const int forward = axis == 0 ? sign_diff(s.b.x, s.a.x) : sign_diff(s.b.y, s.a.y);
      return forward * (axis == 0 ? sign_diff(a.p.x, b.p.x) : sign_diff(a.p.y, b.p.y));
    }
    if (a.s != kNone) {  // p is the crossing of seg with u
      const std::uint32_t u = other(a, seg);
      const int sq = side(u, q);
      return sq == 0 ? 0 : (sq == orient2d(segs_[u].a, segs_[u].b, s.b) ? -1 : 1);
    }
    return -along(seg, q, p);
  }

  // Lexicographic (x, then y).
  bool lex_less(std::uint32_t p, std::uint32_t q) const {
    const int c = compare(p, q, 0);
    return c != 0 ? c < 0 : compare(p, q, 1) < 0;
  }

  // sign(y of p - y).
  int compare_y(std::uint32_t p, double y) const {
    const Pt& a = pts_[p];
    if (a.s == kNone) return (a.p.y > y) - (a.p.y < y);
    for (std::uint32_t t : {a.s, a.u})  // on a horizontal segment
      if (segs_[t].a.y == segs_[t].b.y) return sign_diff(segs_[t].a.y, y);
    return a.wsign * decide([&]<class T>() {
             const H2<T> h = hom<T>(p);
             return h.v - T(y) * h.w;
           });
  }

  // The direction of half-edge h: its segment's, reversed when sg < 0.
  struct Dir {
    const Seg* s;
    int sg;
  };
  Dir dir(std::uint32_t h) const {
    const Edge& e = edges_[h >> 1];
    return {&segs_[e.seg], (h & 1) ? -e.sg : e.sg};
  }
  static int sign_diff(double a, double b) { return (a > b) - (a < b); }
  // 0 for angles in [0, pi), 1 for [pi, 2 pi).
  static int half(Dir d) {
    const int dy = sign_diff(d.s->b.y, d.s->a.y) * d.sg, dx = sign_diff(d.s->b.x, d.s->a.x) * d.sg;
    return (dy > 0 || (dy == 0 && dx > 0)) ? 0 : 1;
  }
  static int cross(Dir p, Dir q) {
    const Seg &s = *p.s, &u = *q.s;
    return p.sg * q.sg * decide([&]<class T>() {
             return (T(s.b.x) - T(s.a.x)) * (T(u.b.y) - T(u.a.y)) -
                    (T(s.b.y) - T(s.a.y)) * (T(u.b.x) - T(u.a.x));
           });
  }
  static bool angle_less(Dir p, Dir q) {
    const int hp = half(p), hq = half(q);
    if (hp != hq) return hp < hq;
    return cross(p, q) > 0;
  }

  // ------------------------------------------------------------------ 0. segments

  std::uint32_t vertex(Vec2 p) {
    const double x = p.x + 0.0, y = p.y + 0.0;  // -0 and 0 are one point
    std::uint64_t hx, hy;
    std::memcpy(&hx, &x, sizeof hx);
    std::memcpy(&hy, &y, sizeof hy);
    const std::uint64_t key = hx * 0x9E3779B97F4A7C15ull ^ (hy + 0x632BE59BD9B4E019ull);
    auto& same = vertex_ids_[key];
    for (std::uint32_t id : same)
      if (pts_[id].p.x == x && pts_[id].p.y == y) return id;
    pts_.push_back(Pt{{x, y}});
    uf_.add();
    same.push_back(static_cast<std::uint32_t>(pts_.size() - 1));
    return same.back();
  }

  Status collect() {
    for (std::size_t o = 0; o < ops_.size(); ++o) {
      for (std::size_t r = 0; r < ops_[o].regions.size(); ++r) {
        const auto& loops = ops_[o].regions[r].loops;
        const std::string where = "2D operand " + std::to_string(o) + " region " + std::to_string(r);
        if (loops.empty()) return invalid(where + " has no loops");
        for (std::size_t li = 0; li < loops.size(); ++li) {
          const auto& loop = loops[li];
          const std::string name =
              where + (li == 0 ? " outer loop" : " hole " + std::to_string(li - 1));
          if (loop.size() < 3)
            return invalid(name + " has " + std::to_string(loop.size()) + " vertices");
          for (std::size_t i = 0; i < loop.size(); ++i) {
            if (!std::isfinite(loop[i].x) || !std::isfinite(loop[i].y))
              return invalid(name + " vertex " + std::to_string(i) + " is not finite");
          }
          const int want = li == 0 ? 1 : -1;
          const bool reverse = area_sign(loop) == -want;
          const std::size_t n = loop.size();
          for (std::size_t i = 0; i < n; ++i) {
            Vec2 a = loop[i], b = loop[(i + 1) % n];
            if (reverse) std::swap(a, b);
            if (a == b) continue;  // a vertex repeated at once: no edge
            Seg s{a, b, vertex(a), vertex(b), static_cast<std::uint32_t>(o)};
            segs_.push_back(s);
          }
        }
      }
    }
    operands_ = static_cast<std::uint32_t>(ops_.size());
    explicit_count_ = static_cast<std::uint32_t>(pts_.size());
    return Status::Ok();
  }

  // ------------------------------------------------------------------ 1. intersect

  void test_pair(std::uint32_t i, std::uint32_t j) {
    const Seg &s = segs_[i], &u = segs_[j];
    const int o1 = orient2d(s.a, s.b, u.a), o2 = orient2d(s.a, s.b, u.b);
    auto put = [&](std::uint32_t seg, std::uint32_t p) {
      const Seg& x = segs_[seg];
      if (p != x.va && p != x.vb) on_[seg].push_back(p);
    };
    if (o1 == 0 && o2 == 0) {  // collinear: endpoints inside the other
      if (point_on_segment(s.a, s.b, u.a)) put(i, u.va);
      if (point_on_segment(s.a, s.b, u.b)) put(i, u.vb);
      if (point_on_segment(u.a, u.b, s.a)) put(j, s.va);
      if (point_on_segment(u.a, u.b, s.b)) put(j, s.vb);
      return;
    }
    if (o1 * o2 > 0) return;
    const int o3 = orient2d(u.a, u.b, s.a), o4 = orient2d(u.a, u.b, s.b);
    if (o3 * o4 > 0) return;
    if (o1 == 0) put(i, u.va);
    if (o2 == 0) put(i, u.vb);
    if (o3 == 0) put(j, s.va);
    if (o4 == 0) put(j, s.vb);
    if (o1 == 0 || o2 == 0 || o3 == 0 || o4 == 0) return;
    Pt c;
    c.s = i;
    c.u = j;
    pts_.push_back(c);
    const auto id = static_cast<std::uint32_t>(pts_.size() - 1);
    pts_[id].wsign = decide([&]<class T>() { return hom<T>(id).w; });
    uf_.add();
    on_[i].push_back(id);
    on_[j].push_back(id);
  }

  void intersect() {
    std::vector<Box> boxes(segs_.size());
    for (std::size_t i = 0; i < segs_.size(); ++i) {
      boxes[i].add(Vec3{segs_[i].a.x, segs_[i].a.y, 0});
      boxes[i].add(Vec3{segs_[i].b.x, segs_[i].b.y, 0});
    }
    on_.assign(segs_.size(), {});
    bvh_ = Bvh(std::move(boxes));
    bvh_.pairs([&](std::uint32_t i, std::uint32_t j) { test_pair(i, j); });
  }

  // ------------------------------------------------------------------ 2. edges

  struct Key {
    double v, e;  // |coordinate * forward - v| <= e
    std::uint32_t id;
  };

  Key key(std::uint32_t p, int axis, double forward) const {
    const Pt& q = pts_[p];
    if (q.s == kNone) return {(axis == 0 ? q.p.x : q.p.y) * forward, 0, p};
    const H2<Fp> h = hom<Fp>(p);
    const Fp& c = axis == 0 ? h.u : h.v;
    const double w = std::fabs(h.w.v) - h.w.e;
    if (!(w > 0)) return {0, INFINITY, p};
    const double v = c.v / h.w.v;
    const double e = ((c.e + std::fabs(v) * h.w.e) / w + std::fabs(v) * 0x1p-51) * kGrow;
    return {v * forward, std::isfinite(e) ? e : INFINITY, p};
  }

  void build_edges() {
    std::vector<Key> keys;
    // Sort each segment's points along it and identify equal ones.
    for (std::size_t si = 0; si < segs_.size(); ++si) {
      const Seg& s = segs_[si];
      auto& list = on_[si];
      list.push_back(s.va);
      list.push_back(s.vb);
      const auto seg = static_cast<std::uint32_t>(si);
      // Keys along the segment's dominant axis with error bounds: the exact order is
      // asked only where two keys' intervals overlap.
      const int axis = std::fabs(s.b.x - s.a.x) >= std::fabs(s.b.y - s.a.y) ? 0 : 1;
      const double forward = axis == 0 ? sign_diff(s.b.x, s.a.x) : sign_diff(s.b.y, s.a.y);
      keys.clear();
      for (std::uint32_t p : list) keys.push_back(key(p, axis, forward));
      std::sort(keys.begin(), keys.end(), [&](const Key& p, const Key& q) {
        if (std::fabs(p.v - q.v) > p.e + q.e) return p.v < q.v;
        return along(seg, p.id, q.id) < 0;
      });
      for (std::size_t i = 0; i < list.size(); ++i) list[i] = keys[i].id;
      std::size_t k = 0;
      for (std::size_t i = 1; i < list.size(); ++i) {
        if (std::fabs(keys[i].v - keys[k].v) <= keys[i].e + keys[k].e &&
            along(seg, list[k], list[i]) == 0) {
          uf_.unite_to_smaller(list[k], list[i]);
        } else {
          list[++k] = list[i];
          keys[k] = keys[i];
        }
      }
      list.resize(k + 1);
    }
    std::unordered_map<std::uint64_t, std::uint32_t> edge_ids;
    edge_ids.reserve(segs_.size() * 2);
    for (std::size_t si = 0; si < segs_.size(); ++si) {
      auto& chain = on_[si];
      for (std::uint32_t& p : chain) p = uf_.find(p);
      chain.erase(std::unique(chain.begin(), chain.end()), chain.end());
      for (std::size_t i = 0; i + 1 < chain.size(); ++i) {
        const std::uint32_t p = chain[i], q = chain[i + 1];
        const std::uint32_t u = std::min(p, q), v = std::max(p, q);
        auto [it, fresh] =
            edge_ids.try_emplace((std::uint64_t{u} << 32) | v, static_cast<std::uint32_t>(edges_.size()));
        if (fresh) edges_.push_back(Edge{u, v, static_cast<std::uint32_t>(si), p == u ? 1 : -1, {}});
        add_to(edges_[it->second].delta, segs_[si].operand, p == u ? 1 : -1);
      }
    }
    edge_of_ = std::move(edge_ids);
  }

  std::uint32_t find_edge(std::uint32_t p, std::uint32_t q) const {
    const std::uint32_t u = std::min(p, q), v = std::max(p, q);
    return edge_of_.at((std::uint64_t{u} << 32) | v);
  }

  // ------------------------------------------------------------------ 3. half-edges

  std::uint32_t origin(std::uint32_t h) const {
    const Edge& e = edges_[h >> 1];
    return (h & 1) ? e.v : e.u;
  }

  void build_half_edges() {
    const std::size_t nh = edges_.size() * 2;
    std::vector<std::uint32_t> count(pts_.size() + 1, 0);
    for (std::uint32_t h = 0; h < nh; ++h) ++count[origin(h) + 1];
    for (std::size_t i = 1; i < count.size(); ++i) count[i] += count[i - 1];
    out_begin_ = count;
    out_.assign(nh, 0);
    for (std::uint32_t h = 0; h < nh; ++h) out_[count[origin(h)]++] = h;
    pos_.assign(nh, 0);
    for (std::size_t v = 0; v < pts_.size(); ++v) {
      const auto b = out_.begin() + out_begin_[v], e = out_.begin() + out_begin_[v + 1];
      std::sort(b, e, [&](std::uint32_t p, std::uint32_t q) { return angle_less(dir(p), dir(q)); });
      for (auto it = b; it != e; ++it) pos_[*it] = static_cast<std::uint32_t>(it - out_.begin());
    }
    next_.assign(nh, 0);
    for (std::uint32_t h = 0; h < nh; ++h) next_[h] = clockwise_after(h ^ 1);
    cycle_.assign(nh, kNone);
    for (std::uint32_t h = 0; h < nh; ++h) {
      if (cycle_[h] != kNone) continue;
      const auto c = static_cast<std::uint32_t>(cycle_first_.size());
      cycle_first_.push_back(h);
      for (std::uint32_t g = h; cycle_[g] == kNone; g = next_[g]) cycle_[g] = c;
    }
  }

  // The outgoing half-edge just clockwise of outgoing half-edge t at its origin.
  std::uint32_t clockwise_after(std::uint32_t t) const {
    const std::uint32_t v = origin(t);
    const std::uint32_t b = out_begin_[v], e = out_begin_[v + 1];
    const std::uint32_t p = pos_[t];
    return out_[p == b ? e - 1 : p - 1];
  }

  // ------------------------------------------------------------------ 4. classify

  // The segment the ray from v (towards -x, an infinitesimal above v) meets first,
  // as the half-edge of its edge there that has the ray's start on its left; kNone
  // when it meets nothing.
  std::uint32_t ray_hit(Vec2 v) const {
    std::uint32_t best = kNone;
    auto accept = [&](const Box& b) { return b.lo.y <= v.y && v.y <= b.hi.y && b.lo.x <= v.x; };
    bvh_.query(accept, [&](std::uint32_t si) {
      const Seg& s = segs_[si];
      if (s.a.y == s.b.y) return;
      const Vec2 lo = s.a.y < s.b.y ? s.a : s.b, hi = s.a.y < s.b.y ? s.b : s.a;
      if (!(lo.y <= v.y && v.y < hi.y)) return;
      if (orient2d(lo, hi, v) >= 0) return;  // not left of v
      if (best == kNone || further_right(si, best, v.y)) best = si;
    });
    if (best == kNone) return kNone;
    // The piece of `best` that holds height v.y + infinitesimal.
    const Seg& s = segs_[best];
    const auto& chain = on_[best];
    const bool up = s.b.y > s.a.y;  // chain runs a -> b
    // Points at or below the ray come first when the chain runs up, last otherwise.
    const auto it = std::partition_point(chain.begin(), chain.end(), [&](std::uint32_t p) {
      const bool below = compare_y(p, v.y) <= 0;
      return up ? below : !below;
    });
    const std::size_t k = static_cast<std::size_t>(it - chain.begin());  // first of the second part
    const std::uint32_t lower = up ? chain[k - 1] : chain[k], upper = up ? chain[k] : chain[k - 1];
    const std::uint32_t e = find_edge(lower, upper);
    // The half-edge running down has +x on its left.
    return edges_[e].u == upper ? 2 * e : 2 * e + 1;
  }

  // Whether segment p meets the line at height y + infinitesimal right of where q does.
  bool further_right(std::uint32_t p, std::uint32_t q, double y) const {
    const Seg &s = segs_[p], &u = segs_[q];
    const Vec2 l1 = s.a.y < s.b.y ? s.a : s.b, h1 = s.a.y < s.b.y ? s.b : s.a;
    const Vec2 l2 = u.a.y < u.b.y ? u.a : u.b, h2 = u.a.y < u.b.y ? u.b : u.a;
    const int at = decide([&]<class T>() {
      const T dx1 = T(h1.x) - T(l1.x), dy1 = T(h1.y) - T(l1.y);
      const T dx2 = T(h2.x) - T(l2.x), dy2 = T(h2.y) - T(l2.y);
      return (T(l1.x) * dy1 + (T(y) - T(l1.y)) * dx1) * dy2 -
             (T(l2.x) * dy2 + (T(y) - T(l2.y)) * dx2) * dy1;
    });
    if (at != 0) return at > 0;
    return decide([&]<class T>() {
             return (T(h1.x) - T(l1.x)) * (T(h2.y) - T(l2.y)) -
                    (T(h2.x) - T(l2.x)) * (T(h1.y) - T(l1.y));
           }) > 0;
  }

  Status classify() {
    const std::size_t nc = cycle_first_.size();
    winding_.assign(nc, {});
    known_.assign(nc, false);
    face_parent_.assign(nc, kNone);
    // Components of the edge graph and their least vertices.
    UnionFind comp(static_cast<std::uint32_t>(pts_.size()));
    for (const Edge& e : edges_) comp.unite(e.u, e.v);
    // The least point of a component is an input vertex, so only those are compared
    // (in doubles, exactly).
    auto explicit_less = [&](std::uint32_t p, std::uint32_t q) {
      const Vec2 a = pts_[p].p, b = pts_[q].p;
      return a.x != b.x ? a.x < b.x : a.y < b.y;
    };
    std::vector<std::uint32_t> least(pts_.size(), kNone);
    for (std::uint32_t v = 0; v < explicit_count_; ++v) {
      if (out_begin_[v + 1] == out_begin_[v]) continue;
      std::uint32_t& l = least[comp.find(v)];
      if (l == kNone || explicit_less(v, l)) l = v;
    }
    std::vector<std::uint32_t> starts;
    for (std::uint32_t l : least)
      if (l != kNone) starts.push_back(l);
    std::sort(starts.begin(), starts.end(), explicit_less);
    std::vector<std::uint32_t> queue;
    for (std::uint32_t v : starts) {  // each component at its least vertex, in order
      // The face left of v: the cycle of the last outgoing half-edge at an angle
      // below pi (or of the last one).
      std::uint32_t h0 = out_[out_begin_[v + 1] - 1];
      for (std::uint32_t k = out_begin_[v]; k < out_begin_[v + 1]; ++k)
        if (half(dir(out_[k])) == 0) h0 = out_[k];
      const std::uint32_t oc = cycle_[h0];
      const std::uint32_t hit = ray_hit(pts_[v].p);
      if (hit != kNone) {
        const std::uint32_t pc = cycle_[hit];
        if (!known_[pc])
          return Error{ErrorCode::kPrecondition, "2D Boolean: a face was reached before its outside"};
        face_parent_[oc] = pc;
        winding_[oc] = winding_[pc];
      }
      known_[oc] = true;
      queue.assign(1, oc);
      while (!queue.empty()) {
        const std::uint32_t c = queue.back();
        queue.pop_back();
        std::uint32_t h = cycle_first_[c];
        do {
          const std::uint32_t c2 = cycle_[h ^ 1];
          if (!known_[c2]) {
            known_[c2] = true;
            winding_[c2] = winding_[c];
            const Edge& e = edges_[h >> 1];
            const int s = (h & 1) ? 1 : -1;  // right of h = left of h minus delta(h)
            for (const auto& [o, d] : e.delta) add_to(winding_[c2], o, s * d);
            queue.push_back(c2);
          }
          h = next_[h];
        } while (h != cycle_first_[c]);
      }
    }
    SparseExpr expr(expr_, operands_);
    kept_.assign(nc, false);
    for (std::size_t c = 0; c < nc; ++c) kept_[c] = expr.contains(winding_[c]);
    return Status::Ok();
  }

  // ------------------------------------------------------------------ 5. output

  bool boundary(std::uint32_t h) const { return kept_[cycle_[h]] && !kept_[cycle_[h ^ 1]]; }

  std::uint32_t boundary_next(std::uint32_t h) const {
    std::uint32_t g = clockwise_after(h ^ 1);
    while (!boundary(g)) g = clockwise_after(g);
    return g;
  }

  // The position of point id, rounded; `moved` when rounding changed it.
  Vec2 rounded(std::uint32_t id, bool& moved) const {
    const Pt& q = pts_[id];
    moved = false;
    if (q.s == kNone) return q.p;
    const H2<Dd> h = hom<Dd>(id);
    double x = (h.u.hi + h.u.lo) / (h.w.hi + h.w.lo), y = (h.v.hi + h.v.lo) / (h.w.hi + h.w.lo);
    const double mw = magnitude(h.w);
    constexpr double kClose = 0x1p-60;  // Dd carried the value to well past a double
    if (!(h.u.e <= kClose * magnitude(h.u) && h.v.e <= kClose * magnitude(h.v) &&
          h.w.e <= kClose * mw) ||
        !std::isfinite(x) || !std::isfinite(y)) {
      const H2<Dyadic> e = hom<Dyadic>(id);
      x = e.u.to_double() / e.w.to_double();
      y = e.v.to_double() / e.w.to_double();
    }
    // On a vertical (horizontal) segment, x (y) is that segment's, exactly.
    bool x_exact = false, y_exact = false;
    for (std::uint32_t t : {q.s, q.u}) {
      const Seg& g = segs_[t];
      if (g.a.x == g.b.x) {
        x = g.a.x;
        x_exact = true;
      }
      if (g.a.y == g.b.y) {
        y = g.a.y;
        y_exact = true;
      }
    }
    moved = (!x_exact && decide([&]<class T>() {
              const H2<T> g = hom<T>(id);
              return g.u - T(x) * g.w;
            }) != 0) ||
            (!y_exact && decide([&]<class T>() {
              const H2<T> g = hom<T>(id);
              return g.v - T(y) * g.w;
            }) != 0);
    return {x, y};
  }

  struct OutLoop {
    std::vector<std::uint32_t> h;  // half-edges in order
    bool outer = false;
    std::uint32_t group = 0;
  };

  Result<Evaluated2D> emit() {
    const std::size_t nh = edges_.size() * 2;
    // Regions: kept cycles joined across kept-kept edges and within one face.
    UnionFind groups(static_cast<std::uint32_t>(cycle_first_.size()));
    for (std::size_t c = 0; c < cycle_first_.size(); ++c)
      if (face_parent_[c] != kNone) groups.unite(static_cast<std::uint32_t>(c), face_parent_[c]);
    for (std::uint32_t h = 0; h < nh; h += 2)
      if (kept_[cycle_[h]] && kept_[cycle_[h + 1]]) groups.unite(cycle_[h], cycle_[h + 1]);
    std::vector<std::uint32_t> boundary_out(pts_.size(), 0);  // boundary half-edges leaving
    for (std::uint32_t h = 0; h < nh; ++h)
      if (boundary(h)) ++boundary_out[origin(h)];
    std::vector<bool> used(nh, false);
    std::vector<OutLoop> loops;
    std::vector<std::uint32_t> stack, at(pts_.size(), kNone);
    for (std::uint32_t h0 = 0; h0 < nh; ++h0) {
      if (used[h0] || !boundary(h0)) continue;
      // Walk the chain, cutting off a loop whenever a vertex comes again.
      stack.clear();
      std::uint32_t h = h0;
      do {
        used[h] = true;
        const std::uint32_t v = origin(h);
        if (at[v] != kNone) {
          OutLoop l;
          l.h.assign(stack.begin() + at[v], stack.end());
          for (std::uint32_t g : l.h) at[origin(g)] = kNone;
          stack.erase(stack.end() - static_cast<std::ptrdiff_t>(l.h.size()), stack.end());
          loops.push_back(std::move(l));
        }
        at[v] = static_cast<std::uint32_t>(stack.size());
        stack.push_back(h);
        h = boundary_next(h);
      } while (h != h0);
      OutLoop l;
      l.h = stack;
      for (std::uint32_t g : l.h) at[origin(g)] = kNone;
      loops.push_back(std::move(l));
    }
    // Orientation at the least vertex; straight vertices dropped.
    Evaluated2D result;
    std::vector<std::uint32_t> region_of(cycle_first_.size(), kNone);
    std::vector<std::vector<Vec2>> built(loops.size());
    bool any_moved = false;
    for (std::size_t li = 0; li < loops.size(); ++li) {
      OutLoop& l = loops[li];
      const std::size_t n = l.h.size();
      std::size_t least = 0;
      for (std::size_t i = 1; i < n; ++i)
        if (lex_less(origin(l.h[i]), origin(l.h[least]))) least = i;
      l.outer = cross(dir(l.h[(least + n - 1) % n]), dir(l.h[least])) > 0;
      l.group = groups.find(cycle_[l.h[0]]);
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t v = origin(l.h[i]);
        if (boundary_out[v] == 1 && cross(dir(l.h[(i + n - 1) % n]), dir(l.h[i])) == 0) continue;
        bool moved = false;
        built[li].push_back(rounded(v, moved));
        any_moved |= moved;
      }
    }
    // Regions in the order their outer loops were found; holes after.
    for (std::size_t li = 0; li < loops.size(); ++li) {
      if (!loops[li].outer) continue;
      if (region_of[loops[li].group] != kNone)
        return Error{ErrorCode::kPrecondition, "2D Boolean: a region with two outer loops"};
      region_of[loops[li].group] = static_cast<std::uint32_t>(result.shape.regions.size());
      result.shape.regions.push_back(Region{{built[li]}});
    }
    for (std::size_t li = 0; li < loops.size(); ++li) {
      if (loops[li].outer) continue;
      const std::uint32_t r = region_of[loops[li].group];
      if (r == kNone) return Error{ErrorCode::kPrecondition, "2D Boolean: a hole with no outer loop"};
      result.shape.regions[r].loops.push_back(built[li]);
    }
    if (any_moved) result.rounding_crossings = check_rounding(result.shape);
    return result;
  }

  // After rounding: loops that collapsed or turned over, and pairs of edges that meet
  // other than at a shared end (each counted once). The loops are cleaned in place.
  static std::size_t check_rounding(Shape2D& shape) {
    std::size_t bad = 0;
    struct E {
      Vec2 p, q;
    };
    std::vector<E> es;
    std::vector<Box> boxes;
    for (Region& r : shape.regions) {
      for (std::size_t li = 0; li < r.loops.size(); ++li) {
        auto& loop = r.loops[li];
        loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
        while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
        if (loop.size() < 3 || area_sign(loop) != (li == 0 ? 1 : -1)) ++bad;
        std::vector<Vec2> sorted = loop;  // a point passed twice: the loop touches itself
        std::sort(sorted.begin(), sorted.end(),
                  [](Vec2 p, Vec2 q) { return p.x != q.x ? p.x < q.x : p.y < q.y; });
        bad += static_cast<std::size_t>(sorted.end() - std::unique(sorted.begin(), sorted.end()));
        for (std::size_t i = 0; i < loop.size(); ++i) {
          es.push_back({loop[i], loop[(i + 1) % loop.size()]});
          Box b;
          b.add(Vec3{es.back().p.x, es.back().p.y, 0});
          b.add(Vec3{es.back().q.x, es.back().q.y, 0});
          boxes.push_back(b);
        }
      }
    }
    const Bvh tree(boxes);
    tree.pairs([&](std::uint32_t i, std::uint32_t j) {
      const E &a = es[i], &b = es[j];
      const bool pp = a.p == b.p, pq = a.p == b.q, qp = a.q == b.p, qq = a.q == b.q;
      if ((pp && qq) || (pq && qp)) {
        ++bad;
        return;
      }
      if (pp || pq || qp || qq) {  // one shared end: bad only when they overlap
        const Vec2 s = (pp || pq) ? a.p : a.q;
        const Vec2 x = s == a.p ? a.q : a.p, y = s == b.p ? b.q : b.p;
        if (orient2d(s, x, y) == 0 &&
            dot_sign({s.x, s.y, 0}, {x.x, x.y, 0}, {s.x, s.y, 0}, {y.x, y.y, 0}) > 0)
          ++bad;
        return;
      }
      if (segments_meet(a.p, a.q, b.p, b.q)) ++bad;
    });
    return bad;
  }

  // ------------------------------------------------------------------ data
  std::span<const Shape2D> ops_;
  const Expr& expr_;
  std::uint32_t operands_ = 0, explicit_count_ = 0;
  std::vector<Seg> segs_;
  std::vector<Pt> pts_;
  UnionFind uf_;  // smallest id as root, so that an explicit point (ids below the
                  // crossings') names a class that holds one
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> vertex_ids_;
  Bvh bvh_;
  std::vector<std::vector<std::uint32_t>> on_;  // by segment: its points, then its chain
  std::vector<Edge> edges_;
  std::unordered_map<std::uint64_t, std::uint32_t> edge_of_;
  std::vector<std::uint32_t> out_begin_, out_, pos_, next_, cycle_, cycle_first_;
  std::vector<Winding> winding_;
  std::vector<bool> known_, kept_;
  std::vector<std::uint32_t> face_parent_;
};

}  // namespace

Result<Evaluated2D> planar_boolean(std::span<const Shape2D> operands, const Expr& expr) {
  Planar p(operands, expr);
  return p.run();
}

}  // namespace cellforge::boolean
