// Implicit points (implicit.h): the constructions lie exactly on what made them, and
// every predicate agrees with an oracle that computes the same sign another way
// (the segment's point as the weighted mean of its ends, the three planes' point by
// Cramer's rule) in the schoolbook Dyadic of dyadic.h, over seeded random cases
// built to be degenerate, where a rounded point gets the sign wrong.
#include "cellforge/geom/implicit.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "cellforge/geom/predicates.h"
#include "geom/dyadic.h"

namespace cellforge {
namespace {

using testing::Dyadic;
using D3 = std::array<Dyadic, 3>;

D3 d3(Vec3 p) { return {Dyadic(p.x), Dyadic(p.y), Dyadic(p.z)}; }
D3 d_sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Dyadic d_dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 d_normal(const PlanePoints& pl) {
  const D3 u = d_sub(d3(pl.b), d3(pl.a)), v = d_sub(d3(pl.c), d3(pl.a));
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

// A point as (X, W) in the oracle's own terms.
struct Exact {
  D3 x;
  Dyadic w;
};

// Segment pq meets plane pl at (dp q - dq p) / (dp - dq): the weighted mean of the ends.
Exact oracle_lpi(Vec3 p, Vec3 q, const PlanePoints& pl) {
  const D3 n = d_normal(pl), a = d3(pl.a), P = d3(p), Q = d3(q);
  const Dyadic dp = d_dot(n, d_sub(P, a)), dq = d_dot(n, d_sub(Q, a));
  return {{dp * Q[0] - dq * P[0], dp * Q[1] - dq * P[1], dp * Q[2] - dq * P[2]}, dp - dq};
}

Dyadic det3(const D3& r0, const D3& r1, const D3& r2) {
  return r0[0] * (r1[1] * r2[2] - r1[2] * r2[1]) - r0[1] * (r1[0] * r2[2] - r1[2] * r2[0]) +
         r0[2] * (r1[0] * r2[1] - r1[1] * r2[0]);
}

// Three planes n_i . x = d_i by Cramer's rule: x_k = det(N with column k := d) / det N.
Exact oracle_tpi(const PlanePoints& a, const PlanePoints& b, const PlanePoints& c) {
  const D3 n[3] = {d_normal(a), d_normal(b), d_normal(c)};
  const Dyadic d[3] = {d_dot(n[0], d3(a.a)), d_dot(n[1], d3(b.a)), d_dot(n[2], d3(c.a))};
  Exact r;
  r.w = det3(n[0], n[1], n[2]);
  for (int k = 0; k < 3; ++k) {
    D3 rows[3] = {n[0], n[1], n[2]};
    for (int i = 0; i < 3; ++i) rows[i][static_cast<std::size_t>(k)] = d[i];
    r.x[static_cast<std::size_t>(k)] = det3(rows[0], rows[1], rows[2]);
  }
  return r;
}

Exact oracle(const ImplicitPoint& x) {
  switch (x.kind) {
    case ImplicitPoint::Kind::kExplicit:
      return {d3(x.p[0]), Dyadic(1.0)};
    case ImplicitPoint::Kind::kLpi:
      return oracle_lpi(x.p[0], x.p[1], {x.p[2], x.p[3], x.p[4]});
    case ImplicitPoint::Kind::kTpi:
      return oracle_tpi({x.p[0], x.p[1], x.p[2]}, {x.p[3], x.p[4], x.p[5]}, {x.p[6], x.p[7], x.p[8]});
  }
  return {};
}

int oracle_orient3d(const PlanePoints& pl, const Exact& x) {
  const D3 n = d_normal(pl), a = d3(pl.a);
  const D3 aw{a[0] * x.w, a[1] * x.w, a[2] * x.w};
  return d_dot(n, d_sub(x.x, aw)).sign() * x.w.sign();
}

int oracle_compare(const Exact& x, const Exact& y, int axis) {
  const auto k = static_cast<std::size_t>(axis);
  return (x.x[k] * y.w - y.x[k] * x.w).sign() * x.w.sign() * y.w.sign();
}

int oracle_orient2d(const Exact& a, const Exact& b, const Exact& c, int drop) {
  const auto i = static_cast<std::size_t>((drop + 1) % 3), j = static_cast<std::size_t>((drop + 2) % 3);
  // det [b - a, c - a] with each point divided by its w, times the w's squared signs.
  const Dyadic bu = b.x[i] * a.w - a.x[i] * b.w, bv = b.x[j] * a.w - a.x[j] * b.w;
  const Dyadic cu = c.x[i] * a.w - a.x[i] * c.w, cv = c.x[j] * a.w - a.x[j] * c.w;
  return (bu * cv - bv * cu).sign() * b.w.sign() * c.w.sign();
}

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}
Vec3 random_point(std::mt19937_64& rng) {
  return {uniform(rng, -10, 10), uniform(rng, -10, 10), uniform(rng, -10, 10)};
}
PlanePoints random_plane(std::mt19937_64& rng) {
  return {random_point(rng), random_point(rng), random_point(rng)};
}
// A point on the line through p and q, rounded (so only nearly on it).
Vec3 near_line(std::mt19937_64& rng, Vec3 p, Vec3 q) { return p + (q - p) * uniform(rng, -2, 3); }

TEST(Implicit, SegmentMeetsPlaneAtHandCheckedPoints) {
  const PlanePoints z1{{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
  const ImplicitPoint x = ImplicitPoint::segment_plane({0, 0, -1}, {2, 4, 3}, z1);
  EXPECT_TRUE(is_defined(x));
  EXPECT_EQ(approx(x), (Vec3{1, 2, 1}));
  EXPECT_TRUE(same_point(x, ImplicitPoint::at({1, 2, 1})));
  EXPECT_EQ(orient3d(z1.a, z1.b, z1.c, x), 0);
  // A tilted plane x + y - z = 0 meets (t, 0, 1 - t) where t - (1 - t) = 0.
  const PlanePoints tilted{{0, 0, 0}, {1, 0, 1}, {0, 1, 1}};
  const ImplicitPoint y = ImplicitPoint::segment_plane({0, 0, 1}, {1, 0, 0}, tilted);
  EXPECT_EQ(approx(y), (Vec3{0.5, 0, 0.5}));
  // The segment lies in a plane parallel to the plane: no point.
  const ImplicitPoint none = ImplicitPoint::segment_plane({0, 0, 2}, {1, 1, 2}, z1);
  EXPECT_FALSE(is_defined(none));
  EXPECT_TRUE(std::isnan(approx(none).x));
  EXPECT_EQ(orient3d(z1.a, z1.b, z1.c, none), 0);
}

TEST(Implicit, ThreePlanesMeetAtHandCheckedPoints) {
  const PlanePoints x2{{2, 0, 0}, {2, 1, 0}, {2, 0, 1}}, y3{{0, 3, 0}, {0, 3, 1}, {1, 3, 0}},
      diag{{0, 0, 0}, {1, 0, 1}, {0, 1, 1}};  // x + y = z
  const ImplicitPoint p = ImplicitPoint::three_planes(x2, y3, diag);
  EXPECT_EQ(approx(p), (Vec3{2, 3, 5}));
  EXPECT_TRUE(same_point(p, ImplicitPoint::at({2, 3, 5})));
  // Two parallel planes: no point.
  const PlanePoints x5{{5, 0, 0}, {5, 1, 0}, {5, 0, 1}};
  EXPECT_FALSE(is_defined(ImplicitPoint::three_planes(x2, x5, diag)));
}

TEST(Implicit, ConstructionsLieExactlyOnWhatMadeThem) {
  std::mt19937_64 rng(1402);
  int rounded_off = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec3 p = random_point(rng), q = random_point(rng);
    const PlanePoints pl = random_plane(rng);
    const ImplicitPoint x = ImplicitPoint::segment_plane(p, q, pl);
    ASSERT_TRUE(is_defined(x));
    EXPECT_EQ(orient3d(pl.a, pl.b, pl.c, x), 0) << i;
    // Any plane through the segment holds the point too.
    const Vec3 r = random_point(rng);
    EXPECT_EQ(orient3d(p, q, r, x), 0) << i;
    // The point is on the line pq: collinear in every projection.
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(orient2d_projected(ImplicitPoint::at(p), ImplicitPoint::at(q), x, k), 0) << i;
    if (orient3d(pl.a, pl.b, pl.c, approx(x)) != 0) ++rounded_off;

    const PlanePoints a = random_plane(rng), b = random_plane(rng), c = random_plane(rng);
    const ImplicitPoint t = ImplicitPoint::three_planes(a, b, c);
    ASSERT_TRUE(is_defined(t));
    for (const PlanePoints& s : {a, b, c}) EXPECT_EQ(orient3d(s.a, s.b, s.c, t), 0) << i;
  }
  // What the exact points are for: their rounded positions are almost never on the plane.
  EXPECT_GT(rounded_off, 1000);
}

TEST(Implicit, ConstructionsThroughAnExplicitPointAreThatPoint) {
  std::mt19937_64 rng(77);
  for (int i = 0; i < 500; ++i) {
    const Vec3 v = random_point(rng);
    const PlanePoints a{v, random_point(rng), random_point(rng)},
        b{random_point(rng), v, random_point(rng)}, c{random_point(rng), random_point(rng), v};
    const ImplicitPoint t = ImplicitPoint::three_planes(a, b, c);
    EXPECT_TRUE(same_point(t, ImplicitPoint::at(v))) << i;
    // A segment from v meets a plane through v at v.
    const ImplicitPoint s = ImplicitPoint::segment_plane(v, random_point(rng), a);
    EXPECT_TRUE(same_point(s, ImplicitPoint::at(v))) << i;
    EXPECT_TRUE(same_point(s, t)) << i;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(compare(s, t, k), 0);
  }
}

// Random points of both kinds, half of them built to be degenerate against the
// predicate's other arguments.
TEST(Implicit, PredicatesAgreeWithTheOracle) {
  std::mt19937_64 rng(2020);
  int zeros = 0, rounded_wrong = 0, cases = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vec3 p = random_point(rng), q = random_point(rng);
    const PlanePoints pl = random_plane(rng);
    const ImplicitPoint x = i % 2 ? ImplicitPoint::segment_plane(p, q, pl)
                                  : ImplicitPoint::three_planes(pl, {p, q, random_point(rng)},
                                                                random_plane(rng));
    const Exact ex = oracle(x);
    // orient3d against a plane through x exactly, through points near x's line
    // (almost through x), or anywhere.
    const PlanePoints through = i % 2 ? PlanePoints{p, q, random_point(rng)} : pl;
    const PlanePoints other =
        i % 3 == 0 ? through
                   : (i % 3 == 1 ? PlanePoints{near_line(rng, p, q), near_line(rng, p, q), random_point(rng)}
                                 : random_plane(rng));
    const int o = orient3d(other.a, other.b, other.c, x), expected = oracle_orient3d(other, ex);
    EXPECT_EQ(o, expected) << i;
    zeros += o == 0;
    rounded_wrong += orient3d(other.a, other.b, other.c, approx(x)) != expected;
    // compare and orient2d against a second point on the same segment or plane.
    const ImplicitPoint y = ImplicitPoint::segment_plane(
        p, i % 4 ? q : near_line(rng, p, q), i % 5 ? random_plane(rng) : pl);
    const Exact ey = oracle(y);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(compare(x, y, k), oracle_compare(ex, ey, k)) << i;
      const ImplicitPoint z = ImplicitPoint::at(i % 2 ? p : near_line(rng, p, q));
      EXPECT_EQ(orient2d_projected(x, y, z, k), oracle_orient2d(ex, ey, oracle(z), k)) << i;
    }
    ++cases;
  }
  EXPECT_EQ(cases, 3000);
  EXPECT_GE(zeros, 1000);        // a third are exactly degenerate
  EXPECT_GE(rounded_wrong, 1000);  // where the rounded point gets the sign wrong
}

TEST(Implicit, OrderAlongALine) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const Vec3 p = random_point(rng), q = random_point(rng);
    const PlanePoints a = random_plane(rng), b = random_plane(rng);
    const ImplicitPoint x = ImplicitPoint::segment_plane(p, q, a),
                        y = ImplicitPoint::segment_plane(p, q, b);
    // Along pq the order is that of the parameters t = dp / (dp - dq) of the oracle.
    const Exact ex = oracle(x), ey = oracle(y);
    const D3 P = d3(p), Q = d3(q);
    const D3 dir = d_sub(Q, P);
    // (y - x).(q - p) = (Xy wx - Xx wy).(q - p) / (wx wy)
    Dyadic s(0.0);
    for (std::size_t k = 0; k < 3; ++k) s = s + (ey.x[k] * ex.w - ex.x[k] * ey.w) * dir[k];
    EXPECT_EQ(compare_along(x, y, p, q), s.sign() * ex.w.sign() * ey.w.sign()) << i;
    EXPECT_EQ(compare_along(x, y, p, q), -compare_along(y, x, p, q));
    EXPECT_EQ(compare_along(x, y, p, q), -compare_along(x, y, q, p));
    EXPECT_EQ(compare_along(x, x, p, q), 0);
  }
}

