// Exact arithmetic on doubles by floating-point expansions.
//
// An expansion is an unevaluated sum e_0 + e_1 + ... + e_{n-1} of doubles, kept in
// order of increasing magnitude, strongly nonoverlapping, and without zero
// components; the empty sum is 0, and the sign of a nonzero expansion is the sign of
// its largest component. Sums, differences and products of expansions are exact.
// The algorithms are those of J. R. Shewchuk, "Adaptive Precision Floating-Point
// Arithmetic and Fast Robust Geometric Predicates", Discrete & Computational Geometry
// 18(3), 1997 (section 2: Two-Sum, Two-Product, Fast-Expansion-Sum, Scale-Expansion,
// Compress), written afresh here.
//
// Preconditions: IEEE 754 binary64 arithmetic rounding to nearest-even (the default;
// no -ffast-math), and no intermediate result overflows or underflows (an error term
// below 2^-1074 cannot be represented). predicates.h states what that means for
// coordinates.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <span>

namespace cellforge::inline geom {

// A double with the rounding error of the operation that produced it:
// hi = fl(a op b) and hi + lo == a op b exactly.
struct TwoDouble {
  double hi, lo;
};

// a + b exactly (Knuth's Two-Sum; no condition on the operands).
inline TwoDouble two_sum(double a, double b) {
  const double s = a + b;
  const double b_virtual = s - a;
  const double a_virtual = s - b_virtual;
  return {s, (a - a_virtual) + (b - b_virtual)};
}

// a + b exactly, for |a| >= |b| (Dekker's Fast-Two-Sum).
inline TwoDouble fast_two_sum(double a, double b) {
  const double s = a + b;
  return {s, b - (s - a)};
}

// a - b exactly.
inline TwoDouble two_diff(double a, double b) { return two_sum(a, -b); }

// a * b exactly: the fused multiply-add yields the rounding error of the product.
inline TwoDouble two_product(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

// An exact real number, the sum of its components(). A value type: copies are deep,
// and up to kInline components live inside the object without a heap allocation.
class Expansion {
 public:
  Expansion() noexcept {}  // zero (the unused inline storage stays uninitialised)
  Expansion(double d);     // NOLINT(google-explicit-constructor): doubles mix freely
  Expansion(const Expansion& other);
  Expansion(Expansion&& other) noexcept;
  Expansion& operator=(const Expansion& other);
  Expansion& operator=(Expansion&& other) noexcept;
  ~Expansion() = default;

  // -1, 0 or +1: exact.
  int sign() const { return size_ == 0 ? 0 : (data()[size_ - 1] > 0 ? 1 : -1); }
  // The value rounded to a double (within a few ulps; exact when it is a double).
  double estimate() const;
  // Nonzero, strongly nonoverlapping, by increasing magnitude.
  std::span<const double> components() const { return {data(), size_}; }

  friend Expansion operator+(const Expansion& a, const Expansion& b);
  friend Expansion operator-(const Expansion& a, const Expansion& b);
  friend Expansion operator*(const Expansion& a, const Expansion& b);
  friend Expansion operator-(const Expansion& a);
  Expansion& operator+=(const Expansion& b) { return *this = *this + b; }
  Expansion& operator-=(const Expansion& b) { return *this = *this - b; }
  Expansion& operator*=(const Expansion& b) { return *this = *this * b; }

 private:
  static constexpr std::uint32_t kInline = 6;

  // Takes a valid component sequence (nonzero, strongly nonoverlapping, increasing).
  explicit Expansion(std::span<const double> components);
  double* data() { return heap_ ? heap_.get() : inline_; }
  const double* data() const { return heap_ ? heap_.get() : inline_; }
  void assign(std::span<const double> components);

  std::unique_ptr<double[]> heap_;  // set iff size_ > kInline
  std::uint32_t size_ = 0;
  double inline_[kInline];
};

}  // namespace cellforge::inline geom
