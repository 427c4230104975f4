// Expansion kernels on raw component arrays, shared by the Expansion value class
// (expansion.cpp) and the allocation-free exact stages of the predicates
// (predicates.cpp).
//
// Every input and output is an expansion as defined in cellforge/geom/expansion.h:
// nonzero components, strongly nonoverlapping, by increasing magnitude. Each kernel
// writes its result to h and returns its length; h never aliases an input (except in
// compress, which works in place). Theorem numbers are those of Shewchuk (1997).
#pragma once

#include <algorithm>
#include <cmath>
#include <span>

#include "cellforge/geom/expansion.h"

namespace cellforge::inline geom::expansion_kernels {

// e + f (Fast-Expansion-Sum with zero elimination, Theorem 13): merge the components
// by magnitude, then sweep from the smallest, keeping every nonzero roundoff.
// h holds at least e.size() + f.size().
inline int sum(std::span<const double> e, std::span<const double> f, double* h) {
  if (e.empty() || f.empty()) {
    const auto nonempty = e.empty() ? f : e;
    std::copy(nonempty.begin(), nonempty.end(), h);
    return static_cast<int>(nonempty.size());
  }
  std::size_t i = 0, j = 0;
  auto smaller_head = [&] {
    const bool take_e = j == f.size() || (i < e.size() && std::fabs(e[i]) < std::fabs(f[j]));
    return take_e ? e[i++] : f[j++];
  };
  int n = 0;
  const double smallest = smaller_head();
  TwoDouble q = fast_two_sum(smaller_head(), smallest);
  while (i < e.size() || j < f.size()) {
    if (q.lo != 0) h[n++] = q.lo;
    q = two_sum(q.hi, smaller_head());
  }
  if (q.lo != 0) h[n++] = q.lo;
  if (q.hi != 0) h[n++] = q.hi;
  return n;
}

// e * b (Scale-Expansion with zero elimination, Theorem 19). h holds 2 * e.size().
inline int scale(std::span<const double> e, double b, double* h) {
  if (e.empty() || b == 0) return 0;
  int n = 0;
  TwoDouble q = two_product(e[0], b);
  if (q.lo != 0) h[n++] = q.lo;
  for (std::size_t i = 1; i < e.size(); ++i) {
    const TwoDouble p = two_product(e[i], b);
    const TwoDouble s = two_sum(q.hi, p.lo);
    if (s.lo != 0) h[n++] = s.lo;
    q = fast_two_sum(p.hi, s.hi);
    if (q.lo != 0) h[n++] = q.lo;
  }
  if (q.hi != 0) h[n++] = q.hi;
  return n;
}

// e * f as the sum over the components of the shorter factor of the longer one
// scaled by it. h holds 2 * e.size() * f.size(); scratch holds that plus
// 2 * max(e.size(), f.size()).
inline int product(std::span<const double> e, std::span<const double> f, double* h,
                   double* scratch) {
  if (e.size() < f.size()) std::swap(e, f);
  if (f.empty()) return 0;
  double* scaled = scratch;
  double* acc = h;
  double* next = scratch + 2 * e.size();
  int n = scale(e, f[0], acc);
  for (std::size_t i = 1; i < f.size(); ++i) {
    const int m = scale(e, f[i], scaled);
    n = sum({acc, static_cast<std::size_t>(n)}, {scaled, static_cast<std::size_t>(m)}, next);
    std::swap(acc, next);
  }
  if (acc != h) std::copy(acc, acc + n, h);
  return n;
}

// The same value in as few components as the sweeps find, nonadjacent (Compress,
// Theorem 23), in place. A downward sweep from the largest component keeps the
// partial sums that left a roundoff; an upward sweep then renormalises them.
inline int compress(double* e, int n) {
  if (n == 0) return 0;
  int bottom = n - 1;
  double q = e[bottom];
  for (int i = n - 2; i >= 0; --i) {
    const TwoDouble s = fast_two_sum(q, e[i]);
    if (s.lo != 0) {
      e[bottom--] = s.hi;
      q = s.lo;
    } else {
      q = s.hi;
    }
  }
  int top = 0;
  for (int i = bottom + 1; i < n; ++i) {
    const TwoDouble s = fast_two_sum(e[i], q);
    if (s.lo != 0) e[top++] = s.lo;
    q = s.hi;
  }
  if (q != 0) e[top++] = q;
  return top;
}

// Sum of the components from the smallest: the value to within a few ulps.
inline double estimate(std::span<const double> e) {
  double s = 0;
  for (double c : e) s += c;
  return s;
}

// A stack-allocated expansion of at most N components, for predicates whose
// expression (and so the bound on its length) is known at compile time.
template <int N>
struct Fixed {
  double c[N];
  int n = 0;

  std::span<const double> span() const { return {c, static_cast<std::size_t>(n)}; }
  int sign() const { return n == 0 ? 0 : (c[n - 1] > 0 ? 1 : -1); }
};

// a - b exactly, as an expansion of at most two components.
inline Fixed<2> exact_diff(double a, double b) {
  const TwoDouble d = two_diff(a, b);
  Fixed<2> r;
  if (d.lo != 0) r.c[r.n++] = d.lo;
  if (d.hi != 0) r.c[r.n++] = d.hi;
  return r;
}

template <int M, int N>
Fixed<M + N> operator+(const Fixed<M>& a, const Fixed<N>& b) {
  Fixed<M + N> r;
  r.n = sum(a.span(), b.span(), r.c);
  return r;
}

template <int N>
Fixed<N> operator-(Fixed<N> a) {
  for (int i = 0; i < a.n; ++i) a.c[i] = -a.c[i];
  return a;
}

template <int M, int N>
Fixed<M + N> operator-(const Fixed<M>& a, const Fixed<N>& b) {
  return a + -b;
}

template <int M, int N>
Fixed<2 * M * N> operator*(const Fixed<M>& a, const Fixed<N>& b) {
  Fixed<2 * M * N> r;
  double scratch[2 * M * N + 2 * std::max(M, N)];
  r.n = product(a.span(), b.span(), r.c, scratch);
  return r;
}

}  // namespace cellforge::inline geom::expansion_kernels
