// Exact predicates: signs against independent exact evaluations (__int128 on scaled
// integers, and the Dyadic oracle), on the near-degenerate inputs where plain double
// evaluation gets the sign wrong; permutation properties over seeded random cases;
// the radial order as a strict weak order.
#include "cellforge/geom/predicates.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "geom/dyadic.h"

namespace cellforge {
namespace {

__extension__ typedef __int128 Int128;  // exact reference arithmetic (GCC, Clang)

using testing::Dyadic;
using testing::sum_of;

// ---- Oracles and naive evaluations ------------------------------------------------

Dyadic d_sub(double a, double b) { return Dyadic(a) - b; }

int oracle_orient2d(Vec2 a, Vec2 b, Vec2 c) {
  return (d_sub(b.x, a.x) * d_sub(c.y, a.y) - d_sub(b.y, a.y) * d_sub(c.x, a.x)).sign();
}

// Components of (b - a) x (c - a).
std::array<Dyadic, 3> oracle_cross(Vec3 a, Vec3 b, Vec3 c) {
  const Dyadic ux = d_sub(b.x, a.x), uy = d_sub(b.y, a.y), uz = d_sub(b.z, a.z);
  const Dyadic vx = d_sub(c.x, a.x), vy = d_sub(c.y, a.y), vz = d_sub(c.z, a.z);
  return {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
}

int oracle_orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  const auto n = oracle_cross(a, b, c);
  return (n[0] * d_sub(d.x, a.x) + n[1] * d_sub(d.y, a.y) + n[2] * d_sub(d.z, a.z)).sign();
}

int oracle_dot_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  return (d_sub(b.x, a.x) * d_sub(d.x, c.x) + d_sub(b.y, a.y) * d_sub(d.y, c.y) +
          d_sub(b.z, a.z) * d_sub(d.z, c.z))
      .sign();
}

int sign_of(double x) { return (x > 0) - (x < 0); }

int naive_orient2d(Vec2 a, Vec2 b, Vec2 c) {
  return sign_of((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

int naive_orient3d(Vec3 a, Vec3 b, Vec3 c, Vec3 d) {
  return sign_of(dot(cross(b - a, c - a), d - a));
}

int naive_dot_sign(Vec3 a, Vec3 b, Vec3 c, Vec3 d) { return sign_of(dot(b - a, d - c)); }

// ---- Random inputs ----------------------------------------------------------------

double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

Vec3 random_point(std::mt19937_64& rng, double scale) {
  return {uniform(rng, -scale, scale), uniform(rng, -scale, scale), uniform(rng, -scale, scale)};
}

// x moved by k ulps, k in [-2, 2].
double nudge(std::mt19937_64& rng, double x) {
  const int k = static_cast<int>(rng() % 5) - 2;
  for (int i = 0; i < std::abs(k); ++i) x = std::nextafter(x, k > 0 ? INFINITY : -INFINITY);
  return x;
}

Vec3 nudge(std::mt19937_64& rng, Vec3 p) {
  return {nudge(rng, p.x), nudge(rng, p.y), nudge(rng, p.z)};
}

// A multiple of 2^-10 in [-64, 64]: sums and small-integer multiples of these are exact.
double lattice(std::mt19937_64& rng) {
  return std::ldexp(static_cast<double>(static_cast<std::int64_t>(rng() % 131072) - 65536), -10);
}

struct Quad {
  Vec3 a, b, c, d;
};

// Four points of one of three kinds: general position, rounded onto a plane and
// nudged by a few ulps, or exactly coplanar on a lattice.
Quad random_quad(std::mt19937_64& rng, int kind) {
  const double scale = std::ldexp(1.0, static_cast<int>(rng() % 21) - 10);
  const Vec3 shift = random_point(rng, 1000);
  Quad q{random_point(rng, scale) + shift, random_point(rng, scale) + shift,
         random_point(rng, scale) + shift, random_point(rng, scale) + shift};
  if (kind == 1) {
    const double s = uniform(rng, -1, 2), t = uniform(rng, -1, 2);
    q.d = nudge(rng, q.a + (q.b - q.a) * s + (q.c - q.a) * t);
  } else if (kind == 2) {
    const double p = static_cast<double>(rng() % 7) - 3, r = static_cast<double>(rng() % 7) - 3;
    const double z0 = lattice(rng);
    for (Vec3* v : {&q.a, &q.b, &q.c, &q.d}) {
      v->x = lattice(rng);
      v->y = lattice(rng);
      v->z = p * v->x + r * v->y + z0;  // exact: at most 2^21 units of 2^-10
    }
  }
  return q;
}

struct Triple {
  Vec2 a, b, c;
};

Triple random_triple(std::mt19937_64& rng, int kind) {
  const Vec3 p = random_point(rng, 1), q = random_point(rng, 1), r = random_point(rng, 1);
  Triple t{{p.x, p.y}, {q.x, q.y}, {r.x, r.y}};
  if (kind == 1) {
    const double s = uniform(rng, -1, 2);
    t.c = {nudge(rng, t.a.x + (t.b.x - t.a.x) * s), nudge(rng, t.a.y + (t.b.y - t.a.y) * s)};
  } else if (kind == 2) {
    const double m = static_cast<double>(rng() % 9) - 4, y0 = lattice(rng);
    for (Vec2* v : {&t.a, &t.b, &t.c}) {
      v->x = lattice(rng);
      v->y = m * v->x + y0;
    }
  }
  return t;
}

// ---- orient2d ---------------------------------------------------------------------

TEST(Orient2d, SignConvention) {
  EXPECT_EQ(orient2d({0, 0}, {1, 0}, {0, 1}), 1);
  EXPECT_EQ(orient2d({0, 0}, {0, 1}, {1, 0}), -1);
  EXPECT_EQ(orient2d({0, 0}, {1, 1}, {3, 3}), 0);
  EXPECT_EQ(orient2d({0.1, 0.1}, {0.3, 0.3}, {0.7, 0.7}), 0);  // y = x exactly
  EXPECT_EQ(orient2d({1, 1}, {1, 1}, {5, -2}), 0);
}

// Kettner et al., "Classroom examples of robustness problems in geometric
// computations": p = (0.5 + i u, 0.5 + j u), u = 2^-53, against q = (12, 12) and
// r = (24, 24). Scaled by 2^53 every coordinate is an integer below 2^58, so __int128
// evaluates the determinant exactly.
TEST(Orient2d, KettnerGridMatchesInt128) {
  constexpr double u = 0x1p-53;
  const Vec2 q{12, 12}, r{24, 24};
  const Int128 qi = Int128{12} << 53, ri = Int128{24} << 53;
  int naive_wrong = 0, exact_zero = 0;
  for (int i = 0; i < 256; ++i) {
    for (int j = 0; j < 256; ++j) {
      const Vec2 p{0.5 + i * u, 0.5 + j * u};
      const Int128 px = (Int128{1} << 52) + i, py = (Int128{1} << 52) + j;
      const Int128 det = (qi - px) * (ri - py) - (qi - py) * (ri - px);
      const int want = (det > 0) - (det < 0);
      ASSERT_EQ(orient2d(p, q, r), want) << "i=" << i << " j=" << j;
      ASSERT_EQ(orient2d(q, r, p), want) << "i=" << i << " j=" << j;
      ASSERT_EQ(orient2d(r, q, p), -want) << "i=" << i << " j=" << j;
      naive_wrong += naive_orient2d(p, q, r) != want;
      exact_zero += want == 0;
    }
  }
  // The filter matters: plain doubles get thousands of these wrong.
  RecordProperty("naive_wrong", naive_wrong);
  // Of 65536: 11972 here, 4911 when the compiler fuses multiply-adds (-mfma).
  EXPECT_GT(naive_wrong, 3000);
  EXPECT_EQ(exact_zero, 256);  // the diagonal i == j
}

TEST(Orient2d, PermutationsOverRandomCases) {
  constexpr std::uint64_t kBaseSeed = 20000;
  int zeros = 0;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 6000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const auto [a, b, c] = random_triple(rng, static_cast<int>(seed % 3));
    const int s = orient2d(a, b, c);
    ASSERT_EQ(s, oracle_orient2d(a, b, c));
    ASSERT_EQ(orient2d(b, c, a), s);
    ASSERT_EQ(orient2d(c, a, b), s);
    ASSERT_EQ(orient2d(b, a, c), -s);
    ASSERT_EQ(orient2d(a, c, b), -s);
    ASSERT_EQ(orient2d(c, b, a), -s);
    zeros += s == 0;
  }
  EXPECT_GE(zeros, 2000);  // every lattice case is collinear
}

// Points a few units apart with full 53-bit mantissas: their differences are exact
// (Sterbenz), their products are not, and many triples are collinear or within a
// unit of it, the cases orient2d decides from two products and their fma residuals.
// Beside them, the same triples moved far apart (inexact differences: the expansions).
TEST(Orient2d, CloseTriplesMatchTheOracle) {
  std::mt19937_64 rng(20261207);
  std::uniform_real_distribution<double> unit(1.0, 2.0);
  int zeros = 0, near = 0;
  for (int n = 0; n < 200000; ++n) {
    const double scale = std::ldexp(1.0, static_cast<int>(rng() % 40) - 20);
    const Vec2 a{unit(rng) * scale, unit(rng) * scale};
    const Vec2 d{unit(rng) * scale * 0.25, unit(rng) * scale * 0.25};
    const int t = static_cast<int>(rng() % 4) - 1;
    Vec2 b{a.x + d.x, a.y + d.y}, c{a.x + t * d.x, a.y + t * d.y};
    if (rng() % 2) c.x = std::nextafter(c.x, rng() % 2 ? 10.0 * scale : 0.0);
    if (n % 5 == 0) b = {b.x * 1e10, b.y * -3e9};
    const int want = oracle_orient2d(a, b, c);
    ASSERT_EQ(orient2d(a, b, c), want) << n;
    ASSERT_EQ(orient2d(b, c, a), want) << n;
    ASSERT_EQ(orient2d(c, b, a), -want) << n;
    zeros += want == 0;
    near += want != 0 && naive_orient2d(a, b, c) != want;
  }
  EXPECT_GT(zeros, 10000);
  RecordProperty("naive_wrong", near);
}

// ---- orient3d ---------------------------------------------------------------------

TEST(Orient3d, SignConvention) {
  const Vec3 o{0, 0, 0}, x{1, 0, 0}, y{0, 1, 0}, z{0, 0, 1};
  EXPECT_EQ(orient3d(o, x, y, z), 1);  // d above the counterclockwise triangle
  EXPECT_EQ(orient3d(o, x, y, -z), -1);
  EXPECT_EQ(orient3d(o, y, x, z), -1);
  EXPECT_EQ(orient3d(o, x, y, Vec3{5, -7, 0}), 0);
}

// The 3D analogue of the Kettner grid: p = (0.5 + i u, 0.5 + j u, 0.5 + k u) against
// the plane through the diagonal line (12, 12, 12)-(24, 24, 24) and (1, 2, 3).
TEST(Orient3d, GridNearAPlaneMatchesOracle) {
  constexpr double u = 0x1p-53;
  const Vec3 q{12, 12, 12}, r{24, 24, 24}, s{1, 2, 3};
  int naive_wrong = 0;
  for (int i = 0; i < 24; ++i) {
    for (int j = 0; j < 24; ++j) {
      for (int k = 0; k < 24; ++k) {
        const Vec3 p{0.5 + i * u, 0.5 + j * u, 0.5 + k * u};
        const int want = oracle_orient3d(q, r, s, p);
        ASSERT_EQ(orient3d(q, r, s, p), want) << i << ' ' << j << ' ' << k;
        ASSERT_EQ(orient3d(p, q, r, s), -want) << i << ' ' << j << ' ' << k;
        naive_wrong += naive_orient3d(p, q, r, s) != -want;
      }
    }
  }
  RecordProperty("naive_wrong", naive_wrong);
  EXPECT_GT(naive_wrong, 4000);  // of 13824: 8757 here, 6896 with fused multiply-adds
}

// Points rounded onto a random plane and nudged by a few ulps: the double
// determinant's sign is noise, the predicate's is the oracle's.
TEST(Orient3d, NearCoplanarMatchesOracleWhereDoublesFail) {
  constexpr std::uint64_t kBaseSeed = 30000;
  int naive_wrong = 0;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 4000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const auto [a, b, c, d] = random_quad(rng, 1);
    const int want = oracle_orient3d(a, b, c, d);
    ASSERT_EQ(orient3d(a, b, c, d), want);
    naive_wrong += naive_orient3d(a, b, c, d) != want;
  }
  RecordProperty("naive_wrong", naive_wrong);
  EXPECT_GT(naive_wrong, 20);  // of 4000: 69 here, 47 with fused multiply-adds
}

TEST(Orient3d, PermutationsOverRandomCases) {
  constexpr std::uint64_t kBaseSeed = 40000;
  int zeros = 0;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 6000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const auto [a, b, c, d] = random_quad(rng, static_cast<int>(seed % 3));
    const int s = orient3d(a, b, c, d);
    ASSERT_EQ(s, oracle_orient3d(a, b, c, d));
    // Odd permutations flip the sign, even ones keep it.
    ASSERT_EQ(orient3d(b, a, c, d), -s);
    ASSERT_EQ(orient3d(a, c, b, d), -s);
    ASSERT_EQ(orient3d(a, b, d, c), -s);
    ASSERT_EQ(orient3d(d, b, c, a), -s);
    ASSERT_EQ(orient3d(b, c, d, a), -s);
    ASSERT_EQ(orient3d(b, c, a, d), s);
    ASSERT_EQ(orient3d(c, d, a, b), s);
    ASSERT_EQ(orient3d(b, a, d, c), s);
    // The same determinant through the exact vector operations.
    ASSERT_EQ(exact_det3(exact_sub(b, a), exact_sub(c, a), exact_sub(d, a)).sign(), s);
    zeros += s == 0;
  }
  EXPECT_GE(zeros, 2000);  // every lattice case is coplanar
}

TEST(Orient3d, CoplanarLatticeNudgedByOneUlp) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 2000; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    auto [a, b, c, d] = random_quad(rng, 2);
    ASSERT_EQ(orient3d(a, b, c, d), 0);
    d.z = std::nextafter(d.z, INFINITY);
    ASSERT_EQ(orient3d(a, b, c, d), oracle_orient3d(a, b, c, d));
  }
}

