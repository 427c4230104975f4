// Stages 3 and 4: classification by winding numbers and selection (stages.h).
//
// A piece is classified at a point strictly inside it (the centroid of three of its
// corners), on both sides: front = x + d n and back = x - d n for an infinitesimal d,
// n the normal of its cluster's reference triangle. The winding number of an operand
// at a point is the sum, over the operand's outward triangles crossed by the ray from
// it along +axis k (the dominant axis of n), of the sign of the triangle normal's
// component k (+1 where the ray leaves). Every test is exact; a ray through an edge,
// a vertex or a coplanar triangle is decided by symbolic perturbation: first by d
// (the side the point is shifted to), then by a shift (e, e^2) of the ray across it
// (axes k+1, k+2) with e infinitesimal, so that each crossing of a closed surface is
// counted exactly once.
//
// Triangles that nothing cuts are classified a patch at a time: the triangles of one
// operand joined across manifold edges, consistently oriented, that touch nothing.
#include <algorithm>
#include <array>
#include <memory>
#include <numeric>
#include <optional>
#include <type_traits>

#include "boolean/parallel.h"
#include "boolean/stages.h"
#include "cellforge/geom/bvh.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"

namespace cellforge::boolean {

namespace {

template <class T>
V3<T> normal_t(const Arrangement& a, const Tri& t) {
  return plane_normal<T>(a.pos[t.v[0]], a.pos[t.v[1]], a.pos[t.v[2]]);
}

int sgn(double x) { return x > 0 ? 1 : (x < 0 ? -1 : 0); }

std::uint64_t ordered(std::uint32_t p, std::uint32_t q) {
  return (static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q);
}

// Winding numbers by operand on the two sides of a point; `touched` lists the
// operands a ray met (with repeats), so that a ray over many operands costs what it
// crosses, not the operand count. `on` marks the operands whose closed point set
// holds the point itself (found for free starts only, RayCaster::cast_free).
struct Windings {
  std::vector<int> front, back;
  std::vector<char> on;
  std::vector<std::uint32_t> touched;
  void reset(std::size_t operands) {
    if (front.size() != operands) {
      front.assign(operands, 0);
      back.assign(operands, 0);
      on.assign(operands, 0);
    }
    for (std::uint32_t o : touched) front[o] = back[o] = on[o] = 0;
    touched.clear();
  }
};

// Where a ray starts: a point strictly inside a piece, on its cluster's plane, with
// the piece's two sides; or a free point, an arrangement point p or the point
// (p + 2q) / 3 strictly inside the segment pq, with no plane.
struct PieceStart {
  const Arrangement& a;
  RepPoint r;
  template <class T>
  H3<T> get() const { return a.rep3<T>(r); }
};
struct FreeStart {
  const Arrangement& a;
  std::uint32_t p, q;
  template <class T>
  H3<T> get() const {
    const H3<T> x = a.point3<T>(p);
    if (p == q) return x;
    const H3<T> y = a.point3<T>(q);
    return {{x.c[0] * y.c[3] + T(2.0) * y.c[0] * x.c[3], x.c[1] * y.c[3] + T(2.0) * y.c[1] * x.c[3],
             x.c[2] * y.c[3] + T(2.0) * y.c[2] * x.c[3], T(3.0) * x.c[3] * y.c[3]}};
  }
};

class RayCaster {
 public:
  explicit RayCaster(const Arrangement& a) : a_(a) {}

  void cast(const RepPoint& r, Windings& w) const {
    // Along the axis closest to the piece's normal: the ray leaves the piece's plane
    // at once, so the edges lying in that plane are not met edge-on.
    Cluster lone;
    const Cluster& c = a_.cluster(r.cluster, lone);
    run(PieceStart{a_, r}, c.k, &a_.tris[c.ref], r.cluster, w);
  }
  // At a free point, its two sides are one: the point is shifted by an infinitesimal
  // along the ray's axis (`axis`, towards `dir` = +1 or -1). The operands whose closed
  // set holds the point are marked in w.on (their windings are those of a point next
  // to it).
  void cast_free(std::uint32_t p, std::uint32_t q, Windings& w, int axis = 2, int dir = 1) const {
    dir_ = dir;
    run(FreeStart{a_, p, q}, axis, nullptr, kInvalidIndex, w);
    dir_ = 1;
  }

  mutable std::size_t rays = 0;

 private:
  template <class Start>
  void run(const Start& start, int k, const Tri* ref, std::uint32_t cluster, Windings& w) const {
    ++rays;
    w.reset(a_.operands);
    k_ = k;
    i_ = (k_ + 1) % 3;
    j_ = (k_ + 2) % 3;
    exact_x_.reset();
    dd_x_.reset();
    const H3<Fp> h = start.template get<Fp>();
    double e[3], x[3];
    // Doubles are good enough when W is known to a relative 2^-20; else exactly.
    const bool rounded_ok = std::abs(h.c[3].v) > h.c[3].e * 0x1p20;
    if (!rounded_ok) exact_x_ = start.template get<Dyadic>();  // too close to call in doubles
    for (int i = 0; i < 3; ++i) {
      if (rounded_ok) {
        x[i] = h.c[i].v / h.c[3].v;
        e[i] = ((h.c[i].e + std::abs(x[i]) * h.c[3].e) / (std::abs(h.c[3].v) - h.c[3].e) +
                std::abs(x[i]) * 4 * kUnit) * 1.01;
      } else {
        x[i] = exact_x_->c[i].to_double() / exact_x_->c[3].to_double();
        e[i] = std::abs(x[i]) * 8 * kUnit + 1e-300;
      }
      x_[i] = Fp(x[i], e[i]);
    }
    const int ws = decide([&]<class T>() { return start.template get<T>().c[3]; });
    auto accept = [&](const auto& b) {  // a Bvh FloatBox: no conversion
      return b.hi[k_] >= x[k_] - e[k_] && b.lo[i_] <= x[i_] + e[i_] && b.hi[i_] >= x[i_] - e[i_] &&
             b.lo[j_] <= x[j_] + e[j_] && b.hi[j_] >= x[j_] - e[j_];
    };
    a_.bvh.query(accept, [&](std::uint32_t t) {
      if (!ref) {
        const Box& b = a_.bvh.box(t);
        bool near = true;
        for (int d = 0; d < 3; ++d) near &= b.lo[d] <= x[d] + e[d] && b.hi[d] >= x[d] - e[d];
        if (near && on_triangle(start, ws, t)) {
          w.on[a_.tris[t].operand] = 1;
          w.touched.push_back(a_.tris[t].operand);
        }
      }
      if (!a_.faces[a_.tris[t].input_face].sheet) contribute(start, ws, ref, cluster, t, w);
    });
    if (ref || a_.wires.empty()) return;
    a_.wire_bvh.query(
        [&](const Box& b) {
          bool near = true;
          for (int d = 0; d < 3; ++d) near &= b.lo[d] <= x[d] + e[d] && b.hi[d] >= x[d] - e[d];
          return near;
        },
        [&](std::uint32_t wi) {
          const WireSeg& s = a_.wires[wi];
          if (on_segment(start, ws, a_.pos[s.p], a_.pos[s.q])) {
            w.on[s.operand] = 1;
            w.touched.push_back(s.operand);
          }
        });
  }

