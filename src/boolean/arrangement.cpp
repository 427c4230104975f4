// Stages 1 and 2 of the Boolean (arrangement.h): exact evaluation of implicit points,
// the pair tests, clusters of coplanar overlapping triangles, and the cutting of a
// cluster into convex pieces, which split.cpp falls back to where cutting along the
// segments alone would make a face pass a point twice (Options::convex_split: always).
//
// Convex cutting. A cluster starts as its triangle (or, with several triangles, as their
// bounding box in (u, v)); every segment that must become an edge (the cluster's
// triangle edges, and the traces of the triangles that cross it) cuts each convex
// piece whose interior it meets along its whole line through that piece. So pieces
// stay convex and every vertex is the meeting of two lines; the extra edges this
// makes where a segment stops inside a piece separate pieces with the same
// classification and go again in the merge. Points found on a line are recorded with
// the line's global key, so that edges lying on one 3D line get every vertex on it
// (no T-junctions) when the result is built.
#include "boolean/arrangement.h"
#include "boolean/parallel.h"

#include <algorithm>
#include <cassert>
#include <mutex>
#include <numeric>
#include <optional>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"

namespace cellforge::boolean {

namespace {

constexpr std::uint64_t kEdgeTag = 1ull << 63;

std::uint64_t ordered(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

int dominant_axis(Vec3 n) {
  const double x = std::abs(n.x), y = std::abs(n.y), z = std::abs(n.z);
  return x >= y && x >= z ? 0 : (y >= z ? 1 : 2);
}

}  // namespace

// ---------------------------------------------------------------- evaluation

namespace {

template <class T>
H3<T> lift(const Arrangement& A, const Cluster& c, const H2<T>& h) {
  const Tri& r = A.tris[c.ref];
  const V3<T> n = plane_normal<T>(A.pos[r.v[0]], A.pos[r.v[1]], A.pos[r.v[2]]);
  const T d = dot(n, vec<T>(A.pos[r.v[0]]));
  const int k = c.k, i = (k + 1) % 3, j = (k + 2) % 3;
  H3<T> out;
  out.c[i] = h.u * n[k];
  out.c[j] = h.v * n[k];
  out.c[k] = d * h.w - n[i] * h.u - n[j] * h.v;
  out.c[3] = h.w * n[k];
  return out;
}

template <class T>
std::array<T, 3> line_coeffs(const Arrangement& A, const Cluster& c, const Line& l) {
  const int k = c.k, i = (k + 1) % 3, j = (k + 2) % 3;
  switch (l.kind) {
    case LineKind::kThrough: {
      const Vec3 p = A.pos[l.a], q = A.pos[l.b];
      return {T(p[j]) - T(q[j]), T(q[i]) - T(p[i]), T(p[i]) * T(q[j]) - T(p[j]) * T(q[i])};
    }
    case LineKind::kTrace: {
      const Tri& r = A.tris[c.ref];
      const Tri& o = A.tris[l.a];
      const V3<T> n = plane_normal<T>(A.pos[r.v[0]], A.pos[r.v[1]], A.pos[r.v[2]]);
      const V3<T> m = plane_normal<T>(A.pos[o.v[0]], A.pos[o.v[1]], A.pos[o.v[2]]);
      const T d = dot(n, vec<T>(A.pos[r.v[0]])), e = dot(m, vec<T>(A.pos[o.v[0]]));
      return {m[i] * n[k] - m[k] * n[i], m[j] * n[k] - m[k] * n[j], m[k] * d - e * n[k]};
    }
    case LineKind::kAxisU:
      return {T(1.0), T(0.0), T(-l.c)};
    case LineKind::kAxisV:
      return {T(0.0), T(1.0), T(-l.c)};
  }
  return {T(0.0), T(0.0), T(0.0)};
}

template <class T>
H2<T> cross2(const std::array<T, 3>& a, const std::array<T, 3>& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

template <class T>
H3<T> compute3(const Arrangement& A, const PointDef& d) {
  switch (d.kind) {
    case PointKind::kVertex:
      return explicit_point<T>(A.pos[d.a]);
    case PointKind::kLpi: {
      const Tri& t = A.tris[d.c];
      return lpi<T>(A.pos[d.a], A.pos[d.b], A.pos[t.v[0]], A.pos[t.v[1]], A.pos[t.v[2]]);
    }
    case PointKind::kCross: {
      const Cluster& c = A.clusters[d.a];
      const H2<T> h = cross2(line_coeffs<T>(A, c, c.lines()[d.b]), line_coeffs<T>(A, c, c.lines()[d.c]));
      return lift(A, c, h);
    }
    case PointKind::kMeet: {
      // X = s + tau (t - s) on line pq: with u = q - p, v = t - s in the projection
      // along k, tau = cross(u, p - s) / cross(u, v).
      const auto [si, ti, k] = A.meets[d.c];
      const int i = (static_cast<int>(k) + 1) % 3, j = (static_cast<int>(k) + 2) % 3;
      const V3<T> p = vec<T>(A.pos[d.a]), q = vec<T>(A.pos[d.b]);
      const V3<T> s = vec<T>(A.pos[si]), t = vec<T>(A.pos[ti]);
      const V3<T> u = sub(q, p), v = sub(t, s), ps = sub(p, s);
      const T den = u[i] * v[j] - u[j] * v[i];
      const T num = u[i] * ps[j] - u[j] * ps[i];
      H3<T> out;
      for (int a = 0; a < 3; ++a) out.c[a] = s[a] * den + v[a] * num;
      out.c[3] = den;
      return out;
    }
  }
  return {};
}

}  // namespace

template <class T>
std::array<T, 3> Arrangement::coeffs(const Cluster& c, const Line& l) const {
  if constexpr (std::is_same_v<T, Fp>) {
    return {l.A, l.B, l.C};
  } else {
    return line_coeffs<T>(*this, c, l);
  }
}

template <class T>
H3<T> Arrangement::point3(std::uint32_t p) const {
  if (p < pos.size()) return explicit_point<T>(pos[p]);
  if constexpr (std::is_same_v<T, Fp>) {
    return h3f[p - pos.size()];
  } else if constexpr (std::is_same_v<T, Dd>) {
    {
      std::shared_lock read(*exact3_lock);
      auto it = near3.find(p);
      if (it != near3.end()) return it->second;
    }
    const H3<T> h = compute3<T>(*this, points[p - pos.size()]);
    std::unique_lock write(*exact3_lock);
    near3.emplace(p, h);
    return h;
  } else {
    {
      std::shared_lock read(*exact3_lock);
      auto it = exact3.find(p);
      if (it != exact3.end()) return it->second;
    }
    H3<T> h = compute3<T>(*this, points[p - pos.size()]);
    std::unique_lock write(*exact3_lock);
    exact3.emplace(p, h);
    return h;
  }
}

template <class T>
H2<T> Arrangement::point2(const Cluster& c, std::uint32_t p) const {
  if (p >= pos.size()) {
    const PointDef& d = points[p - pos.size()];
    if (d.kind == PointKind::kCross && &clusters[d.a] == &c) {
      if constexpr (std::is_same_v<T, Fp>) {
        return h2f[p - pos.size()];
      } else {
        auto& cache = [&]() -> auto& {
          if constexpr (std::is_same_v<T, Dd>) return near2; else return exact2;
        }();
        {
          std::shared_lock read(*exact3_lock);
          auto it = cache.find(p);
          if (it != cache.end()) return it->second;
        }
        const H2<T> h = cross2(coeffs<T>(c, c.lines()[d.b]), coeffs<T>(c, c.lines()[d.c]));
        std::unique_lock write(*exact3_lock);
        cache.emplace(p, h);
        return h;
      }
    }
  }
  return projected(point3<T>(p), c.k);
}

template <class T>
H3<T> Arrangement::rep3(const RepPoint& r) const {
  Cluster lone;
  const Cluster& c = cluster(r.cluster, lone);
  const H2<T> a = point2<T>(c, r.p[0]), b = point2<T>(c, r.p[1]), d = point2<T>(c, r.p[2]);
  const T bd = b.w * d.w, ad = a.w * d.w, ab = a.w * b.w;
  const H2<T> sum{a.u * bd + b.u * ad + d.u * ab, a.v * bd + b.v * ad + d.v * ab,
                  T(3.0) * a.w * bd};
  return lift(*this, c, sum);
}

template H3<Fp> Arrangement::rep3<Fp>(const RepPoint&) const;
template H3<Dd> Arrangement::rep3<Dd>(const RepPoint&) const;
template H3<Dd> Arrangement::point3<Dd>(std::uint32_t) const;
template H3<Dyadic> Arrangement::rep3<Dyadic>(const RepPoint&) const;
template H3<Fp> Arrangement::point3<Fp>(std::uint32_t) const;
template H3<Dyadic> Arrangement::point3<Dyadic>(std::uint32_t) const;

// ---------------------------------------------------------------- predicates

int Arrangement::w3_sign(std::uint32_t p) const {
  if (p < pos.size()) return 1;
  return decide([&]<class T>() { return point3<T>(p).c[3]; });
}

int Arrangement::w2_sign(const Cluster& c, std::uint32_t p) const {
  if (p < pos.size()) return 1;
  return decide([&]<class T>() { return point2<T>(c, p).w; });
}

std::span<const std::uint32_t> Arrangement::plane_vertices(const Tri& t) const {
  const SoupFace& f = faces[t.input_face];
  if (f.planar && f.quad) return loops_of(f)[0];  // the loops stay while this is asked
  return t.v;
}

int Arrangement::side(const Cluster& c, const Line& l, std::uint32_t p) const {
  // An input vertex on the plane a trace traces.
  auto on_traced_plane = [&](std::uint32_t v) {
    const auto on = plane_vertices(tris[l.a]);
    return std::find(on.begin(), on.end(), v) != on.end();
  };
  // Points on the line by construction (every point of a cluster lies in its plane):
  if (p >= pos.size()) {
    const PointDef& d = points[p - pos.size()];
    const auto li = static_cast<std::uint32_t>(&l - c.lines().data());
    // a crossing of this line, or of another trace of this line's plane;
    if (d.kind == PointKind::kCross && &clusters[d.a] == &c) {
      if (d.b == li || d.c == li) return 0;
      if (l.kind == LineKind::kTrace)
        for (std::uint32_t m : {d.b, d.c})
          if (c.lines()[m].kind == LineKind::kTrace &&
              plane_key(cluster_of[c.lines()[m].a]) == plane_key(cluster_of[l.a]))
            return 0;
    }
    if (d.kind == PointKind::kLpi) {
      // where this edge's segment meets a plane, or a segment meets this trace's plane;
      if (l.kind == LineKind::kThrough && ordered(l.a, l.b) == ordered(d.a, d.b)) return 0;
      if (l.kind == LineKind::kTrace && plane_key(cluster_of[l.a]) == plane_key(cluster_of[d.c])) return 0;
      // or a segment lying in this trace's plane meets this cluster's plane;
      if (l.kind == LineKind::kTrace && on_traced_plane(d.a) && on_traced_plane(d.b)) return 0;
    }
  } else if (l.kind == LineKind::kThrough && (p == l.a || p == l.b)) {
    return 0;  // an end of this edge;
  } else if (l.kind == LineKind::kTrace && on_traced_plane(p)) {
    return 0;  // a corner of the triangle (or planar quad) whose plane this traces.
  }
  const auto poly = [&]<class T>() {
    const auto L = coeffs<T>(c, l);
    const H2<T> h = point2<T>(c, p);
    return L[0] * h.u + L[1] * h.v + L[2] * h.w;
  };
  // The filter's projection once, for the side and the sign of w alike.
  const H2<Fp> hf = point2<Fp>(c, p);
  int s = sign_of(l.A * hf.u + l.B * hf.v + l.C * hf.w);
  if (const int ws = sign_of(hf.w); s != kUncertain && ws != kUncertain) return s * ws;
  if (s == kUncertain) {
    // A line u = x (or v = x) with x a known double, and a point whose coordinate
    // there is known too (the common undecided case: a point on an axis-parallel
    // line, whose zero no filter can tell): A (u - x) with A's sign known.
    if (l.fixed != 0) {
      double x = 0;
      if (known_coordinate(p, (c.k + l.fixed) % 3, x))
        return (x < l.at ? -1 : (x > l.at ? 1 : 0)) * (l.fixed == 1 ? l.sign_a : l.sign_b);
    }
    // An input vertex and the line through two: orient2d of their doubles.
    if (p < pos.size() && l.kind == LineKind::kThrough) return orient2d_projected(pos[l.a], pos[l.b], pos[p], c.k);
    // Where segment ab meets this cluster's plane, on the line through input vertices
    // e, f in it: exactly when ab and ef are coplanar (ab crosses the plane at one
    // point), an orient3d of input doubles rather than the point's exact coordinates.
    if (p >= pos.size() && l.kind == LineKind::kThrough) {
      const PointDef& d = points[p - pos.size()];
      if (d.kind == PointKind::kLpi && plane_key(cluster_of[d.c]) == plane_key(cluster_of[c.ref]) &&
          orient3d(pos[d.a], pos[d.b], pos[l.a], pos[l.b]) == 0)
        return 0;
    }
    s = decide(poly);
  }
  return s * w2_sign(c, p);
}

int Arrangement::along(const Cluster& c, const Line& l, std::uint32_t p, std::uint32_t q) const {
  if (p == q) return 0;
  const bool use_u = l.sign_b != 0;
  const int dir = use_u ? l.sign_b : -l.sign_a;
  const auto poly = [&]<class T>(const H2<T>& a, const H2<T>& b) {
    return use_u ? a.u * b.w - b.u * a.w : a.v * b.w - b.v * a.w;
  };
  // The filter on projections computed once, for the order and the signs of w alike.
  const H2<Fp> a = point2<Fp>(c, p), b = point2<Fp>(c, q);
  const int fs = sign_of(poly(a, b)), wa = sign_of(a.w), wb = sign_of(b.w);
  if (fs != kUncertain && wa != kUncertain && wb != kUncertain) return fs * wa * wb * dir;
  // Both coordinates known doubles (points on axis-parallel lines): compared as such.
  if (double x, y; known_coordinate(p, (c.k + (use_u ? 1 : 2)) % 3, x) &&
                   known_coordinate(q, (c.k + (use_u ? 1 : 2)) % 3, y))
    return (x < y ? -1 : (x > y ? 1 : 0)) * dir;
  const int s = decide([&]<class T>() { return poly(point2<T>(c, p), point2<T>(c, q)); });
  return s * w2_sign(c, p) * w2_sign(c, q) * dir;
}

int Arrangement::turn(const Cluster& c, const Line& l, const Line& m) const {
  return decide([&]<class T>() {
    const auto L = coeffs<T>(c, l);
    const auto M = coeffs<T>(c, m);
    return M[0] * L[1] - M[1] * L[0];
  });
}

int Arrangement::orient2(const Cluster& c, std::uint32_t p, std::uint32_t q,
                         std::uint32_t r) const {
  {  // the filter on projections computed once, for the turn and the signs of w alike
    const H2<Fp> a = point2<Fp>(c, p), b = point2<Fp>(c, q), d = point2<Fp>(c, r);
    const int fs = sign_of(orient2_poly(a, b, d)), wa = sign_of(a.w), wb = sign_of(b.w), wd = sign_of(d.w);
    if (fs != kUncertain && wa != kUncertain && wb != kUncertain && wd != kUncertain) return fs * wa * wb * wd;
  }
  const int s = decide([&]<class T>() {
    return orient2_poly(point2<T>(c, p), point2<T>(c, q), point2<T>(c, r));
  });
  return s * w2_sign(c, p) * w2_sign(c, q) * w2_sign(c, r);
}

bool Arrangement::known_coordinate(std::uint32_t p, int axis, double& x) const {
  auto constant = [&](std::uint32_t s, std::uint32_t t) {
    if (pos[s][axis] != pos[t][axis]) return false;
    x = pos[s][axis];
    return true;
  };
  auto perpendicular = [&](const Tri& t) {  // t's plane is `axis` = x
    return constant(t.v[0], t.v[1]) && constant(t.v[0], t.v[2]);
  };
  if (p < pos.size()) {
    x = pos[p][axis];
    return true;
  }
  const PointDef& d = points[p - pos.size()];
  switch (d.kind) {
    case PointKind::kVertex:
      x = pos[d.a][axis];
      return true;
    case PointKind::kLpi:
      return constant(d.a, d.b) || perpendicular(tris[d.c]);
    case PointKind::kCross: {
      const Cluster& c = clusters[d.a];
      if (perpendicular(tris[c.ref])) return true;
      for (std::uint32_t li : {d.b, d.c}) {
        const Line& l = c.lines()[li];
        if ((l.kind == LineKind::kAxisU && axis == (c.k + 1) % 3) ||
            (l.kind == LineKind::kAxisV && axis == (c.k + 2) % 3)) {
          x = l.c;
          return true;
        }
        if (l.kind == LineKind::kThrough && constant(l.a, l.b)) return true;
        if (l.kind == LineKind::kTrace && perpendicular(tris[l.a])) return true;
      }
      return false;
    }
    case PointKind::kMeet:
      return constant(d.a, d.b) || constant(meets[d.c][0], meets[d.c][1]);
  }
  return false;
}

int Arrangement::compare3(std::uint32_t p, std::uint32_t q, int axis) const {
  if (p == q) return 0;
  if (double a, b; known_coordinate(p, axis, a) && known_coordinate(q, axis, b))
    return a < b ? -1 : (a > b ? 1 : 0);
  const int s = decide([&]<class T>() { return compare_poly(point3<T>(p), point3<T>(q), axis); });
  return s * w3_sign(p) * w3_sign(q);
}

bool Arrangement::equal3(std::uint32_t p, std::uint32_t q) const {
  for (int axis = 0; axis < 3; ++axis)
    if (compare3(p, q, axis) != 0) return false;
  return true;
}

bool Arrangement::collinear3(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  if (a < pos.size() && b < pos.size() && c < pos.size()) return collinear3d(pos[a], pos[b], pos[c]);
  // The projection where the approximate cross product is largest first: three
  // points that are not collinear are told apart there by the filter.
  const Vec3 pa = approx3(a), u = approx3(b) - pa, v = approx3(c) - pa;
  const double n[3] = {std::fabs(u.y * v.z - u.z * v.y), std::fabs(u.z * v.x - u.x * v.z),
                       std::fabs(u.x * v.y - u.y * v.x)};
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int x, int y) { return n[x] > n[y]; });
  for (int k : order) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const int s = decide([&]<class T>() {
      const H3<T> p = point3<T>(a), q = point3<T>(b), r = point3<T>(c);
      return p.c[i] * (q.c[j] * r.c[3] - q.c[3] * r.c[j]) -
             p.c[j] * (q.c[i] * r.c[3] - q.c[3] * r.c[i]) +
             p.c[3] * (q.c[i] * r.c[j] - q.c[j] * r.c[i]);
    });
    if (s != 0) return false;
  }
  return true;
}

