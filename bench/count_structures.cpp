// Instruction counts of the 9 adjacency queries, for valgrind's callgrind: the
// machine-independent companion of bench_structures' timings. On models of 3-12
// faces a query takes ~15 ns, and where the compiler placed a loop moves those
// timings by several per cent; an instruction count is the same on every run.
//   build/bin/count_structures MODEL STRUCTURE QUERY [REPEATS]
// runs query QUERY (0-8: V→V V→E V→F E→V E→E E→F F→V F→E F→F) of STRUCTURE
// (cellforge | radial_edge) from every element of MODEL (cube | cube_with_hole |
// sphere64 | two_cubes_edge | book) REPEATS times (default: about 100,000 queries
// in all), inside measured_queries(), and prints the number of queries and answer
// elements.
// scripts/count_queries.sh runs it under callgrind for every combination and
// prints instructions per query.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cellforge/compare/models.h"
#include "cellforge/compare/radial_edge.h"
#include "cellforge/topo/queries.h"

namespace cellforge::compare {
namespace {

struct Elements {
  std::vector<VertexId> vertices;
  std::vector<EdgeId> edges;
  std::vector<FaceId> faces;
};

template <class Out, class Run, class In>
void repeat(const Run& run, const std::vector<In>& from, int repeats, std::size_t& queries,
            std::size_t& elements) {
  if (repeats <= 0) repeats = std::max(1, 100000 / static_cast<int>(from.size()));
  std::vector<Out> out;
  for (int i = 0; i < repeats; ++i) {
    for (In x : from) {
      run(x, out);
      elements += out.size();
    }
  }
  queries += from.size() * static_cast<std::size_t>(repeats);
}

// Query q of a structure whose queries `run(x, out)` answers.
template <class Run>
[[gnu::noinline]] void measured_queries(const Run& run, const Elements& s, int q, int repeats,
                                        std::size_t& queries, std::size_t& elements) {
  switch (q) {
    case 0: return repeat<VertexId>(run, s.vertices, repeats, queries, elements);
    case 1: return repeat<EdgeId>(run, s.vertices, repeats, queries, elements);
    case 2: return repeat<FaceId>(run, s.vertices, repeats, queries, elements);
    case 3: return repeat<VertexId>(run, s.edges, repeats, queries, elements);
    case 4: return repeat<EdgeId>(run, s.edges, repeats, queries, elements);
    case 5: return repeat<FaceId>(run, s.edges, repeats, queries, elements);
    case 6: return repeat<VertexId>(run, s.faces, repeats, queries, elements);
    case 7: return repeat<EdgeId>(run, s.faces, repeats, queries, elements);
    default: return repeat<FaceId>(run, s.faces, repeats, queries, elements);
  }
}

int run(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: count_structures MODEL STRUCTURE QUERY [REPEATS]\n");
    return 2;
  }
  const std::string name = argv[1], structure = argv[2];
  const int q = std::atoi(argv[3]);
  const int repeats = argc > 4 ? std::atoi(argv[4]) : 0;  // 0: about 100,000 queries
  MeshInput input;
  if (name == "cube") input = cube_model();
  else if (name == "cube_with_hole") input = cube_with_hole_model();
  else if (name == "sphere64") input = sphere_model(64);
  else if (name == "two_cubes_edge") input = two_cubes_edge_model();
  else if (name == "book") input = book_model();
  else {
    std::fprintf(stderr, "count_structures: unknown model '%s'\n", name.c_str());
    return 2;
  }
  Model m;
  if (auto built = build_mesh(m, input); !built) {
    std::fprintf(stderr, "count_structures: %s\n", built.error().message.c_str());
    return 1;
  }
  Elements s;
  for (VertexId v : m.vertices()) s.vertices.push_back(v);
  for (EdgeId e : m.edges()) s.edges.push_back(e);
  for (FaceId f : m.faces()) s.faces.push_back(f);
  std::size_t queries = 0, elements = 0;
  if (structure == "cellforge") {
    auto cf = [&m](auto x, auto& out) {
      using Out = typename std::decay_t<decltype(out)>::value_type;
      if constexpr (std::is_same_v<Out, VertexId>) vertices_of(m, x, out);
      else if constexpr (std::is_same_v<Out, EdgeId>) edges_of(m, x, out);
      else faces_of(m, x, out);
    };
    measured_queries(cf, s, q, repeats, queries, elements);
  } else if (structure == "radial_edge") {
    const RadialEdge r = RadialEdge::from_model(m);
    auto re = [&r](auto x, auto& out) {
      using Out = typename std::decay_t<decltype(out)>::value_type;
      if constexpr (std::is_same_v<Out, VertexId>) r.vertices_of(x, out);
      else if constexpr (std::is_same_v<Out, EdgeId>) r.edges_of(x, out);
      else r.faces_of(x, out);
    };
    measured_queries(re, s, q, repeats, queries, elements);
  } else {
    std::fprintf(stderr, "count_structures: unknown structure '%s'\n", structure.c_str());
    return 2;
  }
  std::printf("queries %zu elements %zu\n", queries, elements);
  return 0;
}

}  // namespace
}  // namespace cellforge::compare

int main(int argc, char** argv) { return cellforge::compare::run(argc, argv); }
