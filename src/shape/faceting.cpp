// OpenSCAD's fragment rule and degree trigonometry (see faceting.h).
#include "cellforge/shape/faceting.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>

namespace cellforge::shape {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// x reduced to [0, 360) the way OpenSCAD does it (floor of revolutions).
double reduce_degrees(double x) {
  if (x < 360.0 && x >= 0.0) return x;
  return x - 360.0 * std::floor(x / 360.0);
}

}  // namespace

int fragments(double r, const Faceting& f) {
  const double fn = f.fn;
  if (r < kGridFine || std::isinf(fn) || std::isnan(fn)) return 3;
  if (fn > 0.0) return static_cast<int>(fn >= 3 ? fn : 3);
  const double fa = std::max(f.fa, kMinimumFaFs);
  const double fs = std::max(f.fs, kMinimumFaFs);
  return static_cast<int>(
      std::ceil(std::fmax(std::fmin(360.0 / fa, r * 2 * std::numbers::pi / fs), 5)));
}

int arc_fragments(double r, double angle_degrees, const Faceting& f) {
  const double n = std::ceil(fragments(r, f) * std::fabs(angle_degrees) / 360.0);
  return std::max(1, static_cast<int>(n));
}

double sin_degrees(double x) {
  x = reduce_degrees(x);
  const bool oppose = x >= 180.0;
  if (oppose) x -= 180.0;
  if (x > 90.0) x = 180.0 - x;
  if (x < 45.0) {
    x = x == 30.0 ? 0.5 : std::sin(x * kDegToRad);
  } else if (x == 45.0) {
    x = std::numbers::sqrt2 / 2;
  } else if (x == 60.0) {
    x = std::numbers::sqrt3 / 2;
  } else {
    x = std::cos((90.0 - x) * kDegToRad);
  }
  return oppose ? -x : x;
}

double cos_degrees(double x) {
  x = reduce_degrees(x);
  bool oppose = x >= 180.0;
  if (oppose) x -= 180.0;
  if (x > 90.0) {
    x = 180.0 - x;
    oppose = !oppose;
  }
  if (x > 45.0) {
    x = x == 60.0 ? 0.5 : std::sin((90.0 - x) * kDegToRad);
  } else if (x == 45.0) {
    x = std::numbers::sqrt2 / 2;
  } else if (x == 30.0) {
    x = std::numbers::sqrt3 / 2;
  } else {
    x = std::cos(x * kDegToRad);
  }
  return oppose ? -x : x;
}

std::string format_number(double x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

}  // namespace cellforge::shape