int Arrangement::tri_sign(const Cluster& c, std::uint32_t t) const {
  const Tri& x = tris[t];
  return orient2d_projected(pos[x.v[0]], pos[x.v[1]], pos[x.v[2]], c.k) * c.nk_sign;
}

int Arrangement::plane_side(std::uint32_t t, std::uint32_t p) const {
  const Tri& tri = tris[t];
  if (p < pos.size()) return orient3d(pos[tri.v[0]], pos[tri.v[1]], pos[tri.v[2]], pos[p]);
  const int s = decide([&]<class T>() {
    return plane_side_poly<T>(pos[tri.v[0]], pos[tri.v[1]], pos[tri.v[2]], point3<T>(p));
  });
  return s * w3_sign(p);
}

namespace {

// x = X / W with a bound on its error; infinite when W's sign is uncertain.
double quotient(Fp x, Fp w, double& err) {
  if (!(std::abs(w.v) > w.e)) {
    err = 1e300;
    return 0;
  }
  const double q = x.v / w.v;
  err = ((x.e + std::abs(q) * w.e) / (std::abs(w.v) - w.e) + std::abs(q) * 4 * kUnit) * 1.01;
  return q;
}

}  // namespace

Vec3 Arrangement::approx3(std::uint32_t p, double* err) const {
  if (p < pos.size()) {
    if (err) *err = 0;
    return pos[p];
  }
  const H3<Fp>& h = h3f[p - pos.size()];
  if (!(std::abs(h.c[3].v) > h.c[3].e * 0x1p20)) {  // W not known well in doubles
    const H3<Dyadic> x = point3<Dyadic>(p);
    const double w = x.c[3].to_double();
    const Vec3 r{x.c[0].to_double() / w, x.c[1].to_double() / w, x.c[2].to_double() / w};
    if (err) *err = std::max({std::abs(r.x), std::abs(r.y), std::abs(r.z)}) * 8 * kUnit + 1e-300;
    return r;
  }
  double e[3];
  const Vec3 r{quotient(h.c[0], h.c[3], e[0]), quotient(h.c[1], h.c[3], e[1]),
               quotient(h.c[2], h.c[3], e[2])};
  if (err) *err = std::max({e[0], e[1], e[2]});
  return r;
}

