// The columns behind the per-element property tables (property.h). Not API: Model
// holds a PropertyStore beside its records, ModelEditor resets a slot's values
// when it creates or frees an element there, and property.h's handles read and
// write the typed columns.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <typeinfo>
#include <vector>

namespace cellforge::inline topo::detail {

// The element kinds that carry properties, as PropertyStore indexes them.
enum PropertyKind : int { kVertexProperty, kEdgeProperty, kFaceProperty, kVolumeProperty, kPropertyKinds };

// One named column of values, one per slot of its kind. A slot past the end of the
// column holds the default (columns grow when written, not when elements are made).
class PropertyColumn {
 public:
  explicit PropertyColumn(std::string name) : name_(std::move(name)) {}
  virtual ~PropertyColumn() = default;
  const std::string& name() const { return name_; }
  virtual const std::type_info& type() const = 0;
  virtual std::unique_ptr<PropertyColumn> clone() const = 0;
  // The same name, type and default, no values.
  virtual std::unique_ptr<PropertyColumn> empty_like() const = 0;
  // Slot back to the default (an element made or freed there).
  virtual void reset(std::uint32_t slot) = 0;
  // to[to_slot] = this[from] (to has this column's type).
  virtual void copy_to(std::uint32_t from, PropertyColumn& to, std::uint32_t to_slot) const = 0;

 private:
  std::string name_;
};

template <class T>
class TypedColumn final : public PropertyColumn {
 public:
  TypedColumn(std::string name, T def) : PropertyColumn(std::move(name)), default_(std::move(def)) {}
  const std::type_info& type() const override { return typeid(T); }
  std::unique_ptr<PropertyColumn> clone() const override { return std::make_unique<TypedColumn>(*this); }
  std::unique_ptr<PropertyColumn> empty_like() const override {
    return std::make_unique<TypedColumn>(name(), default_);
  }
  void reset(std::uint32_t slot) override {
    if (slot < values_.size()) values_[slot] = default_;
  }
  void copy_to(std::uint32_t from, PropertyColumn& to, std::uint32_t to_slot) const override {
    auto& t = static_cast<TypedColumn&>(to);
    if (from < values_.size() || to_slot < t.values_.size()) t.at(to_slot) = get(from);
  }
  const T& get(std::uint32_t slot) const { return slot < values_.size() ? values_[slot] : default_; }
  T& at(std::uint32_t slot) {
    if (slot >= values_.size()) values_.resize(std::size_t{slot} + 1, default_);
    return values_[slot];
  }
  const T& default_value() const { return default_; }

 private:
  T default_;
  std::vector<T> values_;
};

// Every property column of a model, by kind. Copies deeply (a copied Model has its
// own tables).
class PropertyStore {
 public:
  PropertyStore() = default;
  PropertyStore(const PropertyStore& o) { *this = o; }
  PropertyStore& operator=(const PropertyStore& o) {
    if (this == &o) return *this;
    for (int k = 0; k < kPropertyKinds; ++k) {
      columns_[k].clear();
      for (const auto& c : o.columns_[k]) columns_[k].push_back(c->clone());
    }
    return *this;
  }
  PropertyStore(PropertyStore&&) noexcept = default;
  PropertyStore& operator=(PropertyStore&&) noexcept = default;

  // An element was made or freed at `slot`: its values go back to the defaults.
  void reset(int kind, std::uint32_t slot) {
    for (const auto& c : columns_[kind]) c->reset(slot);
  }
  PropertyColumn* find(int kind, const std::string& name) const {
    for (const auto& c : columns_[kind])
      if (c->name() == name) return c.get();
    return nullptr;
  }
  PropertyColumn* add(int kind, std::unique_ptr<PropertyColumn> column) {
    columns_[kind].push_back(std::move(column));
    return columns_[kind].back().get();
  }
  bool remove(int kind, const std::string& name) {
    auto& cs = columns_[kind];
    for (auto it = cs.begin(); it != cs.end(); ++it) {
      if ((*it)->name() == name) {
        cs.erase(it);
        return true;
      }
    }
    return false;
  }
  const std::vector<std::unique_ptr<PropertyColumn>>& columns(int kind) const { return columns_[kind]; }

 private:
  std::vector<std::unique_ptr<PropertyColumn>> columns_[kPropertyKinds];
};

}  // namespace cellforge::inline topo::detail
