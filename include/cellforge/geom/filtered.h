// Filtered numbers for predicates on implicit points (implicit.h).
//
// Fp is a double with a bound on its absolute error: every +, - and * adds the
// rounding error of its own result and carries the operands' errors forward
// (first-order forward error analysis, each bound grown by 2^-50 to cover the
// rounding of the bound itself). A sign is certain when |value| > error. When both
// operands are exact and the result is representable (checked with two-sum or the
// fused multiply-add), the result is exact too, so that axis-aligned and small
// integer inputs are decided in the filter even when the answer is zero.
//
// A predicate is written once as a template over the number type and evaluated
// first on Fp, then on Dd (double-double with an error bound), and on Dyadic only
// when neither can decide: decide() below. Dyadic is an exact dyadic rational m * 2^e with an arbitrary-precision
// integer m (GMP's mpn arithmetic): the predicates on implicit points reach degree 30 in the input
// coordinates, beyond what expansions of doubles hold without underflow.
#pragma once
#include <gmp.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>

#include "cellforge/geom/expansion.h"  // two_sum

namespace cellforge::inline geom {

struct Fp {
  double v = 0;  // the value computed in doubles
  double e = 0;  // |exact - v| <= e
  Fp() = default;
  Fp(double x) : v(x), e(0) {}  // NOLINT(google-explicit-constructor): doubles are exact
  Fp(double value, double error) : v(value), e(error) {}
};

inline constexpr double kUnit = 0x1p-53;
inline constexpr double kGrow = 1 + 0x1p-50;
inline constexpr int kUncertain = 2;

// Predicates the filter left to exact arithmetic, on this thread (for the report).
inline std::size_t& exact_evaluations() {
  static thread_local std::size_t n = 0;
  return n;
}

inline Fp operator+(Fp a, Fp b) {
  const double v = a.v + b.v;
  if (a.e == 0 && b.e == 0 && two_sum(a.v, b.v).lo == 0) return {v, 0};
  return {v, (a.e + b.e + std::abs(v) * kUnit) * kGrow};
}
inline Fp operator-(Fp a) { return {-a.v, a.e}; }
inline Fp operator-(Fp a, Fp b) { return a + (-b); }
inline Fp operator*(Fp a, Fp b) {
  const double v = a.v * b.v;
  if (a.e == 0 && b.e == 0 && std::fma(a.v, b.v, -v) == 0) return {v, 0};
  return {v, (std::abs(a.v) * b.e + std::abs(b.v) * a.e + a.e * b.e + std::abs(v) * kUnit) * kGrow};
}

// -1, 0, +1 when certain, kUncertain otherwise.
inline int sign_of(Fp a) {
  if (a.v > a.e) return 1;
  if (-a.v > a.e) return -1;
  return (a.v == 0 && a.e == 0) ? 0 : kUncertain;
}

// A double-double with an error bound, the middle stage of decide(): hi + lo holds
// about 106 bits, and |exact - (hi + lo)| <= e. Two points a few units in the last
// place apart (lpi points on the two planes of a quad that rounding bent) defeat the
// double filter; this settles most of them at a small fraction of an exact
// evaluation's cost. Each operation's own error is at most 2^-103 of its result
// (Joldes, Muller and Popescu 2017 bound the accurate algorithms below by 3u^2 and
// 4u^2, u = 2^-53); a product near the ends of the exponent range, where lo would
// lose bits, makes the bound infinite.
struct Dd {
  double hi = 0, lo = 0, e = 0;
  Dd() = default;
  Dd(double x) : hi(x) {}  // NOLINT(google-explicit-constructor): doubles are exact
  Dd(double h, double l, double err) : hi(h), lo(l), e(err) {}
};

inline constexpr double kDdUnit = 0x1p-103;

inline double magnitude(const Dd& a) { return std::abs(a.hi) + std::abs(a.lo); }

inline Dd operator+(const Dd& a, const Dd& b) {
  const TwoDouble s = two_sum(a.hi, b.hi), t = two_sum(a.lo, b.lo);
  const TwoDouble u = fast_two_sum(s.hi, s.lo + t.hi);
  const TwoDouble r = fast_two_sum(u.hi, u.lo + t.lo);
  const bool exact = a.e == 0 && b.e == 0 && a.lo == 0 && b.lo == 0;  // two doubles: exact
  return {r.hi, r.lo, exact ? 0 : (a.e + b.e + magnitude(Dd(r.hi, r.lo, 0)) * kDdUnit) * kGrow};
}
inline Dd operator-(const Dd& a) { return {-a.hi, -a.lo, a.e}; }
inline Dd operator-(const Dd& a, const Dd& b) { return a + (-b); }
inline Dd operator*(const Dd& a, const Dd& b) {
  const TwoDouble p = two_product(a.hi, b.hi);
  const TwoDouble r = fast_two_sum(p.hi, p.lo + (a.hi * b.lo + a.lo * b.hi));
  const double m = std::abs(r.hi);
  if ((m != 0 && (m < 0x1p-900 || m > 0x1p900)) || (m == 0 && a.hi != 0 && b.hi != 0))
    return {r.hi, r.lo, INFINITY};
  const bool exact = a.e == 0 && b.e == 0 && a.lo == 0 && b.lo == 0;  // two doubles: exact
  const double err = magnitude(a) * b.e + magnitude(b) * a.e + a.e * b.e + (m + std::abs(r.lo)) * kDdUnit;
  return {r.hi, r.lo, exact ? 0 : err * kGrow};
}

inline int sign_of(const Dd& a) {
  if (a.hi - std::abs(a.lo) > a.e) return 1;
  if (-a.hi - std::abs(a.lo) > a.e) return -1;
  return (a.hi == 0 && a.lo == 0 && a.e == 0) ? 0 : kUncertain;
}

// m * 2^e exactly, m a signed integer of any size: the last stage of decide(). The
// magnitude is a little-endian array of 64-bit limbs held inside the number up to
// kInline limbs (a predicate's temporaries never touch the heap: the GMP integers
// used before spent half of an exact evaluation in malloc and free) and on the heap
// beyond; the arithmetic is GMP's mpn layer, which allocates nothing. A double's
// mantissa is stored with its trailing zero bits moved into the exponent, so that
// small integers and halves make short products.
class Dyadic {
 public:
  static constexpr int kInline = 8;

