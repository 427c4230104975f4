// Seed 000's table, measured: topology storage and the cost of the 9 adjacency
// queries in the cellforge structure, Weiler's radial edge structure and
// Baumgart's winged edge structure, on the comparison models of issue 6.
//   build/bin/bench_structures [--svg docs/structure-comparison.svg] [--big N]
// Prints markdown tables; writes a bar chart as SVG. Query times: every query from
// every element of a model (a fixed random sample of 100,000 for the big mesh),
// repeated for at least 2 ms per trial; reported per answer element. The trials
// of the three structures alternate (cellforge, radial edge, winged edge, then
// again), 41 rounds (9 for the big mesh, whose trials are long), and each
// structure keeps its best: a slow spell of the shared machine then hits every
// structure alike instead of one of them. The ratio to radial edge is the median,
// over the rounds, of the ratio of the two trials taken back to back.
// Every structure deduplicates its answers with the same function (topo/dedupe.h);
// cellforge skips it for the F->E and F->V answers of a face that its marks say
// repeats no element (model.h, kRepeatFace), which Weiler's face record cannot say.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cellforge/compare/models.h"
#include "cellforge/compare/radial_edge.h"
#include "cellforge/compare/winged_edge.h"
#include "cellforge/topo/queries.h"

namespace cellforge::compare {
namespace {

constexpr int kStructures = 3;
constexpr const char* kStructureNames[kStructures] = {"cellforge", "radial edge", "winged edge"};
constexpr const char* kQueryNames[9] = {"V→V", "V→E", "V→F", "E→V", "E→E",
                                        "E→F", "F→V", "F→E", "F→F"};

// cellforge's queries with the baselines' member-function interface.
struct CellforgeQueries {
  const Model& m;
  template <class In, class Out>
  void run(In x, std::vector<Out>& out) const {
    if constexpr (std::is_same_v<Out, VertexId>)
      vertices_of(m, x, out);
    else if constexpr (std::is_same_v<Out, EdgeId>)
      edges_of(m, x, out);
    else
      faces_of(m, x, out);
  }
};

template <class S>
struct MemberQueries {
  const S& s;
  template <class In, class Out>
  void run(In x, std::vector<Out>& out) const {
    if constexpr (std::is_same_v<Out, VertexId>)
      s.vertices_of(x, out);
    else if constexpr (std::is_same_v<Out, EdgeId>)
      s.edges_of(x, out);
    else
      s.faces_of(x, out);
  }
};

struct Sample {
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
  std::vector<FaceId> faces;
};

Sample sample_of(const Model& m, std::size_t limit) {
  Sample s;
  for (VertexId v : m.vertices()) s.vertices.push_back(v);
  for (EdgeId e : m.edges()) s.edges.push_back(e);
  for (FaceId f : m.faces()) s.faces.push_back(f);
  std::mt19937 rng(6);
  auto cut = [&](auto& ids) {
    if (ids.size() <= limit) return;
    std::shuffle(ids.begin(), ids.end(), rng);
    ids.resize(limit);
  };
  cut(s.vertices);
  cut(s.edges);
  cut(s.faces);
  return s;
}

// One trial: nanoseconds per answer element of one query over the sample. The
// clock is read after batches of at least ~20,000 queries, so that reading it
// costs nothing.
template <class Out, class Q, class In>
double trial(const Q& q, const std::vector<In>& from) {
  using Clock = std::chrono::steady_clock;
  std::vector<Out> out;
  const std::size_t passes = std::max<std::size_t>(1, 20000 / from.size());
  std::size_t elements = 0;
  const auto start = Clock::now();
  std::chrono::duration<double> elapsed{};
  do {
    for (std::size_t pass = 0; pass < passes; ++pass) {
      for (In x : from) {
        q.run(x, out);
        elements += out.size();
      }
    }
    elapsed = Clock::now() - start;
  } while (elapsed.count() < 0.002);
  return elapsed.count() * 1e9 / static_cast<double>(elements);
}

// One trial of query number `query` (kQueryNames order).
template <class Q>
double trial(const Q& q, const Sample& s, int query) {
  switch (query) {
    case 0: return trial<VertexId>(q, s.vertices);
    case 1: return trial<EdgeId>(q, s.vertices);
    case 2: return trial<FaceId>(q, s.vertices);
    case 3: return trial<VertexId>(q, s.edges);
    case 4: return trial<EdgeId>(q, s.edges);
    case 5: return trial<FaceId>(q, s.edges);
    case 6: return trial<VertexId>(q, s.faces);
    case 7: return trial<EdgeId>(q, s.faces);
    default: return trial<FaceId>(q, s.faces);
  }
}

constexpr int kRounds = 41, kBigRounds = 9;

struct Row {
  std::string model;
  std::size_t faces = 0;
  std::optional<StorageStats> storage[kStructures];
  std::vector<double> ns[kStructures];  // empty when the structure refused the model
  std::vector<double> ratio;            // cellforge ÷ radial edge per query (paired median)
  std::string refusal;                  // the winged edge converter's message
};

Row measure(const std::string& name, const MeshInput& input, std::size_t sample_limit) {
  Row row;
  row.model = name;
  Model m;
  if (auto r = build_mesh(m, input); !r) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), r.error().message.c_str());
    std::exit(1);
  }
  row.faces = m.num_faces();
  const Sample sample = sample_of(m, sample_limit);
  row.storage[0] = cellforge_storage(m);
  const RadialEdge r = RadialEdge::from_model(m);
  row.storage[1] = r.storage();
  auto w = WingedEdge::from_model(m);
  if (w.ok()) {
    row.storage[2] = w->storage();
  } else {
    row.refusal = w.error().message;
  }
  const int structures = w.ok() ? 3 : 2;
  for (int s = 0; s < structures; ++s) row.ns[s].assign(9, INFINITY);
  row.ratio.assign(9, 0);
  for (int q = 0; q < 9; ++q) {
    const bool big = sample.faces.size() < row.faces;
    std::vector<double> paired;
    for (int round = 0; round < (big ? kBigRounds : kRounds); ++round) {
      const double tc = trial(CellforgeQueries{m}, sample, q);
      const double tr = trial(MemberQueries<RadialEdge>{r}, sample, q);
      row.ns[0][q] = std::min(row.ns[0][q], tc);
      row.ns[1][q] = std::min(row.ns[1][q], tr);
      paired.push_back(tc / tr);
      if (w.ok()) {
        double& we = row.ns[2][q];
        we = std::min(we, trial(MemberQueries<WingedEdge>{*w}, sample, q));
      }
    }
    std::nth_element(paired.begin(), paired.begin() + paired.size() / 2, paired.end());
    row.ratio[q] = paired[paired.size() / 2];
  }
  return row;
}

