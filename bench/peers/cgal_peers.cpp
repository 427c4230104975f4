// The CGAL peers of bench_boolean (peers.h): corefinement on Surface_mesh and
// Nef_polyhedron_3, each evaluating the benchmark's expression tree as left folds of
// binary operations (CGAL has no n-ary Boolean).
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/convert_nef_polyhedron_to_polygon_mesh.h>
#include <CGAL/version.h>

#include <chrono>
#include <exception>
#include <optional>

#include "peers.h"

namespace cellforge::bench {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Kind = boolean::Expr::Kind;

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

// The operand as a CGAL surface mesh; nullopt when CGAL will not take a triangle (an
// edge used twice in one direction, i.e. not an oriented 2-manifold).
template <class Point>
std::optional<CGAL::Surface_mesh<Point>> surface_mesh(const TriMesh& t) {
  using Mesh = CGAL::Surface_mesh<Point>;
  Mesh m;
  m.reserve(t.num_vertices(), 3 * t.num_triangles() / 2, t.num_triangles());
  std::vector<typename Mesh::Vertex_index> v(t.num_vertices());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = m.add_vertex(Point(t.xyz[3 * i], t.xyz[3 * i + 1], t.xyz[3 * i + 2]));
  for (std::size_t i = 0; i < t.num_triangles(); ++i)
    if (m.add_face(v[t.tris[3 * i]], v[t.tris[3 * i + 1]], v[t.tris[3 * i + 2]]) == Mesh::null_face())
      return std::nullopt;
  return m;
}

// --- corefinement ---

using CorefMesh = CGAL::Surface_mesh<Epick::Point_3>;

struct Refusal {
  std::string message;
};

CorefMesh coref_eval(const std::vector<TriMesh>& operands, const boolean::Expr& e) {
  if (e.kind == Kind::kOperand) {
    auto m = surface_mesh<Epick::Point_3>(operands[e.operand]);
    if (!m) throw Refusal{"operand " + std::to_string(e.operand) + " is not an oriented 2-manifold"};
    return std::move(*m);
  }
  CorefMesh acc = coref_eval(operands, e.children[0]);
  for (std::size_t i = 1; i < e.children.size(); ++i) {
    CorefMesh b = coref_eval(operands, e.children[i]);
    CorefMesh out;
    bool ok = false;
    if (e.kind == Kind::kUnion) ok = PMP::corefine_and_compute_union(acc, b, out);
    if (e.kind == Kind::kIntersection) ok = PMP::corefine_and_compute_intersection(acc, b, out);
    if (e.kind == Kind::kDifference) ok = PMP::corefine_and_compute_difference(acc, b, out);
    if (!ok)
      throw Refusal{"step " + std::to_string(i) + " of " + std::to_string(e.children.size() - 1) +
                    ": the output would not be manifold"};
    acc = std::move(out);
  }
  return acc;
}

// --- Nef polyhedra ---

using Nef = CGAL::Nef_polyhedron_3<Epeck>;

Nef nef_eval(const std::vector<TriMesh>& operands, const boolean::Expr& e) {
  if (e.kind == Kind::kOperand) {
    auto m = surface_mesh<Epeck::Point_3>(operands[e.operand]);
    if (!m) throw Refusal{"operand " + std::to_string(e.operand) + " is not an oriented 2-manifold"};
    return Nef(*m);
  }
  Nef acc = nef_eval(operands, e.children[0]);
  for (std::size_t i = 1; i < e.children.size(); ++i) {
    const Nef b = nef_eval(operands, e.children[i]);
    if (e.kind == Kind::kUnion) acc += b;
    if (e.kind == Kind::kIntersection) acc *= b;
    if (e.kind == Kind::kDifference) acc -= b;
  }
  return acc;
}

template <class Mesh>
void describe(const Mesh& m, PeerRun& r) {
  r.out_vertices = m.number_of_vertices();
  r.out_triangles = m.number_of_faces();
  for (auto f : faces(m)) r.degenerate_faces += PMP::is_degenerate_triangle_face(f, m) ? 1 : 0;
  if (CGAL::is_closed(m) && m.number_of_faces() > 0) r.volume = CGAL::to_double(PMP::volume(m));
}

template <class Fn>
PeerRun guarded(Fn fn) {
  PeerRun r;
  try {
    fn(r);
  } catch (const Refusal& e) {
    r.status = PeerRun::Status::kRefused;
    r.message = e.message;
  } catch (const std::exception& e) {
    r.status = PeerRun::Status::kError;
    r.message = e.what();
  }
  return r;
}

}  // namespace

const char* cgal_version() { return CGAL_VERSION_STR; }

PeerRun run_cgal_corefinement(const std::vector<TriMesh>& operands, const boolean::Expr& expr,
                              bool check_output) {
  return guarded([&](PeerRun& r) {
    const double t0 = now();
    const CorefMesh out = coref_eval(operands, expr);
    r.seconds = now() - t0;
    describe(out, r);
    if (check_output) r.self_intersecting = PMP::does_self_intersect(out) ? 1 : 0;
  });
}

PeerRun run_cgal_nef(const std::vector<TriMesh>& operands, const boolean::Expr& expr) {
  return guarded([&](PeerRun& r) {
    const double t0 = now();
    const Nef result = nef_eval(operands, expr);
    CGAL::Surface_mesh<Epeck::Point_3> out;
    CGAL::convert_nef_polyhedron_to_polygon_mesh(result, out, true);
    r.seconds = now() - t0;
    describe(out, r);
  });
}

}  // namespace cellforge::bench
