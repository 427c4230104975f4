// Welding positions: exactly (equal coordinates, -0 equal to +0) through a hash of
// the coordinates, or within a tolerance through a uniform grid of cells of that
// size (greedy in input order; the first position of a cluster stays).
#pragma once

#include <cstdint>
#include <cstring>
#include <unordered_map>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"

namespace cellforge::io {

struct Vec3BitsHash {
  std::size_t operator()(const Vec3& v) const {
    std::uint64_t h = 1469598103934665603ull;
    for (double d : {v.x, v.y, v.z}) {
      std::uint64_t u;
      std::memcpy(&u, &d, sizeof u);
      h = (h ^ u) * 1099511628211ull;
      h ^= h >> 29;
    }
    return h;
  }
};

// Interns positions into `out`, returning each one's index there. -0 and +0 are one
// coordinate for the lookup, but `out` keeps the first position as it was given, bit
// for bit (a file's -0 stays -0 through import, export and the database).
class PositionIndex {
 public:
  explicit PositionIndex(std::vector<Vec3>& out) : out_(out) {}
  std::uint32_t add(Vec3 p) {
    const auto plus_zero = [](double d) { return d == 0 ? 0.0 : d; };
    const Vec3 key{plus_zero(p.x), plus_zero(p.y), plus_zero(p.z)};
    auto [it, fresh] = index_.try_emplace(key, static_cast<std::uint32_t>(out_.size()));
    if (fresh) out_.push_back(p);
    return it->second;
  }
  void reserve(std::size_t n) { index_.reserve(n); }

 private:
  std::vector<Vec3>& out_;
  std::unordered_map<Vec3, std::uint32_t, Vec3BitsHash> index_;
};

// Per input position, the index of its representative in `welded`. An error when
// the tolerance is negative, not finite, or too small for the coordinates' range.
inline constexpr std::uint32_t kNoRep = 0xFFFFFFFFu;

Result<std::vector<std::uint32_t>> weld(const std::vector<Vec3>& positions, double tolerance,
                                        std::vector<Vec3>& welded);

}  // namespace cellforge::io