// The plane set up once must give orient3d's sign for every point, above all where the
// double determinant is noise: its filter decides there only when it is right.
TEST(PlaneSide, AgreesWithTheOracleNearThePlane) {
  const Vec3 q{12, 12, 12}, r{24, 24, 24}, s{1, 2, 3};
  const PlaneSide plane(q, r, s);
  constexpr double u = 0x1p-53;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 24; ++j)
      for (int k = 0; k < 24; ++k) {
        const Vec3 p{0.5 + i * u, 0.5 + j * u, 0.5 + k * u};
        ASSERT_EQ(plane(p), oracle_orient3d(q, r, s, p)) << i << ' ' << j << ' ' << k;
      }
  int naive_wrong = 0;
  for (std::uint64_t seed = 90000; seed < 96000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    auto [a, b, c, d] = random_quad(rng, static_cast<int>(seed % 3));
    const PlaneSide abc(a, b, c);
    ASSERT_EQ(abc(d), oracle_orient3d(a, b, c, d));
    naive_wrong += naive_orient3d(a, b, c, d) != oracle_orient3d(a, b, c, d);
    d.z = std::nextafter(d.z, INFINITY);
    ASSERT_EQ(abc(d), oracle_orient3d(a, b, c, d));
    // Far points and large magnitudes, decided by the filter.
    const Vec3 far{d.x * 1e6, d.y * -3e5, d.z * 7e4};
    ASSERT_EQ(abc(far), oracle_orient3d(a, b, c, far));
  }
  EXPECT_GT(naive_wrong, 20);  // the cases are hard ones
}

