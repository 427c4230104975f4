// nef_compare.h: cellforge's Boolean results against CGAL's Nef_polyhedron_3.
#include "nef/nef_compare.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Nef_polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <unordered_map>

#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/geom/winding.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/topo/validate.h"

namespace cellforge::testing::nef {
namespace {

using Kernel = CGAL::Exact_predicates_exact_constructions_kernel;
using Nef = CGAL::Nef_polyhedron_3<Kernel>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Kind = boolean::Expr::Kind;
using Tri = std::array<VertexId, 3>;

Point point(Vec3 p) { return Point(p.x, p.y, p.z); }

// ---- operands as Nef polyhedra

// The triangles of the faces of m with a cell on one side only, the cell behind
// (counterclockwise seen from outside the cell).
std::vector<Tri> bounding_triangles(const Model& m) {
  std::vector<Tri> out;
  for (FaceId f : m.faces()) {
    const bool front = m.front_volume(f).is_valid(), back = m.back_volume(f).is_valid();
    if (front == back) continue;
    for (Tri t : io::triangulate_face(m, f)) {
      if (front) std::swap(t[1], t[2]);
      out.push_back(t);
    }
  }
  return out;
}

// The closed shell made of `tris` as a Nef solid (reversed: the shell turned inside
// out first, for a cavity). Fails the test when CGAL will not take a triangle.
Nef shell_solid(const Model& m, const std::vector<Tri>& tris, bool reversed) {
  Mesh mesh;
  std::unordered_map<std::uint32_t, Mesh::Vertex_index> index;
  const auto vertex = [&](VertexId v) {
    auto [it, fresh] = index.try_emplace(v.value);
    if (fresh) it->second = mesh.add_vertex(point(m.position(v)));
    return it->second;
  };
  for (const Tri& t : tris) {
    const auto a = vertex(t[0]), b = vertex(reversed ? t[2] : t[1]),
               c = vertex(reversed ? t[1] : t[2]);
    if (mesh.add_face(a, b, c) == Mesh::null_face()) {
      ADD_FAILURE() << "Surface_mesh refused a triangle of an operand shell at "
                    << m.position(t[0]);
      return Nef();
    }
  }
  return Nef(mesh);
}

// The operand: the union of its positive shells minus the interiors of its negative
// ones (nef_compare.h, top). Shells are the vertex-connected pieces of its bounding
// triangles; the sign of a shell's volume is exact (sum of a . (b x c) in Kernel::FT).
Nef operand_nef(const Model& m) {
  const std::vector<Tri> tris = bounding_triangles(m);
  std::uint32_t slots = 0;
  for (VertexId v : m.vertices()) slots = std::max(slots, v.value + 1);
  UnionFind sets(slots);
  for (const Tri& t : tris) {
    sets.unite(t[0].value, t[1].value);
    sets.unite(t[0].value, t[2].value);
  }
  std::unordered_map<std::uint32_t, std::vector<Tri>> shells;
  for (const Tri& t : tris) shells[sets.find(t[0].value)].push_back(t);
  Nef solids, cavities;
  for (const auto& [root, shell] : shells) {
    Kernel::FT volume = 0;
    for (const Tri& t : shell) {
      const Kernel::Vector_3 a = point(m.position(t[0])) - CGAL::ORIGIN;
      const Kernel::Vector_3 b = point(m.position(t[1])) - CGAL::ORIGIN;
      const Kernel::Vector_3 c = point(m.position(t[2])) - CGAL::ORIGIN;
      volume += CGAL::scalar_product(a, CGAL::cross_product(b, c));
    }
    const CGAL::Sign s = CGAL::sign(volume);
    EXPECT_NE(s, CGAL::ZERO) << "an operand shell of zero volume";
    if (s == CGAL::POSITIVE) solids += shell_solid(m, shell, false);
    if (s == CGAL::NEGATIVE) cavities += shell_solid(m, shell, true);
  }
  // The operand is closed: its cavities' boundaries belong to it.
  return cavities.is_empty() ? solids : solids - cavities.interior();
}

// The expression on Nef polyhedra, as left folds (Nef's operations are binary).
Nef evaluate_nef(const std::vector<Nef>& operands, const boolean::Expr& e) {
  if (e.kind == Kind::kOperand) return operands[e.operand];
  Nef acc = evaluate_nef(operands, e.children[0]);
  for (std::size_t i = 1; i < e.children.size(); ++i) {
    const Nef b = evaluate_nef(operands, e.children[i]);
    if (e.kind == Kind::kUnion) acc += b;
    if (e.kind == Kind::kIntersection) acc *= b;
    if (e.kind == Kind::kDifference) acc -= b;
  }
  return acc;
}

// num / den exactly.
Point exact_point(std::array<double, 3> num, double den) {
  const Kernel::FT d(den);
  return Point(Kernel::FT(num[0]) / d, Kernel::FT(num[1]) / d, Kernel::FT(num[2]) / d);
}

Where nef_where(const Nef& n, const Point& p) {
  const auto o = n.locate(p);
  Nef::Vertex_const_handle v;
  Nef::Halfedge_const_handle e;
  Nef::Halffacet_const_handle f;
  Nef::Volume_const_handle c;
  if (CGAL::assign(v, o)) return {0, v->mark()};
  if (CGAL::assign(e, o)) return {1, e->mark()};
  if (CGAL::assign(f, o)) return {2, f->mark()};
  if (CGAL::assign(c, o)) return {3, c->mark()};
  ADD_FAILURE() << "Nef located nothing at " << p;
  return {};
}

Where nef_where(const Nef& n, Vec3 p) { return nef_where(n, point(p)); }

// Whether the set of e holds p, from the operands' memberships at p alone: the set
// operations are pointwise, so this is what a non-regularized result must answer.
bool pointwise_in(const std::vector<Nef>& operands, const boolean::Expr& e, const Point& p) {
  std::vector<bool> inside;
  for (const Nef& n : operands) inside.push_back(nef_where(n, p).in);
  return e.contains(inside);
}

// Nef's lower-dimensional parts, read from the marks of its sphere maps: at a vertex,
// svertices are the edges there, sedges the facets and sfaces the volumes.
LowerDim nef_lower_dim(const Nef& n) {
  LowerDim out;
  std::size_t sheet_halves = 0, wire_halves = 0;
  for (auto f = n.halffacets_begin(); f != n.halffacets_end(); ++f) {
    sheet_halves +=
        f->mark() && !f->incident_volume()->mark() && !f->twin()->incident_volume()->mark();
  }
  for (auto e = n.halfedges_begin(); e != n.halfedges_end(); ++e) {
    if (!e->mark()) continue;
    bool alone = !e->is_isolated() || !e->incident_sface()->mark();
    const auto v = e->source();
    for (auto s = v->shalfedges_begin(); alone && s != v->shalfedges_end(); ++s) {
      if (s->source() == Nef::SVertex_const_handle(e))
        alone = !s->mark() && !s->incident_sface()->mark();
    }
    wire_halves += alone;
  }
  for (auto v = n.vertices_begin(); v != n.vertices_end(); ++v) {
    bool alone = v->mark() && !(v->has_shalfloop() && v->shalfloop()->mark());
    for (auto s = v->svertices_begin(); alone && s != v->svertices_end(); ++s) alone = !s->mark();
    for (auto s = v->shalfedges_begin(); alone && s != v->shalfedges_end(); ++s) alone = !s->mark();
    for (auto s = v->sfaces_begin(); alone && s != v->sfaces_end(); ++s) alone = !s->mark();
    out.points += alone;
  }
  out.sheets = sheet_halves / 2;
  out.wires = wire_halves / 2;
  return out;
}

// The vertices of n whose coordinates are doubles exactly (the others have no double
// to sample them at).
std::vector<Vec3> nef_vertices(const Nef& n) {
  std::vector<Vec3> out;
  for (auto v = n.vertices_begin(); v != n.vertices_end(); ++v) {
    const Point& q = v->point();
    const Vec3 p{CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())};
    if (point(p) == q) out.push_back(p);
  }
  return out;
}

// ---- the cellforge result, located exactly

bool marked(const std::vector<bool>& marks, std::uint32_t id) {
  return marks.empty() || (id < marks.size() && marks[id]);
}

struct Box {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  bool holds(Vec3 p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
  // Widened by far more than the few ulps rounding moves a vertex (rounding.cpp).
  Box widened() const {
    const double m = 0x1p-30 * (1 + std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z),
                                              std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)}));
    return {{lo.x - m, lo.y - m, lo.z - m}, {hi.x + m, hi.y + m, hi.z + m}};
  }
};

