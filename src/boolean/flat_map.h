// A hash map from integer keys to small values in one array (open addressing, linear
// probing, at most half full), for the tables the split builds and clears once per
// cluster: std::unordered_map allocates a node per entry and frees them one by one on
// clear, which was a fifth of the split of a plate with 1,000 holes (64,000 clusters of
// a few entries each).
//
// The part of std::unordered_map's interface the split uses: try_emplace, operator[],
// count, erase, clear. Entries have `first` and `second` like the standard map's, but a
// pointer to one lasts only until the next insertion.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace cellforge::boolean {

template <class K, class V>
class FlatMap {
 public:
  struct Entry {
    K first;
    V second;
  };

  std::pair<Entry*, bool> try_emplace(K key, V value = V{}) {
    if (2 * (size_ + 1) > slots_.size()) grow();
    std::size_t i = home(key);
    for (; used_[i]; i = (i + 1) & mask_)
      if (slots_[i].first == key) return {&slots_[i], false};
    used_[i] = 1;
    slots_[i] = {key, std::move(value)};
    ++size_;
    return {&slots_[i], true};
  }

  V& operator[](K key) { return try_emplace(key).first->second; }

  std::size_t count(K key) const { return find_slot(key) != kNone; }
  // The value at key; nullptr when there is none.
  const V* find(K key) const {
    const std::size_t i = find_slot(key);
    return i == kNone ? nullptr : &slots_[i].second;
  }

  // Backward-shift deletion: the entries after the hole that would not be found from
  // their home slot across it move into it.
  std::size_t erase(K key) {
    std::size_t hole = find_slot(key);
    if (hole == kNone) return 0;
    for (std::size_t j = (hole + 1) & mask_; used_[j]; j = (j + 1) & mask_) {
      const std::size_t h = home(slots_[j].first);
      // Entry j stays when its home lies cyclically in (hole, j].
      const bool stays = hole <= j ? (hole < h && h <= j) : (hole < h || h <= j);
      if (stays) continue;
      slots_[hole] = std::move(slots_[j]);
      hole = j;
    }
    used_[hole] = 0;
    --size_;
    return 1;
  }

  // Empty; a table grown large for one cluster is given back rather than swept for
  // each of the many small ones after it.
  void clear() {
    if (size_ == 0) return;
    if (slots_.size() > 1024) {
      slots_.clear();
      used_.clear();
      slots_.shrink_to_fit();
      used_.shrink_to_fit();
      mask_ = 0;
    } else {
      std::fill(used_.begin(), used_.end(), 0);
    }
    size_ = 0;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

 private:
  static constexpr std::size_t kNone = ~std::size_t{0};

  std::size_t home(K key) const {
    return static_cast<std::size_t>((static_cast<std::uint64_t>(key) * 0x9E3779B97F4A7C15ull) >> 32) & mask_;
  }

  std::size_t find_slot(K key) const {
    if (size_ == 0) return kNone;
    for (std::size_t i = home(key); used_[i]; i = (i + 1) & mask_)
      if (slots_[i].first == key) return i;
    return kNone;
  }

  void grow() {
    std::vector<Entry> old_slots = std::move(slots_);
    std::vector<std::uint8_t> old_used = std::move(used_);
    const std::size_t n = old_slots.empty() ? 16 : 2 * old_slots.size();
    slots_.assign(n, Entry{});
    used_.assign(n, 0);
    mask_ = n - 1;
    size_ = 0;
    for (std::size_t i = 0; i < old_slots.size(); ++i)
      if (old_used[i]) try_emplace(old_slots[i].first, std::move(old_slots[i].second));
  }

  std::vector<Entry> slots_;
  std::vector<std::uint8_t> used_;
  std::size_t mask_ = 0;
  std::size_t size_ = 0;
};

}  // namespace cellforge::boolean
