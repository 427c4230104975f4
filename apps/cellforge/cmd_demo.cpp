// `cellforge demo`: builds the bundled Euler-operator examples, validates each and
// prints its counts, its Euler-Poincare figures and the 9 adjacency queries for
// one vertex, one edge and one face.
#include <functional>
#include <iostream>
#include <sstream>

#include "cellforge/topo/examples.h"
#include "cellforge/topo/queries.h"
#include "cellforge/topo/validate.h"
#include "command.h"

namespace cellforge::cli {
namespace {

template <class T>
std::string list(const std::vector<T>& ids) {
  std::ostringstream os;
  os << '{';
  for (std::size_t i = 0; i < ids.size(); ++i) os << (i ? " " : "") << ids[i];
  os << '}';
  return os.str();
}

void report(std::ostream& os, const std::string& title, const Model& m, VertexId v, EdgeId e,
            FaceId f) {
  os << "== " << title << '\n';
  os << "  counts: vertices " << m.num_vertices() << ", edges " << m.num_edges() << ", faces "
     << m.num_faces() << ", loops " << m.num_loops() << ", volumes " << m.num_volumes()
     << ", groups " << m.num_groups() << '\n';
  const auto violations = validate(m);
  os << "  valid: " << (violations.empty() ? "yes" : "NO") << '\n';
  for (const Violation& x : violations) os << "    [" << x.check << "] " << x.message << '\n';
  const EulerFigures fig = euler_figures(m);
  os << "  Euler-Poincare (seed 001): v - e + (f - r) - (V - Vh + Vc) = " << fig.v << " - " << fig.e
     << " + (" << fig.f << " - " << fig.r << ") - (" << fig.volumes << " - " << fig.volume_holes
     << " + " << fig.volume_cavities << ") = " << fig.lhs() << '\n'
     << "                              C - Ch + Cc = " << fig.components << " - " << fig.holes
     << " + " << fig.cavities << " = " << fig.rhs()
     << (fig.unchecked ? "  (right side not checked on non-manifold components)" : "") << '\n';
  os << "  shells " << fig.shells << "; manifold formula v - e + f = 2(s - h) + r: " << fig.v
     << " - " << fig.e << " + " << fig.f << " = " << fig.v - fig.e + fig.f << '\n';
  os << "  queries at " << v << " " << m.position(v) << ", " << e << " (" << m.start_of(e) << "-"
     << m.end_of(e) << "), " << f << ":\n";
  os << "    V->V " << list(query<VertexId>(m, v)) << "  V->E " << list(query<EdgeId>(m, v))
     << "  V->F " << list(query<FaceId>(m, v)) << '\n';
  os << "    E->V " << list(query<VertexId>(m, e)) << "  E->E " << list(query<EdgeId>(m, e))
     << "  E->F " << list(query<FaceId>(m, e)) << '\n';
  os << "    F->V " << list(query<VertexId>(m, f)) << "  F->E " << list(query<EdgeId>(m, f))
     << "  F->F " << list(query<FaceId>(m, f)) << '\n';
}

// The vertex at p, the edge at it with the most uses and a face on that edge.
std::tuple<VertexId, EdgeId, FaceId> pick(const Model& m, Vec3 p) {
  VertexId v;
  for (VertexId x : m.vertices()) {
    if (m.position(x) == p) v = x;
  }
  EdgeId e;
  for (EdgeId x : query<EdgeId>(m, v)) {
    if (!e.is_valid() || m.use_count(x) > m.use_count(e)) e = x;
  }
  return {v, e, m.face_of(m.first_use(e))};
}

constexpr const char* kUsage =
    "usage: cellforge demo\n"
    "  Builds a cube, a cube with a through hole and a non-manifold group with the Euler\n"
    "  operators, validates each and prints counts, Euler-Poincare figures and the 9\n"
    "  adjacency queries for one vertex, edge and face.";

int run(const std::vector<std::string>& args) {
  CLI::App app{"build, validate and query the bundled Euler-operator examples", "cellforge demo"};
  app.footer(kUsage);
  if (auto code = parse(app, args)) return *code;
  int invalid = 0;
  struct Example {
    const char* title;
    std::function<Status(Model&)> make;
    Vec3 at;
  };
  const Example examples[] = {
      {"cube [0,1]^3 (mvsf, mev, mef, make_volume)",
       [](Model& m) {
         auto g = euler_box(m, {0, 0, 0}, {1, 1, 1}, true, "cube");
         return g ? Status::Ok() : Status(g.error());
       },
       {0, 0, 0}},
      {"cube [0,3]^3 with a through hole [1,2]^2 (mev, kemr, mef, kfmrh, mekr)",
       [](Model& m) {
         auto g = euler_box_with_hole(m, {0, 0, 0}, {3, 3, 3}, 1, 2, "cube-with-hole");
         return g ? Status::Ok() : Status(g.error());
       },
       {1, 1, 3}},
      {"non-manifold group: two cubes sharing an edge, a wire edge, an isolated vertex",
       [](Model& m) {
         auto g = euler_nonmanifold_example(m, "nonmanifold");
         return g ? Status::Ok() : Status(g.error());
       },
       {1, 1, 1}},
  };
  for (const Example& x : examples) {
    Model m;
    if (Status s = x.make(m); !s) {
      std::cerr << "cellforge demo: " << x.title << ": " << s.error().message << '\n';
      return 1;
    }
    const auto [v, e, f] = pick(m, x.at);
    report(std::cout, x.title, m, v, e, f);
    invalid += validate(m).empty() ? 0 : 1;
  }
  return invalid == 0 ? 0 : 1;
}

const CommandRegistration registration(
    {"demo", "build, validate and query the bundled Euler-operator examples", kUsage, run, true});

}  // namespace
}  // namespace cellforge::cli
