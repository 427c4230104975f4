// Dyadic: exact numbers m * 2^k (m a schoolbook big integer) — the oracle the geom
// tests compare against. It shares no code or method with the expansion arithmetic
// under test, and needs no GMP: every double is such a number, and sums and products
// of them stay so.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace cellforge::testing {

class Dyadic {
 public:
  Dyadic() = default;
  Dyadic(double d) {  // NOLINT(google-explicit-constructor): exact
    if (d == 0) return;
    int e = 0;
    const double m = std::frexp(std::fabs(d), &e);  // |d| = m 2^e, m in [1/2, 1)
    const auto bits = static_cast<std::uint64_t>(std::ldexp(m, 53));
    mag_ = {static_cast<std::uint32_t>(bits), static_cast<std::uint32_t>(bits >> 32)};
    neg_ = d < 0;
    exp_ = e - 53;
    trim();
  }

  int sign() const { return mag_.empty() ? 0 : (neg_ ? -1 : 1); }

  // The value to about 64 significant bits (for tolerance checks only).
  double approx() const {
    double r = 0;
    const std::size_t from = mag_.size() > 3 ? mag_.size() - 3 : 0;
    for (std::size_t i = from; i < mag_.size(); ++i) {
      r += std::ldexp(static_cast<double>(mag_[i]), exp_ + 32 * static_cast<int>(i));
    }
    return neg_ ? -r : r;
  }

  friend Dyadic operator-(Dyadic a) {
    a.neg_ = !a.neg_ && !a.mag_.empty();
    return a;
  }
  friend Dyadic operator+(Dyadic a, Dyadic b) {
    if (a.mag_.empty()) return b;
    if (b.mag_.empty()) return a;
    if (a.exp_ > b.exp_) std::swap(a, b);
    b.mag_ = shifted_left(b.mag_, b.exp_ - a.exp_);  // both at exponent a.exp_
    if (a.neg_ == b.neg_) {
      a.mag_ = add(a.mag_, b.mag_);
    } else if (less(a.mag_, b.mag_)) {
      a.mag_ = sub(b.mag_, a.mag_);
      a.neg_ = b.neg_;
    } else {
      a.mag_ = sub(a.mag_, b.mag_);
    }
    a.trim();
    return a;
  }
  friend Dyadic operator-(const Dyadic& a, const Dyadic& b) { return a + -b; }
  friend Dyadic operator*(const Dyadic& a, const Dyadic& b) {
    Dyadic r;
    if (a.mag_.empty() || b.mag_.empty()) return r;
    r.mag_.assign(a.mag_.size() + b.mag_.size(), 0);
    for (std::size_t i = 0; i < a.mag_.size(); ++i) {
      std::uint64_t carry = 0;
      for (std::size_t j = 0; j < b.mag_.size(); ++j) {
        const std::uint64_t t = std::uint64_t{a.mag_[i]} * b.mag_[j] + r.mag_[i + j] + carry;
        r.mag_[i + j] = static_cast<std::uint32_t>(t);
        carry = t >> 32;
      }
      r.mag_[i + b.mag_.size()] = static_cast<std::uint32_t>(carry);
    }
    r.neg_ = a.neg_ != b.neg_;
    r.exp_ = a.exp_ + b.exp_;
    r.trim();
    return r;
  }
  friend bool operator==(const Dyadic& a, const Dyadic& b) { return (a - b).sign() == 0; }

  friend std::string to_string(const Dyadic& a) {
    std::string s = a.neg_ ? "-0x" : "0x";
    static const char* digits = "0123456789abcdef";
    for (std::size_t i = a.mag_.size(); i-- > 0;) {
      for (int k = 28; k >= 0; k -= 4) s += digits[(a.mag_[i] >> k) & 15];
    }
    return s + "p" + std::to_string(a.exp_);
  }

 private:
  using Mag = std::vector<std::uint32_t>;  // little-endian limbs, no leading zeros

  void trim() {
    while (!mag_.empty() && mag_.back() == 0) mag_.pop_back();
    if (mag_.empty()) neg_ = false;
  }
  static Mag shifted_left(const Mag& m, int bits) {
    Mag r(bits / 32, 0);
    const int s = bits % 32;
    std::uint32_t carry = 0;
    for (std::uint32_t limb : m) {
      r.push_back(static_cast<std::uint32_t>((std::uint64_t{limb} << s) | carry));
      carry = s == 0 ? 0 : static_cast<std::uint32_t>(limb >> (32 - s));
    }
    r.push_back(carry);
    return r;
  }
  static bool less(Mag a, Mag b) {
    while (!a.empty() && a.back() == 0) a.pop_back();
    while (!b.empty() && b.back() == 0) b.pop_back();
    if (a.size() != b.size()) return a.size() < b.size();
    for (std::size_t i = a.size(); i-- > 0;) {
      if (a[i] != b[i]) return a[i] < b[i];
    }
    return false;
  }
  static Mag add(const Mag& a, const Mag& b) {
    Mag r(std::max(a.size(), b.size()) + 1, 0);
    std::uint64_t carry = 0;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const std::uint64_t t = carry + (i < a.size() ? a[i] : 0) + (i < b.size() ? b[i] : 0);
      r[i] = static_cast<std::uint32_t>(t);
      carry = t >> 32;
    }
    return r;
  }
  static Mag sub(const Mag& a, const Mag& b) {  // a >= b
    Mag r(a.size(), 0);
    std::int64_t borrow = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      std::int64_t t = std::int64_t{a[i]} - (i < b.size() ? b[i] : 0) - borrow;
      borrow = t < 0;
      if (t < 0) t += std::int64_t{1} << 32;
      r[i] = static_cast<std::uint32_t>(t);
    }
    return r;
  }

  bool neg_ = false;
  int exp_ = 0;
  Mag mag_;
};

// The exact sum of a list of doubles (e.g. an expansion's components).
inline Dyadic sum_of(std::span<const double> parts) {
  Dyadic s;
  for (double p : parts) s = s + p;
  return s;
}

}  // namespace cellforge::testing
