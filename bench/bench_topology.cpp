// Topology benchmarks: the 9 adjacency queries on a closed triangle mesh of about
// 10^6 faces (nanoseconds per answer element), topology bytes per triangle and per
// quad, and the bulk builder's speed.
//   build/bin/bench_topology --benchmark_counters_tabular=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/queries.h"
#include "cellforge/topo/validate.h"

namespace cellforge {
namespace {

// A torus grid of n x n quads (optionally split into triangles): closed, genus 1.
MeshInput torus_grid(int n, bool triangles) {
  MeshInput in;
  in.volumes = 1;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / n;
      in.positions.push_back(
          {(3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)});
    }
  }
  auto id = [n](int i, int j) { return std::uint32_t(((i + n) % n) * n + (j + n) % n); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (triangles) {
        in.faces.push_back({{{a, b, c}}, -1, 0});
        in.faces.push_back({{{a, c, d}}, -1, 0});
      } else {
        in.faces.push_back({{{a, b, c, d}}, -1, 0});
      }
    }
  }
  return in;
}

const Model& big_mesh() {
  static const Model m = [] {
    Model model;
    auto r = build_mesh(model, torus_grid(708, true));  // 2 * 708^2 = 1,002,528 triangles
    if (!r) std::abort();
    return model;
  }();
  return m;
}

template <class Out, class In>
void query_bench(benchmark::State& state) {
  const Model& m = big_mesh();
  std::mt19937 rng(42);
  std::vector<In> sample;
  const std::uint32_t slots = std::is_same_v<In, VertexId> ? m.vertex_slots()
                              : std::is_same_v<In, EdgeId> ? m.edge_slots()
                                                           : m.face_slots();
  for (int i = 0; i < 4096; ++i) sample.push_back(In(rng() % slots));
  std::vector<Out> out;
  std::size_t elements = 0, k = 0;
  for (auto _ : state) {
    const In x = sample[k++ & 4095];
    if constexpr (std::is_same_v<Out, VertexId>)
      vertices_of(m, x, out);
    else if constexpr (std::is_same_v<Out, EdgeId>)
      edges_of(m, x, out);
    else
      faces_of(m, x, out);
    elements += out.size();
    benchmark::DoNotOptimize(out.data());
  }
  // Seconds per answer element (printed with an SI prefix: "22.1n" is 22.1 ns).
  state.counters["time_per_element"] = benchmark::Counter(
      static_cast<double>(elements), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
  state.counters["elements_per_query"] = static_cast<double>(elements) / state.iterations();
}

BENCHMARK(query_bench<VertexId, VertexId>)->Name("V->V");
BENCHMARK(query_bench<EdgeId, VertexId>)->Name("V->E");
BENCHMARK(query_bench<FaceId, VertexId>)->Name("V->F");
BENCHMARK(query_bench<VertexId, EdgeId>)->Name("E->V");
BENCHMARK(query_bench<EdgeId, EdgeId>)->Name("E->E");
BENCHMARK(query_bench<FaceId, EdgeId>)->Name("E->F");
BENCHMARK(query_bench<VertexId, FaceId>)->Name("F->V");
BENCHMARK(query_bench<EdgeId, FaceId>)->Name("F->E");
BENCHMARK(query_bench<FaceId, FaceId>)->Name("F->F");

void bytes_per_face(benchmark::State& state) {
  const bool triangles = state.range(0) == 1;
  Model m;
  for (auto _ : state) {
    m = Model();
    auto r = build_mesh(m, torus_grid(triangles ? 708 : 1001, triangles));
    benchmark::DoNotOptimize(r.ok());
  }
  state.counters["faces"] = static_cast<double>(m.num_faces());
  state.counters["topology_bytes_per_face"] =
      static_cast<double>(m.topology_bytes()) / static_cast<double>(m.num_faces());
  state.counters["build_faces_per_s"] = benchmark::Counter(
      static_cast<double>(m.num_faces()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(bytes_per_face)
    ->Arg(1)
    ->Arg(0)
    ->ArgName("triangles")
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

void validate_big_mesh(benchmark::State& state) {
  const Model& m = big_mesh();
  std::size_t violations = 0;
  for (auto _ : state) violations += validate(m).size();
  if (violations != 0) state.SkipWithError("the mesh is not valid");
  state.counters["faces_per_s"] = benchmark::Counter(
      static_cast<double>(m.num_faces()) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(validate_big_mesh)->Unit(benchmark::kMillisecond)->Iterations(2);

}  // namespace
}  // namespace cellforge

BENCHMARK_MAIN();