class ResultLocator {
 public:
  explicit ResultLocator(const boolean::BooleanResult& r) : r_(r) {
    const Model& m = r.model;
    std::uint32_t slots = 0;
    for (VertexId v : m.vertices()) slots = std::max(slots, v.value + 1);
    points_.assign(slots, Vec3{});
    for (VertexId v : m.vertices()) points_[v.value] = m.position(v);
    for (const Tri& t : bounding_triangles(m))
      bounding_.push_back({t[0].value, t[1].value, t[2].value});
    for (FaceId f : m.faces()) {
      FaceTris ft{f, {}, {}};
      for (const Tri& t : io::triangulate_face(m, f)) {
        const std::array<Vec3, 3> p = {m.position(t[0]), m.position(t[1]), m.position(t[2])};
        for (const Vec3& q : p) ft.box.add(q);
        if (!collinear3d(p[0], p[1], p[2])) ft.tris.push_back(p);
      }
      faces_.push_back(std::move(ft));
    }
    const auto moved = [&](VertexId v) { return v.value < r.rounded.size() && r.rounded[v.value]; };
    for (FaceId f : m.faces()) {
      Box b;
      bool any = false;
      m.for_each_face_vertex(f, [&](VertexId v) {
        b.add(m.position(v));
        any |= moved(v);
      });
      if (any) unsure_.push_back(b.widened());
    }
    for (VertexId v : m.vertices()) {
      if (!moved(v)) continue;
      Box b;  // an isolated point's own, the others' within their edges'
      b.add(m.position(v));
      unsure_.push_back(b.widened());
    }
    for (EdgeId e : m.edges()) {
      if (!moved(m.start_of(e)) && !moved(m.end_of(e))) continue;
      Box b;
      b.add(m.position(m.start_of(e)));
      b.add(m.position(m.end_of(e)));
      unsure_.push_back(b.widened());
    }
  }

