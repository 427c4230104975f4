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
// The JSON format and the database do not store them.
//
// A handle names one column of one model and stays valid until remove_property or
// the model's end (moving the model keeps it valid; a copy has its own columns).
#pragma once

#include <string>
#include <type_traits>

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

}  // namespace cellforge::inline topo