// In a plane: the crossing of two lines lies exactly on both, and at hand-checked points.
TEST(Implicit, LinesInAPlaneMeetOnBoth) {
  const H2<Fp> h = lli<Fp>({0, 0}, {4, 2}, {0, 3}, {3, 0});  // y = x / 2 and x + y = 3
  EXPECT_EQ(h.u.v / h.w.v, 2);
  EXPECT_EQ(h.v.v / h.w.v, 1);
  std::mt19937_64 rng(9);
  auto p2 = [&] { return Vec2{uniform(rng, -10, 10), uniform(rng, -10, 10)}; };
  auto h2 = []<class T>(Vec2 p) { return H2<T>{T(p.x), T(p.y), T(1.0)}; };
  for (int i = 0; i < 2000; ++i) {
    const Vec2 a = p2(), b = p2(), c = p2(), d = p2();
    for (const auto& [s0, t0] : {std::pair{a, b}, std::pair{c, d}}) {
      const Vec2 s = s0, t = t0;  // clang 14 cannot capture a structured binding
      EXPECT_EQ(decide([&]<class T>() {
                  return orient2_poly(h2.template operator()<T>(s), h2.template operator()<T>(t),
                                      lli<T>(a, b, c, d));
                }),
                0)
          << i;
    }
  }
}

}  // namespace
}  // namespace cellforge
