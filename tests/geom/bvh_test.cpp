// The bounding-volume hierarchy (geom/bvh.h): its pairs against every pair of boxes
// tested directly, with and without groups, whole and in pieces for threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "cellforge/geom/bvh.h"

namespace cellforge {
namespace {

struct Case {
  std::vector<Box> boxes;
  std::vector<std::uint32_t> groups;
};

// n boxes on a coarse grid (so that many touch exactly), each in one of `groups`
// groups or, one in four, in none.
Case random_case(std::mt19937_64& rng, std::size_t n, std::uint32_t groups) {
  std::uniform_int_distribution<int> at(0, 40), size(0, 6), group(0, static_cast<int>(groups));
  Case c;
  for (std::size_t i = 0; i < n; ++i) {
    Box b;
    const Vec3 lo{double(at(rng)), double(at(rng)), double(at(rng))};
    b.add(lo);
    b.add(lo + Vec3{double(size(rng)), double(size(rng)), double(size(rng))});
    c.boxes.push_back(b);
    const int g = group(rng);
    c.groups.push_back(g == static_cast<int>(groups) || rng() % 4 == 0 ? Bvh::kNoGroup : static_cast<std::uint32_t>(g));
  }
  return c;
}

std::vector<std::array<std::uint32_t, 2>> brute_force(const Case& c, bool use_groups) {
  std::vector<std::array<std::uint32_t, 2>> out;
  for (std::uint32_t i = 0; i < c.boxes.size(); ++i)
    for (std::uint32_t j = i + 1; j < c.boxes.size(); ++j) {
      if (use_groups && c.groups[i] == c.groups[j] && c.groups[i] != Bvh::kNoGroup) continue;
      if (c.boxes[i].overlaps(c.boxes[j])) out.push_back({i, j});
    }
  return out;
}

TEST(Bvh, PairsAreExactlyTheOverlappingPairsOutsideOneGroup) {
  std::mt19937_64 rng(20261205);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 1 + rng() % 300;
    const Case c = random_case(rng, n, 1 + static_cast<std::uint32_t>(rng() % 4));
    for (bool use_groups : {false, true}) {
      const Bvh tree = use_groups ? Bvh(c.boxes, c.groups) : Bvh(c.boxes);
      std::vector<std::array<std::uint32_t, 2>> whole, in_pieces;
      tree.pairs([&](std::uint32_t i, std::uint32_t j) {
        ASSERT_LT(i, j);
        whole.push_back({i, j});
      });
      for (const Bvh::Piece& p : tree.pair_pieces(16))
        tree.pairs(p, [&](std::uint32_t i, std::uint32_t j) { in_pieces.push_back({i, j}); });
      EXPECT_EQ(in_pieces, whole) << "the pieces in order are the whole traversal";
      std::sort(whole.begin(), whole.end());
      EXPECT_TRUE(std::adjacent_find(whole.begin(), whole.end()) == whole.end()) << "each pair once";
      EXPECT_EQ(whole, brute_force(c, use_groups)) << "trial " << trial << ", " << n << " boxes";
    }
  }
}

// Boxes crowded into a small region and one far away: the far one makes the whole
// run one Morton cell at first, and the run is ordered again over its own bounds (and
// again, for a cluster inside the crowd). Both orderings (a sort of short runs, the
// counting passes of long ones) report exactly the overlapping pairs.
TEST(Bvh, AFarBoxDoesNotChangeThePairs) {
  std::mt19937_64 rng(20261207);
  for (const std::size_t n : {50u, 700u, 6000u}) {
    Case c = random_case(rng, n, 2);
    for (std::size_t i = 0; i < n / 3; ++i) {  // a third of them squeezed together
      Box b;
      const double x = 1e-6 * static_cast<double>(rng() % 1000);
      b.add(Vec3{x, x, x});
      b.add(Vec3{x + 1e-6, x + 2e-6, x});
      c.boxes[i] = b;
    }
    Box far;
    far.add(Vec3{1e9, -1e9, 3e9});
    far.add(Vec3{1e9 + 1, -1e9 + 1, 3e9 + 1});
    c.boxes.push_back(far);
    c.groups.push_back(Bvh::kNoGroup);
    for (bool use_groups : {false, true}) {
      const Bvh tree = use_groups ? Bvh(c.boxes, c.groups) : Bvh(c.boxes);
      std::vector<std::array<std::uint32_t, 2>> whole;
      tree.pairs([&](std::uint32_t i, std::uint32_t j) { whole.push_back({i, j}); });
      std::sort(whole.begin(), whole.end());
      EXPECT_EQ(whole, brute_force(c, use_groups)) << n << " boxes";
    }
  }
}

// Boxes whose corners are doubles no float holds, some a few double units apart: the
// floats the tree keeps may make two of them meet that do not (a gap under a float's
// unit), never part two that meet. Every box kept holds the box given.
TEST(Bvh, FloatBoxesReportASupersetWithinAFloatsUnit) {
  std::mt19937_64 rng(20261206);
  std::uniform_real_distribution<double> at(-1000, 1000), size(0, 1e-3);
  std::size_t extra = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Case c;
    for (int i = 0; i < 400; ++i) {
      Box b;
      Vec3 lo{at(rng), at(rng), at(rng)};
      if (i > 0 && rng() % 2 == 0) {  // just past the last box's corner: a gap of a few units
        lo = c.boxes.back().hi;
        lo = {std::nextafter(lo.x, 1e300), std::nextafter(lo.y, 1e300), std::nextafter(lo.z, 1e300)};
      }
      b.add(lo);
      b.add(lo + Vec3{size(rng), size(rng), size(rng)});
      c.boxes.push_back(b);
    }
    const Bvh tree(c.boxes);
    for (std::uint32_t i = 0; i < c.boxes.size(); ++i) {
      const Box kept = tree.box(i);
      for (int k = 0; k < 3; ++k) {
        EXPECT_LE(kept.lo[k], c.boxes[i].lo[k]);
        EXPECT_GE(kept.hi[k], c.boxes[i].hi[k]);
        EXPECT_LE(c.boxes[i].lo[k] - kept.lo[k], std::abs(c.boxes[i].lo[k]) * 0x1p-23);
        EXPECT_LE(kept.hi[k] - c.boxes[i].hi[k], std::abs(c.boxes[i].hi[k]) * 0x1p-23);
      }
    }
    std::vector<std::array<std::uint32_t, 2>> found;
    tree.pairs([&](std::uint32_t i, std::uint32_t j) { found.push_back({i, j}); });
    std::sort(found.begin(), found.end());
    const auto exact = brute_force(c, false);
    EXPECT_TRUE(std::includes(found.begin(), found.end(), exact.begin(), exact.end())) << "trial " << trial;
    for (auto [i, j] : found) EXPECT_TRUE(tree.box(i).overlaps(tree.box(j)));
    extra += found.size() - exact.size();
  }
  EXPECT_GT(extra, 0u) << "the gaps under a float's unit were meant to make some";
}

