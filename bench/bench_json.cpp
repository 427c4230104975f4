// The native JSON reader (io/json.cpp, a hand-written pull parser that fills the
// snapshot tables as it reads) against Debian's nlohmann-json 3 on the same file:
//   - cellforge's read_model (parse, checks, restore and validation);
//   - nlohmann's DOM parse alone, and a SAX pass that builds nothing (the least any
//     use of the library costs);
//   - nlohmann's DOM parse, the tables filled from the DOM, and the same restore():
//     what replacing the parser would give, before its error positions and
//     duplicate-key checks are added back.
// The model: make_sphere fn=700 (245,000 vertices, 244,302 faces; 60.7 MB of JSON). "DOM MB" is
// what the DOM holds (malloc's count before and after, glibc). docs/io.md, "The JSON parser", has
// the figures and the decision.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <cstdlib>
#include <nlohmann/json.hpp>

#include "cellforge/io/mesh_io.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/topo/snapshot.h"

namespace {

using namespace cellforge;

const std::string& model_json() {
  static const std::string text = [] {
    Model m;
    if (!shape::make_sphere(m, {.r = 10, .faceting = {.fn = 700}})) std::abort();
    return io::write_model(m, io::Format::kJson).value();
  }();
  return text;
}

std::span<const std::uint8_t> span_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

void set_rate(benchmark::State& state) {
  state.counters["MB/s"] =
      benchmark::Counter(static_cast<double>(model_json().size()) * state.iterations() / 1e6,
                         benchmark::Counter::kIsRate);
}

void BM_ReadJsonCellforge(benchmark::State& state) {
  for (auto _ : state) {
    Model m;
    auto r = io::read_model(m, span_of(model_json()), io::Format::kJson);
    if (!r) state.SkipWithError(r.error().message.c_str());
    benchmark::DoNotOptimize(m);
  }
  set_rate(state);
}
BENCHMARK(BM_ReadJsonCellforge)->Unit(benchmark::kMillisecond);

// restore() alone on the tables of the same model: read_model minus this is the
// parse.
void BM_RestoreOnly(benchmark::State& state) {
  Model m;
  if (!io::read_model(m, span_of(model_json()), io::Format::kJson)) std::abort();
  const Snapshot tables = snapshot(m);
  for (auto _ : state) {
    auto r = restore(tables);
    if (!r) state.SkipWithError(r.error().message.c_str());
    benchmark::DoNotOptimize(r);
  }
}
BENCHMARK(BM_RestoreOnly)->Unit(benchmark::kMillisecond);

void BM_ParseNlohmannDom(benchmark::State& state) {
  double held = 0;
  for (auto _ : state) {
    const std::size_t before = mallinfo2().uordblks;
    auto doc = nlohmann::json::parse(model_json());
    held = static_cast<double>(mallinfo2().uordblks - before) / 1e6;
    benchmark::DoNotOptimize(doc);
  }
  state.counters["DOM MB"] = held;
  set_rate(state);
}
BENCHMARK(BM_ParseNlohmannDom)->Unit(benchmark::kMillisecond);

// A SAX handler that keeps nothing.
struct NullSax : nlohmann::json_sax<nlohmann::json> {
  std::size_t events = 0;
  bool null() override { return ++events; }
  bool boolean(bool) override { return ++events; }
  bool number_integer(number_integer_t) override { return ++events; }
  bool number_unsigned(number_unsigned_t) override { return ++events; }
  bool number_float(number_float_t, const string_t&) override { return ++events; }
  bool string(string_t&) override { return ++events; }
  bool binary(binary_t&) override { return ++events; }
  bool start_object(std::size_t) override { return ++events; }
  bool key(string_t&) override { return ++events; }
  bool end_object() override { return ++events; }
  bool start_array(std::size_t) override { return ++events; }
  bool end_array() override { return ++events; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override {
    return false;
  }
};

void BM_ParseNlohmannSaxNothingKept(benchmark::State& state) {
  for (auto _ : state) {
    NullSax sax;
    if (!nlohmann::json::sax_parse(model_json(), &sax)) state.SkipWithError("sax failed");
    benchmark::DoNotOptimize(sax.events);
  }
  set_rate(state);
}
BENCHMARK(BM_ParseNlohmannSaxNothingKept)->Unit(benchmark::kMillisecond);

// The snapshot tables from the DOM, as json.cpp fills them from the text.
Snapshot tables_from(const nlohmann::json& doc) {
  Snapshot s;
  for (const auto& g : doc.at("groups")) {
    const auto group = static_cast<std::uint32_t>(s.groups.size());
    s.groups.push_back({g.at("name").get<std::string>()});
    for (const auto& a : g.at("attributes"))
      s.parameters.push_back({group, a.at(0).get<std::string>(), a.at(1).get<std::string>()});
  }
  for (const auto& c : doc.at("cells")) s.cells.push_back(c.get<std::uint32_t>());
  for (const auto& v : doc.at("vertices"))
    s.vertices.push_back({{v.at(0).get<double>(), v.at(1).get<double>(), v.at(2).get<double>()},
                          v.at(3).get<std::uint32_t>()});
  for (const auto& e : doc.at("edges"))
    s.edges.push_back({e.at(0).get<std::uint32_t>(), e.at(1).get<std::uint32_t>()});
  for (const auto& f : doc.at("surfaces")) {
    Surface x;
    x.kind = f.at("kind").get<std::string>();
    x.center = {f.at("center").at(0), f.at("center").at(1), f.at("center").at(2)};
    x.axis = {f.at("axis").at(0), f.at("axis").at(1), f.at("axis").at(2)};
    x.radius = f.at("radius");
    x.radius2 = f.at("radius2");
    x.height = f.at("height");
    x.segments = f.at("segments");
    s.surfaces.push_back(x);
  }
  for (const auto& f : doc.at("faces")) {
    const auto face = static_cast<std::uint32_t>(s.faces.size());
    s.faces.push_back({f.at("group").get<std::uint32_t>(), f.at("front").get<std::int64_t>(),
                       f.at("back").get<std::int64_t>(), f.at("surface").get<std::int64_t>()});
    std::uint32_t ord = 0;
    for (const auto& l : f.at("loops")) {
      const auto loop = static_cast<std::uint32_t>(s.loops.size());
      if (l.contains("point")) {
        s.loops.push_back({face, ord++, l.at("point").get<std::int64_t>()});
        continue;
      }
      s.loops.push_back({face, ord++, Snapshot::kNone});
      const auto& vs = l.at("vertices");
      const auto& es = l.at("edges");
      const auto& rs = l.at("radial");
      for (std::size_t k = 0; k < vs.size(); ++k) {
        const auto e = es.at(k).get<std::uint32_t>();
        const auto a = vs.at(k).get<std::uint32_t>();
        s.uses.push_back({loop, static_cast<std::uint32_t>(k), e, s.edges.at(e).start != a,
                          rs.at(k).get<std::uint32_t>()});
      }
    }
  }
  return s;
}

void BM_ReadJsonNlohmannAndRestore(benchmark::State& state) {
  for (auto _ : state) {
    auto doc = nlohmann::json::parse(model_json());
    auto m = restore(tables_from(doc));
    if (!m) state.SkipWithError(m.error().message.c_str());
    benchmark::DoNotOptimize(m);
  }
  set_rate(state);
}
BENCHMARK(BM_ReadJsonNlohmannAndRestore)->Unit(benchmark::kMillisecond);

// The two readers agree on the model (checked once, before timing).
void BM_ReadersAgree(benchmark::State& state) {
  Model a;
  if (!io::read_model(a, span_of(model_json()), io::Format::kJson)) std::abort();
  auto b = restore(tables_from(nlohmann::json::parse(model_json())));
  if (!b || !(snapshot(a) == snapshot(*b))) state.SkipWithError("the readers disagree");
  for (auto _ : state) benchmark::DoNotOptimize(a);
  state.counters["JSON MB"] = static_cast<double>(model_json().size()) / 1e6;
  state.counters["faces"] = static_cast<double>(a.num_faces());
}
BENCHMARK(BM_ReadersAgree)->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