  // Whether rounding may have moved an element across p (nef_compare.h, top).
  bool unsure(Vec3 p) const {
    return std::any_of(unsure_.begin(), unsure_.end(), [&](const Box& b) { return b.holds(p); });
  }

  Where where(Vec3 p) const {
    const Model& m = r_.model;
    for (VertexId v : m.vertices()) {
      if (m.position(v) == p) return {0, marked(r_.vertex_in, v.value)};
    }
    for (EdgeId e : m.edges()) {
      const Vec3 a = m.position(m.start_of(e)), b = m.position(m.end_of(e));
      Box box;
      box.add(a);
      box.add(b);
      if (box.holds(p) && collinear3d(a, b, p)) return {1, marked(r_.edge_in, e.value)};
    }
    for (const FaceTris& ft : faces_) {
      if (!ft.box.holds(p)) continue;
      for (const auto& t : ft.tris) {
        if (point_on_triangle(t[0], t[1], t[2], p)) return {2, marked(r_.face_in, ft.face.value)};
      }
    }
    return {3, winding_number(points_, bounding_, p).number > 0};
  }

 private:
  struct FaceTris {
    FaceId face;
    std::vector<std::array<Vec3, 3>> tris;  // without the zero-area ones
    Box box;
  };
  const boolean::BooleanResult& r_;
  std::vector<Vec3> points_;  // by vertex id value
  std::vector<std::array<std::uint32_t, 3>> bounding_;
  std::vector<FaceTris> faces_;
  std::vector<Box> unsure_;
};