// ---- Projections, collinearity, ordering along a line ------------------------------

TEST(Orient2dProjected, IsTheSignOfACrossProductComponent) {
  const Vec3 a{1, 0, 0}, b{0, 1, 0}, c{0, 0, 1};  // (b - a) x (c - a) = (1, 1, 1)
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(orient2d_projected(a, b, c, axis), 1);
  for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(orient2d_projected(a, c, b, axis), -1);
  EXPECT_EQ(orient2d_projected({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 0), 0);

  constexpr std::uint64_t kBaseSeed = 50000;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 3000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    const auto q = random_quad(rng, static_cast<int>(seed % 3));
    // a, b and d are nearly collinear in the near-coplanar cases only by chance; use
    // d = a + (b - a) s rounded, to make all three projections close calls.
    const Vec3 d = nudge(rng, q.a + (q.b - q.a) * uniform(rng, -1, 2));
    const auto n = oracle_cross(q.a, q.b, d);
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_EQ(orient2d_projected(q.a, q.b, d, axis), n[axis].sign()) << "axis " << axis;
    }
  }
}

TEST(Collinear3d, ExactLinesAndNudges) {
  std::mt19937_64 rng(6);
  for (int i = 0; i < 3000; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    const Vec3 a{lattice(rng), lattice(rng), lattice(rng)};
    const Vec3 v{static_cast<double>(rng() % 9) - 4, static_cast<double>(rng() % 9) - 4,
                 static_cast<double>(rng() % 9) - 4};
    auto on_line = [&] { return a + v * (static_cast<double>(rng() % 64) / 4 - 8); };
    const Vec3 p = on_line(), q = on_line();
    ASSERT_TRUE(collinear3d(a, p, q));
    ASSERT_TRUE(collinear3d(p, q, a));
    Vec3 off = q;
    off.y = std::nextafter(off.y, INFINITY);
    const auto n = oracle_cross(a, p, off);
    const bool want = n[0].sign() == 0 && n[1].sign() == 0 && n[2].sign() == 0;
    ASSERT_EQ(collinear3d(a, p, off), want);
  }
  EXPECT_TRUE(collinear3d({1, 2, 3}, {1, 2, 3}, {1, 2, 3}));
  EXPECT_TRUE(collinear3d({0.1, 0.2, 0.3}, {0.1, 0.2, 0.3}, {-5, 7, 1e10}));
  EXPECT_FALSE(collinear3d({0, 0, 0}, {1, 1, 1}, {1, 1, std::nextafter(1.0, 2.0)}));
}