  // The sign of a polynomial that is affine in the point: first on the point's
  // rounded coordinates with their error bounds (tight, unlike the homogeneous form),
  // then exactly on its homogeneous coordinates (with W's sign ws).
  // `line`: input vertices s, u (s != u) such that f vanishes on the line su (a
  // triangle edge's side function in the projection along axis `k`: on every plane
  // through su that runs along k), else null.
  template <class Start, class Affine>
  int affine_sign(const Start& start, int ws, Affine f, const std::uint32_t* line = nullptr, int k = 0) const {
    const int s = sign_of(f(H3<Fp>{{x_[0], x_[1], x_[2], Fp(1.0)}}));
    if (s != kUncertain) return s;
    if constexpr (std::is_same_v<Start, FreeStart>) {
      // f at (p + 2q) / 3 is (f(p) + 2 f(q)) / 3: the signs at the ends decide unless
      // they differ. Each known without the site's arithmetic where it can be: zero for
      // a point made on the line su, on doubles at an input vertex; an implicit end
      // off the line is asked only when the other end's sign is zero.
      auto known = [&](std::uint32_t v) {
        if (line && (on_line(v, line[0], line[1]) || on_plane_along(v, line[0], line[1], k))) return 0;
        if (v >= a_.pos.size()) return kUncertain;
        const Vec3 x = a_.pos[v];
        return decide([&]<class T>() { return f(explicit_point<T>(x)); });
      };
      auto at = [&](std::uint32_t v) {
        const int sign = known(v);
        if (sign != kUncertain) return sign;
        return a_.w3_sign(v) * decide([&]<class T>() { return f(a_.point3<T>(v)); });
      };
      const int sp = known(start.p), sq = start.q == start.p ? sp : known(start.q);
      if (sp != kUncertain && sq != kUncertain) {
        if (sp == sq || sq == 0) return sp;
        if (sp == 0) return sq;
      } else if (sp == 0) {
        return at(start.q);
      } else if (sq == 0) {
        return at(start.p);
      }
    }
    // The homogeneous coordinates in double-double (exact for the small integers of
    // grid-aligned parts, whose points on a plane defeat the rounded coordinates).
    if (!dd_x_) dd_x_ = start.template get<Dd>();
    if (const int d = sign_of(f(*dd_x_)); d != kUncertain) return ws * d;
    ++exact_evaluations();
    if (!exact_x_) exact_x_ = start.template get<Dyadic>();
    return ws * sign_of(f(*exact_x_));
  }

  // The side of the start of triangle ti's plane (0: on it). A free start between two
  // points whose sides are known without arithmetic (input vertices by orient3d on
  // doubles, implicit points made on that plane by construction) is on the side they
  // share; otherwise, and for a piece's start, exactly.
  template <class Start>
  int plane_sign(const Start& start, int ws, std::uint32_t ti) const {
    const Tri& t = a_.tris[ti];
    const Vec3 p0 = a_.pos[t.v[0]];
    auto f = [&]<class T>(const H3<T>& x) {
      const V3<T> n = normal_t<T>(a_, t);
      return n[0] * (x.c[0] - T(p0.x) * x.c[3]) + n[1] * (x.c[1] - T(p0.y) * x.c[3]) +
             n[2] * (x.c[2] - T(p0.z) * x.c[3]);
    };
    if constexpr (std::is_same_v<Start, FreeStart>) {
      const int sp = known_side(start.p, ti);
      const int sq = start.q == start.p ? sp : known_side(start.q, ti);
      if (sp != kUncertain && sq != kUncertain) {
        if (sp == sq || sq == 0) return sp;
        if (sp == 0) return sq;
      }
      // One end on the plane: the site's side is the other end's (its own point's
      // arithmetic, not the site's, whose degree is twice as high).
      const std::uint32_t other = sp == 0 && sq == kUncertain   ? start.q
                                  : sq == 0 && sp == kUncertain ? start.p
                                                                : kInvalidIndex;
      if (other != kInvalidIndex) {
        const int so = sign_of(f(a_.point3<Fp>(other)));
        if (so != kUncertain) return a_.w3_sign(other) * so;
      }
    }
    return affine_sign(start, ws, f);
  }
  int known_side(std::uint32_t p, std::uint32_t ti) const {
    const Tri& t = a_.tris[ti];
    if (p < a_.pos.size()) {
      // A corner of the triangle's face (a site at its own triangle: no arithmetic).
      const auto on = a_.plane_vertices(t);
      if (std::find(on.begin(), on.end(), p) != on.end()) return 0;
      return orient3d(a_.pos[t.v[0]], a_.pos[t.v[1]], a_.pos[t.v[2]], a_.pos[p]);
    }
    const std::uint32_t plane = a_.plane_key(a_.cluster_of[ti]);
    const PointDef& d = a_.points[p - a_.pos.size()];
    if (d.kind == PointKind::kLpi && a_.plane_key(a_.cluster_of[d.c]) == plane) return 0;
    if (d.kind == PointKind::kCross && a_.plane_key(d.a) == plane) return 0;
    // A point of the line ab (an edge's line meeting a plane, two segments meeting)
    // is on the plane when a and b are (the point may lie beyond them: a chord runs
    // across a whole piece).
    if ((d.kind == PointKind::kLpi || d.kind == PointKind::kMeet) && d.a < a_.pos.size() && d.b < a_.pos.size()) {
      const auto on = a_.plane_vertices(t);
      auto on_plane = [&](std::uint32_t v) {
        return std::find(on.begin(), on.end(), v) != on.end() ||
               orient3d(a_.pos[t.v[0]], a_.pos[t.v[1]], a_.pos[t.v[2]], a_.pos[v]) == 0;
      };
      if (on_plane(d.a) && on_plane(d.b)) return 0;
    }
    return kUncertain;
  }

  // Whether point v is made on the line through input vertices s and u (known without
  // arithmetic): one of them, or a point of an edge or segment su.
  bool on_line(std::uint32_t v, std::uint32_t s, std::uint32_t u) const {
    if (v == s || v == u) return true;
    if (v < a_.pos.size()) return false;
    const PointDef& d = a_.points[v - a_.pos.size()];
    if (d.kind != PointKind::kLpi && d.kind != PointKind::kMeet) return false;
    if ((d.a == s && d.b == u) || (d.a == u && d.b == s)) return true;
    if (d.kind != PointKind::kMeet) return false;
    const auto& m = a_.meets[d.c];  // the other segment
    return (m[0] == s && m[1] == u) || (m[0] == u && m[1] == s);
  }