bool Arrangement::rounds_exactly(std::uint32_t p) const {
  if (p < pos.size()) return true;
  const H3<Fp>& h = h3f[p - pos.size()];
  const bool w_exact = h.c[3].e == 0 && h.c[3].v != 0;
  for (int i = 0; i < 3; ++i) {
    // A coordinate known from how the point was made (the result's position takes it).
    if (double known = 0; known_coordinate(p, i, known)) continue;
    if (!w_exact || h.c[i].e != 0) return false;
    const double x = h.c[i].v / h.c[3].v;
    if (x * h.c[3].v != h.c[i].v || std::fma(x, h.c[3].v, -h.c[i].v) != 0) return false;
  }
  return true;
}

bool Arrangement::coordinate_is(std::uint32_t p, int axis, double x) const {
  if (p < pos.size()) return pos[p][axis] == x;
  return decide([&]<class T>() {
           const H3<T> h = point3<T>(p);
           return h.c[axis] - T(x) * h.c[3];
         }) == 0;
}

void Arrangement::approx2(const Cluster& c, std::uint32_t p, double& u, double& v,
                          double& err) const {
  const H2<Fp> h = point2<Fp>(c, p);
  if (!(std::abs(h.w.v) > h.w.e * 0x1p20)) {  // W not known well in doubles
    const H2<Dyadic> x = point2<Dyadic>(c, p);
    const double w = x.w.to_double();
    u = x.u.to_double() / w;
    v = x.v.to_double() / w;
    err = std::max(std::abs(u), std::abs(v)) * 8 * kUnit + 1e-300;
    return;
  }
  double eu, ev;
  u = quotient(h.u, h.w, eu);
  v = quotient(h.v, h.w, ev);
  err = std::max(eu, ev);
}

// ---------------------------------------------------------------- keys

std::uint32_t Arrangement::fresh_key() {
  key_parent.push_back(static_cast<std::uint32_t>(key_parent.size()));
  return key_parent.back();
}

std::uint32_t Arrangement::edge_key(std::uint32_t p, std::uint32_t q) {
  auto [it, fresh] = key_ids.try_emplace(kEdgeTag | ordered(p, q), 0);
  if (fresh) {
    it->second = fresh_key();
    if (has_edge_key.size() < pos.size()) has_edge_key.resize(pos.size(), 0);
    for (std::uint32_t v : {p, q})
      if (v < has_edge_key.size()) has_edge_key[v] = 1;
  }
  return it->second;
}

void Arrangement::find_alone_vertices() {
  constexpr std::uint32_t kUnset = kInvalidIndex - 1;
  alone_in.assign(pos.size(), kUnset);
  for (std::uint32_t t = 0; t < tris.size(); ++t)
    for (std::uint32_t v : tris[t].v) {
      std::uint32_t& o = alone_in[v];
      if (near_other[t] || (o != kUnset && o != tris[t].operand)) {
        o = kInvalidIndex;
      } else if (o == kUnset) {
        o = tris[t].operand;
      }
    }
  for (std::uint32_t& o : alone_in)
    if (o == kUnset) o = kInvalidIndex;
}

bool Arrangement::is_triangle_edge(std::uint32_t p, std::uint32_t q) const {
  return !edge_uses.uses(p, q).empty();
}

bool Arrangement::is_contact_edge(std::uint32_t p, std::uint32_t q) const {
  return std::binary_search(contact_edges.begin(), contact_edges.end(), ordered(p, q));
}

std::uint32_t Arrangement::find_edge_key(std::uint32_t p, std::uint32_t q) const {
  if ((p < has_edge_key.size() && !has_edge_key[p]) || (q < has_edge_key.size() && !has_edge_key[q]) ||
      (has_edge_key.empty() && p < pos.size() && q < pos.size()))
    return kInvalidIndex;
  const std::uint32_t* key = key_ids.find(kEdgeTag | ordered(p, q));
  return key ? *key : kInvalidIndex;
}

std::uint32_t Arrangement::pair_key(std::uint32_t c1, std::uint32_t c2) {
  auto [it, fresh] = key_ids.try_emplace(ordered(c1, c2), 0);
  if (fresh) it->second = fresh_key();
  return it->second;
}

std::uint32_t Arrangement::line_root(std::uint32_t k) {
  while (key_parent[k] != k) k = key_parent[k] = key_parent[key_parent[k]];
  return k;
}

void Arrangement::line_union(std::uint32_t a, std::uint32_t b) {
  a = line_root(a);
  b = line_root(b);
  if (a != b) key_parent[std::max(a, b)] = std::min(a, b);
}

// ---------------------------------------------------------------- construction

Arrangement::Arrangement(std::vector<Vec3> positions, std::vector<Tri> triangles,
                         std::vector<SoupFace> soup_faces, LoopTable loops, std::uint32_t n_operands,
                         std::vector<WireSeg> wire_list, std::vector<char> embedded_operands,
                         std::vector<std::array<std::uint32_t, 2>> joins, EdgeUseTable edges, int threads)
    : pos(std::move(positions)),
      tris(std::move(triangles)),
      faces(std::move(soup_faces)),
      loop_table(std::move(loops)),
      wires(std::move(wire_list)),
      operands(n_operands),
      embedded(std::move(embedded_operands)),
      plane_joins(std::move(joins)),
      edge_uses(std::move(edges)) {
  embedded.resize(operands, 0);
  // Made unset and filled on the threads (their pages first touched there).
  RawVector<FloatBox> boxes(tris.size());
  RawVector<std::uint32_t> groups(tris.size());  // an embedded operand's triangles: one group
  parallel_ranges<char>(tris.size(), threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t t = lo; t < hi; ++t) {
      Box b;
      for (std::uint32_t v : tris[t].v) b.add(pos[v]);
      boxes[t] = FloatBox::around(b);
      groups[t] = embedded[tris[t].operand] ? tris[t].operand : Bvh::kNoGroup;
    }
  });
  bvh = Bvh(std::move(boxes), std::move(groups), threads);
  wire_boxes.resize(wires.size());
  for (std::size_t w = 0; w < wires.size(); ++w) {
    wire_boxes[w].add(pos[wires[w].p]);
    wire_boxes[w].add(pos[wires[w].q]);
  }
  if (!wires.empty()) wire_bvh = Bvh(wire_boxes);
}

std::uint32_t Arrangement::new_point(PointDef def, const Cluster* home) {
  const auto id = static_cast<std::uint32_t>(pos.size() + points.size());
  points.push_back(def);
  h3f.push_back(compute3<Fp>(*this, def));
  if (home) {
    h2f.push_back(cross2(coeffs<Fp>(*home, home->lines()[def.b]), coeffs<Fp>(*home, home->lines()[def.c])));
  } else {
    h2f.push_back({});
  }
  return id;
}

namespace {

}  // namespace

std::uint32_t Arrangement::lpi_point(std::uint32_t p, std::uint32_t q, std::uint32_t cluster) {
  if (p > q) std::swap(p, q);
  const std::uint32_t plane = plane_key(cluster);
  auto [it, fresh] = lpi_ids_.try_emplace({ordered(p, q), plane}, 0);
  if (fresh) it->second = new_point({PointKind::kLpi, p, q, cluster_ref(plane)}, nullptr);
  return it->second;
}

std::uint32_t Arrangement::crossing_point(std::uint32_t ci, std::uint32_t li, std::uint32_t m) {
  Cluster& c = clusters[ci];
  const Line* through = &c.lines()[li];
  const Line* trace = &c.lines()[m];
  if (through->kind != LineKind::kThrough) std::swap(through, trace);
  if (through->kind == LineKind::kThrough && trace->kind == LineKind::kTrace)
    return lpi_point(through->a, through->b, cluster_of[trace->a]);
  // The traces of two planes that share two input vertices p, q (neighbours in a mesh)
  // cross where pq's line meets this plane: that edge's lpi point, which the clusters
  // of the two triangles find on their common edge too. As a crossing it would be a
  // second id for the point, told apart only by an exact comparison. A planar quad's
  // four vertices all lie on its triangles' plane.
  if (through->kind == LineKind::kTrace && trace->kind == LineKind::kTrace) {
    const auto x = plane_vertices(tris[through->a]), y = plane_vertices(tris[trace->a]);
    std::uint32_t common[2], n = 0;
    for (std::uint32_t v : x)
      if (n < 2 && std::find(y.begin(), y.end(), v) != y.end()) common[n++] = v;
    if (n == 2) return lpi_point(common[0], common[1], ci);
  }
  return new_point({PointKind::kCross, ci, std::min(li, m), std::max(li, m)}, &c);
}

std::uint32_t Arrangement::edge_line(Cluster& c, FlatMap<std::uint32_t, std::uint32_t>& made,
                                     std::uint32_t p, std::uint32_t q) {
  const std::uint32_t key = edge_key(p, q);
  auto [it, fresh] = made.try_emplace(key, 0);
  if (fresh) {
    Line l = Line::make(LineKind::kThrough, p, q);
    l.key = key;
    it->second = add_line(c, std::move(l));
  }
  return it->second;
}

