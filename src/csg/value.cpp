#include "cellforge/csg/value.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "closure.h"

namespace cellforge::csg {

double Range::count() const {
  if (!std::isfinite(begin) || !std::isfinite(step) || !std::isfinite(end)) return 0;
  if (step == 0) return 0;
  if ((step > 0 && end < begin) || (step < 0 && end > begin)) return 0;
  // OpenSCAD counts an end within a relative DBL_EPSILON of a step as reached, so that
  // [0 : 0.1 : 0.3] has 4 values although 0.3 / 0.1 is 2.9999999999999996.
  const double q = (end - begin) / step;
  double n = std::floor(q);
  if (n + 1 - q <= std::numeric_limits<double>::epsilon() * (n + 1)) n += 1;
  return n + 1;
}

Value Value::vector(Vector v) {
  std::uint32_t depth = 0;
  for (const Value& e : v) depth = std::max(depth, e.nesting());
  return Value(Data(std::make_shared<const VectorData>(VectorData{std::move(v), depth + 1})));
}

bool Value::truthy() const {
  switch (type()) {
    case Type::kUndef:
      return false;
    case Type::kBool:
      return as_bool();
    case Type::kNumber:
      return as_number() != 0;
    case Type::kString:
      return !as_string().empty();
    case Type::kVector:
      return !as_vector().empty();
    case Type::kRange:
      return true;
    case Type::kFunction:
      return true;
  }
  return false;
}

std::string format_number(double x) {
  if (std::isnan(x)) return "nan";
  if (std::isinf(x)) return x > 0 ? "inf" : "-inf";
  if (x == 0) return "0";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.5e", x);
  const std::string s = buf;
  const std::size_t e = s.find('e');
  const int exponent = std::atoi(s.c_str() + e + 1);
  auto strip = [](std::string t) {
    if (t.find('.') == std::string::npos) return t;
    while (!t.empty() && t.back() == '0') t.pop_back();
    if (!t.empty() && t.back() == '.') t.pop_back();
    return t;
  };
  if (exponent < -5 || exponent >= 6) {
    return strip(s.substr(0, e)) + "e" + (exponent < 0 ? "-" : "+") +
           std::to_string(std::abs(exponent));
  }
  std::snprintf(buf, sizeof buf, "%.*f", 5 - exponent, x);
  return strip(buf);
}

const char* type_name(Value::Type t) {
  switch (t) {
    case Value::Type::kUndef:
      return "undefined";
    case Value::Type::kBool:
      return "bool";
    case Value::Type::kNumber:
      return "number";
    case Value::Type::kString:
      return "string";
    case Value::Type::kVector:
      return "vector";
    case Value::Type::kRange:
      return "range";
    case Value::Type::kFunction:
      return "function";
  }
  return "?";
}

namespace {

void append(std::string& out, const Value& v, bool quote) {
  switch (v.type()) {
    case Value::Type::kUndef:
      out += "undef";
      return;
    case Value::Type::kBool:
      out += v.as_bool() ? "true" : "false";
      return;
    case Value::Type::kNumber:
      out += format_number(v.as_number());
      return;
    case Value::Type::kString:
      if (quote) out += '"';
      out += v.as_string();
      if (quote) out += '"';
      return;
    case Value::Type::kVector: {
      out += '[';
      bool first = true;
      for (const Value& e : v.as_vector()) {
        if (!first) out += ", ";
        first = false;
        append(out, e, true);
      }
      out += ']';
      return;
    }
    case Value::Type::kRange: {
      const Range& r = v.as_range();
      out += "[" + format_number(r.begin) + " : " + format_number(r.step) + " : " +
             format_number(r.end) + "]";
      return;
    }
    case Value::Type::kFunction:
      out += closure_text(*v.as_function());
      return;
  }
}

}  // namespace

std::string Value::to_text() const {
  std::string out;
  append(out, *this, false);
  return out;
}

std::string Value::to_echo() const {
  std::string out;
  append(out, *this, true);
  return out;
}

bool Value::operator==(const Value& o) const {
  if (type() != o.type()) return false;
  switch (type()) {
    case Type::kUndef:
      return true;
    case Type::kBool:
      return as_bool() == o.as_bool();
    case Type::kNumber:
      return as_number() == o.as_number();
    case Type::kString:
      return as_string() == o.as_string();
    case Type::kVector:
      return as_vector() == o.as_vector();
    case Type::kRange:
      return as_range().begin == o.as_range().begin && as_range().step == o.as_range().step &&
             as_range().end == o.as_range().end;
    case Type::kFunction:
      return as_function() == o.as_function();
  }
  return false;
}

}  // namespace cellforge::csg
