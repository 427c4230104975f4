// The values of the OpenSCAD language: undef, booleans, numbers (doubles), strings,
// vectors, ranges and function literals (closures). Values are immutable and cheap
// to copy (strings and vectors are shared).
//
// to_text() gives OpenSCAD's str() text and to_echo() its echo text (strings quoted):
// numbers with 6 significant digits, fixed unless the exponent is below -5 or at
// least 6 ("0.333333", "1e+6", "1.234e-6", "0.00001"), vectors as "[1, 2]", ranges as
// "[0 : 1 : 5]".
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <variant>
#include <vector>

namespace cellforge::csg {

class Value;
using Vector = std::vector<Value>;

// A vector's elements and how deeply vectors nest in it (1: no vector inside).
struct VectorData {
  Vector items;
  std::uint32_t depth = 1;
};

struct Range {
  double begin = 0, step = 1, end = 0;
  // Number of values begin, begin + step, ... <= end (0 for an empty or invalid range;
  // OpenSCAD's rule: a negative step runs down, a zero step is empty).
  double count() const;
  double at(double i) const { return begin + i * step; }
};

struct Closure;  // a function literal with its environment (evaluator)

class Value {
 public:
  enum class Type { kUndef, kBool, kNumber, kString, kVector, kRange, kFunction };

  Value() = default;
  static Value boolean(bool b) { return Value(Data(b)); }
  static Value number(double d) { return Value(Data(d)); }
  static Value string(std::string s) {
    return Value(Data(std::make_shared<const std::string>(std::move(s))));
  }
  static Value vector(Vector v);
  static Value range(Range r) { return Value(Data(r)); }
  static Value function(std::shared_ptr<const Closure> c) { return Value(Data(std::move(c))); }

  Type type() const { return static_cast<Type>(data_.index()); }
  bool is_undef() const { return type() == Type::kUndef; }
  bool is_bool() const { return type() == Type::kBool; }
  bool is_number() const { return type() == Type::kNumber; }
  bool is_string() const { return type() == Type::kString; }
  bool is_vector() const { return type() == Type::kVector; }
  bool is_range() const { return type() == Type::kRange; }
  bool is_function() const { return type() == Type::kFunction; }

  bool as_bool() const { return std::get<bool>(data_); }
  double as_number() const { return std::get<double>(data_); }
  const std::string& as_string() const { return *std::get<3>(data_); }
  const Vector& as_vector() const { return std::get<4>(data_)->items; }
  // How deeply vectors nest in this value (0 for anything but a vector).
  std::uint32_t nesting() const { return is_vector() ? std::get<4>(data_)->depth : 0; }
  const Range& as_range() const { return std::get<Range>(data_); }
  const std::shared_ptr<const Closure>& as_function() const { return std::get<6>(data_); }

  // OpenSCAD's truth: false, 0, "", [] and undef are false (a range is true).
  bool truthy() const;

  std::string to_text() const;  // str()
  std::string to_echo() const;  // echo(): strings in quotes

  bool operator==(const Value& o) const;

 private:
  using Data =
      std::variant<std::monostate, bool, double, std::shared_ptr<const std::string>,
                   std::shared_ptr<const VectorData>, Range, std::shared_ptr<const Closure>>;
  explicit Value(Data d) : data_(std::move(d)) {}
  Data data_;
};

// OpenSCAD's number text (6 significant digits; see the file comment).
std::string format_number(double x);

// The type's name as OpenSCAD's messages give it ("number", "vector", ...).
const char* type_name(Value::Type t);

}  // namespace cellforge::csg