  // Whether point v is made on a face's plane that holds s and u and runs along axis
  // k (a wall, for a ray up it): v, s and u then project along k onto one line. The
  // faces are those of the edge v was made on (an lpi of it, the wall's diagonal).
  bool on_plane_along(std::uint32_t v, std::uint32_t s, std::uint32_t u, int k) const {
    if (v < a_.pos.size()) return false;
    const PointDef& d = a_.points[v - a_.pos.size()];
    if (d.kind != PointKind::kLpi) return false;
    for (const EdgeUseTable::Use& use : a_.edge_uses.uses(d.a, d.b)) {
      const Tri& f = a_.tris[use.tri()];
      const auto on = a_.plane_vertices(f);
      const auto has = [&](std::uint32_t x) { return std::find(on.begin(), on.end(), x) != on.end(); };
      if (has(s) && has(u) && orient2d_projected(a_.pos[f.v[0]], a_.pos[f.v[1]], a_.pos[f.v[2]], k) == 0)
        return true;
    }
    return false;
  }

  // Whether the start lies on the closed triangle t: on its plane, and inside or on
  // its sides in the projection along its normal's largest component.
  template <class Start>
  bool on_triangle(const Start& start, int ws, std::uint32_t ti) const {
    const Tri& t = a_.tris[ti];
    const Vec3 p[3] = {a_.pos[t.v[0]], a_.pos[t.v[1]], a_.pos[t.v[2]]};
    int k = 0, mk = 0;
    for (int axis = 0; axis < 3 && mk == 0; ++axis) {
      mk = orient2d_projected(p[0], p[1], p[2], axis);
      k = axis;
    }
    if (mk == 0) return false;
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    for (int q = 0; q < 3; ++q) {
      const Vec3 s = p[q], u = p[(q + 1) % 3];
      const std::uint32_t line[2] = {t.v[q], t.v[(q + 1) % 3]};
      const int o = affine_sign(start, ws, [&]<class T>(const H3<T>& x) {
        return (T(u[i]) - T(s[i])) * (x.c[j] - T(s[j]) * x.c[3]) -
               (T(u[j]) - T(s[j])) * (x.c[i] - T(s[i]) * x.c[3]);
      }, line, k);
      if (o == -mk) return false;
    }
    return plane_sign(start, ws, ti) == 0;
  }

  // Whether the start lies on the closed segment pq (a point where p == q).
  template <class Start>
  bool on_segment(const Start& start, int ws, Vec3 p, Vec3 q) const {
    for (int i = 0; i < 3; ++i) {
      // The components of d x (X - p) vanish (X - p itself where p == q).
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      const int s = affine_sign(start, ws, [&]<class T>(const H3<T>& x) {
        if (p == q) return x.c[i] - T(p[i]) * x.c[3];
        return (T(q[j]) - T(p[j])) * (x.c[k] - T(p[k]) * x.c[3]) -
               (T(q[k]) - T(p[k])) * (x.c[j] - T(p[j]) * x.c[3]);
      });
      if (s != 0) return false;
    }
    if (p == q) return true;
    for (const Vec3 from : {p, q}) {
      const Vec3 to = from == p ? q : p;
      const int s = affine_sign(start, ws, [&]<class T>(const H3<T>& x) {
        T sum = T(0.0);
        for (int i = 0; i < 3; ++i) sum = sum + (T(to[i]) - T(from[i])) * (x.c[i] - T(from[i]) * x.c[3]);
        return sum;
      });
      if (s < 0) return false;
    }
    return true;
  }

  // ref: the piece's reference triangle (its plane and sides), null for a free start.
  template <class Start>
  void contribute(const Start& start, int ws, const Tri* ref, std::uint32_t cluster, std::uint32_t ti,
                  Windings& w) const {
    const Tri& t = a_.tris[ti];
    const Vec3 p[3] = {a_.pos[t.v[0]], a_.pos[t.v[1]], a_.pos[t.v[2]]};
    const int k = k_, i = i_, j = j_;
    const int mk = orient2d_projected(p[0], p[1], p[2], k);
    if (mk == 0) return;  // parallel to the ray
    bool in_front = true, in_back = true;
    for (int q = 0; q < 3; ++q) {
      const Vec3 s = p[q], u = p[(q + 1) % 3];
      const std::uint32_t line[2] = {t.v[q], t.v[(q + 1) % 3]};
      const int o = affine_sign(start, ws, [&]<class T>(const H3<T>& x) {
        return (T(u[i]) - T(s[i])) * (x.c[j] - T(s[j]) * x.c[3]) -
               (T(u[j]) - T(s[j])) * (x.c[i] - T(s[i]) * x.c[3]);
      }, line, k);
      if (o != 0) {
        if (o != mk) return;
        continue;
      }
      // Shifted off the line by the side (for a free start, along the ray: no shift
      // across it), else across the ray by (e, e^2).
      const int d = ref ? decide([&]<class T>() {
        const V3<T> n = normal_t<T>(a_, *ref);
        return (T(u[i]) - T(s[i])) * n[j] - (T(u[j]) - T(s[j])) * n[i];
      }) : 0;
      const int eps = s[j] != u[j] ? sgn(s[j] - u[j]) : sgn(u[i] - s[i]);
      in_front &= (d != 0 ? d : eps) == mk;
      in_back &= (d != 0 ? -d : eps) == mk;
    }
    if (!in_front && !in_back) return;
    // A triangle on the piece's plane has the point on its plane: known without
    // arithmetic (the exact test would be of degree 30).
    bool coplanar = false;
    if (ref) {
      const Vec3 r0 = a_.pos[ref->v[0]], r1 = a_.pos[ref->v[1]], r2 = a_.pos[ref->v[2]];
      coplanar = a_.cluster_of[ti] == cluster ||
                 (orient3d(r0, r1, r2, p[0]) == 0 && orient3d(r0, r1, r2, p[1]) == 0 &&
                  orient3d(r0, r1, r2, p[2]) == 0);
    }
    const int s = coplanar ? 0 : plane_sign(start, ws, ti);
    int sf = s, sb = s;
    if (s == 0) {
      // On the triangle's plane: shifted by the side (a free start: up the ray's axis).
      const int d = ref ? decide([&]<class T>() {
        const V3<T> n = normal_t<T>(a_, t), m = normal_t<T>(a_, *ref);
        return n[0] * m[0] + n[1] * m[1] + n[2] * m[2];
      }) : dir_ * mk;
      if (d != 0) {
        sf = d;
        sb = -d;
      } else {
        const int mi = orient2d_projected(p[0], p[1], p[2], i);
        sf = sb = mi != 0 ? mi : orient2d_projected(p[0], p[1], p[2], j);
      }
    }
    if (in_front && sf == -mk) w.front[t.operand] += mk;
    if (in_back && sb == -mk) w.back[t.operand] += mk;
    w.touched.push_back(t.operand);
  }

