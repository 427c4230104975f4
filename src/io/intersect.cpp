// Self-intersections (intersect.h): candidate pairs from a bounding-volume hierarchy
// over the triangles' boxes (geom/bvh.h), each decided by the exact triangle test.
// Triangles with the same three vertices are one entry of the hierarchy (their faces
// are listed with it), so a stack of equal triangles costs one triangle, not the
// square of their number.
#include "io/intersect.h"

#include <algorithm>
#include <unordered_map>

#include "cellforge/geom/bvh.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/io/triangulate.h"

namespace cellforge::io {

namespace {

struct TriangleKeyHash {
  std::size_t operator()(const std::array<std::uint32_t, 3>& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (std::uint32_t x : k) h = (h ^ x) * 1099511628211ull;
    return h ^ (h >> 29);
  }
};

}  // namespace

std::vector<std::pair<FaceId, FaceId>> self_intersections(const Model& m) {
  struct Tri {
    std::array<VertexId, 3> v;
    std::vector<FaceId> faces;  // every face with a triangle on these three vertices
  };
  std::vector<Tri> tris;
  std::unordered_map<std::array<std::uint32_t, 3>, std::uint32_t, TriangleKeyHash> index;
  for (FaceId f : m.faces()) {
    for (const auto& t : triangulate_face(m, f)) {
      std::array<std::uint32_t, 3> key{t[0].value, t[1].value, t[2].value};
      std::sort(key.begin(), key.end());
      const auto [it, fresh] = index.try_emplace(key, static_cast<std::uint32_t>(tris.size()));
      if (fresh) tris.push_back({t, {}});
      auto& faces = tris[it->second].faces;
      if (faces.empty() || faces.back() != f) faces.push_back(f);
    }
  }
  std::vector<std::pair<FaceId, FaceId>> out;
  const auto emit = [&](FaceId a, FaceId b) {
    if (a != b) out.push_back(a < b ? std::make_pair(a, b) : std::make_pair(b, a));
  };
  std::vector<Box> boxes(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (VertexId v : tris[i].v) boxes[i].add(m.position(v));
  const Bvh bvh(std::move(boxes));
  bvh.pairs([&](std::uint32_t s, std::uint32_t t) {
    const Tri &a = tris[s], &b = tris[t];
    if (a.faces.size() == 1 && b.faces.size() == 1 && a.faces[0] == b.faces[0]) return;
    for (VertexId u : a.v)
      for (VertexId v : b.v)
        if (u == v) return;
    const Vec3 pa[3] = {m.position(a.v[0]), m.position(a.v[1]), m.position(a.v[2])};
    const Vec3 pb[3] = {m.position(b.v[0]), m.position(b.v[1]), m.position(b.v[2])};
    if (!triangles_meet(pa, pb)) return;
    for (FaceId f : a.faces)
      for (FaceId g : b.faces) emit(f, g);
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace cellforge::io
