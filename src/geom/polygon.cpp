// Polygon helpers (polygon.h).
//
// The area filter: the shoelace sum S = sum_i (x_i y_(i+1) - x_(i+1) y_i) has m = 2n
// products. Each rounded product and the recursive sum of the m terms give an error
// of at most gamma_m T, gamma_m = m eps / (1 - m eps), T the exact sum of the
// products' magnitudes; the computed magnitude sum P >= (1 - gamma_m) T. For
// m eps <= 2^-10 that is below (m + 1) eps P, and 2 (m + 1) eps P leaves room for the
// rounding of the bound itself.
#include "cellforge/geom/polygon.h"

#include <cmath>

#include "cellforge/geom/expansion.h"

namespace cellforge::inline geom {

namespace {

constexpr double kEps = 0x1p-53;

}  // namespace

Vec3 newell_normal(std::span<const Vec3> loop, Vec3 sum) {
  if (loop.size() < 3) return sum;
  const Vec3 o = loop[0];
  for (std::size_t i = 1; i + 1 < loop.size(); ++i) sum = sum + cross(loop[i] - o, loop[i + 1] - o);
  return sum;
}

double polygon_area(std::span<const Vec3> loop) { return length(newell_normal(loop)) / 2; }

double signed_area2(std::span<const Vec2> loop) {
  double a = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % loop.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return a;
}

int area_sign(std::span<const Vec2> loop) {
  const std::size_t n = loop.size();
  double sum = 0, magnitude = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % n];
    const double l = p.x * q.y, r = q.x * p.y;
    sum += l - r;
    magnitude += std::fabs(l) + std::fabs(r);
  }
  const double m = 2.0 * static_cast<double>(n);
  if (m * kEps <= 0x1p-10) {
    const double bound = 2 * (m + 1) * kEps * magnitude;
    if (sum > bound) return 1;
    if (-sum > bound) return -1;
  }
  Expansion exact;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = loop[i], q = loop[(i + 1) % n];
    exact += Expansion(p.x) * q.y - Expansion(q.x) * p.y;
  }
  return exact.sign();
}

int winding_number(std::span<const Vec2> loop, Vec2 p) {
  int w = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    if (a.y <= p.y && p.y < b.y && orient2d(a, b, p) > 0) ++w;
    if (b.y <= p.y && p.y < a.y && orient2d(a, b, p) < 0) --w;
  }
  return w;
}

Projection::Projection(Vec3 n) {
  const double ax = std::fabs(n.x), ay = std::fabs(n.y), az = std::fabs(n.z);
  drop = (ax >= ay && ax >= az) ? 0 : (ay >= az ? 1 : 2);
  flip = n[drop] < 0;
}

}  // namespace cellforge::inline geom