TEST(CompareAlong, OrdersPointsOnALine) {
  const Vec3 a{0.25, -3, 7}, v{3, 1, -2};
  const Vec3 b = a + v;
  for (int i = -5; i <= 5; ++i) {
    for (int j = -5; j <= 5; ++j) {
      const Vec3 p = a + v * i, q = a + v * j;
      EXPECT_EQ(compare_along(a, b, p, q), sign_of(j - i)) << i << ' ' << j;
      EXPECT_EQ(compare_along(b, a, p, q), -sign_of(j - i)) << i << ' ' << j;
    }
  }
}

TEST(DotSign, NearPerpendicularMatchesOracle) {
  constexpr std::uint64_t kBaseSeed = 60000;
  int naive_wrong = 0, zeros = 0;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 4000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    Vec3 a, b, c, d;
    if (seed % 2 == 0) {  // d - c perpendicular to b - a, rounded and nudged
      a = random_point(rng, 100);
      b = random_point(rng, 100);
      c = random_point(rng, 100);
      d = nudge(rng, c + cross(b - a, random_point(rng, 1)));
    } else {  // exactly perpendicular: lattice points, small-integer cross product
      a = {lattice(rng), lattice(rng), lattice(rng)};
      b = {lattice(rng), lattice(rng), 0};
      c = {lattice(rng), lattice(rng), lattice(rng)};
      const Vec3 r{static_cast<double>(rng() % 7) - 3, static_cast<double>(rng() % 7) - 3, 1};
      d = c + cross(b - a, r);
      ASSERT_EQ(dot_sign(a, b, c, d), 0);
      ++zeros;
    }
    const int want = oracle_dot_sign(a, b, c, d);
    ASSERT_EQ(dot_sign(a, b, c, d), want);
    ASSERT_EQ(dot_sign(c, d, a, b), want);
    ASSERT_EQ(dot_sign(b, a, c, d), -want);
    ASSERT_EQ(compare_along(a, b, c, d), want);
    if (seed % 2 == 0) naive_wrong += naive_dot_sign(a, b, c, d) != want;
  }
  RecordProperty("naive_wrong", naive_wrong);
  // Of 2000 near-perpendicular cases: 220 here, 119 with fused multiply-adds.
  EXPECT_GT(naive_wrong, 60);
  EXPECT_EQ(zeros, 2000);
}