  const Arrangement& a_;
  mutable int k_ = 0, i_ = 1, j_ = 2;  // the ray's axis and the two across it
  mutable int dir_ = 1;                // a free start's shift along the axis
  mutable Fp x_[3];  // the point of the current ray, rounded, with error bounds
  mutable std::optional<H3<Dd>> dd_x_;         // in double-double, once needed
  mutable std::optional<H3<Dyadic>> exact_x_;  // and exactly, once needed
};

// The expression on the windings of a point's two sides. A flat expression (one
// union, intersection or difference of distinct operands, as a run of OpenSCAD's set
// operations becomes once nested runs are made one) is decided from the operands the
// ray met alone; any other through Expr::contains.
class Selector {
 public:
  Selector(const Expr& e, std::size_t operands) : expr_(e.flattened()), member_(operands, 0) {
    const Expr& expr = expr_;
    flat_ = expr.kind != Expr::Kind::kOperand && !expr.children.empty();
    for (const Expr& c : expr.children) {
      flat_ &= c.kind == Expr::Kind::kOperand && c.operand >= 0 &&
               static_cast<std::size_t>(c.operand) < operands && !member_[c.operand];
      if (flat_) member_[c.operand] = 1;
    }
    if (flat_) first_ = static_cast<std::uint32_t>(expr.children[0].operand);
  }

  // +1: keep with the reference normal outward; -1: keep reversed; 0: drop.
  int select(const Windings& w) {
    const bool f = contains(w, w.front), b = contains(w, w.back);
    if (f == b) return 0;
    return b ? 1 : -1;
  }

  // The point set on a piece and on its two sides: `on` lists the operands whose
  // faces hold the piece (closed sets hold their boundary), the others are inside
  // where their winding is positive.
  struct Sides {
    bool front, back, on;
  };
  Sides sides(const Windings& w, const std::vector<std::uint32_t>& on) {
    Sides s{contains(w, w.front), contains(w, w.back), false};
    const auto in = [&](std::uint32_t o) { return w.front[o] > 0 && w.back[o] > 0; };
    if (flat_) {
      gather(w, in);
      for (std::uint32_t o : on)
        if (member_[o]) seen_.push_back(o);
      s.on = flat_contains();
      return s;
    }
    inside_.assign(w.front.size(), false);
    for (std::uint32_t o : w.touched) inside_[o] = in(o);
    for (std::uint32_t o : on) inside_[o] = true;
    s.on = expr_.contains(inside_);
    return s;
  }

  // At a free point: whether the point is in the set, and whether the points next to
  // it (where its ray starts) are.
  std::pair<bool, bool> at_point(const Windings& w) {
    const bool around = contains(w, w.front);
    const auto in = [&](std::uint32_t o) { return w.on[o] || w.front[o] > 0; };
    if (flat_) {
      gather(w, in);
      return {flat_contains(), around};
    }
    inside_.assign(w.front.size(), false);
    for (std::uint32_t o : w.touched) inside_[o] = in(o);
    return {expr_.contains(inside_), around};
  }

 private:
  bool contains(const Windings& w, const std::vector<int>& wind) {
    if (!flat_) {
      inside_.assign(wind.size(), false);
      for (std::uint32_t o : w.touched) inside_[o] = wind[o] > 0;
      return expr_.contains(inside_);
    }
    gather(w, [&](std::uint32_t o) { return wind[o] > 0; });
    return flat_contains();
  }

  // seen_: the member operands the ray met that `in` holds (with repeats).
  template <class In>
  void gather(const Windings& w, In in) {
    seen_.clear();
    for (std::uint32_t o : w.touched)
      if (member_[o] && in(o)) seen_.push_back(o);
  }

  // A flat expression on the member operands listed in seen_ (with repeats).
  bool flat_contains() {
    std::sort(seen_.begin(), seen_.end());
    seen_.erase(std::unique(seen_.begin(), seen_.end()), seen_.end());
    switch (expr_.kind) {
      case Expr::Kind::kUnion:
        return !seen_.empty();
      case Expr::Kind::kIntersection:
        return seen_.size() == expr_.children.size();
      case Expr::Kind::kDifference:
        return seen_.size() == 1 && seen_[0] == first_;
      case Expr::Kind::kOperand:
        break;
    }
    return false;
  }