// cellforge's lower-dimensional parts (LowerDim): kept faces with no cell on either
// side, kept edges whose faces are all such or not kept, kept vertices with nothing
// kept around them.
LowerDim cellforge_lower_dim(const boolean::BooleanResult& r) {
  const Model& m = r.model;
  const auto bare = [&](FaceId f) {
    return !m.front_volume(f).is_valid() && !m.back_volume(f).is_valid();
  };
  const auto face_in = [&](FaceId f) { return marked(r.face_in, f.value); };
  const auto edge_in = [&](EdgeId e) { return marked(r.edge_in, e.value); };
  const auto edge_alone = [&](EdgeId e) {
    for (EdgeUseId u : m.radial(e)) {
      const FaceId f = m.face_of(u);
      if (face_in(f) || !bare(f)) return false;
    }
    return true;
  };
  LowerDim out;
  for (FaceId f : m.faces()) out.sheets += face_in(f) && bare(f);
  for (EdgeId e : m.edges()) out.wires += edge_in(e) && edge_alone(e);
  for (VertexId v : m.vertices()) {
    bool alone = marked(r.vertex_in, v.value);
    for (EdgeEnd end : m.ends_around(v))
      alone = alone && !edge_in(end.edge) && edge_alone(end.edge);
    const LoopId l = m.point_loop(v);
    if (l.is_valid()) alone = alone && !face_in(m.face_of(l)) && bare(m.face_of(l));
    out.points += alone;
  }
  return out;
}

// ---- sampled points

void add_model_points(const Model& m, std::vector<Vec3>& out) {
  for (VertexId v : m.vertices()) out.push_back(m.position(v));
  for (EdgeId e : m.edges())
    out.push_back((m.position(m.start_of(e)) + m.position(m.end_of(e))) * 0.5);
  for (FaceId f : m.faces()) {
    const std::vector<Vec3> loop = m.loop_points(m.outer_loop(f));
    Vec3 sum{};
    for (const Vec3& p : loop) sum = sum + p;
    out.push_back(sum * (1.0 / static_cast<double>(loop.size())));
    // A point inside the face near a corner: a third of the way from the corner to
    // the centroid of its neighbours, which lies in the face for convex corners.
    if (loop.size() >= 3)
      out.push_back((loop[0] * 4.0 + loop[1] + loop[loop.size() - 1] * 3.0) * 0.125);
  }
}

std::vector<Vec3> sample_points(const Case& c, const boolean::BooleanResult& r, const Nef& n) {
  std::vector<Vec3> pts = nef_vertices(n);
  Box box;
  for (const Model* m : c.operands) {
    add_model_points(*m, pts);
    for (VertexId v : m->vertices()) box.add(m->position(v));
  }
  add_model_points(r.model, pts);
  const Vec3 size = box.hi - box.lo;
  const double step = c.grid_step > 0 ? c.grid_step : std::max({size.x, size.y, size.z}) / 8;
  std::mt19937_64 rng(c.seed);
  const auto count = [&](double extent) { return static_cast<int>(std::ceil(extent / step)) + 2; };
  std::uniform_int_distribution<int> ix(-1, count(size.x)), iy(-1, count(size.y)),
      iz(-1, count(size.z));
  for (std::size_t i = 0; i < c.grid_points; ++i) {
    pts.push_back(
        {box.lo.x + step * ix(rng), box.lo.y + step * iy(rng), box.lo.z + step * iz(rng)});
  }
  std::sort(pts.begin(), pts.end(), [](Vec3 a, Vec3 b) {
    return a.x != b.x ? a.x < b.x : (a.y != b.y ? a.y < b.y : a.z < b.z);
  });
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
  return pts;
}

