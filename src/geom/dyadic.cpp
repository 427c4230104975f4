// Dyadic (filtered.h): exact m * 2^e on GMP's mpn layer, limbs inside the number.
#include <algorithm>
#include <bit>
#include <climits>
#include <cstdint>

#include "cellforge/geom/filtered.h"

namespace cellforge::inline geom {

__extension__ typedef unsigned __int128 UInt128;

static_assert(GMP_NUMB_BITS == 64 && GMP_NAIL_BITS == 0, "Dyadic expects 64-bit limbs without nails");

Dyadic::Dyadic(double d) {
  if (d == 0) return;
  const auto bits = std::bit_cast<std::uint64_t>(d);
  const auto biased = static_cast<long>((bits >> 52) & 0x7ff);
  std::uint64_t m = bits & ((std::uint64_t{1} << 52) - 1);
  long e = -1074;  // a subnormal: m 2^-1074
  if (biased != 0) {
    m |= std::uint64_t{1} << 52;
    e = biased - 1075;
  }
  const int zeros = std::countr_zero(m);
  inline_[0] = m >> zeros;
  e_ = e + zeros;
  size_ = d < 0 ? -1 : 1;
}

double Dyadic::to_double() const {
  if (size_ == 0) return 0;
  mpz_t view;  // a read-only mpz over the limbs: nothing copied or allocated
  mpz_roinit_n(view, limbs_, size_);
  long exp = 0;
  const double d = mpz_get_d_2exp(&exp, view);
  const long total = std::clamp(exp + e_, static_cast<long>(INT_MIN / 2), static_cast<long>(INT_MAX / 2));
  return std::ldexp(d, static_cast<int>(total));
}

Dyadic operator*(const Dyadic& a, const Dyadic& b) {
  Dyadic r;
  if (a.size_ == 0 || b.size_ == 0) return r;
  const int an = a.size_ < 0 ? -a.size_ : a.size_, bn = b.size_ < 0 ? -b.size_ : b.size_;
  const bool negative = (a.size_ < 0) != (b.size_ < 0);
  r.e_ = a.e_ + b.e_;
  if (an == 1 && bn == 1) {
    const UInt128 p = static_cast<UInt128>(a.limbs_[0]) * b.limbs_[0];
    r.limbs_[0] = static_cast<mp_limb_t>(p);
    r.limbs_[1] = static_cast<mp_limb_t>(p >> 64);
    r.set_size(2, negative);
    return r;
  }
  r.reserve(an + bn);
  if (an >= bn) {
    mpn_mul(r.limbs_, a.limbs_, an, b.limbs_, bn);
  } else {
    mpn_mul(r.limbs_, b.limbs_, bn, a.limbs_, an);
  }
  r.set_size(an + bn, negative);
  return r;
}

Dyadic Dyadic::add(const Dyadic& a, const Dyadic& b, bool negate_b) {
  if (b.size_ == 0) return a;
  if (a.size_ == 0) {
    Dyadic r(b);
    if (negate_b) r.size_ = -r.size_;
    return r;
  }
  const bool neg_a = a.size_ < 0, neg_b = (b.size_ < 0) != negate_b;
  // The one of larger exponent is shifted up to the other's.
  const bool a_up = a.e_ >= b.e_;
  const Dyadic& up = a_up ? a : b;
  const Dyadic& low = a_up ? b : a;
  const bool neg_up = a_up ? neg_a : neg_b, neg_low = a_up ? neg_b : neg_a;
  const auto shift = static_cast<unsigned long>(up.e_ - low.e_);
  const int un = up.size_ < 0 ? -up.size_ : up.size_, ln = low.size_ < 0 ? -low.size_ : low.size_;
  const auto whole = static_cast<int>(shift / 64);
  const auto bits = static_cast<unsigned>(shift % 64);
  const int xn = un + whole + 1;         // the shifted magnitude, its carry limb included
  const int n = std::max(xn, ln) + 1;    // and room for the sum's carry
  Dyadic r;
  r.reserve(n);
  mp_limb_t* x = r.limbs_;
  std::fill(x, x + whole, mp_limb_t{0});
  if (bits != 0) {
    x[whole + un] = mpn_lshift(x + whole, up.limbs_, un, bits);
  } else {
    std::copy(up.limbs_, up.limbs_ + un, x + whole);
    x[whole + un] = 0;
  }
  std::fill(x + xn, x + n, mp_limb_t{0});
  r.e_ = low.e_;
  if (neg_up == neg_low) {
    mpn_add(x, x, n, low.limbs_, ln);  // the top limb is zero: no carry out
    r.set_size(n, neg_up);
  } else {
    bool negative = neg_up;
    if (mpn_sub(x, x, n, low.limbs_, ln) != 0) {  // |low| was the larger: 2^(64 n) - (|low| - x)
      mpn_neg(x, x, n);
      negative = !negative;
    }
    r.set_size(n, negative);
  }
  return r;
}

}  // namespace cellforge::inline geom