  Dyadic() = default;
  Dyadic(double d);  // NOLINT(google-explicit-constructor): doubles are exact
  Dyadic(const Dyadic& o) { copy_from(o); }
  Dyadic(Dyadic&& o) noexcept { move_from(o); }
  Dyadic& operator=(const Dyadic& o) {
    if (this != &o) copy_from(o);
    return *this;
  }
  Dyadic& operator=(Dyadic&& o) noexcept {
    if (this != &o) {
      release();
      move_from(o);
    }
    return *this;
  }
  ~Dyadic() { release(); }

  int sign() const { return (size_ > 0) - (size_ < 0); }
  // The value within a relative 2^-52 (the mantissa is truncated to 53 bits).
  double to_double() const;

  friend Dyadic operator*(const Dyadic& a, const Dyadic& b);
  friend Dyadic operator+(const Dyadic& a, const Dyadic& b) { return add(a, b, false); }
  friend Dyadic operator-(const Dyadic& a, const Dyadic& b) { return add(a, b, true); }
  friend Dyadic operator-(const Dyadic& a) {
    Dyadic r(a);
    r.size_ = -r.size_;
    return r;
  }

 private:
  static Dyadic add(const Dyadic& a, const Dyadic& b, bool negate_b);
  // Room for n limbs, the value dropped.
  void reserve(int n) {
    if (n <= cap_) return;
    release();
    limbs_ = new mp_limb_t[static_cast<std::size_t>(n)];
    cap_ = n;
  }
  void release() {
    if (limbs_ != inline_) delete[] limbs_;
    limbs_ = inline_;
    cap_ = kInline;
  }
  void copy_from(const Dyadic& o) {
    const int n = o.size_ < 0 ? -o.size_ : o.size_;
    reserve(n);
    for (int i = 0; i < n; ++i) limbs_[i] = o.limbs_[i];
    size_ = o.size_;
    e_ = o.e_;
  }
  void move_from(Dyadic& o) {  // *this holds no heap block
    if (o.limbs_ != o.inline_) {
      limbs_ = o.limbs_;
      cap_ = o.cap_;
      o.limbs_ = o.inline_;
      o.cap_ = kInline;
    } else {
      const int n = o.size_ < 0 ? -o.size_ : o.size_;
      for (int i = 0; i < n; ++i) inline_[i] = o.inline_[i];
    }
    size_ = o.size_;
    e_ = o.e_;
  }
  // Drops zero limbs at the top; the sign is `negative`.
  void set_size(int n, bool negative) {
    while (n > 0 && limbs_[n - 1] == 0) --n;
    size_ = negative ? -n : n;
    if (n == 0) e_ = 0;
  }

  mp_limb_t* limbs_ = inline_;
  int size_ = 0;  // the number of limbs in use, negated for a negative value
  int cap_ = kInline;
  long e_ = 0;
  mp_limb_t inline_[kInline];
};

inline int sign_of(const Dyadic& a) { return a.sign(); }

// The sign of a polynomial given as a callable templated on the number type.
template <class Poly>
int decide(Poly poly) {
  const int s = sign_of(poly.template operator()<Fp>());
  if (s != kUncertain) return s;
  const int d = sign_of(poly.template operator()<Dd>());
  if (d != kUncertain) return d;
  ++exact_evaluations();
  return sign_of(poly.template operator()<Dyadic>());
}

}  // namespace cellforge::inline geom
