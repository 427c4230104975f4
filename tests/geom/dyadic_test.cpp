// geom::Dyadic, the exact stage of decide() (filtered.h), against the schoolbook oracle
// of tests/geom/dyadic.h, which shares no code with it: signs, the order of every pair,
// values to double precision, and identities that must come out exactly zero; over
// integers, halves, exponents across the whole range, subnormals, and numbers large
// enough to leave the inline limbs for the heap.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include "cellforge/geom/filtered.h"
#include "geom/dyadic.h"

namespace cellforge {
namespace {

using Oracle = testing::Dyadic;

double random_double(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 5);
  std::uniform_real_distribution<double> unit(-1, 1);
  switch (kind(rng)) {
    case 0:
      return static_cast<double>(std::uniform_int_distribution<int>(-1000, 1000)(rng));
    case 1:
      return std::uniform_int_distribution<int>(-64, 64)(rng) * 0.5;
    case 2:  // any exponent a double has, subnormals included
      return std::ldexp(unit(rng), std::uniform_int_distribution<int>(-1074, 1000)(rng));
    case 3:
      return 0.0;
    default:  // CAD-sized
      return std::ldexp(unit(rng), std::uniform_int_distribution<int>(-30, 30)(rng));
  }
}

struct Pair {
  Dyadic g;
  Oracle o;
  int degree;
};

::testing::AssertionResult agree(const Pair& p) {
  if (p.g.sign() != p.o.sign())
    return ::testing::AssertionFailure() << "sign " << p.g.sign() << " against " << p.o.sign() << " ("
                                         << to_string(p.o) << ")";
  const double want = p.o.approx(), got = p.g.to_double();
  if (std::isfinite(want) && std::abs(want) > 1e-290 && std::abs(want) < 1e290 &&
      !(std::abs(got - want) <= 0x1p-48 * std::abs(want)))
    return ::testing::AssertionFailure() << "value " << got << " against " << want;
  return ::testing::AssertionSuccess();
}

TEST(Dyadic, AgreesWithTheOracle) {
  std::mt19937_64 rng(20261207);
  for (int round = 0; round < 3000; ++round) {
    std::vector<Pair> v;
    for (int i = 0; i < 6; ++i) {
      const double d = random_double(rng);
      v.push_back({Dyadic(d), Oracle(d), 1});
    }
    for (int step = 0; step < 40; ++step) {
      std::uniform_int_distribution<std::size_t> pick(0, v.size() - 1);
      const Pair &a = v[pick(rng)], &b = v[pick(rng)];
      switch (std::uniform_int_distribution<int>(0, 3)(rng)) {
        case 0:
          v.push_back({a.g + b.g, a.o + b.o, std::max(a.degree, b.degree)});
          break;
        case 1:
          v.push_back({a.g - b.g, a.o - b.o, std::max(a.degree, b.degree)});
          break;
        case 2:
          if (a.degree + b.degree <= 12) v.push_back({a.g * b.g, a.o * b.o, a.degree + b.degree});
          break;
        default:
          v.push_back({-a.g, -a.o, a.degree});
      }
      ASSERT_TRUE(agree(v.back())) << "round " << round << " step " << step;
    }
    // The order of pairs: exact, whatever the values' sizes.
    for (std::size_t i = 0; i < v.size(); ++i)
      for (std::size_t j = i + 1; j < v.size(); j += 3)
        ASSERT_EQ((v[i].g - v[j].g).sign(), (v[i].o - v[j].o).sign()) << "round " << round;
  }
}

TEST(Dyadic, IdentitiesAreExactlyZero) {
  std::mt19937_64 rng(5);
  for (int round = 0; round < 20000; ++round) {
    const Dyadic a(random_double(rng)), b(random_double(rng)), c(random_double(rng)), d(random_double(rng));
    EXPECT_EQ(((a + b) * c - a * c - b * c).sign(), 0);
    EXPECT_EQ(((a + b) + c - (a + (b + c))).sign(), 0);
    EXPECT_EQ((a * b * c * d - d * (c * (b * a))).sign(), 0);
    EXPECT_EQ((a - a).sign(), 0);
    EXPECT_EQ((a * b - b * a).sign(), 0);
    // Near zero but not zero: the smallest double added to a product.
    const Dyadic tiny(std::ldexp(1.0, -1074));
    EXPECT_EQ(((a * b + tiny) - a * b).sign(), 1);
  }
}

TEST(Dyadic, LargeNumbersLeaveTheInlineLimbs) {
  // A product of 40 doubles with full 53-bit mantissas: 2,120 bits, past the inline
  // limbs; copies and moves of both kinds keep the value.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(1, 2);
  Dyadic g(1.0);
  Oracle o(1.0);
  for (int i = 0; i < 40; ++i) {
    const double x = unit(rng) * (i % 2 ? -1 : 1);
    g = g * Dyadic(x);
    o = o * Oracle(x);
    ASSERT_EQ(g.sign(), o.sign());
  }
  const Dyadic copy = g;
  Dyadic moved = std::move(g);
  EXPECT_EQ((copy - moved).sign(), 0);
  Dyadic small(3.0);
  small = moved;  // an inline number given a heap block
  EXPECT_EQ((small - copy).sign(), 0);
  moved = Dyadic(2.0);  // a heap number given an inline value
  EXPECT_EQ((moved - Dyadic(2.0)).sign(), 0);
  const Oracle one_more = o + Oracle(std::ldexp(1.0, -1074));
  const Dyadic g_more = copy + Dyadic(std::ldexp(1.0, -1074));
  EXPECT_EQ((g_more - copy).sign(), 1);
  EXPECT_EQ((one_more - o).sign(), 1);
  EXPECT_NEAR(copy.to_double() / o.approx(), 1.0, 1e-14);
}

TEST(Dyadic, DecideSettlesZeroOnlyExactly) {
  // A point exactly on a line, with coordinates no filter can multiply exactly: the
  // zero comes from the exact stage.
  const double a = 0.1, b = 0.7, c = 1.0 / 3;
  const int s = decide([&]<class T>() { return T(a) * T(b) * T(c) - T(c) * T(a) * T(b); });
  EXPECT_EQ(s, 0);
  const int t = decide([&]<class T>() { return T(a) * T(b) * T(c) - T(c) * T(a) * T(b) + T(0x1p-1074); });
  EXPECT_EQ(t, 1);
}

}  // namespace
}  // namespace cellforge
