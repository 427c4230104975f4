// 2D Boolean benchmark (issue 17): the named cases below through the planar arrangement
// (planar.cpp, what ops2d.h runs) and through the older route of prisms and the 3D
// Boolean (lifted_boolean), on the same operands. Prints a markdown table: input
// segments, the best of --runs runs of each route, their ratio, and the two areas.
// Offset cases time ops2d's offset() itself (planar) against the same pieces united
// through the 3D route.
//
//   bench_ops2d [--runs N] [--case SUBSTR] [--no-lifted]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "boolean/planar.h"
#include "cellforge/boolean/ops2d.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/region.h"

using namespace cellforge;
using boolean::Expr;
using boolean::Op;
using shape::Region;
using shape::Shape2D;

namespace {

Shape2D circle(double r, int n, Vec2 c = {}) {
  Region g = *shape::circle(r, {.fn = static_cast<double>(n)});
  for (Vec2& p : g.loops[0]) p = {p.x + c.x, p.y + c.y};
  return shape::shape_of(std::move(g));
}

Shape2D rect(double x0, double y0, double x1, double y1) {
  return shape::shape_of(Region{{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}}});
}

// A star with n points: 2n vertices alternating between radii r and r/2.
Shape2D star(int n, double r) {
  std::vector<Vec2> loop;
  for (int i = 0; i < 2 * n; ++i) {
    const double a = std::numbers::pi * i / n, q = i % 2 ? r / 2 : r;
    loop.push_back({q * std::cos(a), q * std::sin(a)});
  }
  return shape::shape_of(Region{{loop}});
}

// A wavy closed curve: n vertices at radius 10 + sin(k theta).
Shape2D wavy(int n, int k) {
  std::vector<Vec2> loop;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * std::numbers::pi * i / n, q = 10 + std::sin(k * a);
    loop.push_back({q * std::cos(a), q * std::sin(a)});
  }
  return shape::shape_of(Region{{loop}});
}

struct Case {
  std::string name;
  std::vector<Shape2D> operands;
  Expr expr;
  bool lifted = true;  // also through the 3D route (too slow on the largest cases)
};

std::vector<Case> cases() {
  std::vector<Case> cs;
  for (int fn : {200, 1000, 10000}) {
    const std::string f = "two circles $fn=" + std::to_string(fn);
    cs.push_back({f + ", union", {circle(10, fn), circle(10, fn, {7, 3})},
                  Expr::over(Op::kUnion, 2), fn <= 200});
    cs.push_back({f + ", difference", {circle(10, fn), circle(10, fn, {7, 3})},
                  Expr::over(Op::kDifference, 2), fn <= 200});
  }
  for (int n : {20, 100}) {
    std::vector<Shape2D> ops;
    for (int i = 0; i < n; ++i)
      ops.push_back(circle(1, 64, {std::cos(i * 0.7) * 10 + i * 0.2, std::sin(i * 0.5) * 10}));
    cs.push_back({std::to_string(n) + " circles $fn=64, n-ary union", ops, Expr::over(Op::kUnion, n),
                  n <= 20});
  }
  for (int n : {10, 40}) {
    std::vector<Shape2D> ops = {rect(0, 0, 5 * n + 1, 5 * n + 1)};
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) ops.push_back(rect(1 + 5 * i, 1 + 5 * j, 4 + 5 * i, 4 + 5 * j));
    cs.push_back({"plate minus " + std::to_string(n * n) + " squares", ops,
                  Expr::over(Op::kDifference, n * n + 1), n <= 10});
  }
  cs.push_back({"star 2000 vertices minus 999-gon",
                {star(1000, 10), shape::shape_of(*shape::regular_polygon(999, 8))},
                Expr::over(Op::kDifference, 2), false});
  cs.push_back({"wavy 5000 vertices, intersection with its copy turned",
                {wavy(5000, 40), [] {
                   Shape2D s = wavy(5000, 40);
                   for (Vec2& p : s.regions[0].loops[0])
                     p = {p.x * std::cos(0.01) - p.y * std::sin(0.01),
                          p.x * std::sin(0.01) + p.y * std::cos(0.01)};
                   return s;
                 }()},
                Expr::over(Op::kIntersection, 2), false});
  return cs;
}