std::uint32_t Arrangement::add_line(Cluster& c, Line l) {
  const auto co = line_coeffs<Fp>(*this, c, l);
  l.A = co[0];
  l.B = co[1];
  l.C = co[2];
  int sa = sign_of(l.A), sb = sign_of(l.B);
  if (sa == kUncertain) sa = decide([&]<class T>() { return line_coeffs<T>(*this, c, l)[0]; });
  if (sb == kUncertain) sb = decide([&]<class T>() { return line_coeffs<T>(*this, c, l)[1]; });
  l.sign_a = static_cast<std::int8_t>(sa);
  l.sign_b = static_cast<std::int8_t>(sb);
  // A u + C = 0 (B exactly 0) or B v + C = 0: the double it fixes, where one is known.
  if (sa == 0 || sb == 0) {
    const int ax = (c.k + (sb == 0 ? 1 : 2)) % 3;
    bool known = false;
    switch (l.kind) {
      case LineKind::kThrough:  // B (or A) is the ends' difference there: exactly 0
        known = true;
        l.at = pos[l.a][ax];
        break;
      case LineKind::kTrace: {
        const Tri& o = tris[l.a];
        known = pos[o.v[0]][ax] == pos[o.v[1]][ax] && pos[o.v[0]][ax] == pos[o.v[2]][ax];
        if (known) l.at = pos[o.v[0]][ax];
        break;
      }
      case LineKind::kAxisU:
      case LineKind::kAxisV:
        known = true;
        l.at = l.c;
        break;
    }
    if (known) l.fixed = static_cast<std::int8_t>(sb == 0 ? 1 : 2);
  }
  c.lines().push_back(std::move(l));
  return static_cast<std::uint32_t>(c.lines().size() - 1);
}

// ---------------------------------------------------------------- stage 1

namespace {

// Vertices of triangle b on the plane of a (o[k] == 0) that lie strictly inside an
// edge of a: the point must become a vertex of that edge.
template <class Record>
void vertices_on_edges(const Arrangement& A, const Tri& a, const Tri& b, const int o[3],
                       Record record) {
  for (int k = 0; k < 3; ++k) {
    if (o[k] != 0) continue;
    const std::uint32_t v = b.v[k];
    // A corner of a (the soup has no degenerate triangle) is on no edge of a.
    if (v == a.v[0] || v == a.v[1] || v == a.v[2]) continue;
    const Vec3 pv = A.pos[v];
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t p = a.v[e], q = a.v[(e + 1) % 3];
      const Vec3 pp = A.pos[p], pq = A.pos[q];
      // A point of segment pq lies in its box (exactly: coordinates are compared).
      bool in_box = true;
      for (int d = 0; d < 3; ++d) in_box &= std::min(pp[d], pq[d]) <= pv[d] && pv[d] <= std::max(pp[d], pq[d]);
      if (!in_box || !collinear3d(pp, pq, pv)) continue;
      if (compare_along(pp, pq, pp, pv) > 0 && compare_along(pp, pq, pv, pq) > 0) record(p, q, v);
    }
  }
}

// Coplanar triangles whose interiors overlap (no edge line of either separates them).
bool coplanar_overlap(const Arrangement& A, const Tri& a, const Tri& b, int k) {
  const Tri* t[2] = {&a, &b};
  for (int s = 0; s < 2; ++s) {
    const Tri& x = *t[s];
    const Tri& y = *t[1 - s];
    const int o = orient2d_projected(A.pos[x.v[0]], A.pos[x.v[1]], A.pos[x.v[2]], k);
    for (int e = 0; e < 3; ++e) {
      const Vec3 p = A.pos[x.v[e]], q = A.pos[x.v[(e + 1) % 3]];
      bool separated = true;
      for (std::uint32_t v : y.v)
        if (orient2d_projected(p, q, A.pos[v], k) * o > 0) separated = false;
      if (separated) return false;
    }
  }
  return true;
}

}  // namespace

// orient3d of y's corners against triangle x's plane; 0 without arithmetic for x's own
// corners (the exact stage would run for every neighbour in a mesh), and the fourth
// vertex of x's quad known from the quad's fold (near-planar quads would each go to
// the exact stage).
void Arrangement::sides_of(const Tri& x, const Tri& y, int o[3]) const {
  const std::size_t t = static_cast<std::size_t>(&x - tris.data());
  std::optional<PlaneSide> plane;  // at the first corner that needs arithmetic
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t v = y.v[k];
    if (v == x.v[0] || v == x.v[1] || v == x.v[2]) {
      o[k] = 0;
    } else if (v == quad_other[t]) {
      o[k] = quad_side[t];
    } else {
      if (!plane) plane.emplace(pos[x.v[0]], pos[x.v[1]], pos[x.v[2]]);
      o[k] = (*plane)(pos[v]);
    }
  }
}

// Whether segment pq, in the plane of triangle x, meets x's interior (closed: x's
// closed set): no line of x's edges and not the line pq itself separates them (exact,
// in x's dominant projection).
bool Arrangement::segment_enters(const Tri& x, std::uint32_t p, std::uint32_t q, bool closed) const {
  const Vec3 a = pos[x.v[0]], b = pos[x.v[1]], c = pos[x.v[2]];
  const int k = dominant_axis(cross(b - a, c - a));
  const int o = orient2d_projected(a, b, c, k);
  const Vec3 pp = pos[p], pq = pos[q];
  for (int e = 0; e < 3; ++e) {
    const Vec3 s = pos[x.v[e]], t = pos[x.v[(e + 1) % 3]];
    const int sp = orient2d_projected(s, t, pp, k) * o, sq = orient2d_projected(s, t, pq, k) * o;
    if (closed ? (sp < 0 && sq < 0) : (sp <= 0 && sq <= 0)) return false;
  }
  int above = 0, below = 0;
  for (const Vec3 v : {a, b, c}) {
    const int s = orient2d_projected(pp, pq, v, k);
    above += s > 0;
    below += s < 0;
  }
  return closed ? above < 3 && below < 3 : above > 0 && below > 0;
}

// What the exact test of one candidate pair found, gathered per range of pairs so
// that ranges can be tested on threads and applied in order (the same result at any
// thread count).
struct Arrangement::PairEvents {
  std::vector<std::array<std::uint32_t, 3>> edge_points;  // edge p, q; the vertex on it
  std::vector<std::array<std::uint32_t, 2>> coplanar, same_plane;  // pairs to join
  std::vector<std::array<std::uint32_t, 2>> touching;  // triangle, vertex on its plane
  std::vector<std::array<std::uint32_t, 3>> crossing;  // i, j, which of them is cut
  std::vector<std::uint64_t> contact_edges;            // Arrangement::contact_edges
  std::vector<std::uint32_t> near_other;               // triangles of pairs of two operands
  std::size_t tested = 0, hit = 0;
};

void Arrangement::test_pair(std::uint32_t i, std::uint32_t j, PairEvents& ev) const {
  ++ev.tested;
  if (tris[i].operand != tris[j].operand) {
    ev.near_other.push_back(i);
    ev.near_other.push_back(j);
  }
  auto record = [&](std::uint32_t p, std::uint32_t q, std::uint32_t v) { ev.edge_points.push_back({p, q, v}); };
  const Tri& a = tris[i];
  const Tri& b = tris[j];
  const Vec3 a0 = pos[a.v[0]], a1 = pos[a.v[1]], a2 = pos[a.v[2]];
  int shared = 0;
  for (std::uint32_t v : b.v) shared += v == a.v[0] || v == a.v[1] || v == a.v[2];
  // Two tiles of one face that share an edge lie on either side of it: they meet in
  // it alone, and they are coplanar exactly when the face is planar (decided once).
  // Tiles of one strictly convex face meet only in their shared edges and corners.
  if (a.input_face == b.input_face && faces[a.input_face].simple) return;
  const bool one_face = a.input_face == b.input_face && shared == 2;
  if (one_face && !faces[a.input_face].planar) return;
  int ob[3] = {0, 0, 0}, pos_b = 0, neg_b = 0;
  if (!one_face) sides_of(a, b, ob);
  for (int k = 0; k < 3; ++k) {
    pos_b += ob[k] > 0;
    neg_b += ob[k] < 0;
  }
  if (pos_b == 3 || neg_b == 3) return;
  // Neighbours in one mesh, the common case: sharing an edge and not coplanar, they
  // meet in that edge alone; sharing a corner with the rest of b on one side of a's
  // plane, in that corner alone. Either is each one's own boundary already.
  if ((shared == 2 && pos_b + neg_b == 1) || (shared == 1 && (pos_b == 2 || neg_b == 2))) return;
  if (pos_b == 0 && neg_b == 0) {
    ev.same_plane.push_back({i, j});
    int oa[3] = {0, 0, 0};
    vertices_on_edges(*this, a, b, ob, record);
    vertices_on_edges(*this, b, a, oa, record);
    const int k = dominant_axis(cross(a1 - a0, a2 - a0));
    if (coplanar_overlap(*this, a, b, k)) {
      ev.coplanar.push_back({i, j});
      ++ev.hit;
    }
    return;
  }
  int oa[3], pos_a = 0, neg_a = 0;
  sides_of(b, a, oa);
  for (int k = 0; k < 3; ++k) {
    pos_a += oa[k] > 0;
    neg_a += oa[k] < 0;
  }
  if (pos_a == 3 || neg_a == 3) return;
  if ((shared == 2 && pos_a + neg_a == 1) || (shared == 1 && (pos_a == 2 || neg_a == 2))) return;
  if (shared == 0 && oa[0] * oa[1] * oa[2] != 0 && ob[0] * ob[1] * ob[2] != 0) {
    const Vec3 pa[3] = {a0, a1, a2}, pb[3] = {pos[b.v[0]], pos[b.v[1]], pos[b.v[2]]};
    if (straddling_triangles_apart(pa, pb, oa, ob)) return;
  }
  vertices_on_edges(*this, a, b, ob, record);
  vertices_on_edges(*this, b, a, oa, record);
  // b cuts a's cluster where it crosses a's plane, or where one of its edges lies in
  // that plane (the surfaces meet along the edge even when b stays on one side);
  // an edge that a shares is a's own boundary already.
  auto cuts = [&](const Tri& x, const Tri& y, const int o[3], int pos_y, int neg_y) {
    if (pos_y > 0 && neg_y > 0) return true;
    if (pos_y + neg_y != 1) return false;
    std::uint32_t e[2];
    int n = 0;
    for (int k = 0; k < 3; ++k)
      if (o[k] == 0) e[n++] = y.v[k];
    // Along x's side too, when that side may be a diagonal of x's planar face.
    const SoupFace& f = faces[x.input_face];
    return segment_enters(x, e[0], e[1], f.planar && f.tris.size() > 1);
  };
  // A triangle resting on the other's plane by one corner, the rest on one side, meets
  // the other in that corner at most: the other's trace cuts nothing of it (the touch
  // below records the corner).
  auto corner_only = [](int pos, int neg) { return pos + neg == 2 && (pos == 0 || neg == 0); };
  const bool cut_a = !corner_only(pos_a, neg_a) && cuts(a, b, ob, pos_b, neg_b);
  const bool cut_b = !corner_only(pos_b, neg_b) && cuts(b, a, oa, pos_a, neg_a);
  // An edge of y in x's plane that meets x (runs inside it, for one operand's own
  // triangles, whose edges meet their neighbours' planes all along a mesh): y's
  // surface may cross x's plane there, so the triangles on either side of the edge
  // are classified apart.
  auto contact = [&](const Tri& x, const Tri& y, const int o[3], int pos_y, int neg_y) {
    if (pos_y + neg_y != 1) return;
    std::uint32_t e[2];
    int n = 0;
    for (int k = 0; k < 3; ++k)
      if (o[k] == 0) e[n++] = y.v[k];
    if (segment_enters(x, e[0], e[1], x.operand != y.operand)) ev.contact_edges.push_back(ordered(e[0], e[1]));
  };
  contact(a, b, ob, pos_b, neg_b);
  contact(b, a, oa, pos_a, neg_a);
  // A corner of one resting on the other's plane, the rest on one side: a point
  // where the surfaces touch, a vertex of the other's arrangement if inside it.
  auto touch = [&](std::uint32_t x, const Tri& y, const int o[3], int pos_y, int neg_y) {
    if (pos_y + neg_y != 2 || (pos_y != 0 && neg_y != 0)) return;
    for (int k = 0; k < 3; ++k)
      if (o[k] == 0) ev.touching.push_back({x, y.v[k]});
  };
  touch(i, b, ob, pos_b, neg_b);
  touch(j, a, oa, pos_a, neg_a);
  if (!cut_a && !cut_b) return;
  ev.crossing.push_back({i, j, static_cast<std::uint32_t>(cut_a) | (static_cast<std::uint32_t>(cut_b) << 1)});
  ++ev.hit;
}

