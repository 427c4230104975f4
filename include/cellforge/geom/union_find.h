// Disjoint sets over the integers 0 .. n-1 (union by index, path halving), for the
// connected pieces the validator and the importers count: components, shells, fans,
// patches. Small and header-only; it sits in geom/ because every layer above uses it.
#pragma once

#include <cstdint>
#include <numeric>
#include <vector>

namespace cellforge::inline geom {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }
  // n singletons again, keeping the storage (for a set reused in a loop).
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), std::uint32_t{0});
  }
  // A new singleton; its element.
  std::uint32_t add() {
    parent_.push_back(static_cast<std::uint32_t>(parent_.size()));
    return parent_.back();
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  // Joins the sets of a and b (b's root goes under a's); false when they were one.
  bool unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    parent_[b] = a;
    return true;
  }
  // Joins the sets of a and b under the smaller root: used alone, every set's root is
  // its smallest element (a canonical name that does not depend on the joins' order).
  bool unite_to_smaller(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (b < a) std::swap(a, b);
    parent_[b] = a;
    return true;
  }
  std::size_t size() const { return parent_.size(); }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace cellforge::inline geom
