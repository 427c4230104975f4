// Helpers for the Boolean tests: operand models and a run that checks what every
// result must satisfy (it validates, it is closed, its rounding made no crossing).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <unordered_map>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/transform.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/diagnose.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/topo/validate.h"
#include "support/fixtures.h"

namespace cellforge::testing {

inline Model box_model(Vec3 lo, Vec3 hi) {
  MeshInput in;
  in.volumes = 1;
  add_box(in, lo, hi, 0);
  return build(in);
}

struct BoolCase {
  boolean::BooleanResult result;
  double volume = 0;
  std::size_t vertices = 0, edges = 0, faces = 0, volumes = 0;
};

// `rounds_exactly`: every result vertex is a double (inputs on a grid), so rounding
// may make no crossing at all; otherwise the crossings are counted (a goal of zero,
// not yet met: docs/boolean.md).
inline BoolCase run_expr(const boolean::Expr& e, std::vector<const Model*> ops, bool rounds_exactly = true) {
  BoolCase c;
  auto r = boolean::evaluate(ops, e);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
  if (!r.ok()) return c;
  c.result = std::move(r.value());
  const Model& m = c.result.model;
  const auto v = validate(m);
  EXPECT_TRUE(v.empty()) << to_string(v);
  if (rounds_exactly) {
    EXPECT_EQ(c.result.report.rounding_self_intersections, 0u);
  } else if (c.result.report.rounding_self_intersections != 0) {
    std::printf("rounding made %zu crossings\n", c.result.report.rounding_self_intersections);
  }
  // The report's count, which the rounding repair's own last check supplies when it
  // found nothing, against an independent check of the built model: io's exact
  // self-intersection test of every pair of faces that share no vertex.
  if (c.result.report.rounding_self_intersections == 0 && m.num_faces() > 0) {
    io::DiagnoseOptions only_crossings;
    only_crossings.geometry = false;
    const io::Diagnosis d = io::diagnose(m, only_crossings);
    EXPECT_TRUE(d.self_intersections.empty())
        << d.self_intersections.size() << " face pairs cross, first f" << d.self_intersections[0].first.value
        << "/f" << d.self_intersections[0].second.value;
  }
  c.volume = m.num_faces() ? shape::mass_properties(m).volume : 0;
  c.vertices = m.num_vertices();
  c.edges = m.num_edges();
  c.faces = m.num_faces();
  c.volumes = m.num_volumes();
  return c;
}

inline BoolCase run(boolean::Op op, std::vector<const Model*> ops, bool rounds_exactly = true) {
  const boolean::Expr e = boolean::Expr::over(op, static_cast<int>(ops.size()));
  return run_expr(e, std::move(ops), rounds_exactly);
}

// The faces of every group of m, with positions mapped by t, in one new model.
inline Model moved(const Model& m, const shape::Transform& t) {
  MeshInput in;
  std::unordered_map<std::uint32_t, std::uint32_t> vi, ci;
  auto vid = [&](VertexId v) {
    auto [it, fresh] = vi.try_emplace(v.value, static_cast<std::uint32_t>(in.positions.size()));
    if (fresh) in.positions.push_back(t.apply(m.position(v)));
    return it->second;
  };
  auto cid = [&](VolumeId c) {
    if (!c.is_valid()) return -1;
    auto [it, fresh] = ci.try_emplace(c.value, static_cast<std::uint32_t>(in.volumes));
    if (fresh) ++in.volumes;
    return static_cast<int>(it->second);
  };
  const bool mirror = t.determinant() < 0;
  for (FaceId f : m.faces()) {
    MeshFace mf;
    for (LoopId l = m.outer_loop(f); l.is_valid(); l = m.next_loop(l)) {
      std::vector<std::uint32_t> loop;
      for (VertexId v : m.loop_vertices(l)) loop.push_back(vid(v));
      if (mirror) std::reverse(loop.begin(), loop.end());
      mf.loops.push_back(std::move(loop));
    }
    mf.front = cid(m.front_volume(f));
    mf.back = cid(m.back_volume(f));
    in.faces.push_back(std::move(mf));
  }
  return build(in);
}

inline Model sphere_model(double r, int fn, Vec3 at = {}) {
  Model m;
  EXPECT_TRUE(shape::make_sphere(m, {.r = r, .faceting = {.fn = static_cast<double>(fn)}}).ok());
  return at == Vec3{} ? std::move(m) : moved(m, shape::Transform::translate(at));
}

inline Model cylinder_model(double r, double h, int fn, Vec3 at = {}) {
  Model m;
  EXPECT_TRUE(shape::make_cylinder(m, {.h = h, .r1 = r, .r2 = r, .faceting = {.fn = static_cast<double>(fn)}}).ok());
  return at == Vec3{} ? std::move(m) : moved(m, shape::Transform::translate(at));
}

// Winding number of the closed faces of m (their cells behind) at p, by a ray along
// +x, exactly: written apart from the Boolean's own classification, to check it.
// A ray through an edge or vertex is shifted by (0, e, e^2); p on a face gives -1.
inline int winding_at(const Model& m, Vec3 p) {
  int w = 0;
  for (FaceId f : m.faces()) {
    const int sense = m.back_volume(f).is_valid() ? 1 : (m.front_volume(f).is_valid() ? -1 : 0);
    if (sense == 0 || (m.back_volume(f).is_valid() && m.front_volume(f).is_valid())) continue;
    for (const auto& tri : io::triangulate_face(m, f)) {
      const Vec3 t[3] = {m.position(tri[0]), m.position(tri[1]), m.position(tri[2])};
      const int mx = orient2d_projected(t[0], t[1], t[2], 0);
      if (mx == 0) continue;
      bool inside = true;
      for (int e = 0; e < 3 && inside; ++e) {
        const Vec3 a = t[e], b = t[(e + 1) % 3];
        int o = orient2d_projected(a, b, p, 0);
        if (o == 0) o = a.z != b.z ? (a.z > b.z ? 1 : -1) : (b.y > a.y ? 1 : -1);
        inside = o == mx;
      }
      if (!inside) continue;
      const int s = orient3d(t[0], t[1], t[2], p);
      if (s == 0) return -1;
      if (s == -mx) w += sense * mx;
    }
  }
  return w;
}

}  // namespace cellforge::testing