// Enough pieces of the pair enumeration that two or more threads share them evenly.
constexpr std::size_t kPairPieces = 256;

void Arrangement::intersect(int threads) {
  // Each quad tile's test of the quad's fourth vertex: the quad's fold sign times the
  // parity of the permutation taking the quad's loop to (tile, vertex), since orient3d
  // alternates in its four arguments.
  quad_other.assign(tris.size(), kInvalidIndex);
  quad_side.assign(tris.size(), 0);
  for (const SoupFace& f : faces) {
    if (!f.quad) continue;
    const auto quad = loops_of(f)[0];
    for (std::uint32_t t : f.tris) {
      const Tri& x = tris[t];
      std::uint32_t w = kInvalidIndex;
      for (std::uint32_t q : quad)
        if (q != x.v[0] && q != x.v[1] && q != x.v[2]) w = q;
      const std::uint32_t order[4] = {x.v[0], x.v[1], x.v[2], w};
      int at[4], found = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
          if (order[i] == quad[j]) {
            at[i] = j;
            ++found;
          }
      if (found != 4) continue;  // a tile not on three of the quad's corners
      int inversions = 0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) inversions += at[i] > at[j];
      quad_other[t] = w;
      quad_side[t] = static_cast<std::int8_t>(inversions % 2 == 0 ? f.fold : -f.fold);
    }
  }
  std::vector<std::array<std::uint32_t, 3>> crossing;  // i, j, which of them is cut
  std::vector<std::array<std::uint32_t, 2>> touching;  // triangle, vertex on its plane
  UnionFind coplanar(tris.size());
  UnionFind same_plane(tris.size());
  // Tiles of a planar face lie in one plane (those of a strictly convex face are never
  // tested as pairs, nor any two of an embedded operand's triangles).
  for (const SoupFace& f : faces)
    if (f.simple || (f.planar && embedded[f.operand]))
      for (std::uint32_t t : f.tris) same_plane.unite(f.tris[0], t);
  for (auto [x, y] : plane_joins) same_plane.unite(x, y);
  // The candidate pairs in pieces of the tree, tested on threads, their events
  // applied in the tree's order (the same at any thread count).
  const std::vector<Bvh::Piece> pieces = bvh.pair_pieces(kPairPieces);
  std::vector<PairEvents> events =
      parallel_jobs<PairEvents>(pieces.size(), threads, [&](std::size_t k, PairEvents& out) {
        bvh.pairs(pieces[k], [&](std::uint32_t i, std::uint32_t j) { test_pair(i, j, out); });
      });
  for (const PairEvents& e : events) {
    pairs_tested += e.tested;
    pairs_hit += e.hit;
    for (auto [p, q, v] : e.edge_points) edge_points.push_back({edge_key(p, q), v});
    for (auto [x, y] : e.coplanar) coplanar.unite(x, y);
    for (auto [x, y] : e.same_plane) same_plane.unite(x, y);
    touching.insert(touching.end(), e.touching.begin(), e.touching.end());
    crossing.insert(crossing.end(), e.crossing.begin(), e.crossing.end());
    contact_edges.insert(contact_edges.end(), e.contact_edges.begin(), e.contact_edges.end());
  }
  near_other.assign(tris.size(), 0);
  for (const PairEvents& e : events)
    for (std::uint32_t t : e.near_other) near_other[t] = 1;

  std::sort(contact_edges.begin(), contact_edges.end());
  contact_edges.erase(std::unique(contact_edges.begin(), contact_edges.end()), contact_edges.end());

  // Clusters: components of the coplanar-overlap relation, numbered by their
  // smallest triangle. Only triangles that some event names get a record: the
  // others stay lone (kLoneCluster | t).
  std::vector<char> recorded(tris.size(), 0);
  for (const PairEvents& e : events) {
    for (auto [x, y] : e.coplanar) recorded[x] = recorded[y] = 1;
    for (auto [x, y] : e.same_plane) recorded[x] = recorded[y] = 1;
  }
  for (auto [t, v] : touching) recorded[t] = 1;
  for (auto [i, j, which] : crossing) recorded[i] = recorded[j] = 1;
  // A plane's triangles (same_plane) are recorded together, so that they share one
  // plane key (plane_of).
  {
    std::vector<char> root_recorded(tris.size(), 0);
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      if (recorded[t]) root_recorded[same_plane.find(t)] = 1;
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      if (root_recorded[same_plane.find(t)]) recorded[t] = 1;
  }
  std::vector<PairEvents>().swap(events);
  cluster_of.resize(tris.size());
  for (std::uint32_t t = 0; t < tris.size(); ++t) cluster_of[t] = kLoneCluster | t;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    if (!recorded[t]) continue;
    const std::uint32_t r = coplanar.find(t);
    if (is_lone(cluster_of[r])) {
      cluster_of[r] = static_cast<std::uint32_t>(clusters.size());
      clusters.emplace_back();
    }
    cluster_of[t] = cluster_of[r];
    clusters[cluster_of[t]].add_tri(t);
  }
  for (Cluster& c : clusters) {
    c.ref = c.tris()[0];
    orient_cluster(c);
    c.touched = c.tris().size() > 1;
  }
  // A plane's clusters take the cluster of its smallest triangle (whatever the
  // order of the joins was).
  plane_of.resize(clusters.size());
  {
    FlatMap<std::uint32_t, std::uint32_t> first;  // by same_plane root
    for (std::uint32_t t = 0; t < tris.size(); ++t) {
      if (!recorded[t]) continue;
      auto [it, fresh] = first.try_emplace(same_plane.find(t), cluster_of[t]);
      plane_of[cluster_of[t]] = it->second;
    }
  }
  std::vector<char>().swap(recorded);

  for (auto [t, v] : touching) {
    const Tri& x = tris[t];
    const Vec3 p0 = pos[x.v[0]], p1 = pos[x.v[1]], p2 = pos[x.v[2]];
    const int k = clusters[cluster_of[t]].k;
    const int o = orient2d_projected(p0, p1, p2, k);
    if (v == x.v[0] || v == x.v[1] || v == x.v[2]) continue;
    if (orient2d_projected(p0, p1, pos[v], k) * o > 0 && orient2d_projected(p1, p2, pos[v], k) * o > 0 &&
        orient2d_projected(p2, p0, pos[v], k) * o > 0) {
      Cluster& c = clusters[cluster_of[t]];
      if (std::find(c.touch_points().begin(), c.touch_points().end(), v) == c.touch_points().end())
        c.touch_points().push_back(v);
      c.touched = true;
    }
  }
  // Each crossing pair cuts both clusters along the other's trace.
  for (auto [i, j, which] : crossing) {
    if (which & 1) add_pair(i, j);
    if (which & 2) add_pair(j, i);
  }
  // The quads' fourth vertices serve the pair tests alone (sides_of).
  std::vector<std::uint32_t>().swap(quad_other);
  std::vector<std::int8_t>().swap(quad_side);
}

void Arrangement::orient_cluster(Cluster& c) const {
  const Tri& r = tris[c.ref];
  const Vec3 p0 = pos[r.v[0]], p1 = pos[r.v[1]], p2 = pos[r.v[2]];
  c.k = dominant_axis(cross(p1 - p0, p2 - p0));
  c.nk_sign = orient2d_projected(p0, p1, p2, c.k);
  if (c.nk_sign == 0) {  // the rounded normal misled: take an axis that is exact
    for (int k = 0; k < 3 && c.nk_sign == 0; ++k) {
      c.k = k;
      c.nk_sign = orient2d_projected(p0, p1, p2, k);
    }
  }
}