// ---- Exact vectors ----------------------------------------------------------------

TEST(ExactNewellNormal, IsTwiceTheVectorArea) {
  const std::vector<Vec3> rect{{0, 0, 5}, {2, 0, 5}, {2, 3, 5}, {0, 3, 5}};
  const ExactVec3 n = exact_newell_normal(rect);
  EXPECT_EQ(n.x.sign(), 0);
  EXPECT_EQ(n.y.sign(), 0);
  EXPECT_EQ(n.z.estimate(), 12.0);
  EXPECT_EQ(exact_newell_normal(std::vector<Vec3>{{1, 2, 3}, {4, 5, 6}}).z.sign(), 0);

  std::mt19937_64 rng(7);
  for (int i = 0; i < 500; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    std::vector<Vec3> poly(3 + rng() % 8);
    for (auto& p : poly) p = random_point(rng, 10);
    std::array<Dyadic, 3> want;
    for (std::size_t k = 0; k < poly.size(); ++k) {
      const Vec3 p = poly[k], q = poly[(k + 1) % poly.size()];
      want[0] = want[0] + (Dyadic(p.y) * q.z - Dyadic(p.z) * q.y);
      want[1] = want[1] + (Dyadic(p.z) * q.x - Dyadic(p.x) * q.z);
      want[2] = want[2] + (Dyadic(p.x) * q.y - Dyadic(p.y) * q.x);
    }
    const ExactVec3 got = exact_newell_normal(poly);
    ASSERT_EQ(sum_of(got.x.components()), want[0]);
    ASSERT_EQ(sum_of(got.y.components()), want[1]);
    ASSERT_EQ(sum_of(got.z.components()), want[2]);
  }
}

