// Typed per-element property tables: a named value of type T for every vertex,
// edge, face or volume of a model (the face a face came from, its colour, ...).
//
//   FaceProperty<std::uint32_t> source = add_property<FaceProperty<std::uint32_t>>(m, "source").value();
//   source.set(f, 7);   source[f] == 7;   source[g] == source.default_value()
//
// Values live in the model, one column per property, indexed by the element's id
// slot (model.h: ids are slots, reused after a deletion). They survive edits: an
// element keeps its value while it lives, whatever the operators do around it; an
// element the operators or the builder make gets the default, and a deleted one's
// value goes back to the default, so the slot is reusable. (Edge uses and loops,
// whose ids change when they move, have no tables.) Copying the model copies its
// tables; extract() and append() (parts.h) carry them with the elements.
//
// Columns whose value type is one of PropertyType's (fixed-width integers, float,
// double, std::string, Colour, Vec3) are part of the model's snapshot
// (snapshot.h), and so of the native JSON and the database, losslessly; columns
// of any other type live in memory only.
//
// A handle names one column of one model and stays valid until remove_property or
// the model's end (moving the model keeps it valid; a copy has its own columns).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <typeinfo>
#include <variant>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

namespace detail {
template <class IdT>
constexpr int property_kind() {
  if constexpr (std::is_same_v<IdT, VertexId>) return kVertexProperty;
  else if constexpr (std::is_same_v<IdT, EdgeId>) return kEdgeProperty;
  else if constexpr (std::is_same_v<IdT, FaceId>) return kFaceProperty;
  else {
    static_assert(std::is_same_v<IdT, VolumeId>, "properties are per vertex, edge, face or volume");
    return kVolumeProperty;
  }
}
}  // namespace detail

// A read-only handle (from a const model).
template <class IdT, class T>
class PropertyView {
 public:
  using id_type = IdT;
  using value_type = T;
  PropertyView() = default;
  explicit PropertyView(const detail::TypedColumn<T>* column) : column_(column) {}
  bool is_valid() const { return column_ != nullptr; }
  const T& operator[](IdT id) const { return column_->get(id.value); }
  const T& get(IdT id) const { return column_->get(id.value); }
  const std::string& name() const { return column_->name(); }
  const T& default_value() const { return column_->default_value(); }

 protected:
  const detail::TypedColumn<T>* column_ = nullptr;
};

// A handle that reads and writes.
template <class IdT, class T>
class Property : public PropertyView<IdT, T> {
  static_assert(!std::is_same_v<T, bool>, "a bool property: use std::uint8_t (std::vector<bool> has no references)");

 public:
  Property() = default;
  explicit Property(detail::TypedColumn<T>* column) : PropertyView<IdT, T>(column), column_(column) {}
  void set(IdT id, T value) { column_->at(id.value) = std::move(value); }
  T& ref(IdT id) { return column_->at(id.value); }  // grows the column to id

 private:
  detail::TypedColumn<T>* column_ = nullptr;
};

template <class T>
using VertexProperty = Property<VertexId, T>;
template <class T>
using EdgeProperty = Property<EdgeId, T>;
template <class T>
using FaceProperty = Property<FaceId, T>;
template <class T>
using VolumeProperty = Property<VolumeId, T>;

// The property `name` of P's kind: made with default `def` (every element, present
// and future, starts with it) or, when it exists with P's value type, the existing
// one (def unused). An error when the name is taken by another value type.
template <class P>
Result<P> add_property(Model& m, const std::string& name, typename P::value_type def = {}) {
  using T = typename P::value_type;
  constexpr int kind = detail::property_kind<typename P::id_type>();
  detail::PropertyStore& store = m.property_store();
  if (detail::PropertyColumn* c = store.find(kind, name)) {
    if (c->type() != typeid(T)) {
      return Error{ErrorCode::kInvalidInput,
                   "property '" + name + "' exists with another value type"};
    }
    return P(static_cast<detail::TypedColumn<T>*>(c));
  }
  auto column = std::make_unique<detail::TypedColumn<T>>(name, std::move(def));
  return P(static_cast<detail::TypedColumn<T>*>(store.add(kind, std::move(column))));
}

