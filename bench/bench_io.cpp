// io/ benchmarks on a 10^6-triangle binary STL (a sphere-like closed mesh made of
// a subdivided cube): parse (MB/s, triangles/s), import with welding and topology,
// write, and `admesh` reading the same file when it is installed. Peak memory is
// the process's max RSS after the run (Linux getrusage).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "cellforge/io/mesh_io.h"

namespace {

using namespace cellforge;

// A cube [-1,1]^3 with each face split into n x n squares, two triangles each,
// projected onto the unit sphere: 12 n^2 triangles, closed and consistent.
std::string sphere_stl(int n) {
  Model m;
  io::PolygonSoup soup;
  const int axes[6][3] = {{0, 1, 2}, {0, 1, 2}, {1, 2, 0}, {1, 2, 0}, {2, 0, 1}, {2, 0, 1}};
  for (int f = 0; f < 6; ++f) {
    const double side = (f % 2) ? 1 : -1;
    const auto point = [&](int i, int j) {
      double c[3];
      c[axes[f][0]] = -1 + 2.0 * i / n;
      c[axes[f][1]] = -1 + 2.0 * j / n;
      c[axes[f][2]] = side;
      const Vec3 p{c[0], c[1], c[2]};
      return p / length(p);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const auto base = static_cast<std::uint32_t>(soup.positions.size());
        soup.positions.insert(soup.positions.end(),
                              {point(i, j), point(i + 1, j), point(i + 1, j + 1), point(i, j + 1)});
        // Windings are fixed by repair_orientation below.
        if ((side > 0) == (f / 2 != 1)) {
          soup.polygons.push_back({base, base + 1, base + 2});
          soup.polygons.push_back({base, base + 2, base + 3});
        } else {
          soup.polygons.push_back({base, base + 2, base + 1});
          soup.polygons.push_back({base, base + 3, base + 2});
        }
      }
  }
  auto r = io::import_soup(m, soup, {.repair_orientation = true});  // outward, consistent
  if (!r) std::abort();
  return io::write_model(m, io::Format::kStl).value();
}

const std::string& stl_bytes() {
  static const std::string bytes = sphere_stl(289);  // 12 * 289^2 = 1002252 triangles
  return bytes;
}

std::span<const std::uint8_t> span_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

void set_rates(benchmark::State& state, std::size_t bytes, std::size_t triangles) {
  state.counters["MB/s"] = benchmark::Counter(static_cast<double>(bytes) * state.iterations() / 1e6,
                                              benchmark::Counter::kIsRate);
  state.counters["triangles/s"] = benchmark::Counter(
      static_cast<double>(triangles) * state.iterations(), benchmark::Counter::kIsRate);
}

std::size_t triangles_in(const std::string& stl) { return (stl.size() - 84) / 50; }

void BM_ParseBinaryStl(benchmark::State& state) {
  const std::string& stl = stl_bytes();
  for (auto _ : state) {
    auto soup = io::parse_mesh(span_of(stl), io::Format::kStl);
    benchmark::DoNotOptimize(soup);
  }
  set_rates(state, stl.size(), triangles_in(stl));
}
BENCHMARK(BM_ParseBinaryStl)->Unit(benchmark::kMillisecond);

void BM_ReadBinaryStlIntoModel(benchmark::State& state) {  // parse + weld + build_mesh
  const std::string& stl = stl_bytes();
  for (auto _ : state) {
    Model m;
    auto r = io::read_model(m, span_of(stl), io::Format::kStl);
    if (!r) state.SkipWithError(r.error().message.c_str());
    benchmark::DoNotOptimize(m);
  }
  set_rates(state, stl.size(), triangles_in(stl));
}
BENCHMARK(BM_ReadBinaryStlIntoModel)->Unit(benchmark::kMillisecond);

void BM_ImportSoup(benchmark::State& state) {  // welding + topology only
  const auto soup = io::parse_mesh(span_of(stl_bytes()), io::Format::kStl).value();
  for (auto _ : state) {
    Model m;
    auto r = io::import_soup(m, soup, {});
    benchmark::DoNotOptimize(r);
  }
  set_rates(state, stl_bytes().size(), soup.polygons.size());
}
BENCHMARK(BM_ImportSoup)->Unit(benchmark::kMillisecond);

void BM_WriteBinaryStl(benchmark::State& state) {
  Model m;
  if (!io::read_model(m, span_of(stl_bytes()), io::Format::kStl)) std::abort();
  std::size_t size = 0;
  for (auto _ : state) {
    auto bytes = io::write_model(m, io::Format::kStl);
    size = bytes->size();
    benchmark::DoNotOptimize(bytes);
  }
  set_rates(state, size, m.num_faces());
}
BENCHMARK(BM_WriteBinaryStl)->Unit(benchmark::kMillisecond);

// N copies of one triangle (issue 18: 200,000 of them took 48 s to convert): every
// edge has N face uses, so any per-edge work quadratic in the uses shows here.
void BM_ImportIdenticalTriangles(benchmark::State& state) {
  io::PolygonSoup soup;
  soup.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  soup.polygons.assign(static_cast<std::size_t>(state.range(0)), {0, 1, 2});
  for (auto _ : state) {
    Model m;
    auto r = io::import_soup(m, soup, {});
    if (!r) state.SkipWithError(r.error().message.c_str());
    benchmark::DoNotOptimize(m);
  }
  state.counters["triangles/s"] = benchmark::Counter(
      static_cast<double>(state.range(0)) * state.iterations(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ImportIdenticalTriangles)->Arg(20000)->Arg(200000)->Unit(benchmark::kMillisecond);

// admesh reading (and checking) the same file, as an external process.
void BM_AdmeshReadSameFile(benchmark::State& state) {
  if (std::system("command -v admesh > /dev/null 2>&1") != 0) {
    state.SkipWithError("admesh not installed");
    return;
  }
  const auto path = std::filesystem::temp_directory_path() / "cellforge_bench_io.stl";
  std::ofstream(path, std::ios::binary) << stl_bytes();
  const std::string cmd = "admesh " + path.string() + " > /dev/null 2>&1";
  for (auto _ : state) {
    if (std::system(cmd.c_str()) != 0) state.SkipWithError("admesh failed");
  }
  set_rates(state, stl_bytes().size(), triangles_in(stl_bytes()));
}
BENCHMARK(BM_AdmeshReadSameFile)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::printf("mesh: %zu triangles, %.1f MB binary STL\n", triangles_in(stl_bytes()),
              stl_bytes().size() / 1e6);
  benchmark::RunSpecifiedBenchmarks();
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("peak RSS of this process: %.0f MB\n", usage.ru_maxrss / 1024.0);
  benchmark::Shutdown();
  return 0;
}