TEST(ExactNewellNormal, IsTranslationInvariant) {
  std::mt19937_64 rng(8);
  for (int i = 0; i < 300; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    std::vector<Vec3> poly(3 + rng() % 6), moved;
    const Vec3 shift{lattice(rng), lattice(rng), lattice(rng)};
    for (auto& p : poly) {
      p = {lattice(rng), lattice(rng), lattice(rng)};
      moved.push_back(p + shift);  // exact on the lattice
    }
    const ExactVec3 n = exact_newell_normal(poly), m = exact_newell_normal(moved);
    ASSERT_EQ((n.x - m.x).sign(), 0);
    ASSERT_EQ((n.y - m.y).sign(), 0);
    ASSERT_EQ((n.z - m.z).sign(), 0);
  }
}

// ---- Radial order -----------------------------------------------------------------

// Directions around an integer axis t: random integer vectors, their positive
// multiples and shifts along t (same angle), their opposites, and vectors in the
// plane of t and d0 (angle 0 or pi).
std::vector<Vec3> radial_fixture(std::mt19937_64& rng, Vec3 t, Vec3 d0) {
  auto small = [&] { return static_cast<double>(rng() % 13) - 6; };
  auto parallel_to_t = [&](Vec3 d) { return cross(t, d) == Vec3{}; };  // exact: small ints
  std::vector<Vec3> dirs{d0, d0 * 3, -d0, d0 + t, -d0 - t * 2};
  while (dirs.size() < 40) {
    const Vec3 d{small(), small(), small()};
    if (parallel_to_t(d)) continue;
    dirs.push_back(d);
    switch (rng() % 4) {
      case 0:
        dirs.push_back(d * 2);
        break;
      case 1:
        dirs.push_back(d + t * small());
        break;
      case 2:
        dirs.push_back(-d);
        break;
      default:
        dirs.push_back(d0 * small() + t * small());  // in the plane of t and d0
        if (parallel_to_t(dirs.back())) dirs.pop_back();
    }
  }
  return dirs;
}

