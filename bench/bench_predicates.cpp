// Predicate benchmarks, nanoseconds per call (time per iteration), cycling through
// 1024 precomputed inputs:
//   random           points in general position: the floating-point filter decides;
//   coplanar_lattice exactly coplanar points whose differences are exact doubles: the
//                    exact stage, on short expansions;
//   coplanar_wide    exactly coplanar points (on the plane x = y) of mixed magnitudes,
//                    so every difference has a rounding tail: the exact stage at full
//                    length.
// Run: build-geom/bin/bench_predicates
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "cellforge/geom/predicates.h"

namespace cellforge {
namespace {

constexpr std::size_t kPool = 1024;

struct Quad {
  Vec3 a, b, c, d;
};

std::vector<Quad> make_quads(int kind) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> grid(-65536, 65536), coef(-3, 3), expo(-20, 20);
  std::vector<Quad> quads(kPool);
  for (Quad& q : quads) {
    const int p = coef(rng), r = coef(rng);
    for (Vec3* v : {&q.a, &q.b, &q.c, &q.d}) {
      if (kind == 0) {
        *v = {unit(rng), unit(rng), unit(rng)};
      } else if (kind == 1) {
        v->x = std::ldexp(grid(rng), -10);
        v->y = std::ldexp(grid(rng), -10);
        v->z = p * v->x + r * v->y;
      } else {
        const double s = std::ldexp(unit(rng), expo(rng));
        *v = {s, s, std::ldexp(unit(rng), expo(rng))};
      }
    }
  }
  return quads;
}

void BM_Orient3d(benchmark::State& state) {
  const std::vector<Quad> quads = make_quads(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Quad& q = quads[i++ % kPool];
    benchmark::DoNotOptimize(orient3d(q.a, q.b, q.c, q.d));
  }
}
BENCHMARK(BM_Orient3d)->ArgName("random")->Arg(0);
BENCHMARK(BM_Orient3d)->ArgName("coplanar_lattice")->Arg(1);
BENCHMARK(BM_Orient3d)->ArgName("coplanar_wide")->Arg(2);

void BM_Orient2d(benchmark::State& state) {
  const std::vector<Quad> quads = make_quads(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Quad& q = quads[i++ % kPool];
    // The xy projection: random stays random, coplanar_wide has x == y (collinear).
    benchmark::DoNotOptimize(orient2d({q.a.x, q.a.y}, {q.b.x, q.b.y}, {q.c.x, q.c.y}));
  }
}
BENCHMARK(BM_Orient2d)->ArgName("random")->Arg(0);
BENCHMARK(BM_Orient2d)->ArgName("collinear_wide")->Arg(2);

// The same determinant through the general Expansion value class (no filter).
void BM_ExactDet3(benchmark::State& state) {
  const std::vector<Quad> quads = make_quads(static_cast<int>(state.range(0)));
  std::size_t i = 0;
  for (auto _ : state) {
    const Quad& q = quads[i++ % kPool];
    benchmark::DoNotOptimize(
        exact_det3(exact_sub(q.b, q.a), exact_sub(q.c, q.a), exact_sub(q.d, q.a)).sign());
  }
}
BENCHMARK(BM_ExactDet3)->ArgName("random")->Arg(0);
BENCHMARK(BM_ExactDet3)->ArgName("coplanar_wide")->Arg(2);

}  // namespace
}  // namespace cellforge

BENCHMARK_MAIN();
