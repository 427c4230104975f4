// The signed volume enclosed by a closed polygonal surface, as a measure (doubles)
// and as an exact sign.
//
// Each polygon p_0 ... p_(k-1) is taken as the fan of triangles (p_0, p_i, p_(i+1)), and
// each triangle adds det[a - o, b - o, c - o] (six times the signed volume of the
// tetrahedron it spans with a reference point o). For a closed surface the exact sum
// is the same for every o (it is six times the enclosed volume, positive when the
// polygons run counterclockwise seen from outside); o near the surface keeps the
// floating-point terms small.
#pragma once

#include <cstdint>
#include <span>
#include <type_traits>

#include "cellforge/geom/expansion.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

// Six times the signed volume, in doubles, with a bound on its rounding error: sign()
// is exact when it is not 0 (undecided).
class VolumeFilter {
 public:
  explicit VolumeFilter(Vec3 origin) : origin_(origin) {}
  void add_triangle(Vec3 a, Vec3 b, Vec3 c);
  double volume6() const { return sum_; }
  // +1 or -1 when the bound decides the sign, 0 when it cannot.
  int sign() const;

 private:
  Vec3 origin_;
  double sum_ = 0, permanent_ = 0;
  std::uint64_t terms_ = 0;
};

// The same sum in exact arithmetic (slow: for the cases the filter leaves open).
class ExactVolume {
 public:
  explicit ExactVolume(Vec3 origin) : origin_(origin) {}
  void add_triangle(Vec3 a, Vec3 b, Vec3 c);
  int sign() const { return sum_.sign(); }

 private:
  Vec3 origin_;
  Expansion sum_;
};

// Calls add(a, b, c) for each triangle of the fan of the loop points[loop[0]], ...
template <class Index, class Add>
void for_each_fan_triangle(std::span<const Vec3> points, std::span<const Index> loop, Add add) {
  for (std::size_t i = 1; i + 1 < loop.size(); ++i)
    add(points[loop[0]], points[loop[i]], points[loop[i + 1]]);
}

// The exact sign of the enclosed volume of a closed surface whose polygons are index
// loops into points: the filter first, the exact sum when it cannot decide. An empty
// surface gives 0.
template <class Loops>
int volume_sign(std::span<const Vec3> points, const Loops& loops) {
  Vec3 origin;
  for (const auto& l : loops) {
    if (!l.empty()) {
      origin = points[l[0]];
      break;
    }
  }
  VolumeFilter filter(origin);
  using Index = std::remove_cvref_t<decltype(loops.begin()->front())>;
  const auto add = [&](auto& sum) {
    for (const auto& l : loops)
      for_each_fan_triangle<Index>(points, l,
                                   [&](Vec3 a, Vec3 b, Vec3 c) { sum.add_triangle(a, b, c); });
  };
  add(filter);
  if (const int s = filter.sign(); s != 0) return s;
  ExactVolume exact(origin);
  add(exact);
  return exact.sign();
}

}  // namespace cellforge::inline geom