  const Expr expr_;
  std::vector<char> member_;
  bool flat_ = false;
  std::uint32_t first_ = 0;
  std::vector<bool> inside_;
  std::vector<std::uint32_t> seen_;
};

// Reverses a loop and its edge keys (keys[i] belongs to the edge pts[i] -> pts[i+1]).
void reverse_loop(std::vector<std::uint32_t>& pts, std::vector<std::uint32_t>& keys) {
  const std::size_t n = pts.size();
  std::vector<std::uint32_t> k2(n);
  for (std::size_t j = 0; j < n; ++j) k2[j] = keys[(2 * n - 2 - j) % n];
  std::reverse(pts.begin(), pts.end());
  keys = std::move(k2);
}

// A point strictly inside a piece (a simple polygon, counterclockwise): the centroid
// of an ear, three consecutive corners turning left with no other corner in their
// closed triangle (then no side of the piece enters it either). A convex piece's
// first corner that turns is one.
RepPoint rep_of(const Arrangement& a, std::uint32_t ci, const Piece& p) {
  const Cluster& c = a.clusters[ci];
  const std::size_t n = p.pts.size();
  // A triangle: every corner turns left (a piece has area), the first is the ear.
  if (n == 3) return {ci, {p.pts[2], p.pts[0], p.pts[1]}};
  thread_local std::vector<int> turn;  // one allocation a thread, not one a piece
  turn.resize(n);
  bool convex = true;
  for (std::size_t i = 0; i < n; ++i) {
    // Two sides on one line (a segment cut at a point of another's) go straight on.
    const std::uint32_t before = p.lines[(i + n - 1) % n], after = p.lines[i];
    turn[i] = before == after || c.lines()[before].key == c.lines()[after].key
                  ? 0
                  : a.orient2(c, p.pts[(i + n - 1) % n], p.pts[i], p.pts[(i + 1) % n]);
    convex &= turn[i] >= 0;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (turn[i] <= 0) continue;
    const std::uint32_t x = p.pts[(i + n - 1) % n], y = p.pts[i], z = p.pts[(i + 1) % n];
    bool ear = true;
    for (std::size_t m = 0; m < n && ear && !convex; ++m) {
      const std::uint32_t q = p.pts[m];
      if (q == x || q == y || q == z) continue;
      ear = !(a.orient2(c, x, y, q) >= 0 && a.orient2(c, y, z, q) >= 0 && a.orient2(c, z, x, q) >= 0);
    }
    if (ear) return {ci, {x, y, z}};
  }
  return {ci, {p.pts[0], p.pts[1], p.pts[2]}};
}

// Whether the point r (strictly inside a piece) is inside input triangle t of r's
// cluster; the piece never straddles t's edges but its face's diagonals inside the
// cluster (Arrangement::open_edges), where r may lie: on one, it is inside.
// The piece's point in filtered doubles and the sign of its W are computed once for
// all the triangles it is tested against (`xf`, `ws`); the slower stages only for a
// side the filter leaves open.
bool covers(const Arrangement& a, std::uint32_t t, const RepPoint& r, const H3<Fp>& xf, int ws) {
  Cluster lone;
  const Cluster& c = a.cluster(r.cluster, lone);
  const int k = c.k, i = (k + 1) % 3, j = (k + 2) % 3;
  const Tri& tri = a.tris[t];
  const int o = orient2d_projected(a.pos[tri.v[0]], a.pos[tri.v[1]], a.pos[tri.v[2]], k);
  for (int e = 0; e < 3; ++e) {
    const Vec3 s = a.pos[tri.v[e]], q = a.pos[tri.v[(e + 1) % 3]];
    auto side_poly = [&]<class T>(const H3<T>& x) {
      return (T(q[i]) - T(s[i])) * (x.c[j] - T(s[j]) * x.c[3]) - (T(q[j]) - T(s[j])) * (x.c[i] - T(s[i]) * x.c[3]);
    };
    int side = sign_of(side_poly(xf));
    if (side == kUncertain) side = decide([&]<class T>() { return side_poly(a.rep3<T>(r)); });
    if (ws * side * o < 0 || (side == 0 && !(a.open_edges[t] & (1u << e)))) return false;
  }
  return true;
}

// Pieces that one ray classifies together. Two pieces of one-triangle clusters that
// meet along a part of an input edge (the same two points of it) have equal winding
// numbers on their like sides when the two triangles are the only ones at the edge,
// of one operand and consistently oriented, and no other surface reaches the open
// part: none lies along the edge (a contact edge, an input vertex inside it, an end
// on another's edge) and one crossing it makes a point of it, an end of the part. By
// job (index into `jobs`): the smallest job of its group, whose ray decides.
// Every triangle edge of the arrangement, sorted by edge (then triangle), and the input
// vertices found on another triangle's edge: what the patches of untouched triangles
// and the groups of pieces that share a ray both ask of an edge.
struct EdgeUses {
  const EdgeUseTable& edges;
  std::vector<char> on_other_edge;  // by input vertex
};

EdgeUses edge_uses(const Arrangement& a) {
  EdgeUses u{a.edge_uses, std::vector<char>(a.pos.size(), 0)};
  for (auto [key, v] : a.edge_points)
    if (v < u.on_other_edge.size()) u.on_other_edge[v] = 1;  // implicit ones (wires) have keys
  return u;
}

// Whether a segment of a cluster (a triangle's edge, a constraint) has both ends on
// the axis line u = m or v = m (d = 0, 1), exactly. Made once per cluster: the values
// m of the triangle edges along an axis line, and the constraints whose two ends may
// share a coordinate, with the interval where it may be (sorted by its start), so
// that a line looks only at the constraints around it.
struct AxisLineSegments {
  struct Near {
    double lo, hi;
    std::uint32_t q;
  };
  bool made = false;
  std::array<std::vector<double>, 2> edge_values;
  std::array<std::vector<Near>, 2> near;
  std::array<double, 2> widest{0, 0};