double seconds(const std::function<void()>& f, int runs) {
  double best = 1e300;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

std::size_t segments(const std::vector<Shape2D>& ops) {
  std::size_t n = 0;
  for (const Shape2D& s : ops)
    for (const Region& r : s.regions)
      for (const auto& l : r.loops) n += l.size();
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  int runs = 3;
  std::string only;
  bool lifted = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--runs") && i + 1 < argc) {
      runs = std::atoi(argv[++i]);
    } else if (!std::strcmp(argv[i], "--case") && i + 1 < argc) {
      only = argv[++i];
    } else if (!std::strcmp(argv[i], "--no-lifted")) {
      lifted = false;
    } else {
      std::fprintf(stderr, "usage: bench_ops2d [--runs N] [--case SUBSTR] [--no-lifted]\n");
      return 2;
    }
  }
  std::printf("| case | segments | planar ms | 3D route ms | 3D / planar | area planar | area 3D |\n");
  std::printf("|---|---:|---:|---:|---:|---:|---:|\n");
  for (const Case& c : cases()) {
    if (!only.empty() && c.name.find(only) == std::string::npos) continue;
    double area_p = 0, area_l = 0;
    const double tp = seconds(
        [&] {
          auto r = boolean::planar_boolean(c.operands, c.expr);
          if (!r) std::fprintf(stderr, "%s: %s\n", c.name.c_str(), r.error().message.c_str());
          area_p = r ? shape::area(r->shape) : NAN;
        },
        runs);
    double tl = NAN;
    if (lifted && c.lifted) {
      tl = seconds(
          [&] {
            auto r = boolean::lifted_boolean(c.operands, c.expr);
            if (!r) std::fprintf(stderr, "%s: %s\n", c.name.c_str(), r.error().message.c_str());
            area_l = r ? shape::area(r->shape) : NAN;
          },
          runs);
    }
    std::printf("| %s | %zu | %.2f | %.1f | %.0f | %.9g | %.9g |\n", c.name.c_str(),
                segments(c.operands), tp * 1e3, tl * 1e3, tl / tp, area_p, area_l);
    std::fflush(stdout);
  }
  // offset() of many-vertex shapes (the planar route only).
  struct Off {
    std::string name;
    Shape2D shape;
    boolean::OffsetOptions o;
  };
  const std::vector<Off> offs = {
      {"offset(r=1) of circle $fn=1000", circle(10, 1000), {.amount = 1, .faceting = {.fn = 64}}},
      {"offset(r=0.5) of wavy 2000 vertices", wavy(2000, 30), {.amount = 0.5, .faceting = {.fn = 32}}},
      {"offset(delta=-0.3) of wavy 2000 vertices", wavy(2000, 30),
       {.amount = -0.3, .join = boolean::OffsetJoin::kMiter}},
      {"offset(r=0.3) of 400 squares", [] {
         Shape2D s;
         for (int i = 0; i < 20; ++i)
           for (int j = 0; j < 20; ++j) s.regions.push_back(rect(i, j, i + 0.8, j + 0.8).regions[0]);
         return s;
       }(), {.amount = 0.3, .faceting = {.fn = 32}}},
  };
  std::printf("\n| offset case | segments | planar ms | area |\n|---|---:|---:|---:|\n");
  for (const Off& c : offs) {
    if (!only.empty() && c.name.find(only) == std::string::npos) continue;
    double a = 0;
    const double t = seconds(
        [&] {
          auto r = boolean::offset(c.shape, c.o);
          if (!r) std::fprintf(stderr, "%s: %s\n", c.name.c_str(), r.error().message.c_str());
          a = r ? shape::area(*r) : NAN;
        },
        runs);
    std::printf("| %s | %zu | %.2f | %.9g |\n", c.name.c_str(), segments({c.shape}), t * 1e3, a);
  }
  return 0;
}