std::string fixed(double x, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, x);
  return buf;
}

std::string grouped(std::size_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

void print_tables(const std::vector<Row>& rows) {
  std::printf("## Topology storage\n\n");
  std::printf(
      "| model | faces | structure | records | references | bytes | bytes/face | × radial edge "
      "|\n");
  std::printf("|---|---:|---|---:|---:|---:|---:|---:|\n");
  for (const Row& r : rows) {
    for (int s = 0; s < kStructures; ++s) {
      if (!r.storage[s]) {
        std::printf("| %s | %s | %s | refused: %s |||||\n", r.model.c_str(),
                    grouped(r.faces).c_str(), kStructureNames[s], r.refusal.c_str());
        continue;
      }
      const StorageStats& st = *r.storage[s];
      std::printf("| %s | %s | %s | %s | %s | %s | %s | %s |\n", r.model.c_str(),
                  grouped(r.faces).c_str(), kStructureNames[s], grouped(st.records).c_str(),
                  grouped(st.references).c_str(), grouped(st.bytes).c_str(),
                  fixed(double(st.bytes) / double(r.faces), 1).c_str(),
                  fixed(double(st.bytes) / double(r.storage[1]->bytes), 3).c_str());
    }
  }
  std::printf("\n## Query cost, ns per answer element\n\n| model | structure |");
  for (const char* q : kQueryNames) std::printf(" %s |", q);
  std::printf("\n|---|---|");
  for (int q = 0; q < 9; ++q) std::printf("---:|");
  std::printf("\n");
  for (const Row& r : rows) {
    for (int s = 0; s < kStructures; ++s) {
      std::printf("| %s | %s |", r.model.c_str(), kStructureNames[s]);
      for (int q = 0; q < 9; ++q) {
        std::printf(" %s |", r.ns[s].empty() ? "—" : fixed(r.ns[s][q], 2).c_str());
      }
      std::printf("\n");
    }
    std::printf("| %s | *cellforge ÷ radial edge* |", r.model.c_str());
    for (int q = 0; q < 9; ++q) std::printf(" *%s* |", fixed(r.ratio[q], 2).c_str());
    std::printf("\n");
  }
}

void print_verdict(const std::vector<Row>& rows) {
  double worst_bytes = 0, worst_time = 0;
  std::string worst_bytes_model, worst_time_at;
  int slower = 0, total = 0;
  for (const Row& r : rows) {
    const double ratio = double(r.storage[0]->bytes) / double(r.storage[1]->bytes);
    if (ratio > worst_bytes) worst_bytes = ratio, worst_bytes_model = r.model;
    for (int q = 0; q < 9; ++q) {
      const double t = r.ratio[q];
      ++total;
      if (t > 1) ++slower;
      if (t > worst_time) worst_time = t, worst_time_at = r.model + " " + kQueryNames[q];
    }
  }
  std::printf("\n## Targets\n\n");
  std::printf("- bytes: cellforge ÷ radial edge is at most %s (%s): ≤ 0.5 %s, ≤ 0.1 %s\n",
              fixed(worst_bytes, 3).c_str(), worst_bytes_model.c_str(),
              worst_bytes <= 0.5 ? "met" : "NOT met", worst_bytes <= 0.1 ? "met" : "NOT met");
  std::printf(
      "- queries: cellforge slower than radial edge in %d of %d (model, query) pairs; "
      "worst ratio %s (%s)\n",
      slower, total, fixed(worst_time, 2).c_str(), worst_time_at.c_str());
}

// Two bar charts: topology bytes per face by model, and ns per answer element by
// query on the last (largest) model.
void write_svg(const std::vector<Row>& rows, const std::string& path) {
  static constexpr const char* kColors[kStructures] = {"#1b9e77", "#d95f02", "#7570b3"};
  const int width = 980, panel = 300, top = 60;
  std::ostringstream svg;
  svg << "<svg xmlns='http://www.w3.org/2000/svg' width='" << width << "' height='"
      << top + 2 * (panel + 90) << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
  for (int s = 0; s < kStructures; ++s) {
    svg << "<rect x='" << 60 + s * 150 << "' y='14' width='14' height='14' fill='" << kColors[s]
        << "'/><text x='" << 80 + s * 150 << "' y='26'>" << kStructureNames[s] << "</text>\n";
  }
  auto panel_at = [&](int index, const std::string& title, const std::vector<std::string>& labels,
                      const std::vector<std::vector<double>>& values, const std::string& unit) {
    const int y0 = top + index * (panel + 90);
    double vmax = 0;
    for (const auto& v : values)
      for (double x : v) vmax = std::max(vmax, x);
    const double scale = (panel - 40) / vmax;
    const int base = y0 + panel, group = (width - 80) / static_cast<int>(labels.size());
    const int bar = std::min(28, (group - 10) / kStructures);
    svg << "<text x='60' y='" << y0 + 10 << "' font-size='14' font-weight='bold'>" << title
        << "</text>\n<line x1='55' y1='" << base << "' x2='" << width - 10 << "' y2='" << base
        << "' stroke='black'/>\n";
    for (std::size_t g = 0; g < labels.size(); ++g) {
      const int gx = 60 + static_cast<int>(g) * group;
      for (int s = 0; s < kStructures; ++s) {
        const int x = gx + s * bar;
        const double v = values[g][s];
        if (std::isnan(v)) {
          svg << "<text x='" << x + bar / 2 << "' y='" << base - 4
              << "' font-size='9' text-anchor='end' transform='rotate(-90 " << x + bar / 2 << ' '
              << base - 4 << ")'>refused</text>\n";
          continue;
        }
        const int h = std::max(1, static_cast<int>(v * scale));
        svg << "<rect x='" << x << "' y='" << base - h << "' width='" << bar - 2 << "' height='"
            << h << "' fill='" << kColors[s] << "'><title>" << kStructureNames[s] << ": "
            << fixed(v, 1) << ' ' << unit << "</title></rect>\n<text x='" << x + bar / 2 - 1
            << "' y='" << base - h - 3 << "' font-size='9' text-anchor='middle'>"
            << fixed(v, v < 10 ? 1 : 0) << "</text>\n";
      }
      svg << "<text x='" << gx + kStructures * bar / 2 << "' y='" << base + 16
          << "' text-anchor='middle'>" << labels[g] << "</text>\n";
    }
  };
  std::vector<std::string> models;
  std::vector<std::vector<double>> bytes;
  for (const Row& r : rows) {
    models.push_back(r.model);
    auto& b = bytes.emplace_back();
    for (int s = 0; s < kStructures; ++s) {
      b.push_back(r.storage[s] ? double(r.storage[s]->bytes) / double(r.faces) : NAN);
    }
  }
  panel_at(0, "Topology bytes per face", models, bytes, "B/face");
  const Row& big = rows.back();
  std::vector<std::string> queries(std::begin(kQueryNames), std::end(kQueryNames));
  std::vector<std::vector<double>> ns(9);
  for (int q = 0; q < 9; ++q) {
    for (int s = 0; s < kStructures; ++s) ns[q].push_back(big.ns[s].empty() ? NAN : big.ns[s][q]);
  }
  panel_at(1, "ns per answer element, " + big.model, queries, ns, "ns");
  svg << "</svg>\n";
  std::ofstream(path) << svg.str();
}

int run(int argc, char** argv) {
  std::string svg = "docs/structure-comparison.svg";
  int big_n = 1000;  // torus grid big_n x big_n/2: 2 * 1000 * 500 = 10^6 triangles
  for (int i = 1; i < argc; i += 2) {
    const std::string flag = argv[i];
    if ((flag != "--svg" && flag != "--big") || i + 1 >= argc) {
      std::fprintf(stderr, "usage: bench_structures [--svg FILE] [--big N]\n");
      return 2;
    }
    if (flag == "--svg") {
      svg = argv[i + 1];
    } else {
      // Peak memory grows ~1.25 kB a triangle (1.24 GB measured at N = 1000, most
      // of it the radial edge copy): N = 3000, 9 * 10^6 triangles, needs ~11 GB.
      char* end = nullptr;
      const long n = std::strtol(argv[i + 1], &end, 10);
      if (end == argv[i + 1] || *end != '\0' || n < 4 || n > 3000) {
        std::fprintf(stderr,
                     "bench_structures: --big takes an integer 4..3000 (a torus of N x N/2 "
                     "quads, 2 * N * N/2 triangles), not '%s'\n",
                     argv[i + 1]);
        return 2;
      }
      big_n = static_cast<int>(n);
    }
  }
  const std::size_t all = SIZE_MAX;
  std::vector<Row> rows;
  rows.push_back(measure("cube", cube_model(), all));
  rows.push_back(measure("cube with hole", cube_with_hole_model(), all));
  rows.push_back(measure("sphere $fn=64", sphere_model(64), all));
  rows.push_back(measure("two cubes, one edge", two_cubes_edge_model(), all));
  rows.push_back(measure("book", book_model(), all));
  rows.push_back(measure("torus " + grouped(2ull * big_n * (big_n / 2)) + " triangles",
                         torus_model(big_n, big_n / 2), 100000));
  print_tables(rows);
  print_verdict(rows);
  write_svg(rows, svg);
  std::printf("\nchart: %s\n", svg.c_str());
  return 0;
}

}  // namespace
}  // namespace cellforge::compare

int main(int argc, char** argv) { return cellforge::compare::run(argc, argv); }