  void clear() { made = false; }
  void make(const Arrangement& a, const Cluster& c) {
    made = true;
    for (int d = 0; d < 2; ++d) {
      const int axis = (c.k + 1 + d) % 3;
      edge_values[d].clear();
      near[d].clear();
      widest[d] = 0;
      for (std::uint32_t t : c.tris())
        for (int v = 0; v < 3; ++v) {
          const double x = a.pos[a.tris[t].v[v]][axis];
          if (x == a.pos[a.tris[t].v[(v + 1) % 3]][axis]) edge_values[d].push_back(x);
        }
      std::sort(edge_values[d].begin(), edge_values[d].end());
      // Where the point's coordinate may be: its approximation, its error bound, and
      // the relative slack of the exact test's own filter.
      const auto interval = [&](std::uint32_t p) {
        double err = 0;
        const double x = a.approx3(p, &err)[axis];
        const double r = (err + (std::abs(x) + err) * 4 * kUnit) * 1.01;
        return std::array<double, 2>{x - r, x + r};
      };
      for (std::uint32_t q = 0; q < c.constraints().size(); ++q) {
        const auto ip = interval(c.constraints()[q].p), iq = interval(c.constraints()[q].q);
        const double lo = std::max(ip[0], iq[0]), hi = std::min(ip[1], iq[1]);
        if (lo > hi) continue;
        near[d].push_back({lo, hi, q});
        widest[d] = std::max(widest[d], hi - lo);
      }
      std::sort(near[d].begin(), near[d].end(),
                [](const Near& x, const Near& y) { return x.lo < y.lo || (x.lo == y.lo && x.q < y.q); });
    }
  }
  bool on(const Arrangement& a, const Cluster& c, int d, double m) const {
    if (std::binary_search(edge_values[d].begin(), edge_values[d].end(), m)) return true;
    const int axis = (c.k + 1 + d) % 3;
    auto it = std::lower_bound(near[d].begin(), near[d].end(), m - widest[d],
                               [](const Near& x, double v) { return x.lo < v; });
    for (; it != near[d].end() && it->lo <= m; ++it) {
      if (it->hi < m) continue;
      const Constraint& s = c.constraints()[it->q];
      if (a.coordinate_is(s.p, axis, m) && a.coordinate_is(s.q, axis, m)) return true;
    }
    return false;
  }
};

std::vector<std::uint32_t> shared_rays(const Arrangement& a, const std::vector<std::array<std::uint32_t, 2>>& jobs,
                                       const EdgeUses& uses, int threads) {
  std::vector<std::uint32_t> keys_with_vertex;
  for (auto [key, v] : a.edge_points)
    if (v < a.pos.size()) keys_with_vertex.push_back(key);
  std::sort(keys_with_vertex.begin(), keys_with_vertex.end());
  const auto cut_alone = [&](std::uint32_t t) {
    const std::uint32_t ci = a.cluster_of[t];
    return !Arrangement::is_lone(ci) && a.clusters[ci].touched && a.clusters[ci].tris().size() == 1;
  };
  // Edges across which groups may form, found on threads.
  const std::vector<std::uint64_t> good = uses.edges.gather<std::uint64_t>(
      threads, [&](std::uint32_t p, std::uint32_t q, std::span<const EdgeUseTable::Use> at, auto& out) {
        if (at.size() != 2) return;
        const EdgeUseTable::Use &x = at[0], &y = at[1];
        if (!cut_alone(x.tri()) || !cut_alone(y.tri()) || x.forward() == y.forward() ||
            a.tris[x.tri()].operand != a.tris[y.tri()].operand)
          return;
        if (uses.on_other_edge[p] || uses.on_other_edge[q] || a.is_contact_edge(p, q)) return;
        const std::uint32_t key = a.find_edge_key(p, q);
        if (key != kInvalidIndex && std::binary_search(keys_with_vertex.begin(), keys_with_vertex.end(), key)) return;
        out.push_back(ordered(p, q));
      });
  // The pieces' sides along those edges: (edge, the side's two points, job).
  struct Side {
    std::uint64_t edge, part;
    std::uint32_t job;
  };
  std::vector<Side> sides;
  for (std::uint32_t k = 0; k < jobs.size(); ++k) {
    const Cluster& c = a.clusters[jobs[k][0]];
    if (c.tris().size() != 1) continue;
    const Piece& piece = c.pieces()[jobs[k][1]];
    for (std::size_t e = 0; e < piece.pts.size(); ++e) {
      const Line& l = c.lines()[piece.lines[e]];
      if (l.kind != LineKind::kThrough) continue;
      const std::uint64_t edge = ordered(l.a, l.b);
      if (!std::binary_search(good.begin(), good.end(), edge)) continue;
      sides.push_back({edge, ordered(piece.pts[e], piece.pts[(e + 1) % piece.pts.size()]), k});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.edge < y.edge || (x.edge == y.edge && (x.part < y.part || (x.part == y.part && x.job < y.job)));
  });
  UnionFind groups(jobs.size());
  for (std::size_t i = 0; i + 1 < sides.size(); ++i) {
    const Side &x = sides[i], &y = sides[i + 1];
    if (x.edge != y.edge || x.part != y.part || jobs[x.job][0] == jobs[y.job][0]) continue;
    if (i + 2 < sides.size() && sides[i + 2].edge == x.edge && sides[i + 2].part == x.part) continue;
    groups.unite_to_smaller(x.job, y.job);
  }
  // Pieces of one cluster on either side of an axis line (the k-d split's, or one
  // through a touching point) have equal verdicts where nothing lies along that line:
  // every surface that meets the cluster's plane there is one of its segments (its
  // triangles' edges, the constraints), and no segment has both ends on the line.
  if (a.wires.empty()) {
    struct AxisSide {
      std::uint32_t cluster, line;
      std::uint64_t part;
      std::uint32_t job;
      auto operator<=>(const AxisSide&) const = default;
    };
    std::vector<AxisSide> axis_sides;
    std::vector<std::int8_t> free;  // by line of the current cluster: -1 unknown
    AxisLineSegments along;  // of the current cluster, made at its first axis line
    for (std::uint32_t k = 0; k < jobs.size(); ++k) {
      const std::uint32_t ci = jobs[k][0];
      const Cluster& c = a.clusters[ci];
      if (k == 0 || jobs[k - 1][0] != ci) {
        free.assign(c.lines().size(), -1);
        along.clear();
      }
      const Piece& piece = c.pieces()[jobs[k][1]];
      for (std::size_t e = 0; e < piece.pts.size(); ++e) {
        const std::uint32_t li = piece.lines[e];
        const Line& l = c.lines()[li];
        if (l.kind != LineKind::kAxisU && l.kind != LineKind::kAxisV) continue;
        if (free[li] < 0) {
          if (!along.made) along.make(a, c);
          free[li] = along.on(a, c, l.kind == LineKind::kAxisU ? 0 : 1, l.c) ? 0 : 1;
        }
        if (free[li] == 0) continue;
        axis_sides.push_back({ci, li, ordered(piece.pts[e], piece.pts[(e + 1) % piece.pts.size()]), k});
      }
    }
    std::sort(axis_sides.begin(), axis_sides.end());
    for (std::size_t i = 0; i + 1 < axis_sides.size(); ++i) {
      const AxisSide &x = axis_sides[i], &y = axis_sides[i + 1];
      if (x.cluster == y.cluster && x.line == y.line && x.part == y.part) groups.unite_to_smaller(x.job, y.job);
    }
  }
  std::vector<std::uint32_t> root(jobs.size());
  for (std::uint32_t k = 0; k < jobs.size(); ++k) root[k] = groups.find(k);
  return root;
}

}  // namespace

Selection classify_and_select(const Arrangement& a, const Expr& expr, const Options& options,
                              Report& report) {
  const int threads = options.threads;
  const bool closed = options.keep_lower_dim || options.cells;
  Selection selection;
  std::vector<OutPoly>& out = selection.polys;
  // A ray per job on threads, each range with its own caster; verdicts read in order.
  struct Verdict {
    std::uint32_t source = kInvalidIndex;  // the input triangle it lies on; none: skip it
    int keep = 0;
    FaceKind kind = FaceKind::kBoundary;
    bool mark = true;
    std::uint32_t settled = kInvalidIndex;  // OutSide::settled
  };
  struct Part {
    std::vector<Verdict> verdicts;
    std::size_t rays = 0;
  };
  // The verdict on a face of the arrangement from its two sides and its own points.
  auto judge = [&](Selector& selector, const Windings& w, const std::vector<std::uint32_t>& on, Verdict& v) {
    if (!closed) {
      v.keep = selector.select(w);
      return;
    }
    const Selector::Sides s = selector.sides(w, on);
    v.mark = s.on;
    // One operand holds the face and its membership flips across it, yet the set is
    // the same on both sides and on the face: the set does not depend on it here.
    const std::uint32_t x = on.empty() ? kInvalidIndex : on[0];
    if (s.front == s.back && s.on == s.front && x != kInvalidIndex &&
        std::all_of(on.begin(), on.end(), [&](std::uint32_t o) { return o == x; }) &&
        (w.front[x] > 0) != (w.back[x] > 0))
      v.settled = x;
    if (s.front != s.back) {
      v.keep = s.back ? 1 : -1;
    } else if (!s.front && s.on && options.keep_lower_dim) {
      v.keep = 1;
      v.kind = FaceKind::kSheet;
    } else if (s.front && (options.cells || (!s.on && options.keep_lower_dim))) {
      v.keep = 1;
      v.kind = FaceKind::kInner;
    }
    if (!options.keep_lower_dim) v.mark = true;
  };
  auto classify = [&](std::size_t n, auto&& job) {
    std::vector<Part> parts = parallel_ranges<Part>(n, threads, [&](std::size_t lo, std::size_t hi, Part& part) {
      RayCaster rays(a);
      Windings w;
      Selector selector(expr, a.operands);
      std::vector<std::uint32_t> on;
      for (std::size_t k = lo; k < hi; ++k) {
        Verdict v;
        on.clear();
        if (std::optional<RepPoint> r = job(k, v.source, on)) {
          rays.cast(*r, w);
          judge(selector, w, on, v);
        }
        part.verdicts.push_back(v);
      }
      part.rays = rays.rays;
    });
    std::vector<Verdict> all;
    for (Part& p : parts) {
      all.insert(all.end(), p.verdicts.begin(), p.verdicts.end());
      report.rays += p.rays;
    }
    return all;
  };

  // Pieces of the clusters something cuts.
  std::vector<std::array<std::uint32_t, 2>> jobs;  // cluster, piece
  for (std::uint32_t ci = 0; ci < a.clusters.size(); ++ci) {
    const Cluster& c = a.clusters[ci];
    if (!c.touched) continue;
    report.touched_triangles += c.tris().size();
    for (std::uint32_t pi = 0; pi < c.pieces().size(); ++pi) jobs.push_back({ci, pi});
  }
  // A face per piece kept and per input face kept whole, as a rule: room made once
  // (pages are touched as used), not grown by doubling and copying.
  out.reserve(jobs.size() + a.faces.size());
  const EdgeUses uses = edge_uses(a);
  const std::vector<std::uint32_t> ray_of = shared_rays(a, jobs, uses, threads);
  // Clusters of many triangles (coplanar faces of many operands: a Menger sponge's
  // planes): a tree of their triangles' boxes, so that a piece tests only the
  // triangles whose boxes hold its corners' box.
  std::vector<std::unique_ptr<Bvh>> cluster_tree(a.clusters.size());
  for (std::uint32_t ci = 0; ci < a.clusters.size(); ++ci) {
    const Cluster& c = a.clusters[ci];
    if (!c.touched || c.tris().size() <= 8) continue;
    std::vector<Box> boxes;
    boxes.reserve(c.tris().size());
    for (std::uint32_t t : c.tris()) boxes.push_back(a.bvh.box(t));
    cluster_tree[ci] = std::make_unique<Bvh>(std::move(boxes));
  }
  std::vector<Verdict> pieces = classify(jobs.size(), [&](std::size_t k, std::uint32_t& source,
                                                           std::vector<std::uint32_t>& on) {
    const auto [ci, pi] = jobs[k];
    const Cluster& c = a.clusters[ci];
    if (c.tris().size() == 1) {
      source = c.tris()[0];
      on.push_back(a.tris[source].operand);
      if (ray_of[k] != k) return std::optional<RepPoint>();  // its group's ray decides
      return std::optional<RepPoint>(rep_of(a, ci, c.pieces()[pi]));
    }
    const RepPoint r = rep_of(a, ci, c.pieces()[pi]);
    int source_sign = 0;
    std::vector<std::uint32_t> candidates;  // indices into c.tris(), in order
    if (cluster_tree[ci]) {
      Box near;
      for (std::uint32_t q : r.p) {
        double e = 0;
        const Vec3 x = a.approx3(q, &e);
        near.add(x - Vec3{e, e, e});
        near.add(x + Vec3{e, e, e});
      }
      cluster_tree[ci]->query([&](const Box& b) { return b.overlaps(near); },
                              [&](std::uint32_t t) { candidates.push_back(t); });
      std::sort(candidates.begin(), candidates.end());
    } else {
      candidates.resize(c.tris().size());
      std::iota(candidates.begin(), candidates.end(), 0u);
    }
    const H3<Fp> xf = a.rep3<Fp>(r);
    const int ws = decide([&]<class T>() { return a.rep3<T>(r).c[3]; });
    for (std::uint32_t t : candidates) {
      if (!covers(a, c.tris()[t], r, xf, ws)) continue;
      on.push_back(a.tris[c.tris()[t]].operand);
      if (source == kInvalidIndex || source_sign < 0) {
        const int sign = a.tri_sign(c, c.tris()[t]);
        if (source == kInvalidIndex || sign > 0) {
          source = c.tris()[t];
          source_sign = sign;
        }
      }
    }
    // Outside every triangle of the cluster: no face. Inside, in a group: its ray decides.
    return source == kInvalidIndex || ray_of[k] != k ? std::nullopt : std::optional<RepPoint>(r);
  });
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (ray_of[k] == k) continue;
    const Verdict& root = pieces[ray_of[k]];  // an earlier job
    pieces[k].keep = root.keep;
    pieces[k].kind = root.kind;
    pieces[k].mark = root.mark;
    const bool same_operand = pieces[k].source != kInvalidIndex && root.source != kInvalidIndex &&
                              a.tris[pieces[k].source].operand == a.tris[root.source].operand;
    pieces[k].settled = same_operand ? root.settled : kInvalidIndex;
  }
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    const Verdict& v = pieces[k];
    if (v.source == kInvalidIndex) continue;
    ++report.pieces;
    if (v.keep == 0) continue;
    const Cluster& c = a.clusters[jobs[k][0]];
    const Piece& p = c.pieces()[jobs[k][1]];
    OutPoly poly;
    poly.cluster = jobs[k][0];
    poly.normal_sign = v.keep;
    poly.tri = v.source;
    poly.kind = v.kind;
    poly.mark = v.mark;
    std::vector<std::uint32_t> pts = p.pts, keys(p.lines.size());
    for (std::size_t i = 0; i < p.lines.size(); ++i) keys[i] = c.lines()[p.lines[i]].key;
    if (c.nk_sign * v.keep < 0) reverse_loop(pts, keys);
    poly.loops.push_back(std::move(pts));
    poly.keys.push_back(std::move(keys));
    out.push_back(std::move(poly));
  }

  // Untouched triangles, a patch at a time.
  const std::vector<char>& on_other_edge = uses.on_other_edge;
  UnionFind patches(a.tris.size());
  auto untouched = [&](std::uint32_t t) { return !a.cluster_touched(a.cluster_of[t]); };
  uses.edges.each_edge([&](std::uint32_t p, std::uint32_t q, std::span<const EdgeUseTable::Use> at) {
    if (at.size() != 2) return;
    const EdgeUseTable::Use &x = at[0], &y = at[1];
    // Not across an edge that another solid touches at a point inside it, nor at an
    // end that lies on another's edge (the other's edge may run along this one, its
    // faces passing between the two triangles).
    if (untouched(x.tri()) && untouched(y.tri()) && x.forward() != y.forward() &&
        a.tris[x.tri()].operand == a.tris[y.tri()].operand && a.find_edge_key(p, q) == kInvalidIndex &&
        !on_other_edge[p] && !on_other_edge[q] && !a.is_contact_edge(p, q)) {
      patches.unite(x.tri(), y.tri());
    }
  });
  // One ray per patch, from its root triangle.
  std::vector<std::uint32_t> roots;
  std::vector<char> is_root(a.tris.size(), 0);
  for (std::uint32_t t = 0; t < a.tris.size(); ++t) {
    if (!untouched(t)) continue;
    const std::uint32_t root = patches.find(t);
    if (!is_root[root]) roots.push_back(root);
    is_root[root] = 1;
  }
  const std::vector<Verdict> patch = classify(roots.size(), [&](std::size_t k, std::uint32_t& source,
                                                                std::vector<std::uint32_t>& on) {
    const Tri& rt = a.tris[roots[k]];
    source = roots[k];
    on.push_back(rt.operand);
    return std::optional<RepPoint>(RepPoint{a.cluster_of[roots[k]], {rt.v[0], rt.v[1], rt.v[2]}});
  });
  std::vector<char>().swap(is_root);
  std::vector<std::uint32_t> patch_of(a.tris.size(), kInvalidIndex);  // by root
  for (std::size_t k = 0; k < roots.size(); ++k) patch_of[roots[k]] = static_cast<std::uint32_t>(k);
  std::vector<std::int8_t> tri_keep(a.tris.size(), 0);
  for (std::uint32_t t = 0; t < a.tris.size(); ++t)
    if (untouched(t)) tri_keep[t] = static_cast<std::int8_t>(patch[patch_of[patches.find(t)]].keep);
  // The whole verdict on an untouched triangle, and whether two agree.
  auto verdict_of = [&](std::uint32_t t) -> const Verdict& { return patch[patch_of[patches.find(t)]]; };
  auto same_verdict = [&](std::uint32_t t, std::uint32_t u) {
    if (!untouched(t) || !untouched(u)) return false;
    const Verdict &x = verdict_of(t), &y = verdict_of(u);
    return x.keep == y.keep && x.kind == y.kind && x.mark == y.mark;
  };
  auto set_verdict = [&](OutPoly& poly, std::uint32_t t) {
    poly.kind = verdict_of(t).kind;
    poly.mark = verdict_of(t).mark;
  };
  // Room for every kept untouched triangle as a face of its own (the most there can
  // be), reserved, not filled: a list doubled as it grows copies and touches its pages
  // twice (34 MB of faces for two spheres of 10^6 triangles).
  {
    std::size_t at_most = out.size();
    for (std::uint32_t t = 0; t < a.tris.size(); ++t) at_most += tri_keep[t] != 0;
    out.reserve(at_most);
  }
  std::vector<std::uint64_t> rim;  // a face's loop edges, reused face by face
  for (const SoupFace& f : a.faces) {
    bool whole = !f.tris.empty();
    for (std::uint32_t t : f.tris)
      whole &= untouched(t) && tri_keep[t] != 0 && same_verdict(t, f.tris[0]);
    // Not when something touches a diagonal inside it (the face must take the point).
    if (whole && f.tris.size() > 1) {
      rim.clear();
      for (const auto loop : a.loops_of(f))
        for (std::size_t k = 0; k < loop.size(); ++k) {
          const std::uint32_t p = loop[k], q = loop[(k + 1) % loop.size()];
          rim.push_back((static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q));
        }
      std::sort(rim.begin(), rim.end());
      for (std::uint32_t t : f.tris)
        for (int e = 0; e < 3 && whole; ++e) {
          const std::uint32_t p = a.tris[t].v[e], q = a.tris[t].v[(e + 1) % 3];
          const std::uint64_t key = (static_cast<std::uint64_t>(std::min(p, q)) << 32) | std::max(p, q);
          whole = std::binary_search(rim.begin(), rim.end(), key) || a.find_edge_key(p, q) == kInvalidIndex;
        }
    }
    if (whole) {
      const int keep = tri_keep[f.tris[0]];
      OutPoly poly;
      poly.tri = f.tris[0];
      poly.normal_sign = keep;
      set_verdict(poly, f.tris[0]);
      if (f.planar) poly.cluster = a.cluster_of[f.tris[0]];
      poly.source = LoopSource::kFace;  // loops made later; no keys: the input edges'
      out.push_back(std::move(poly));
      continue;
    }
    for (std::uint32_t t : f.tris) {
      if (!untouched(t) || tri_keep[t] == 0) continue;
      OutPoly poly;
      poly.tri = t;
      poly.cluster = a.cluster_of[t];
      poly.normal_sign = tri_keep[t];
      set_verdict(poly, t);
      poly.source = LoopSource::kTriangle;  // loops made later; no keys: the input edges'
      out.push_back(std::move(poly));
    }
  }
  // The edges of the arrangement's faces that were dropped: where lower-dimensional
  // parts may lie (an edge of a kept face is held by it).
  if (options.keep_lower_dim) {
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      if (pieces[k].source == kInvalidIndex || pieces[k].keep != 0) continue;
      const Cluster& c = a.clusters[jobs[k][0]];
      const Piece& p = c.pieces()[jobs[k][1]];
      for (std::size_t i = 0; i < p.pts.size(); ++i)
        selection.sides.push_back(
            {p.pts[i], p.pts[(i + 1) % p.pts.size()], c.lines()[p.lines[i]].key, pieces[k].settled});
    }
    for (std::uint32_t t = 0; t < a.tris.size(); ++t) {
      if (!untouched(t) || tri_keep[t] != 0) continue;
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t p = a.tris[t].v[e], q = a.tris[t].v[(e + 1) % 3];
        selection.sides.push_back({p, q, a.find_edge_key(p, q), verdict_of(t).settled});
      }
    }
  }
  return selection;
}

