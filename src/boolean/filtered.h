// Filtered numbers for the Boolean's predicates on implicit points.
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
// first on Fp, and again on Expansion (geom/expansion.h) only when the filter
// cannot decide: decide(f, g) below.
#pragma once
#include <cmath>

#include "cellforge/geom/expansion.h"

namespace cellforge::boolean {

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
inline int sign_of(const Expansion& a) { return a.sign(); }

// The sign of a polynomial given as a callable templated on the number type.
template <class Poly>
int decide(Poly poly) {
  const int s = sign_of(poly.template operator()<Fp>());
  if (s != kUncertain) return s;
  return sign_of(poly.template operator()<Expansion>());
}

}  // namespace cellforge::boolean