const Cluster& Arrangement::cluster(std::uint32_t ci, Cluster& scratch) const {
  if (!is_lone(ci)) return clusters[ci];
  scratch = Cluster();
  scratch.add_tri(ci & ~kLoneCluster);
  scratch.ref = ci & ~kLoneCluster;
  orient_cluster(scratch);
  return scratch;
}

bool Arrangement::may_be_diagonal(const Tri& t, std::uint32_t p, std::uint32_t q) const {
  const SoupFace& f = faces[t.input_face];
  if (!f.planar || f.tris.size() < 2) return false;
  for (const auto loop : loops_of(f))
    for (std::size_t i = 0; i < loop.size(); ++i)
      if (ordered(loop[i], loop[(i + 1) % loop.size()]) == ordered(p, q)) return false;
  return true;
}

// Triangle b crosses the plane of triangle t, or has an edge in it: the constraint
// on t's cluster.
void Arrangement::add_pair(std::uint32_t t, std::uint32_t b) {
  const std::uint32_t ct = cluster_of[t], cb = cluster_of[b];
  const Tri& a = tris[t];
  const Tri& o = tris[b];
  int s[3];
  sides_of(a, o, s);
  std::uint32_t ends[3];
  int n = 0;
  const std::size_t points_before = points.size();
  const SoupFace& bf = faces[o.input_face];
  const bool convex_quad = bf.quad && bf.convex;
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (s[k] == 0) ends[n++] = o.v[k];
    if (s[k] * s[k1] < 0) {
      std::uint32_t p = o.v[k], q = o.v[k1];
      if (convex_quad && may_be_diagonal(o, p, q)) {
        const std::uint32_t other = bf.tris[0] == b ? bf.tris[1] : bf.tris[0];
        const Tri& ot = tris[other];
        const std::uint32_t w = ot.v[0] != p && ot.v[0] != q ? ot.v[0] : (ot.v[1] != p && ot.v[1] != q ? ot.v[1] : ot.v[2]);
        const int sw = w == a.v[0] || w == a.v[1] || w == a.v[2]
                           ? 0
                           : (w == quad_other[t] ? quad_side[t] : PlaneSide(pos[a.v[0]], pos[a.v[1]], pos[a.v[2]])(pos[w]));
        if (sw != 0) (sw * s[k] < 0 ? q : p) = w;
      }
      ends[n++] = lpi_point(p, q, ct);
    }
  }
  // A point made for a cut that is then dropped is taken back.
  auto drop_new_points = [&] {
    while (points.size() > points_before) {
      const PointDef d = points.back();
      lpi_ids_.erase({ordered(d.a, d.b), plane_key(cluster_of[d.c])});
      const auto id = static_cast<std::uint32_t>(pos.size() + points.size() - 1);  // the id is reused
      exact3.erase(id);
      near3.erase(id);
      near2.erase(id);
      exact2.erase(id);
      points.pop_back();
      h3f.pop_back();
      h2f.pop_back();
    }
  };
  assert(n == 2);
  if (n < 2) return;
  // Triangles of a mesh that share a corner v often cross each other's planes by a
  // rounding's width; the cut then runs from v away from t and cuts nothing. It
  // enters t only if its other end lies strictly inside t's angle at v.
  const Cluster& c = clusters[ct];
  for (int e = 0; e < 2; ++e) {
    const std::uint32_t v = ends[e], x = ends[1 - e];
    const int at = v == a.v[0] ? 0 : (v == a.v[1] ? 1 : (v == a.v[2] ? 2 : -1));
    if (at < 0) continue;
    const std::uint32_t next = a.v[(at + 1) % 3], prev = a.v[(at + 2) % 3];
    const int turn = orient2d_projected(pos[a.v[0]], pos[a.v[1]], pos[a.v[2]], c.k);
    const int o_next = orient2(c, v, next, x) * turn, o_prev = orient2(c, v, x, prev) * turn;
    // Along one of t's sides it cuts nothing, unless that side is a diagonal of t's
    // planar face, which the split makes no edge of otherwise (open_edges).
    if (o_next < 0 || o_prev < 0 || (o_next == 0 && !may_be_diagonal(a, v, next)) ||
        (o_prev == 0 && !may_be_diagonal(a, prev, v))) {
      drop_new_points();
      return;
    }
  }
  clusters[ct].constraints().push_back({cb, b, ends[0], ends[1], t});
  clusters[ct].touched = true;
}

// ---------------------------------------------------------------- stage 2

// ---------------------------------------------------------------- wires

namespace {

// An axis along which the projection of triangle abc has area (-1: none).
int projection_axis(Vec3 a, Vec3 b, Vec3 c) {
  const int k = dominant_axis(cross(b - a, c - a));
  for (int d = 0; d < 3; ++d)
    if (orient2d_projected(a, b, c, (k + d) % 3) != 0) return (k + d) % 3;
  return -1;
}

// Whether v lies strictly inside segment pq (all input points; exact).
bool strictly_inside(Vec3 p, Vec3 q, Vec3 v) {
  if (v == p || v == q || !collinear3d(p, q, v)) return false;
  for (int d = 0; d < 3; ++d)
    if (p[d] != q[d]) return (p[d] < v[d]) == (v[d] < q[d]) && v[d] != p[d] && v[d] != q[d];
  return false;
}

}  // namespace

void Arrangement::split_wires() {
  // Records point x on input edge st when it lies strictly inside it, so that the
  // faces along that edge take it as a vertex (output.cpp's T-junction step).
  auto along_inside = [&](std::uint32_t s, std::uint32_t t, std::uint32_t x) {
    const int ax = dominant_axis(pos[t] - pos[s]);
    return compare3(s, x, ax) * compare3(x, t, ax) > 0;
  };
  auto on_edge = [&](std::uint32_t s, std::uint32_t t, std::uint32_t x) {
    if (x == s || x == t) return;
    const bool inside = x < pos.size() ? strictly_inside(pos[s], pos[t], pos[x])
                                       : collinear3(s, t, x) && along_inside(s, t, x);
    if (inside) edge_points.push_back({edge_key(s, t), x});
  };
  for (const WireSeg& w : wires) {
    if (w.p == w.q) {
      // An isolated point on a triangle's edge becomes that edge's vertex.
      Box b;
      b.add(pos[w.p]);
      bvh.query([&](const auto& x) { return x.overlaps(b); }, [&](std::uint32_t t) {
        for (int e = 0; e < 3; ++e) on_edge(tris[t].v[e], tris[t].v[(e + 1) % 3], w.p);
      });
      wire_pieces.push_back(w);
      continue;
    }
    const Vec3 p = pos[w.p], q = pos[w.q];
    std::vector<std::uint32_t> cuts;
    Box box;
    box.add(p);
    box.add(q);
    bvh.query([&](const auto& x) { return x.overlaps(box); }, [&](std::uint32_t ti) {
      const Tri& t = tris[ti];
      const Vec3 a = pos[t.v[0]], b = pos[t.v[1]], c = pos[t.v[2]];
      const int sp = orient3d(a, b, c, p), sq = orient3d(a, b, c, q);
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t v = t.v[e];
        if (strictly_inside(p, q, pos[v])) cuts.push_back(v);  // through a vertex
        on_edge(t.v[e], t.v[(e + 1) % 3], w.p);                 // an end on an edge
        on_edge(t.v[e], t.v[(e + 1) % 3], w.q);
      }
      if (sp * sq < 0) {
        // Through the plane: where it meets the plane, if inside the closed triangle.
        const std::uint32_t ci = cluster_of[ti];
        Cluster lone;
        const Cluster& cl = cluster(ci, lone);
        const int o = orient2(cl, t.v[0], t.v[1], t.v[2]);
        const std::uint32_t x = lpi_point(w.p, w.q, ci);
        bool inside = true;
        for (int e = 0; e < 3 && inside; ++e) inside = orient2(cl, t.v[e], t.v[(e + 1) % 3], x) * o >= 0;
        if (!inside) return;
        cuts.push_back(x);
        for (int e = 0; e < 3; ++e)
          if (orient2(cl, t.v[e], t.v[(e + 1) % 3], x) == 0) on_edge(t.v[e], t.v[(e + 1) % 3], x);
      } else if (sp == 0 && sq == 0) {
        // In the plane: where it crosses the triangle's edges.
        const int k = projection_axis(a, b, c);
        if (k < 0) return;
        for (int e = 0; e < 3; ++e) {
          const std::uint32_t s = t.v[e], u = t.v[(e + 1) % 3];
          const Vec3 ps = pos[s], pu = pos[u];
          if (orient2d_projected(p, q, ps, k) * orient2d_projected(p, q, pu, k) < 0 &&
              orient2d_projected(ps, pu, p, k) * orient2d_projected(ps, pu, q, k) < 0) {
            meets.push_back({s, u, static_cast<std::uint32_t>(k)});
            const std::uint32_t x =
                new_point({PointKind::kMeet, w.p, w.q, static_cast<std::uint32_t>(meets.size() - 1)}, nullptr);
            cuts.push_back(x);
            edge_points.push_back({edge_key(s, u), x});
          }
        }
      }
    });
    // Other wires and points: an end or a point inside it, or a crossing in one plane.
    wire_bvh.query([&](const auto& x) { return x.overlaps(box); }, [&](std::uint32_t oi) {
      const WireSeg& o = wires[oi];
      if (&o == &w) return;
      const Vec3 a = pos[o.p], b = pos[o.q];
      if (strictly_inside(p, q, a)) cuts.push_back(o.p);
      if (o.q != o.p && strictly_inside(p, q, b)) cuts.push_back(o.q);
      if (o.p == o.q || orient3d(p, q, a, b) != 0) return;
      for (int k = 0; k < 3; ++k) {
        const int s1 = orient2d_projected(p, q, a, k), s2 = orient2d_projected(p, q, b, k);
        const int s3 = orient2d_projected(a, b, p, k), s4 = orient2d_projected(a, b, q, k);
        if (s1 == 0 && s2 == 0) continue;  // on one line in this projection: try another
        if (s1 * s2 < 0 && s3 * s4 < 0) {
          meets.push_back({o.p, o.q, static_cast<std::uint32_t>(k)});
          cuts.push_back(new_point({PointKind::kMeet, w.p, w.q, static_cast<std::uint32_t>(meets.size() - 1)}, nullptr));
        }
        return;
      }
    });
    // In order along the wire, each point once.
    const int axis = dominant_axis(q - p);
    std::sort(cuts.begin(), cuts.end(), [&](std::uint32_t x, std::uint32_t y) {
      return compare3(x, y, axis) * (p[axis] < q[axis] ? 1 : -1) < 0;
    });
    cuts.erase(std::unique(cuts.begin(), cuts.end(),
                           [&](std::uint32_t x, std::uint32_t y) { return compare3(x, y, axis) == 0; }),
               cuts.end());
    std::uint32_t from = w.p;
    for (std::uint32_t x : cuts) {
      wire_pieces.push_back({from, x, w.operand});
      from = x;
    }
    wire_pieces.push_back({from, w.q, w.operand});
  }
}