// The angle of d from d0 about t, in [0, 2pi), in long double.
long double angle(Vec3 t, Vec3 d0, Vec3 d) {
  const Vec3 e1 = cross(cross(t, d0), t);  // d0 projected (times |t|^2)
  const Vec3 e2 = cross(t, e1);
  const long double x = static_cast<long double>(dot(d, e1)) / length(e1);
  const long double y = static_cast<long double>(dot(d, e2)) / length(e2);
  long double th = std::atan2(y, x);
  if (th < 0) th += 2 * std::numbers::pi_v<long double>;
  return th;
}

TEST(RadialLess, IsAStrictWeakOrderMatchingTheAngle) {
  for (std::uint64_t seed = 70000; seed < 70020; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    auto small = [&] { return static_cast<double>(rng() % 9) - 4; };
    Vec3 t, d0;
    do t = {small(), small(), small()};
    while (t == Vec3{});
    do d0 = {small(), small(), small()};
    while (cross(t, d0) == Vec3{});
    const std::vector<Vec3> dirs = radial_fixture(rng, t, d0);
    const std::size_t n = dirs.size();
    const ExactVec3 et = exact(t), ed0 = exact(d0);
    std::vector<ExactVec3> ed;
    for (Vec3 d : dirs) ed.push_back(exact(d));
    std::vector<std::vector<bool>> less(n, std::vector<bool>(n));
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) less[i][j] = radial_less(et, ed0, ed[i], ed[j]);
    }
    auto equiv = [&](std::size_t i, std::size_t j) { return !less[i][j] && !less[j][i]; };
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_FALSE(less[i][i]) << i;
      for (std::size_t j = 0; j < n; ++j) {
        ASSERT_FALSE(less[i][j] && less[j][i]) << i << ' ' << j;
        for (std::size_t k = 0; k < n; ++k) {
          if (less[i][j] && less[j][k]) {
            ASSERT_TRUE(less[i][k]) << i << ' ' << j << ' ' << k;
          }
          if (equiv(i, j) && equiv(j, k)) {
            ASSERT_TRUE(equiv(i, k)) << i << ' ' << j << ' ' << k;
          }
        }
        // Agrees with the floating-point angle wherever that is clear-cut; directions
        // at the same angle (multiples, shifts along t) are equivalent.
        const long double ai = angle(t, d0, dirs[i]), aj = angle(t, d0, dirs[j]);
        if (std::fabs(ai - aj) > 1e-9L) {
          ASSERT_EQ(less[i][j], ai < aj) << dirs[i] << ' ' << dirs[j];
        }
        const Vec3 c = cross(cross(t, dirs[i]), cross(t, dirs[j]));  // exact: small ints
        if (c == Vec3{} && dot(cross(t, dirs[i]), cross(t, dirs[j])) > 0) {
          ASSERT_TRUE(equiv(i, j)) << dirs[i] << ' ' << dirs[j];
        }
      }
      // The opposite direction lies half a turn away.
      const int h = radial_half(et, ed0, ed[i]), hn = radial_half(et, ed0, exact(-dirs[i]));
      ASSERT_EQ(hn, (h + 2) % 4) << dirs[i];
    }
    EXPECT_EQ(radial_half(et, ed0, ed0), 0);
    EXPECT_EQ(radial_half(et, ed0, exact(-d0)), 2);
    EXPECT_EQ(radial_half(et, ed0, exact(d0 * 5 - t * 3)), 0);
    std::vector<std::size_t> order(n);
    for (std::size_t i = 0; i < n; ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](auto i, auto j) { return less[i][j]; });
    for (std::size_t i = 1; i < n; ++i) {
      ASSERT_LE(angle(t, d0, dirs[order[i - 1]]), angle(t, d0, dirs[order[i]]) + 1e-9L);
    }
  }
}

