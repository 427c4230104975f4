// The names of property owners and value types, and the range check of a stored
// value (property.h).
#include "cellforge/topo/property.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace cellforge::inline topo {

namespace {

constexpr std::array<std::string_view, 4> kOwnerNames = {"vertex", "edge", "face", "cell"};
constexpr std::array<std::string_view, 13> kTypeNames = {
    "int8",   "int16", "int32",  "int64",  "uint8",  "uint16", "uint32",
    "uint64", "float", "double", "string", "colour", "vec3"};

template <class T>
Status in_range(const PropertyValue& v, std::string_view type) {
  using Wide = std::conditional_t<std::is_signed_v<T>, std::int64_t, std::uint64_t>;
  const Wide* w = std::get_if<Wide>(&v);
  if (!w) {
    return Error{ErrorCode::kInvalidInput,
                 "expected " +
                     std::string(std::is_signed_v<T> ? "an integer" : "a non-negative integer") +
                     " (" + std::string(type) + ")"};
  }
  if (!std::in_range<T>(*w)) {
    return Error{ErrorCode::kInvalidInput,
                 std::to_string(*w) + " is out of the range of " + std::string(type)};
  }
  return Status::Ok();
}

}  // namespace

std::string_view owner_name(PropertyOwner owner) {
  const auto k = static_cast<std::size_t>(owner);
  return k < kOwnerNames.size() ? kOwnerNames[k] : std::string_view("?");
}

std::optional<PropertyOwner> owner_from_name(std::string_view name) {
  for (std::size_t k = 0; k < kOwnerNames.size(); ++k)
    if (kOwnerNames[k] == name) return static_cast<PropertyOwner>(k);
  return std::nullopt;
}

std::string_view type_name(PropertyType type) {
  const auto k = static_cast<std::size_t>(type);
  return k < kTypeNames.size() ? kTypeNames[k] : std::string_view("?");
}

std::optional<PropertyType> type_from_name(std::string_view name) {
  for (std::size_t k = 0; k < kTypeNames.size(); ++k)
    if (kTypeNames[k] == name) return static_cast<PropertyType>(k);
  return std::nullopt;
}

std::optional<PropertyType> property_type_of(const std::type_info& t) {
  using P = PropertyType;
  const std::pair<const std::type_info&, P> types[] = {{typeid(std::int8_t), P::kInt8},
                                                       {typeid(std::int16_t), P::kInt16},
                                                       {typeid(std::int32_t), P::kInt32},
                                                       {typeid(std::int64_t), P::kInt64},
                                                       {typeid(std::uint8_t), P::kUInt8},
                                                       {typeid(std::uint16_t), P::kUInt16},
                                                       {typeid(std::uint32_t), P::kUInt32},
                                                       {typeid(std::uint64_t), P::kUInt64},
                                                       {typeid(float), P::kFloat},
                                                       {typeid(double), P::kDouble},
                                                       {typeid(std::string), P::kString},
                                                       {typeid(Colour), P::kColour},
                                                       {typeid(Vec3), P::kVec3}};
  for (const auto& [info, type] : types)
    if (info == t) return type;
  return std::nullopt;
}

std::vector<std::string> unstored_properties(const Model& m) {
  std::vector<std::string> out;
  for (int kind = 0; kind < detail::kPropertyKinds; ++kind) {
    for (const auto& c : m.property_store().columns(kind)) {
      if (!property_type_of(c->type()))
        out.push_back(std::string(owner_name(static_cast<PropertyOwner>(kind))) + " property '" +
                      c->name() + "'");
    }
  }
  return out;
}

Status check_value(PropertyType type, const PropertyValue& v) {
  const std::string_view name = type_name(type);
  auto expected = [&](const char* what) {
    return Error{ErrorCode::kInvalidInput,
                 std::string("expected ") + what + " (" + std::string(name) + ")"};
  };
  switch (type) {
    case PropertyType::kInt8:
      return in_range<std::int8_t>(v, name);
    case PropertyType::kInt16:
      return in_range<std::int16_t>(v, name);
    case PropertyType::kInt32:
      return in_range<std::int32_t>(v, name);
    case PropertyType::kInt64:
      return in_range<std::int64_t>(v, name);
    case PropertyType::kUInt8:
      return in_range<std::uint8_t>(v, name);
    case PropertyType::kUInt16:
      return in_range<std::uint16_t>(v, name);
    case PropertyType::kUInt32:
      return in_range<std::uint32_t>(v, name);
    case PropertyType::kUInt64:
      return in_range<std::uint64_t>(v, name);
    case PropertyType::kFloat: {
      const double* d = std::get_if<double>(&v);
      if (!d) return expected("a number");
      const bool fits = !std::isfinite(*d) || (std::abs(*d) <= std::numeric_limits<float>::max() &&
                                               static_cast<double>(static_cast<float>(*d)) == *d);
      if (!fits) return Error{ErrorCode::kInvalidInput, "the number is not a float"};
      return Status::Ok();
    }
    case PropertyType::kDouble:
      return std::holds_alternative<double>(v) ? Status::Ok() : Status(expected("a number"));
    case PropertyType::kString:
      return std::holds_alternative<std::string>(v) ? Status::Ok() : Status(expected("a string"));
    case PropertyType::kColour:
      return std::holds_alternative<Colour>(v) ? Status::Ok() : Status(expected("a colour"));
    case PropertyType::kVec3:
      return std::holds_alternative<Vec3>(v) ? Status::Ok() : Status(expected("a vector"));
  }
  return Error{ErrorCode::kInvalidInput,
               "unknown property type " + std::to_string(static_cast<int>(type))};
}

}  // namespace cellforge::inline topo
