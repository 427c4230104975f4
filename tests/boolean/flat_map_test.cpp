// The split's hash map (boolean/flat_map.h) against std::unordered_map: the same
// answers over seeded random insertions, look-ups, erasures and clears, with keys
// drawn from a small range so that probe runs collide, wrap and shift back.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <unordered_map>

#include "boolean/flat_map.h"

namespace cellforge::boolean {
namespace {

template <class K>
void agree_with_unordered_map(std::uint32_t seed, K key_range) {
  std::mt19937 rng(seed);
  FlatMap<K, std::uint32_t> flat;
  std::unordered_map<K, std::uint32_t> ref;
  for (int step = 0; step < 20000; ++step) {
    const K key = static_cast<K>(rng() % key_range) * (K{1} << (sizeof(K) * 4));  // high bits too
    const int op = static_cast<int>(rng() % 100);
    if (op < 45) {
      const auto value = static_cast<std::uint32_t>(rng());
      const auto [entry, fresh] = flat.try_emplace(key, value);
      const auto [it, ref_fresh] = ref.try_emplace(key, value);
      ASSERT_EQ(fresh, ref_fresh);
      ASSERT_EQ(entry->first, key);
      ASSERT_EQ(entry->second, it->second);
    } else if (op < 60) {
      const auto value = static_cast<std::uint32_t>(rng());
      flat[key] = value;
      ref[key] = value;
    } else if (op < 85) {
      ASSERT_EQ(flat.erase(key), ref.erase(key));
    } else if (op < 99) {
      ASSERT_EQ(flat.count(key), ref.count(key));
      if (ref.count(key)) {
        ASSERT_EQ(flat[key], ref[key]);
      }
    } else {
      flat.clear();
      ref.clear();
    }
    ASSERT_EQ(flat.size(), ref.size());
  }
  for (const auto& [key, value] : ref) {
    ASSERT_EQ(flat.count(key), 1u);
    ASSERT_EQ(flat[key], value);
  }
}

TEST(FlatMap, AgreesWithUnorderedMap) {
  for (std::uint32_t seed = 1; seed <= 40; ++seed) {
    agree_with_unordered_map<std::uint32_t>(seed, seed % 2 ? 64 : 3000);
    agree_with_unordered_map<std::uint64_t>(seed, seed % 2 ? 64 : 3000);
  }
}

TEST(FlatMap, ClearOfALargeTableGivesItBack) {
  FlatMap<std::uint32_t, std::uint32_t> m;
  for (std::uint32_t k = 0; k < 5000; ++k) m[k] = k;
  EXPECT_EQ(m.size(), 5000u);
  m.clear();
  EXPECT_TRUE(m.empty());
  EXPECT_EQ(m.count(17), 0u);
  m[17] = 3;
  EXPECT_EQ(m[17], 3u);
  EXPECT_EQ(m.size(), 1u);
}

}  // namespace
}  // namespace cellforge::boolean