// radial_half and radial_less decide in doubles first (the expansions summed, with
// a bound on the sum's error) and exactly when that cannot tell: on faces through one
// edge whose third points lie a few units in the last place off one plane (the
// directions nearly coplanar, some exactly), each answer is the exact one.
TEST(RadialHalf, FilterAgreesWithTheExactAnswer) {
  const Vec3 a{0.1, 0.7, -0.3}, b{1.3, -0.2, 0.9}, p0{0.45, 1.9, 0.35};
  const ExactVec3 t = exact_sub(b, a);
  auto dir = [&](Vec3 p) { return exact_cross(exact_cross(exact_sub(b, a), exact_sub(p, a)), t); };
  auto exact_half = [&](const ExactVec3& d0, const ExactVec3& d) {
    const int s = exact_det3(t, d0, d).sign();
    if (s != 0) return s > 0 ? 1 : 3;
    return exact_dot(exact_cross(t, d0), exact_cross(t, d)).sign() > 0 ? 0 : 2;
  };
  std::vector<ExactVec3> dirs;
  for (int dx = -3; dx <= 3; ++dx)
    for (int dz = -3; dz <= 3; ++dz) {
      Vec3 p = p0;
      for (int k = 0; k < std::abs(dx); ++k) p.x = std::nextafter(p.x, dx > 0 ? 10.0 : -10.0);
      for (int k = 0; k < std::abs(dz); ++k) p.z = std::nextafter(p.z, dz > 0 ? 10.0 : -10.0);
      dirs.push_back(dir(p));
      dirs.push_back(exact_cross(t, exact_cross(exact_sub(b, a), exact_sub(p, a))));  // opposite
    }
  int zeros = 0;
  for (const ExactVec3& d0 : dirs)
    for (const ExactVec3& d : dirs) {
      const int want = exact_half(d0, d);
      zeros += want == 0 || want == 2;
      ASSERT_EQ(radial_half(t, d0, d), want);
    }
  EXPECT_GT(zeros, 0);  // coplanar pairs are met, and told apart exactly
  for (std::size_t i = 0; i < dirs.size(); ++i)
    for (std::size_t j = 0; j < dirs.size(); ++j) {
      const int hi = exact_half(dirs[0], dirs[i]), hj = exact_half(dirs[0], dirs[j]);
      const bool want = hi != hj ? hi < hj
                                 : (hi == 1 || hi == 3) && exact_det3(t, dirs[i], dirs[j]).sign() > 0;
      ASSERT_EQ(radial_less(t, dirs[0], dirs[i], dirs[j]), want) << i << ' ' << j;
    }
}

// Directions given as exact expansions (as topo/radial.cpp builds them: N x t) with
// non-integer coordinates: same axioms on a tilted axis.
TEST(RadialLess, StrictWeakOrderOnExactCrossProducts) {
  std::mt19937_64 rng(9);
  const Vec3 a{0.1, 0.7, -0.3}, b{1.3, -0.2, 0.9};
  const ExactVec3 t = exact_sub(b, a);
  std::vector<ExactVec3> dirs;
  for (int i = 0; i < 24; ++i) {
    const Vec3 p = random_point(rng, 1);  // a face through a, b and p
    const ExactVec3 n = exact_cross(exact_sub(b, a), exact_sub(p, a));
    dirs.push_back(exact_cross(n, t));  // into the face, perpendicular to t
    if (i % 3 == 0) dirs.push_back(exact_cross(exact_sub(a, b), n));  // the same, recomputed
    if (i % 4 == 0) dirs.push_back(exact_cross(t, n));                // opposite
  }
  const std::size_t n = dirs.size();
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_FALSE(radial_less(t, dirs[0], dirs[i], dirs[i]));
    for (std::size_t j = 0; j < n; ++j) {
      const bool ij = radial_less(t, dirs[0], dirs[i], dirs[j]);
      const bool ji = radial_less(t, dirs[0], dirs[j], dirs[i]);
      ASSERT_FALSE(ij && ji);
      for (std::size_t k = 0; k < n; ++k) {
        if (ij && radial_less(t, dirs[0], dirs[j], dirs[k])) {
          ASSERT_TRUE(radial_less(t, dirs[0], dirs[i], dirs[k])) << i << ' ' << j << ' ' << k;
        }
      }
    }
  }
  // Recomputed copies are equivalent, opposites half a turn apart.
  EXPECT_FALSE(radial_less(t, dirs[0], dirs[0], dirs[1]));
  EXPECT_FALSE(radial_less(t, dirs[0], dirs[1], dirs[0]));
  EXPECT_EQ(radial_half(t, dirs[0], dirs[2]), 2);
}

}  // namespace
}  // namespace cellforge
