// Helpers for the Boolean tests: operand models and a run that checks what every
// result must satisfy (it validates, it is closed, its rounding made no crossing).
#pragma once
#include <gtest/gtest.h>

#include <initializer_list>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/build/mass.h"
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

inline BoolCase run_expr(const boolean::Expr& e, std::vector<const Model*> ops) {
  BoolCase c;
  auto r = boolean::evaluate(ops, e);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().message);
  if (!r.ok()) return c;
  c.result = std::move(r.value());
  const Model& m = c.result.model;
  const auto v = validate(m);
  EXPECT_TRUE(v.empty()) << to_string(v);
  EXPECT_EQ(c.result.report.rounding_self_intersections, 0u);
  c.volume = m.num_faces() ? build::mass_properties(m).volume : 0;
  c.vertices = m.num_vertices();
  c.edges = m.num_edges();
  c.faces = m.num_faces();
  c.volumes = m.num_volumes();
  return c;
}

inline BoolCase run(boolean::Op op, std::vector<const Model*> ops) {
  const boolean::Expr e = boolean::Expr::over(op, static_cast<int>(ops.size()));
  return run_expr(e, std::move(ops));
}

}  // namespace cellforge::testing
