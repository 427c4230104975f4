// Building primitives and sweeps through build_mesh, transforming them, and their
// mass properties, by size (segments).
#include <benchmark/benchmark.h>

#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/sweep.h"
#include "cellforge/shape/transform.h"

namespace {

using namespace cellforge;
using namespace cellforge::shape;

void BM_Sphere(benchmark::State& state) {
  const double fn = static_cast<double>(state.range(0));
  for (auto _ : state) {
    Model m;
    auto g = make_sphere(m, {.r = 10, .faceting = {.fn = fn}});
    benchmark::DoNotOptimize(g.ok());
  }
  const auto rings = (state.range(0) + 1) / 2;
  state.counters["faces"] = static_cast<double>(2 + (rings - 1) * state.range(0));
}
BENCHMARK(BM_Sphere)->Arg(32)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond);

void BM_TwistedExtrude(benchmark::State& state) {
  auto c = circle(10, {.fn = 64});
  for (auto _ : state) {
    Model m;
    auto g = linear_extrude(
        m, *c, {.height = 10, .twist = 360, .slices = static_cast<int>(state.range(0))});
    benchmark::DoNotOptimize(g.ok());
  }
}
BENCHMARK(BM_TwistedExtrude)->Arg(16)->Arg(256)->Unit(benchmark::kMillisecond);

void BM_Transform(benchmark::State& state) {
  Model m;
  auto g = make_sphere(m, {.r = 10, .faceting = {.fn = static_cast<double>(state.range(0))}});
  const Transform t = Transform::mirror({1, 1, 0}) * Transform::rotate_xyz({10, 20, 30});
  for (auto _ : state) {
    Model copy = m;
    auto h = transformed(copy, *g, t);
    benchmark::DoNotOptimize(h.ok());
  }
}
BENCHMARK(BM_Transform)->Arg(128)->Unit(benchmark::kMillisecond);

void BM_MassProperties(benchmark::State& state) {
  Model m;
  auto g = make_sphere(m, {.r = 10, .faceting = {.fn = static_cast<double>(state.range(0))}});
  for (auto _ : state) benchmark::DoNotOptimize(mass_properties(m, *g).volume);
}
BENCHMARK(BM_MassProperties)->Arg(128)->Arg(512)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
