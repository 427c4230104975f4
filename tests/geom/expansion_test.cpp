// Expansion arithmetic: exact against an independent oracle (tests/geom/dyadic.h) and
// against __int128, with the representation invariants checked after every operation.
#include "cellforge/geom/expansion.h"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "geom/dyadic.h"
#include "geom/expansion_kernels.h"

namespace cellforge {
namespace {

__extension__ typedef __int128 Int128;  // exact reference arithmetic (GCC, Clang)
__extension__ typedef unsigned __int128 UInt128;

using testing::Dyadic;
using testing::sum_of;

// The least significant nonzero bit of y, as a power of two.
double lowest_bit(double y) {
  int e = 0;
  const double m = std::frexp(std::fabs(y), &e);
  const auto bits = static_cast<std::uint64_t>(std::ldexp(m, 53));
  return std::ldexp(1.0, e - 53 + std::countr_zero(bits));
}

// Nonzero components by increasing magnitude, each one entirely below the lowest
// nonzero bit of the next (nonoverlapping).
::testing::AssertionResult well_formed(std::span<const double> c) {
  for (std::size_t i = 0; i < c.size(); ++i) {
    if (c[i] == 0 || !std::isfinite(c[i])) {
      return ::testing::AssertionFailure() << "component " << i << " is " << c[i];
    }
    if (i > 0 && !(std::fabs(c[i - 1]) < lowest_bit(c[i]))) {
      return ::testing::AssertionFailure()
             << "components " << i - 1 << " and " << i << " overlap: " << c[i - 1] << ", " << c[i];
    }
  }
  return ::testing::AssertionSuccess();
}

// |estimate - exact| <= 2^-50 |exact|.
::testing::AssertionResult estimate_close(const Expansion& e, const Dyadic& exact) {
  const Dyadic err = Dyadic(e.estimate()) - exact;
  const Dyadic abs_err = err.sign() < 0 ? -err : err;
  const Dyadic abs_exact = exact.sign() < 0 ? -exact : exact;
  if ((abs_exact - abs_err * 0x1p50).sign() >= 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "estimate " << e.estimate() << " of " << exact.approx();
}

::testing::AssertionResult exactly(const Expansion& e, const Dyadic& exact) {
  if (!well_formed(e.components())) return well_formed(e.components());
  if (!(sum_of(e.components()) == exact)) {
    return ::testing::AssertionFailure()
           << "value " << to_string(sum_of(e.components())) << " != " << to_string(exact);
  }
  if (e.sign() != exact.sign()) {
    return ::testing::AssertionFailure() << "sign " << e.sign() << " != " << exact.sign();
  }
  return estimate_close(e, exact);
}

// A double with a random 53-bit significand, sign and exponent in [lo, hi].
double random_double(std::mt19937_64& rng, int lo, int hi) {
  const double m = std::ldexp(static_cast<double>(rng() >> 11), -53);  // [0, 1)
  const int e = std::uniform_int_distribution<int>(lo, hi)(rng);
  return ((rng() & 1) ? -1 : 1) * std::ldexp(0.5 + m / 2, e);
}

TEST(ErrorFreeTransforms, TwoSumAndTwoProductLoseNothing) {
  std::mt19937_64 rng(1);
  for (int i = 0; i < 20000; ++i) {
    const double a = random_double(rng, -60, 60), b = random_double(rng, -60, 60);
    const TwoDouble s = two_sum(a, b), d = two_diff(a, b), p = two_product(a, b);
    ASSERT_EQ(Dyadic(s.hi) + s.lo, Dyadic(a) + b) << a << " + " << b;
    ASSERT_EQ(Dyadic(d.hi) + d.lo, Dyadic(a) - b) << a << " - " << b;
    ASSERT_EQ(Dyadic(p.hi) + p.lo, Dyadic(a) * b) << a << " * " << b;
    ASSERT_EQ(s.hi + s.lo, s.hi);  // the error is below half an ulp of the sum
    ASSERT_EQ(p.hi + p.lo, p.hi);
    const double big = std::fabs(a) >= std::fabs(b) ? a : b, small = big == a ? b : a;
    const TwoDouble f = fast_two_sum(big, small);
    ASSERT_EQ(Dyadic(f.hi) + f.lo, Dyadic(a) + b);
  }
}

TEST(Expansion, CancellationKeepsTheSmallTerms) {
  const Expansion one = Expansion(1e100) + 1.0 - 1e100;
  EXPECT_EQ(one.sign(), 1);
  EXPECT_EQ(one.estimate(), 1.0);
  EXPECT_EQ(one.components().size(), 1u);

  EXPECT_EQ((Expansion(1.0) - 1e100 + 1e100).estimate(), 1.0);
  EXPECT_EQ((Expansion(1e100) + 1e-100 - 1e100).estimate(), 1e-100);
  EXPECT_EQ((Expansion(1e100) - 1e100).sign(), 0);
  // The doubles nearest 0.1, 0.2 and 0.3 do not add up: they miss by 2^-55 exactly.
  EXPECT_EQ((Expansion(0.1) + 0.2 - 0.3).estimate(), 0x1p-55);
  // (1 + 2^-52)^2 = 1 + 2^-51 + 2^-104: the last term is beyond any double's reach.
  const Expansion sq = Expansion(1 + 0x1p-52) * (1 + 0x1p-52);
  EXPECT_EQ((sq - 1.0 - 0x1p-51).estimate(), 0x1p-104);
}

TEST(Expansion, ZeroAndNegation) {
  const Expansion zero;
  EXPECT_EQ(zero.sign(), 0);
  EXPECT_TRUE(zero.components().empty());
  EXPECT_EQ(zero.estimate(), 0.0);
  EXPECT_TRUE(Expansion(0.0).components().empty());
  EXPECT_TRUE(Expansion(-0.0).components().empty());

  const Expansion x = Expansion(3.0) * 1e-30 + 7.0;
  EXPECT_TRUE((x - x).components().empty());
  EXPECT_TRUE((x * 0.0).components().empty());
  EXPECT_TRUE((zero * x).components().empty());
  EXPECT_EQ((-x).sign(), -1);
  EXPECT_TRUE(exactly(-x, -(Dyadic(3.0) * 1e-30 + 7.0)));
  EXPECT_TRUE(exactly(x + -x, Dyadic()));
}

// v exactly as an expansion: three pieces of at most 40 bits each.
Expansion from_int128(Int128 v) {
  const bool neg = v < 0;
  UInt128 m = neg ? -static_cast<UInt128>(v) : v;
  Expansion r;
  for (int shift = 0; m != 0; shift += 40, m >>= 40) {
    r += std::ldexp(static_cast<double>(static_cast<std::uint64_t>(m & ((1ull << 40) - 1))), shift);
  }
  return neg ? -r : r;
}

TEST(Expansion, SmallIntegerArithmeticMatchesInt128) {
  std::mt19937_64 rng(2);
  std::uniform_int_distribution<std::int64_t> draw(-(1 << 24), 1 << 24);
  for (int i = 0; i < 20000; ++i) {
    std::int64_t v[7];
    double d[7];
    for (int k = 0; k < 7; ++k) d[k] = static_cast<double>(v[k] = draw(rng));
    // (ab - cd)(ef + g): up to 2^98, far beyond a double's 53 bits.
    const Int128 want =
        (Int128{v[0]} * v[1] - Int128{v[2]} * v[3]) * (Int128{v[4]} * v[5] + Int128{v[6]});
    const Expansion got =
        (Expansion(d[0]) * d[1] - Expansion(d[2]) * d[3]) * (Expansion(d[4]) * d[5] + d[6]);
    ASSERT_EQ((got - from_int128(want)).sign(), 0) << "case " << i;
    ASSERT_EQ(got.sign(), want > 0 ? 1 : (want < 0 ? -1 : 0));
    const long double approx = static_cast<long double>(want);
    ASSERT_LE(std::fabs(got.estimate() - approx), 0x1p-50L * std::fabs(approx)) << i;
    ASSERT_TRUE(well_formed(got.components()));
  }
}

// Random chains of +, -, * over values built to cancel: exact at every step.
TEST(Expansion, RandomExpressionsAreExact) {
  constexpr std::uint64_t kBaseSeed = 1000;
  for (std::uint64_t seed = kBaseSeed; seed < kBaseSeed + 3000; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::vector<Expansion> pool;
    std::vector<Dyadic> oracle;
    auto push = [&](Expansion e, Dyadic d) {
      pool.push_back(std::move(e));
      oracle.push_back(std::move(d));
    };
    for (int i = 0; i < 4; ++i) {
      const double x = random_double(rng, -40, 40);
      push(x, x);
      const double near = std::nextafter(x, 0.0) * (1 + 0x1p-40);  // shares leading bits
      push(-near, -Dyadic(near));
    }
    for (int step = 0; step < 14; ++step) {
      const std::size_t i = rng() % pool.size(), j = rng() % pool.size();
      // Multiply only where no term can overflow or underflow (the precondition).
      const double mag = std::fabs(pool[i].estimate()) + std::fabs(pool[j].estimate());
      const bool can_multiply =
          pool[i].sign() != 0 && pool[j].sign() != 0 && mag < 0x1p150 &&
          lowest_bit(pool[i].components()[0]) * lowest_bit(pool[j].components()[0]) > 0x1p-1000;
      switch (rng() % 3) {
        case 0:
          push(pool[i] + pool[j], oracle[i] + oracle[j]);
          break;
        case 1:
          push(pool[i] - pool[j], oracle[i] - oracle[j]);
          break;
        default:
          if (can_multiply) {
            push(pool[i] * pool[j], oracle[i] * oracle[j]);
          } else {
            push(pool[i] - pool[j], oracle[i] - oracle[j]);
          }
      }
      ASSERT_TRUE(exactly(pool.back(), oracle.back())) << "step " << step;
    }
  }
}

TEST(Expansion, LongExpansionsCopyAndMoveDeeply) {
  // 2^(55 k) for k = -9..9: no two components can merge, so 19 stay.
  Expansion long_one;
  Dyadic want;
  for (int k = -9; k <= 9; ++k) {
    long_one += std::ldexp(1.0, 55 * k);
    want = want + std::ldexp(1.0, 55 * k);
  }
  ASSERT_EQ(long_one.components().size(), 19u);
  ASSERT_TRUE(exactly(long_one, want));

  Expansion copy = long_one;
  EXPECT_TRUE(exactly(copy, want));
  const Expansion& alias = copy;
  copy = alias;  // self-assignment keeps the value
  EXPECT_TRUE(exactly(copy, want));
  Expansion moved = std::move(copy);
  EXPECT_TRUE(exactly(moved, want));
  moved = Expansion(2.0);
  EXPECT_TRUE(exactly(moved, 2.0));
  moved = long_one;
  EXPECT_TRUE(exactly(long_one * long_one, want * want));
  Expansion short_one(5.0);
  Expansion moved_short = std::move(short_one);
  EXPECT_TRUE(exactly(moved_short, 5.0));
  EXPECT_TRUE(exactly(moved - long_one, Dyadic()));
}

// The kernels directly: an uncompressed product compresses to the same value, no
// longer, still well formed.
TEST(ExpansionKernels, CompressKeepsTheValue) {
  namespace k = expansion_kernels;
  std::mt19937_64 rng(3);
  for (int i = 0; i < 5000; ++i) {
    SCOPED_TRACE("case " + std::to_string(i));
    k::Fixed<4> a, b;
    Dyadic da, db;
    for (auto* x : {&a, &b}) {
      // Two-term expansions x = hi + lo with lo far below hi.
      const double hi = random_double(rng, -20, 20);
      const double lo = random_double(rng, -90, -70);
      const TwoDouble s = fast_two_sum(hi, lo);
      x->n = 0;
      if (s.lo != 0) x->c[x->n++] = s.lo;
      x->c[x->n++] = s.hi;
      (x == &a ? da : db) = Dyadic(s.hi) + s.lo;
    }
    auto p = a * b - a;
    ASSERT_TRUE(well_formed(p.span()));
    ASSERT_EQ(sum_of(p.span()), da * db - da);
    const int before = p.n;
    p.n = k::compress(p.c, p.n);
    ASSERT_LE(p.n, before);
    ASSERT_TRUE(well_formed(p.span()));
    ASSERT_EQ(sum_of(p.span()), da * db - da);
  }
}

}  // namespace
}  // namespace cellforge
