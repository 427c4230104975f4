#include "io/intersect.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "cellforge/geom/intersect.h"
#include "cellforge/io/triangulate.h"

namespace cellforge::io {

std::vector<std::pair<FaceId, FaceId>> self_intersections(const Model& m) {
  struct Tri {
    std::array<VertexId, 3> v;
    FaceId face;
    Vec3 lo, hi;
  };
  std::vector<Tri> tris;
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double extent = 0;
  for (FaceId f : m.faces()) {
    for (const auto& t : triangulate_face(m, f)) {
      Tri tri{t, f, m.position(t[0]), m.position(t[0])};
      for (VertexId v : t) {
        const Vec3 p = m.position(v);
        tri.lo = {std::min(tri.lo.x, p.x), std::min(tri.lo.y, p.y), std::min(tri.lo.z, p.z)};
        tri.hi = {std::max(tri.hi.x, p.x), std::max(tri.hi.y, p.y), std::max(tri.hi.z, p.z)};
      }
      lo = {std::min(lo.x, tri.lo.x), std::min(lo.y, tri.lo.y), std::min(lo.z, tri.lo.z)};
      hi = {std::max(hi.x, tri.hi.x), std::max(hi.y, tri.hi.y), std::max(hi.z, tri.hi.z)};
      extent += std::max({tri.hi.x - tri.lo.x, tri.hi.y - tri.lo.y, tri.hi.z - tri.lo.z});
      tris.push_back(tri);
    }
  }
  std::vector<std::pair<FaceId, FaceId>> out;
  if (tris.size() < 2) return out;
  // Cells about twice the mean triangle size, at most ~64 cells per axis per
  // million triangles' worth of span.
  const double span = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  double cell = std::max(2 * extent / static_cast<double>(tris.size()), span / 1024);
  if (!(cell > 0)) cell = 1;
  const auto cell_of = [&](double x, double base) {
    return static_cast<std::int64_t>(std::floor((x - base) / cell));
  };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    return static_cast<std::uint64_t>(i) * 73856093u ^ static_cast<std::uint64_t>(j) * 19349663u ^
           static_cast<std::uint64_t>(k) * 83492791u ^ (static_cast<std::uint64_t>(i) << 42) ^
           (static_cast<std::uint64_t>(j) << 21);
  };
  const auto test = [&](std::uint32_t s, std::uint32_t t) {
    const Tri &a = tris[s], &b = tris[t];
    if (a.face == b.face) return;
    if (a.hi.x < b.lo.x || b.hi.x < a.lo.x || a.hi.y < b.lo.y || b.hi.y < a.lo.y ||
        a.hi.z < b.lo.z || b.hi.z < a.lo.z)
      return;
    for (VertexId u : a.v)
      for (VertexId v : b.v)
        if (u == v) return;
    const Vec3 pa[3] = {m.position(a.v[0]), m.position(a.v[1]), m.position(a.v[2])};
    const Vec3 pb[3] = {m.position(b.v[0]), m.position(b.v[1]), m.position(b.v[2])};
    if (triangles_meet(pa, pb))
      out.push_back(a.face < b.face ? std::make_pair(a.face, b.face)
                                    : std::make_pair(b.face, a.face));
  };
  // Triangles spanning many cells are tested against every triangle instead.
  constexpr std::int64_t kMaxCells = 512;
  std::vector<std::uint32_t> large, candidates;
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    const Tri& a = tris[t];
    const std::int64_t i0 = cell_of(a.lo.x, lo.x), i1 = cell_of(a.hi.x, lo.x);
    const std::int64_t j0 = cell_of(a.lo.y, lo.y), j1 = cell_of(a.hi.y, lo.y);
    const std::int64_t k0 = cell_of(a.lo.z, lo.z), k1 = cell_of(a.hi.z, lo.z);
    if ((i1 - i0 + 1) * (j1 - j0 + 1) * (k1 - k0 + 1) > kMaxCells) {
      large.push_back(t);
      continue;
    }
    candidates.clear();
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) {
          auto& bucket = grid[key(i, j, k)];
          candidates.insert(candidates.end(), bucket.begin(), bucket.end());
          bucket.push_back(t);
        }
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
    for (std::uint32_t s : candidates) test(s, t);
  }
  for (std::size_t i = 0; i < large.size(); ++i)
    for (std::uint32_t t = 0; t < tris.size(); ++t)
      if (t != large[i] && (t > large[i] || !std::binary_search(large.begin(), large.end(), t)))
        test(std::min(t, large[i]), std::max(t, large[i]));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cellforge::io