std::string where_text(Where w) {
  static const char* const kDims[] = {"a vertex", "an edge", "a face", "a volume"};
  return std::string(w.in ? "in, on " : "out, on ") + kDims[w.dim];
}

bool agree(const Case& c, Where a, Where b) {
  // Regularized sets are closed, and their boundary is what lies on an element.
  return a.in == b.in && (!c.regularized || c.cells || (a.dim < 3) == (b.dim < 3));
}

// The deepest subexpression of e whose results disagree at p, both answers told (or
// "" when they agree there, or when rounding leaves p unsure): the smallest part of a
// failing case to look at.
std::string deepest_disagreement(const Case& c, const boolean::Expr& e,
                                 const std::vector<Nef>& operands, Vec3 p,
                                 const boolean::Options& options) {
  for (const boolean::Expr& child : e.children) {
    std::string s = deepest_disagreement(c, child, operands, p, options);
    if (!s.empty()) return s;
  }
  auto r = boolean::evaluate(c.operands, e, options);
  if (!r.ok()) return describe(e) + ": cellforge fails: " + r.error().message;
  const ResultLocator mine(r.value());
  if (mine.unsure(p)) return "";
  Nef n = evaluate_nef(operands, e);
  if (c.regularized) n = n.regularization();
  const Where a = mine.where(p), b = nef_where(n, p);
  if (agree(c, a, b)) return "";
  std::string s = describe(e) + ": cellforge " + where_text(a) + "; Nef " + where_text(b);
  if (!validate(r.value().model).empty()) s += " (cellforge's result does not validate)";
  if (!n.is_valid()) s += " (Nef's result is not valid)";
  if (e.kind != Kind::kDifference && e.children.size() > 1) {
    // Union and intersection commute: Nef's answer folding the other way round.
    boolean::Expr reversed = e;
    std::reverse(reversed.children.begin(), reversed.children.end());
    Nef m = evaluate_nef(operands, reversed);
    if (c.regularized) m = m.regularization();
    s += "; Nef folding the other way: " + where_text(nef_where(m, p));
  }
  return s;
}

}  // namespace

std::ostream& operator<<(std::ostream& os, const LowerDim& d) {
  return os << d.sheets << " sheets, " << d.wires << " wires, " << d.points << " points";
}

std::string describe(const boolean::Expr& e) {
  if (e.kind == Kind::kOperand) return "#" + std::to_string(e.operand);
  const char* op = e.kind == Kind::kUnion ? " u " : (e.kind == Kind::kIntersection ? " n " : " - ");
  std::string s = "(";
  for (std::size_t i = 0; i < e.children.size(); ++i) s += (i ? op : "") + describe(e.children[i]);
  return s + ")";
}

Where cellforge_where(const Case& c, Vec3 p) {
  boolean::Options options;
  options.keep_lower_dim = !c.regularized;
  options.cells = c.cells;
  auto r = boolean::evaluate(c.operands, c.expr, options);
  EXPECT_TRUE(r.ok()) << c.name << ": " << (r.ok() ? "" : r.error().message);
  if (!r.ok()) return {};
  return ResultLocator(r.value()).where(p);
}

Where nef_result_where(const Case& c, Vec3 p) { return nef_result_where(c, {p.x, p.y, p.z}, 1); }

bool nef_operands_hold(const Case& c, Vec3 p) { return nef_operands_hold(c, {p.x, p.y, p.z}, 1); }

Where nef_result_where(const Case& c, std::array<double, 3> num, double den) {
  std::vector<Nef> operands;
  for (const Model* m : c.operands) operands.push_back(operand_nef(*m));
  Nef n = evaluate_nef(operands, c.expr);
  if (c.regularized) n = n.regularization();
  return nef_where(n, exact_point(num, den));
}