// The tree built on several threads is the one built on one: the same pairs, in the
// same order (the Boolean's events are applied in that order). 70,000 boxes: above the
// size that splits the build and the one that sorts in slices (three: uneven slices).
TEST(Bvh, ThreadsBuildTheSameTree) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> at(0, 1000), size(0, 8);
  Case c;  // above the size that splits the build, a few neighbours each
  for (int i = 0; i < 70000; ++i) {
    Box b;
    const Vec3 lo{at(rng), at(rng), at(rng)};
    b.add(lo);
    b.add(lo + Vec3{size(rng), size(rng), size(rng)});
    c.boxes.push_back(b);
    c.groups.push_back(rng() % 3 == 0 ? Bvh::kNoGroup : static_cast<std::uint32_t>(rng() % 3));
  }
  RawVector<FloatBox> boxes;
  for (const Box& b : c.boxes) boxes.push_back(FloatBox::around(b));
  const RawVector<std::uint32_t> groups(c.groups.begin(), c.groups.end());
  auto pairs_of = [&](int threads) {
    std::vector<std::array<std::uint32_t, 2>> out;
    Bvh(boxes, groups, threads).pairs([&](std::uint32_t i, std::uint32_t j) { out.push_back({i, j}); });
    return out;
  };
  const auto one = pairs_of(1);
  EXPECT_FALSE(one.empty());
  EXPECT_EQ(pairs_of(2), one);
  EXPECT_EQ(pairs_of(3), one);
  EXPECT_EQ(pairs_of(4), one);
}

TEST(Bvh, OneGroupAloneHasNoPairs) {
  std::mt19937_64 rng(7);
  Case c = random_case(rng, 500, 1);
  std::fill(c.groups.begin(), c.groups.end(), 3u);
  std::size_t count = 0;
  Bvh(c.boxes, c.groups).pairs([&](std::uint32_t, std::uint32_t) { ++count; });
  EXPECT_EQ(count, 0u);
  EXPECT_GT(brute_force(c, false).size(), 0u);
}

}  // namespace
}  // namespace cellforge