void Arrangement::release_loops() {
  loop_table.clear();
  for (SoupFace& f : faces) f.loop_count = 0;
}

void Arrangement::release_all() {
  auto free = [](auto&... x) { ((x = std::decay_t<decltype(x)>()), ...); };
  free(pos, tris, quad_other, quad_side, open_edges, faces, loop_table, wires, wire_pieces, wire_boxes,
       wire_bvh, meets, plane_joins, edge_uses, bvh, cluster_of, plane_of, clusters, points, h3f, h2f,
       edge_points, contact_edges, near_other, alone_in, key_ids, has_edge_key, key_parent, exact3,
       near3, near2, exact2, lpi_ids_);
}

void Arrangement::release_pieces(bool keep_tree) {
  for (Cluster& c : clusters) {
    c.pieces().release();
    c.constraints().release();
    c.touch_points().release();
  }
  if (!keep_tree) edge_uses.clear();
  lpi_ids_ = {};
  if (keep_tree) return;
  bvh = Bvh();
}

void Arrangement::piece_box(const Cluster& c, Piece& p) const {
  p.box2 = Box();
  for (std::uint32_t q : p.pts) {
    double u, v, e;
    approx2(c, q, u, v, e);
    p.box2.add(Vec3{u - e, v - e, 0});
    p.box2.add(Vec3{u + e, v + e, 0});
  }
}

// The diagonals of a planar face's tiling, where both tiles at the diagonal are in
// cluster c, separate nothing: the face covers both sides. Only the faces' boundaries
// and the other cuts are segments (a plate's face with many holes tiles into long thin
// triangles whose diagonals would cut the cluster into slivers).
void Arrangement::mark_open_edges(const Cluster& c) {
  struct TileEdge {
    std::uint64_t edge;
    std::uint32_t face, t;
    int e;
  };
  std::vector<TileEdge> tile_edges;
  for (std::uint32_t t : c.tris())
    if (faces[tris[t].input_face].planar)
      for (int e = 0; e < 3; ++e)
        tile_edges.push_back({ordered(tris[t].v[e], tris[t].v[(e + 1) % 3]), tris[t].input_face, t, e});
  std::sort(tile_edges.begin(), tile_edges.end(), [](const TileEdge& x, const TileEdge& y) {
    return std::tie(x.face, x.edge, x.t) < std::tie(y.face, y.edge, y.t);
  });
  std::vector<std::uint64_t> loop_edges;  // of the face being looked at
  std::uint32_t loop_face = kInvalidIndex;
  for (std::size_t k = 0; k + 1 < tile_edges.size(); ++k) {
    const TileEdge &x = tile_edges[k], &y = tile_edges[k + 1];
    if (x.face != y.face || x.edge != y.edge || x.t == y.t) continue;
    if (k + 2 < tile_edges.size() && tile_edges[k + 2].face == x.face && tile_edges[k + 2].edge == x.edge) continue;
    if (k > 0 && tile_edges[k - 1].face == x.face && tile_edges[k - 1].edge == x.edge) continue;
    if (loop_face != x.face) {
      loop_face = x.face;
      loop_edges.clear();
      for (const auto loop : loops_of(faces[x.face]))
        for (std::size_t i = 0; i < loop.size(); ++i) loop_edges.push_back(ordered(loop[i], loop[(i + 1) % loop.size()]));
      std::sort(loop_edges.begin(), loop_edges.end());
    }
    if (std::binary_search(loop_edges.begin(), loop_edges.end(), x.edge)) continue;  // a slit
    // Used by a triangle of another face too (another operand's edge on the diagonal):
    // a place where that surface may cross this one.
    if (edge_uses.uses(static_cast<std::uint32_t>(x.edge >> 32), static_cast<std::uint32_t>(x.edge)).size() > 2) continue;
    open_edges[x.t] |= static_cast<std::uint8_t>(1u << x.e);
    open_edges[y.t] |= static_cast<std::uint8_t>(1u << y.e);
  }
}