// The property `name` of P's kind and value type; an invalid handle when there is
// none (or it has another value type).
template <class P>
P find_property(Model& m, const std::string& name) {
  using T = typename P::value_type;
  detail::PropertyColumn* c = m.property_store().find(detail::property_kind<typename P::id_type>(), name);
  return c && c->type() == typeid(T) ? P(static_cast<detail::TypedColumn<T>*>(c)) : P();
}
template <class P>
PropertyView<typename P::id_type, typename P::value_type> find_property(const Model& m,
                                                                       const std::string& name) {
  using T = typename P::value_type;
  const detail::PropertyColumn* c =
      m.property_store().find(detail::property_kind<typename P::id_type>(), name);
  using View = PropertyView<typename P::id_type, T>;
  return c && c->type() == typeid(T) ? View(static_cast<const detail::TypedColumn<T>*>(c)) : View();
}

// Drops the property (its handles become dangling); false when there is none.
template <class IdT>
bool remove_property(Model& m, const std::string& name) {
  return m.property_store().remove(detail::property_kind<IdT>(), name);
}

// The names of the properties of IdT's kind, in the order they were added.
template <class IdT>
std::vector<std::string> property_names(const Model& m) {
  std::vector<std::string> out;
  for (const auto& c : m.property_store().columns(detail::property_kind<IdT>())) out.push_back(c->name());
  return out;
}

// A colour in linear 0..1 components (the "colour" face property of io/'s readers).
struct Colour {
  float r = 1, g = 1, b = 1, a = 1;
  friend bool operator==(const Colour&, const Colour&) = default;
};

// The element kinds that carry properties, as files and the database name them:
// "vertex", "edge", "face", "cell" (a VolumeId, a 3-cell).
enum class PropertyOwner : std::uint8_t { kVertex, kEdge, kFace, kCell };
std::string_view owner_name(PropertyOwner owner);
std::optional<PropertyOwner> owner_from_name(std::string_view name);

// The value types that snapshots, files and the database keep, by name: "int8"
// ... "int64", "uint8" ... "uint64", "float", "double", "string", "colour", "vec3".
enum class PropertyType : std::uint8_t {
  kInt8, kInt16, kInt32, kInt64, kUInt8, kUInt16, kUInt32, kUInt64,
  kFloat, kDouble, kString, kColour, kVec3,
};
std::string_view type_name(PropertyType type);
std::optional<PropertyType> type_from_name(std::string_view name);

// PropertyType of T, or nullopt for a type that stays in memory only.
template <class T>
constexpr std::optional<PropertyType> property_type_of() {
  using P = PropertyType;
  if constexpr (std::is_same_v<T, std::int8_t>) return P::kInt8;
  else if constexpr (std::is_same_v<T, std::int16_t>) return P::kInt16;
  else if constexpr (std::is_same_v<T, std::int32_t>) return P::kInt32;
  else if constexpr (std::is_same_v<T, std::int64_t>) return P::kInt64;
  else if constexpr (std::is_same_v<T, std::uint8_t>) return P::kUInt8;
  else if constexpr (std::is_same_v<T, std::uint16_t>) return P::kUInt16;
  else if constexpr (std::is_same_v<T, std::uint32_t>) return P::kUInt32;
  else if constexpr (std::is_same_v<T, std::uint64_t>) return P::kUInt64;
  else if constexpr (std::is_same_v<T, float>) return P::kFloat;
  else if constexpr (std::is_same_v<T, double>) return P::kDouble;
  else if constexpr (std::is_same_v<T, std::string>) return P::kString;
  else if constexpr (std::is_same_v<T, Colour>) return P::kColour;
  else if constexpr (std::is_same_v<T, Vec3>) return P::kVec3;
  else return std::nullopt;
}

// The same for a column's value type at run time (detail::PropertyColumn::type()).
std::optional<PropertyType> property_type_of(const std::type_info& type);

// The names of the properties of every kind whose value type stays in memory only
// (no PropertyType), as "face property 'tag'": what snapshots, files and the
// database leave out.
std::vector<std::string> unstored_properties(const Model& m);

// One stored value: signed integers as int64, unsigned ones as uint64, float and
// double as double (a float is exact in a double); the PropertyType beside it
// says which C++ type it is.
using PropertyValue = std::variant<std::int64_t, std::uint64_t, double, std::string, Colour, Vec3>;

// Whether v is a value of `type` (the right alternative, in the type's range: a
// double of a float column must be a float). The message names what is wrong.
Status check_value(PropertyType type, const PropertyValue& v);

}  // namespace cellforge::inline topo