bool nef_operands_hold(const Case& c, std::array<double, 3> num, double den) {
  std::vector<Nef> operands;
  for (const Model* m : c.operands) operands.push_back(operand_nef(*m));
  return pointwise_in(operands, c.expr, exact_point(num, den));
}

Outcome compare(const Case& c) {
  Outcome out;
  boolean::Options options;
  options.keep_lower_dim = !c.regularized;
  options.cells = c.cells;
  auto r = boolean::evaluate(c.operands, c.expr, options);
  const std::string title = c.name + ": " + describe(c.expr) +
                            (c.regularized ? "" : " (not regularized)") +
                            (c.cells ? " (cells)" : "");
  EXPECT_TRUE(r.ok()) << title << ": " << (r.ok() ? "" : r.error().message);
  if (!r.ok()) return out;
  const boolean::BooleanResult& res = r.value();
  const auto violations = validate(res.model);
  EXPECT_TRUE(violations.empty()) << title << ": " << to_string(violations);
  out.rounded_vertices =
      static_cast<std::size_t>(std::count(res.rounded.begin(), res.rounded.end(), true));

  std::vector<Nef> operands;
  for (const Model* m : c.operands) operands.push_back(operand_nef(*m));
  Nef nef = evaluate_nef(operands, c.nef_expr ? *c.nef_expr : c.expr);
  if (c.regularized) nef = nef.regularization();

  const ResultLocator mine(res);
  std::ostringstream first;
  for (const Vec3& p : sample_points(c, res, nef)) {
    if (mine.unsure(p)) {
      ++out.skipped;
      continue;
    }
    ++out.compared;
    const Where a = mine.where(p), b = nef_where(nef, p);
    ++out.nef_dims[b.dim];
    if (agree(c, a, b)) continue;
    first.precision(17);
    if (!c.regularized && !c.nef_expr && a.in != b.in &&
        pointwise_in(operands, c.expr, point(p)) == a.in) {
      // Nef's result contradicts its own operands there (nef_compare.h, Outcome).
      if (out.nef_errors++ == 0) {
        std::ostringstream at;
        at.precision(17);
        at << "(" << p.x << ", " << p.y << ", " << p.z << ")";
        out.first_nef_error = at.str();
      }
      continue;
    }
    if (out.disagreements == 0 && c.expr.kind != Kind::kOperand) {
      first << "\n  first where (" << p.x << ", " << p.y << ", " << p.z
            << ") has different answers: " << deepest_disagreement(c, c.expr, operands, p, options);
    }
    if (out.disagreements++ < 5) {
      first << "\n  at (" << p.x << ", " << p.y << ", " << p.z << "): cellforge " << where_text(a)
            << "; Nef " << where_text(b);
    }
  }
  out.cellforge = cellforge_lower_dim(res);
  out.nef = nef_lower_dim(nef);
  out.first_disagreement = first.str();
  if (c.regularized) {
    EXPECT_EQ(out.nef, LowerDim{}) << title << ": Nef";
    EXPECT_EQ(out.cellforge, LowerDim{}) << title << ": cellforge";
  } else {
    EXPECT_EQ(out.cellforge.points, out.nef.points) << title << ": isolated points";
    EXPECT_EQ(out.cellforge.sheets > 0, out.nef.sheets > 0)
        << title << ": " << out.cellforge << " against " << out.nef;
    EXPECT_EQ(out.cellforge.wires > 0, out.nef.wires > 0)
        << title << ": " << out.cellforge << " against " << out.nef;
  }
  if (out.nef_errors > 0) {
    std::printf("%s: Nef's result contradicts its operands at %zu points, first at %s\n",
                title.c_str(), out.nef_errors, out.first_nef_error.c_str());
  }
  EXPECT_EQ(out.disagreements, 0u)
      << title << " (" << out.compared << " points compared)" << out.first_disagreement;
  return out;
}

}  // namespace cellforge::testing::nef