void Arrangement::split_cluster(std::uint32_t ci) {
  Cluster& c = clusters[ci];
  const int k = c.k, i = (k + 1) % 3, j = (k + 2) % 3;
  std::unordered_map<std::uint64_t, std::uint32_t> crossings;  // line pair -> point
  FlatMap<std::uint32_t, std::uint32_t> through;    // edge key -> line
  auto through_line = [&](std::uint32_t p, std::uint32_t q) { return edge_line(c, through, p, q); };

  struct Segment {
    std::uint32_t line, p, q;
    auto operator<=>(const Segment&) const = default;
  };
  std::vector<Segment> segments;
  if (c.tris().size() == 1) {
    const Tri& t = tris[c.tris()[0]];
    std::array<std::uint32_t, 3> v = t.v;
    if (orient2d_projected(pos[v[0]], pos[v[1]], pos[v[2]], k) < 0) std::swap(v[1], v[2]);
    Piece p;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t l = through_line(v[e], v[(e + 1) % 3]);
      c.lines()[l].points.push_back(v[e]);
      c.lines()[l].points.push_back(v[(e + 1) % 3]);
      p.pts.push_back(v[e]);
      p.lines.push_back(l);
    }
    c.pieces().push_back(std::move(p));
  } else {
    double lo[2] = {1e308, 1e308}, hi[2] = {-1e308, -1e308};
    for (std::uint32_t t : c.tris()) {
      for (std::uint32_t v : tris[t].v) {
        lo[0] = std::min(lo[0], pos[v][i]);
        hi[0] = std::max(hi[0], pos[v][i]);
        lo[1] = std::min(lo[1], pos[v][j]);
        hi[1] = std::max(hi[1], pos[v][j]);
      }
    }
    // The box, counterclockwise: sides v = lo, u = hi, v = hi, u = lo.
    const std::uint32_t sides[4] = {
        add_line(c, Line::make(LineKind::kAxisV, 0, 0, lo[1])), add_line(c, Line::make(LineKind::kAxisU, 0, 0, hi[0])),
        add_line(c, Line::make(LineKind::kAxisV, 0, 0, hi[1])), add_line(c, Line::make(LineKind::kAxisU, 0, 0, lo[0]))};
    for (std::uint32_t l : sides) c.lines()[l].key = fresh_key();
    Piece p;
    for (int e = 0; e < 4; ++e) {
      const std::uint32_t a = sides[(e + 3) % 4], b = sides[e];
      const std::uint32_t corner = new_point({PointKind::kCross, ci, a, b}, &c);
      crossings[ordered(a, b)] = corner;
      c.lines()[a].points.push_back(corner);
      c.lines()[b].points.push_back(corner);
      p.pts.push_back(corner);
      p.lines.push_back(b);
    }
    c.pieces().push_back(std::move(p));
    mark_open_edges(c);
    for (std::uint32_t t : c.tris())
      for (int e = 0; e < 3; ++e) {
        if (open_edges[t] & (1u << e)) continue;
        const std::uint32_t a = tris[t].v[e], b = tris[t].v[(e + 1) % 3];
        segments.push_back({through_line(a, b), a, b});
      }
  }
  // One line per other plane (the halves of a planar quad are two clusters, one plane).
  std::unordered_map<std::uint32_t, std::uint32_t> traces;  // other plane -> line
  for (const Constraint& k2 : c.constraints()) {
    // An edge of the other triangle lying in this plane (a wall resting on a plate):
    // the line through its two input vertices, of lower degree than the trace, and
    // the one the edge's own cluster and a coplanar face with that edge use.
    if (k2.p < pos.size() && k2.q < pos.size()) {
      if (k2.p != k2.q) segments.push_back({through_line(k2.p, k2.q), k2.p, k2.q});
      continue;
    }
    auto [it, fresh] = traces.try_emplace(plane_of[k2.other_cluster], 0);
    if (fresh) {
      Line l = Line::make(LineKind::kTrace, k2.other_tri);
      l.key = pair_key(plane_of[ci], plane_of[k2.other_cluster]);
      it->second = add_line(c, std::move(l));
    }
    if (k2.p != k2.q && !equal3(k2.p, k2.q)) segments.push_back({it->second, k2.p, k2.q});
  }
  // The same segment twice cuts nothing the second time (a triangle's edge and the
  // edge of a wall resting on it, a face's tiles sharing an edge).
  for (Segment& sg : segments)
    if (sg.p > sg.q) std::swap(sg.p, sg.q);
  std::sort(segments.begin(), segments.end());
  segments.erase(std::unique(segments.begin(), segments.end()), segments.end());
  piece_box(c, c.pieces()[0]);

  std::vector<Piece> made;
  // Piece pi cut by a line (where it overlaps segment pq; p = kInvalidIndex: wholly).
  auto cut = [&](std::size_t pi, std::uint32_t line, std::uint32_t p, std::uint32_t q) {
    made.clear();
    if (!split_piece(c, ci, pi, line, p, q, made, crossings)) return;
    c.pieces()[pi] = std::move(made[0]);
    piece_box(c, c.pieces()[pi]);
    c.pieces().push_back(std::move(made[1]));
    piece_box(c, c.pieces().back());
  };
  // Segments, with bounds in (u, v) that hold their exact ends.
  std::vector<Box> seg_box(segments.size());
  for (std::size_t si = 0; si < segments.size(); ++si)
    for (std::uint32_t q : {segments[si].p, segments[si].q}) {
      double u, v, e;
      approx2(c, q, u, v, e);
      seg_box[si].add(Vec3{u - e, v - e, 0});
      seg_box[si].add(Vec3{u + e, v + e, 0});
    }
  // Each segment cuts the pieces of `region` (indices into c.pieces()) whose boxes meet
  // its own; the pieces it makes join the region.
  auto cut_all = [&](std::vector<std::uint32_t>& region, const std::vector<std::uint32_t>& segs) {
    for (std::uint32_t si : segs) {
      const Segment& s = segments[si];
      const Box& sb = seg_box[si];
      for (std::size_t k = 0, n = region.size(); k < n; ++k) {
        const Box& pb = c.pieces()[region[k]].box2;
        if (pb.lo.x > sb.hi.x || sb.lo.x > pb.hi.x || pb.lo.y > sb.hi.y || sb.lo.y > pb.hi.y)
          continue;
        const std::size_t before = c.pieces().size();
        cut(region[k], s.line, s.p, s.q);
        if (c.pieces().size() > before) region.push_back(static_cast<std::uint32_t>(before));
      }
    }
  };
  // Many segments in one cluster (a plate with many holes): whole chords of few
  // pieces would run across the whole cluster, making long slivers and costing
  // segments x pieces. The cluster is first cut, as a k-d tree, by axis-parallel
  // lines u = m or v = m (m a double: the median of the segments' middles), each
  // half keeping the segments that may reach it, until a region holds few. Those
  // lines only separate pieces of one classification; the merge removes them.
  constexpr std::size_t kLeafSegments = 16;
  auto subdivide = [&](auto&& self, std::vector<std::uint32_t> region, std::vector<std::uint32_t> segs,
                       int depth) -> void {
    if (segs.size() <= kLeafSegments || depth >= 40) return cut_all(region, segs);
    Box rb;
    for (std::uint32_t pi : region) rb.add(c.pieces()[pi].box2);
    const int axis = rb.hi.x - rb.lo.x >= rb.hi.y - rb.lo.y ? 0 : 1;
    std::vector<double> mids;
    mids.reserve(segs.size());
    for (std::uint32_t si : segs) mids.push_back((seg_box[si].lo[axis] + seg_box[si].hi[axis]) / 2);
    std::nth_element(mids.begin(), mids.begin() + mids.size() / 2, mids.end());
    const double m = mids[mids.size() / 2];
    std::vector<std::uint32_t> segs_lo, segs_hi;
    for (std::uint32_t si : segs) {
      if (seg_box[si].lo[axis] <= m) segs_lo.push_back(si);
      if (seg_box[si].hi[axis] >= m) segs_hi.push_back(si);
    }
    // A split that leaves every segment on both sides gains nothing.
    if (!(m > rb.lo[axis] && m < rb.hi[axis]) || segs_lo.size() == segs.size() ||
        segs_hi.size() == segs.size())
      return cut_all(region, segs);
    const std::uint32_t l =
        add_line(c, Line::make(axis == 0 ? LineKind::kAxisU : LineKind::kAxisV, 0, 0, m));
    c.lines()[l].key = fresh_key();
    std::vector<std::uint32_t> lo, hi;
    for (std::uint32_t pi : region) {
      const std::size_t before = c.pieces().size();
      cut(pi, l, kInvalidIndex, kInvalidIndex);
      if (c.pieces().size() > before) {  // made[0] is on the positive side (u or v > m)
        hi.push_back(pi);
        lo.push_back(static_cast<std::uint32_t>(before));
        continue;
      }
      int s = 0;
      for (std::size_t q = 0; q < c.pieces()[pi].pts.size() && s == 0; ++q)
        s = side(c, c.lines()[l], c.pieces()[pi].pts[q]);
      (s > 0 ? hi : lo).push_back(pi);
    }
    self(self, std::move(lo), std::move(segs_lo), depth + 1);
    self(self, std::move(hi), std::move(segs_hi), depth + 1);
  };
  {
    std::vector<std::uint32_t> all_segs(segments.size()), region(c.pieces().size());
    std::iota(all_segs.begin(), all_segs.end(), 0u);
    std::iota(region.begin(), region.end(), 0u);
    subdivide(subdivide, std::move(region), std::move(all_segs), 0);
  }
  // A touching point becomes a vertex where the lines u = p_u and v = p_v through it
  // cross (it lies on both exactly, as a double); they cut only the pieces it is in.
  // A corner of one of the cluster's triangles is a vertex already, where the
  // triangle's two edges through it cross (a cylinder's wall resting on a plate by
  // its bottom ring, the cap in the plate's cluster: every ring vertex touches).
  // (Segments of two lines end there, so the second's cut meets the first's line at it.)
  std::vector<std::uint32_t> corners;
  if (!c.touch_points().empty() && c.tris().size() > 1) {
    std::vector<std::pair<std::uint32_t, std::uint32_t>> ends;  // point, line
    for (const Segment& sg : segments) {
      ends.push_back({sg.p, sg.line});
      ends.push_back({sg.q, sg.line});
    }
    std::sort(ends.begin(), ends.end());
    for (std::size_t k = 0; k + 1 < ends.size(); ++k)
      if (ends[k].first == ends[k + 1].first && ends[k].second != ends[k + 1].second &&
          (corners.empty() || corners.back() != ends[k].first))
        corners.push_back(ends[k].first);
  }
  for (std::uint32_t v : c.touch_points()) {
    if (std::binary_search(corners.begin(), corners.end(), v)) continue;
    const Vec3 p = pos[v];
    for (LineKind kind : {LineKind::kAxisU, LineKind::kAxisV}) {
      const std::uint32_t l = add_line(c, Line::make(kind, 0, 0, kind == LineKind::kAxisU ? p[i] : p[j]));
      c.lines()[l].key = fresh_key();
      for (std::size_t pi = 0, n = c.pieces().size(); pi < n; ++pi) {
        const Piece& P = c.pieces()[pi];
        // p in the closed piece: on each side's line or on the piece's side of it (a
        // line's direction is its own, not the piece's: the side of a corner off it).
        bool inside = true;
        for (std::size_t q = 0; q < P.pts.size() && inside; ++q) {
          const Line& side_line = c.lines()[P.lines[q]];
          const int sv = side(c, side_line, v);
          int sp = 0;
          for (std::size_t r = 0; r < P.pts.size() && sp == 0 && sv != 0; ++r)
            sp = side(c, side_line, P.pts[r]);
          inside = sv == 0 || sv == sp;
        }
        if (inside) cut(pi, l, kInvalidIndex, kInvalidIndex);
      }
    }
  }
}

bool Arrangement::split_piece(Cluster& c, std::uint32_t ci, std::size_t pi, std::uint32_t li,
                              std::uint32_t s0, std::uint32_t s1, std::vector<Piece>& out,
                              std::unordered_map<std::uint64_t, std::uint32_t>& crossings) {
  const Piece& P = c.pieces()[pi];
  const std::size_t n = P.pts.size();
  std::vector<int> sides(n);
  bool pos_side = false, neg_side = false;
  for (std::size_t q = 0; q < n; ++q) {
    sides[q] = side(c, c.lines()[li], P.pts[q]);
    pos_side |= sides[q] > 0;
    neg_side |= sides[q] < 0;
  }
  if (!pos_side || !neg_side) {
    for (std::size_t q = 0; q < n; ++q) {
      if (sides[q] != 0) continue;
      c.lines()[li].points.push_back(P.pts[q]);
      if (sides[(q + 1) % n] == 0) line_union(c.lines()[li].key, c.lines()[P.lines[q]].key);
    }
    return false;
  }
  // The sequence with the crossing points put in, each with its side.
  struct Corner {
    std::uint32_t pt, line;
    int side;
  };
  std::vector<Corner> seq;
  seq.reserve(n + 2);
  std::uint32_t chord[2];
  int nc = 0;
  for (std::size_t q = 0; q < n; ++q) {
    seq.push_back({P.pts[q], P.lines[q], sides[q]});
    if (sides[q] == 0) chord[nc++ & 1] = P.pts[q];
    const int next = sides[(q + 1) % n];
    if (sides[q] * next < 0) {
      const std::uint32_t m = P.lines[q];
      auto [it, fresh] = crossings.try_emplace(ordered(li, m), 0);
      if (fresh) {
        it->second = crossing_point(ci, li, m);
        c.lines()[li].points.push_back(it->second);
        c.lines()[m].points.push_back(it->second);
      }
      seq.push_back({it->second, m, 0});
      chord[nc++ & 1] = it->second;
    }
  }
  assert(nc == 2);
  // Cut only where the segment overlaps the chord with positive length.
  const Line& L = c.lines()[li];
  std::uint32_t a = chord[0], b = chord[1], lo = s0, hi = s1;
  if (s0 != kInvalidIndex) {  // kInvalidIndex: cut the whole chord
    if (along(c, L, a, b) > 0) std::swap(a, b);
    if (along(c, L, lo, hi) > 0) std::swap(lo, hi);
  }
  if (s0 != kInvalidIndex && !(along(c, L, a, hi) < 0 && along(c, L, lo, b) < 0)) return false;

  for (std::size_t q = 0; q < n; ++q)
    if (sides[q] == 0) c.lines()[li].points.push_back(P.pts[q]);
  out.resize(2);
  const std::size_t m = seq.size();
  for (Piece& o : out) {  // each side takes at most all corners
    o.pts.reserve(m);
    o.lines.reserve(m);
  }
  for (std::size_t q = 0; q < m; ++q) {
    const Corner& k = seq[q];
    const Corner& next = seq[(q + 1) % m];
    if (k.side >= 0) {
      out[0].pts.push_back(k.pt);
      out[0].lines.push_back(next.side >= 0 ? k.line : li);
    }
    if (k.side <= 0) {
      out[1].pts.push_back(k.pt);
      out[1].lines.push_back(next.side <= 0 ? k.line : li);
    }
  }
  return true;
}

}  // namespace cellforge::boolean
