// OpenSCAD's fragment rule and degree trigonometry (see faceting.h).
#include "cellforge/shape/faceting.h"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <numbers>
#include <utility>

namespace cellforge::shape {

namespace {

constexpr double kDegToRad = std::numbers::pi / 180.0;

// x reduced to [0, 360) the way OpenSCAD does it (floor of revolutions).
double reduce_degrees(double x) {
  if (x < 360.0 && x >= 0.0) return x;
  return x - 360.0 * std::floor(x / 360.0);
}

}  // namespace

int saturated_count(double x) {
  if (!(x > 0)) return 0;
  if (x >= static_cast<double>(INT_MAX)) return INT_MAX;
  return static_cast<int>(x);
}

Status check_faceting(const Faceting& f) {
  for (const auto& [name, value] : {std::pair{"fn", f.fn}, {"fa", f.fa}, {"fs", f.fs}}) {
    if (!std::isfinite(value) || value < 0)
      return Error{ErrorCode::kInvalidInput,
                   std::string(name) + " must be finite and >= 0, got " + format_number(value)};
  }
  return Status::Ok();
}

Status check_vertex_count(std::uint64_t vertices, std::uint64_t max_vertices,
                          const std::string& what) {
  if (vertices <= max_vertices) return Status::Ok();
  return Error{ErrorCode::kInvalidInput, what + " would make " + std::to_string(vertices) +
                                             " vertices, more than the limit of " +
                                             std::to_string(max_vertices) +
                                             " (max_vertices raises it)"};
}

int fragments(double r, const Faceting& f) {
  const double fn = f.fn;
  if (r < kGridFine || std::isinf(fn) || std::isnan(fn)) return 3;
  if (fn > 0.0) return fn >= 3 ? saturated_count(fn) : 3;
  const double fa = std::max(f.fa, kMinimumFaFs);
  const double fs = std::max(f.fs, kMinimumFaFs);
  return saturated_count(
      std::ceil(std::fmax(std::fmin(360.0 / fa, r * 2 * std::numbers::pi / fs), 5)));
}

int arc_fragments(double r, double angle_degrees, const Faceting& f) {
  const double n = std::ceil(fragments(r, f) * std::fabs(angle_degrees) / 360.0);
  return std::max(1, saturated_count(n));
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