std::vector<SiteVerdict> classify_sites(const Arrangement& a, const Expr& expr,
                                        const std::vector<std::array<std::uint32_t, 2>>& sites,
                                        int threads, bool both_sides, const std::vector<std::int8_t>& axes) {
  const Box bounds = a.bvh.bounds();
  // Up the axis whose top of the box the site is nearest to (a thin plate's
  // thickness, not its width with a row of holes across it).
  auto axis_of = [&](const std::array<std::uint32_t, 2>& s) {
    const Vec3 x = (a.approx3(s[0]) + a.approx3(s[1]) * 2.0) * (1.0 / 3);
    int best = 2;
    double least = bounds.hi[2] - x[2];
    for (int k = 1; k >= 0; --k)
      if (bounds.hi[k] - x[k] < least) least = bounds.hi[k] - x[k], best = k;
    return best;
  };
  std::vector<std::vector<SiteVerdict>> parts = parallel_ranges<std::vector<SiteVerdict>>(
      sites.size(), threads, [&](std::size_t lo, std::size_t hi, std::vector<SiteVerdict>& part) {
        RayCaster rays(a);
        Windings w;
        Selector selector(expr, a.operands);
        for (std::size_t k = lo; k < hi; ++k) {
          const int first = axes.empty() ? axis_of(sites[k]) : axes[k];
          rays.cast_free(sites[k][0], sites[k][1], w, first);
          const auto [in, around] = selector.at_point(w);
          SiteVerdict v{in, around, false, static_cast<std::int8_t>(first)};
          // Shifted both ways along each axis: two sides that differ are the two
          // sides of a face of the result through the point.
          for (int axis = 0; axis < 3 && both_sides && !v.on_face; ++axis)
            for (int dir : {1, -1}) {
              if (axis == first && dir == 1) continue;
              rays.cast_free(sites[k][0], sites[k][1], w, axis, dir);
              v.on_face |= selector.at_point(w).second != around;
            }
          part.push_back(v);
        }
      });
  std::vector<SiteVerdict> all;
  all.reserve(sites.size());
  for (auto& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

}  // namespace cellforge::boolean
