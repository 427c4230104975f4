#include "io/weld.h"

#include <array>
#include <cmath>
#include <string>

namespace cellforge::io {

namespace {

struct CellHash {
  std::size_t operator()(const std::array<std::int64_t, 3>& c) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::int64_t x : c) h = (h ^ static_cast<std::uint64_t>(x)) * 1099511628211ull;
    return h ^ (h >> 31);
  }
};

}  // namespace

Result<std::vector<std::uint32_t>> weld(const std::vector<Vec3>& positions, double tolerance,
                                        std::vector<Vec3>& welded) {
  std::vector<std::uint32_t> map(positions.size());
  welded.clear();
  if (!(tolerance >= 0) || !std::isfinite(tolerance)) {
    return Error{ErrorCode::kInvalidInput,
                 "weld_tolerance must be a finite number >= 0, not " + std::to_string(tolerance)};
  }
  if (tolerance == 0) {
    PositionIndex index(welded);
    index.reserve(positions.size());
    for (std::size_t i = 0; i < positions.size(); ++i) map[i] = index.add(positions[i]);
    return map;
  }
  std::unordered_map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>, CellHash> grid;
  grid.reserve(positions.size());
  constexpr double kMaxCell = 4e18;  // cell indices must fit in int64 with room for +-1
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const Vec3 p = positions[i];
    std::array<std::int64_t, 3> cell;
    for (int k = 0; k < 3; ++k) {
      const double c = std::floor(p[k] / tolerance);
      if (!(std::fabs(c) < kMaxCell)) {
        return Error{ErrorCode::kInvalidInput, "weld_tolerance " + std::to_string(tolerance) +
                                                   " is too small for the coordinates of vertex " +
                                                   std::to_string(i)};
      }
      cell[k] = static_cast<std::int64_t>(c);
    }
    std::uint32_t found = kNoRep;
    for (int dx = -1; dx <= 1 && found == kNoRep; ++dx)
      for (int dy = -1; dy <= 1 && found == kNoRep; ++dy)
        for (int dz = -1; dz <= 1 && found == kNoRep; ++dz) {
          const auto it = grid.find({cell[0] + dx, cell[1] + dy, cell[2] + dz});
          if (it == grid.end()) continue;
          for (std::uint32_t r : it->second) {
            const Vec3 q = welded[r];
            if (std::fabs(q.x - p.x) <= tolerance && std::fabs(q.y - p.y) <= tolerance &&
                std::fabs(q.z - p.z) <= tolerance) {
              found = r;
              break;
            }
          }
        }
    if (found == kNoRep) {
      found = static_cast<std::uint32_t>(welded.size());
      welded.push_back(p);
      grid[cell].push_back(found);
    }
    map[i] = found;
  }
  return map;
}

}  // namespace cellforge::io
