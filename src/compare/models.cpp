#include "cellforge/compare/models.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <tuple>

namespace cellforge::compare {

namespace {

// Collects faces, welding identical positions into one vertex.
class Soup {
 public:
  std::uint32_t point(Vec3 p) {
    const auto [it, added] = index_.try_emplace(std::tuple(p.x, p.y, p.z),
                                                static_cast<std::uint32_t>(in_.positions.size()));
    if (added) in_.positions.push_back(p);
    return it->second;
  }
  void face(const std::vector<std::vector<Vec3>>& loops, int front, int back) {
    MeshFace f;
    f.front = front;
    f.back = back;
    for (const auto& loop : loops) {
      auto& idx = f.loops.emplace_back();
      for (Vec3 p : loop) idx.push_back(point(p));
    }
    in_.volumes = std::max({in_.volumes, front + 1, back + 1});
    in_.faces.push_back(std::move(f));
  }
  // The faces of box [lo, hi] (the four sides before bottom and top), outward or,
  // with `inward`, turned towards the box's inside.
  void box(Vec3 lo, Vec3 hi, int front, int back, bool inward = false, bool sides_only = false) {
    auto c = [&](int i) {
      return Vec3{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    };
    static constexpr int kFaces[6][4] = {{0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2},
                                         {1, 3, 7, 5}, {0, 2, 3, 1}, {4, 5, 7, 6}};
    for (int k = 0; k < (sides_only ? 4 : 6); ++k) {
      std::vector<Vec3> loop;
      for (int j = 0; j < 4; ++j) loop.push_back(c(kFaces[k][inward ? 3 - j : j]));
      face({loop}, front, back);
    }
  }
  MeshInput take() { return std::move(in_); }

 private:
  MeshInput in_;
  std::map<std::tuple<double, double, double>, std::uint32_t> index_;
};

}  // namespace

MeshInput cube_model() {
  Soup s;
  s.box({0, 0, 0}, {1, 1, 1}, -1, 0);
  return s.take();
}

MeshInput cube_with_hole_model() {
  Soup s;
  auto square = [](double a, double b, double z, bool ccw) {
    std::vector<Vec3> q = {{a, a, z}, {b, a, z}, {b, b, z}, {a, b, z}};
    if (!ccw) std::reverse(q.begin(), q.end());
    return q;
  };
  s.face({square(0, 3, 3, true), square(1, 2, 3, false)}, -1, 0);
  s.face({square(0, 3, 0, false), square(1, 2, 0, true)}, -1, 0);
  s.box({0, 0, 0}, {3, 3, 3}, -1, 0, false, true);
  s.box({1, 1, 0}, {2, 2, 3}, -1, 0, true, true);  // the hole's walls face into the hole
  return s.take();
}

MeshInput two_cubes_edge_model() {
  Soup s;
  s.box({0, 0, 0}, {1, 1, 1}, -1, 0);
  s.box({1, 1, 0}, {2, 2, 1}, -1, 1);
  return s.take();
}

MeshInput two_cubes_vertex_model() {
  Soup s;
  s.box({0, 0, 0}, {1, 1, 1}, -1, 0);
  s.box({1, 1, 1}, {2, 2, 2}, -1, 1);
  return s.take();
}

MeshInput book_model() {
  Soup s;
  for (int k = 0; k < 3; ++k) {
    const double a = 2 * M_PI * k / 3;
    const Vec3 out{std::cos(a), std::sin(a), 0};
    s.face({{{0, 0, 0}, out, out + Vec3{0, 0, 1}, {0, 0, 1}}}, -1, -1);
  }
  return s.take();
}

MeshInput sphere_model(int fn, double r) {
  MeshInput in;
  in.volumes = 1;
  const int rings = (fn + 1) / 2;
  for (int i = 0; i < rings; ++i) {
    const double phi = M_PI * (i + 0.5) / rings;
    for (int j = 0; j < fn; ++j) {
      const double theta = 2 * M_PI * j / fn;
      in.positions.push_back({r * std::sin(phi) * std::cos(theta),
                              r * std::sin(phi) * std::sin(theta), r * std::cos(phi)});
    }
  }
  auto at = [fn](int i, int j) { return static_cast<std::uint32_t>(i * fn + (j % fn)); };
  MeshFace top, bottom;
  top.back = bottom.back = 0;
  auto& t = top.loops.emplace_back();
  auto& b = bottom.loops.emplace_back();
  for (int j = 0; j < fn; ++j) {
    t.push_back(at(0, j));
    b.push_back(at(rings - 1, fn - 1 - j));
  }
  in.faces.push_back(std::move(top));
  for (int i = 0; i + 1 < rings; ++i) {
    for (int j = 0; j < fn; ++j) {
      in.faces.push_back({{{at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), at(i, j)}}, -1, 0});
    }
  }
  in.faces.push_back(std::move(bottom));
  return in;
}

MeshInput torus_model(int n, int m, std::uint32_t seed) {
  MeshInput in;
  in.volumes = 1;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      const double tube = seed ? 1 + jitter(rng) : 1;
      in.positions.push_back({(3 + tube * std::cos(v)) * std::cos(u),
                              (3 + tube * std::cos(v)) * std::sin(u), tube * std::sin(v)});
    }
  }
  auto id = [n, m](int i, int j) { return static_cast<std::uint32_t>((i % n) * m + (j % m)); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (seed && (rng() & 1u)) {
        in.faces.push_back({{{a, b, d}}, -1, 0});
        in.faces.push_back({{{b, c, d}}, -1, 0});
      } else {
        in.faces.push_back({{{a, b, c}}, -1, 0});
        in.faces.push_back({{{a, c, d}}, -1, 0});
      }
    }
  }
  return in;
}

}  // namespace cellforge::compare
