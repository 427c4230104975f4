// Signed volume (volume.h).
//
// The filter's bound: each term t_i = det[a - o, b - o, c - o] is computed as orient3d
// computes its determinant, with an error of at most 7 eps P_i (Shewchuk 1997,
// o3derrboundA, P_i the computed permanent). Summing n terms recursively adds at most
// gamma_(n-1) sum |t_i|, and |t_i| <= (1 + 8 eps) P_i; the computed sum of the P_i is
// at least (1 - gamma_(n-1)) of the exact one. For n eps <= 2^-10 the whole error is
// below (8 + 2n) eps P with P the computed sum of permanents; (9 + 2n) eps P leaves room
// for the rounding of the bound itself.
#include "cellforge/geom/volume.h"

#include <cmath>

namespace cellforge::inline geom {

namespace {

constexpr double kEps = 0x1p-53;

}  // namespace

void VolumeFilter::add_triangle(Vec3 a, Vec3 b, Vec3 c) {
  const Vec3 u = a - origin_, v = b - origin_, w = c - origin_;
  const double vywz = v.y * w.z, vzwy = v.z * w.y;
  const double vzwx = v.z * w.x, vxwz = v.x * w.z;
  const double vxwy = v.x * w.y, vywx = v.y * w.x;
  sum_ += u.x * (vywz - vzwy) + u.y * (vzwx - vxwz) + u.z * (vxwy - vywx);
  permanent_ += (std::fabs(vywz) + std::fabs(vzwy)) * std::fabs(u.x) +
                (std::fabs(vzwx) + std::fabs(vxwz)) * std::fabs(u.y) +
                (std::fabs(vxwy) + std::fabs(vywx)) * std::fabs(u.z);
  ++terms_;
}

int VolumeFilter::sign() const {
  const double n = static_cast<double>(terms_);
  if (n * kEps > 0x1p-10) return 0;
  const double bound = (9 + 2 * n) * kEps * permanent_;
  if (sum_ > bound) return 1;
  if (-sum_ > bound) return -1;
  return 0;
}

void ExactVolume::add_triangle(Vec3 a, Vec3 b, Vec3 c) {
  const auto d = [](double x, double o) { return Expansion(x) - o; };
  const Expansion ux = d(a.x, origin_.x), uy = d(a.y, origin_.y), uz = d(a.z, origin_.z);
  const Expansion vx = d(b.x, origin_.x), vy = d(b.y, origin_.y), vz = d(b.z, origin_.z);
  const Expansion wx = d(c.x, origin_.x), wy = d(c.y, origin_.y), wz = d(c.z, origin_.z);
  sum_ += ux * (vy * wz - vz * wy) + uy * (vz * wx - vx * wz) + uz * (vx * wy - vy * wx);
}

}  // namespace cellforge::inline geom
