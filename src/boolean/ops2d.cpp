// 2D operations (ops2d.h). The Booleans, offset, the 2D Minkowski sum and the shadow
// projection run on the planar arrangement of planar.cpp. The section projection
// (cut) intersects the solid with a slab in 3D and reads the result's faces on z = 0
// back; lifted_boolean (planar.h) evaluates 2D Booleans that way too — shapes lifted
// to prisms over z in [0, 1], the 3D expression evaluated, z = 0 read back — as the
// oracle the tests and the benchmark compare the planar route with.
//
// Reading back: the faces on z = 0 point down (-z), so their loops reversed run with
// the result's interior on the left seen from +z. Faces of one region may come apart
// (the Boolean leaves a face whose boundary would pass a vertex twice unmerged), so
// the loops are not taken face by face: their directed edges are pooled, an edge met
// in both directions (between two faces of the result) cancels, the rest are walked
// into closed chains, and a chain that passes a vertex twice is cut there into simple
// loops. Counterclockwise loops are outer boundaries; each clockwise loop is a hole of
// the smallest outer loop that contains it. Containment is exact: a hole vertex off
// the outer loop is tested by its winding number; a hole vertex on it by the side of
// the outer loop the hole's next edge leaves into (orient2d against the outer loop's
// edges there).
#include "cellforge/boolean/ops2d.h"

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <numbers>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/shape/hull.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/topo/builder.h"
#include "boolean/planar.h"

namespace cellforge::boolean {

using shape::Region;
using shape::Shape2D;

namespace {

Error invalid(std::string message) { return Error{ErrorCode::kInvalidInput, std::move(message)}; }

// ---------------------------------------------------------------- lifting

// Appends the prism over each loop set (loops[0] outer, the rest holes; oriented here:
// outer counterclockwise, holes clockwise) between z = 0 and z = height as cell `cell`.
void add_prism(MeshInput& mesh, const std::vector<std::vector<Vec2>>& loops, int cell,
               double height = 1) {
  MeshFace bottom, top;
  bottom.back = top.back = cell;
  std::vector<MeshFace> walls;
  for (std::size_t li = 0; li < loops.size(); ++li) {
    std::vector<Vec2> loop = loops[li];
    const int want = li == 0 ? 1 : -1;
    if (area_sign(loop) == -want) std::reverse(loop.begin(), loop.end());
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    const auto n = static_cast<std::uint32_t>(loop.size());
    for (Vec2 p : loop) mesh.positions.push_back({p.x, p.y, 0});
    for (Vec2 p : loop) mesh.positions.push_back({p.x, p.y, height});
    std::vector<std::uint32_t> b, t;
    for (std::uint32_t i = 0; i < n; ++i) {
      b.push_back(base + (n - 1 - i));  // reversed: the bottom points down
      t.push_back(base + n + i);
      MeshFace w;
      w.back = cell;
      const std::uint32_t j = (i + 1) % n;
      w.loops = {{base + i, base + j, base + n + j, base + n + i}};
      walls.push_back(std::move(w));
    }
    bottom.loops.push_back(std::move(b));
    top.loops.push_back(std::move(t));
  }
  mesh.faces.push_back(std::move(bottom));
  mesh.faces.push_back(std::move(top));
  for (MeshFace& w : walls) mesh.faces.push_back(std::move(w));
  mesh.volumes = std::max(mesh.volumes, cell + 1);
}

Status check_region(const Region& r, const std::string& where) {
  if (r.loops.empty()) return invalid(where + " has no loops");
  for (std::size_t li = 0; li < r.loops.size(); ++li) {
    const auto& loop = r.loops[li];
    const std::string name = where + (li == 0 ? " outer loop" : " hole " + std::to_string(li - 1));
    if (loop.size() < 3) return invalid(name + " has " + std::to_string(loop.size()) + " vertices");
    for (std::size_t i = 0; i < loop.size(); ++i) {
      if (!std::isfinite(loop[i].x) || !std::isfinite(loop[i].y))
        return invalid(name + " vertex " + std::to_string(i) + " is not finite");
      if (loop[i] == loop[(i + 1) % loop.size()])
        return invalid(name + " repeats vertex " + std::to_string(i) + " at once");
    }
    if (area_sign(loop) == 0) return invalid(name + " has zero area");
  }
  return Status::Ok();
}

// Every region of `pieces` as one cell of one model (their union, as a Boolean operand).
Result<Model> lift(std::span<const Region> pieces, const std::string& what) {
  MeshInput mesh;
  mesh.group_name = what;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    if (Status s = check_region(pieces[i], what + " region " + std::to_string(i)); !s)
      return s.error();
    add_prism(mesh, pieces[i].loops, static_cast<int>(i));
  }
  Model m;
  auto built = build_mesh(m, mesh);
  if (!built) return Error{built.error().code, what + ": " + built.error().message};
  return m;
}

// ---------------------------------------------------------------- reading back

struct Loop2 {
  std::vector<std::uint32_t> v;  // vertex ids of the result model
  std::vector<Vec2> p;
  Vec2 lo, hi;  // bounding box
  double area = 0;
};

Loop2 make_loop(const Model& m, std::vector<std::uint32_t> ids) {
  Loop2 l;
  l.v = std::move(ids);
  for (std::uint32_t id : l.v) {
    const Vec3 q = m.position(VertexId(id));
    l.p.push_back({q.x, q.y});
  }
  l.lo = l.hi = l.p[0];
  for (Vec2 q : l.p) {
    l.lo = {std::min(l.lo.x, q.x), std::min(l.lo.y, q.y)};
    l.hi = {std::max(l.hi.x, q.x), std::max(l.hi.y, q.y)};
  }
  l.area = signed_area2(l.p) / 2;
  return l;
}

bool box_inside(const Loop2& inner, const Loop2& outer) {
  return inner.lo.x >= outer.lo.x && inner.lo.y >= outer.lo.y && inner.hi.x <= outer.hi.x &&
         inner.hi.y <= outer.hi.y;
}

// Whether direction a -> b leaves the point a into the interior of `o` (on the left of
// o's edges), given that a lies on o; nullopt when b runs along o's boundary there.
std::optional<bool> leaves_into(const Loop2& o, Vec2 a, std::uint32_t a_id, Vec2 b) {
  const std::size_t n = o.p.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 p = o.p[(i + n - 1) % n], q = o.p[i], r = o.p[(i + 1) % n];
    if (o.v[i] == a_id) {  // a is vertex q of o: the interior is the wedge from r to p
      const int to_r = orient2d(q, r, b), to_p = orient2d(q, p, b);
      if ((to_r == 0 && dot_sign({q.x, q.y, 0}, {r.x, r.y, 0}, {q.x, q.y, 0}, {b.x, b.y, 0}) > 0) ||
          (to_p == 0 && dot_sign({q.x, q.y, 0}, {p.x, p.y, 0}, {q.x, q.y, 0}, {b.x, b.y, 0}) > 0))
        return std::nullopt;
      if (orient2d(q, r, p) > 0) return to_r > 0 && to_p < 0;  // convex corner
      return to_r > 0 || to_p < 0;
    }
    if (o.v[i] != a_id && o.v[(i + 1) % n] != a_id && point_on_segment(q, r, a)) {
      const int s = orient2d(q, r, b);
      if (s == 0) return std::nullopt;
      return s > 0;
    }
  }
  return std::nullopt;
}

bool on_loop(const Loop2& o, Vec2 a, std::uint32_t a_id) {
  const std::size_t n = o.p.size();
  for (std::size_t i = 0; i < n; ++i)
    if (o.v[i] == a_id || point_on_segment(o.p[i], o.p[(i + 1) % n], a)) return true;
  return false;
}

// Hole h (clockwise) lies inside outer loop o (counterclockwise); the two loops do
// not cross (they come from one arrangement).
bool contains(const Loop2& o, const Loop2& h) {
  if (!box_inside(h, o)) return false;
  const std::size_t n = h.p.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!on_loop(o, h.p[i], h.v[i])) return winding_number(o.p, h.p[i]) != 0;
  for (std::size_t i = 0; i < n; ++i)
    if (auto in = leaves_into(o, h.p[i], h.v[i], h.p[(i + 1) % n])) return *in;
  return false;
}

// The regions bounded by the faces on z = 0 of a Boolean result over lifted prisms.
// The faces read are those on z = 0: all of whose points have z == 0, or, given the
// Boolean's face sources, those whose source plane (three input points) lies in
// z = 0 — a face made where a slanted edge crosses the plane has vertices whose z is
// rounded (about 1e-15) although the exact face lies in the plane.
Shape2D read_plane(const Model& m, const std::vector<FaceSource>* sources = nullptr) {
  // Vertices by position: rounding may bring two exact points onto one double, and
  // the boundary then passes that point twice (it is cut there below).
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> by_hash;
  std::unordered_map<std::uint32_t, std::uint32_t> canon;
  auto canonical = [&](VertexId v) {
    auto [it, fresh] = canon.try_emplace(v.value, v.value);
    if (!fresh) return it->second;
    const Vec3 p = m.position(v);
    const double x = p.x + 0.0, y = p.y + 0.0;  // -0 and 0 are one point
    std::uint64_t hx, hy;
    std::memcpy(&hx, &x, sizeof hx);
    std::memcpy(&hy, &y, sizeof hy);
    auto& same = by_hash[hx * 0x9E3779B97F4A7C15ull ^ hy];
    for (std::uint32_t o : same) {
      const Vec3 q = m.position(VertexId(o));
      if (q.x == p.x && q.y == p.y) return it->second = o;
    }
    same.push_back(v.value);
    return v.value;
  };
  // Directed edges (seen from +z), with opposite pairs cancelled.
  std::unordered_map<std::uint64_t, int> count;
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t{a} << 32) | b; };
  for (FaceId f : m.faces()) {
    bool flat = true;
    if (sources) {
      flat = f.value < sources->size();
      for (int k = 0; flat && k < 3; ++k) flat = (*sources)[f.value].plane[k].z == 0;
    } else {
      for (const Vec3& q : m.loop_points(m.outer_loop(f))) flat &= q.z == 0;
    }
    if (!flat) continue;
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) continue;
      const std::vector<VertexId> vs = m.loop_vertices(l);
      for (std::size_t i = 0; i < vs.size(); ++i) {
        const std::uint32_t a = canonical(vs[(i + 1) % vs.size()]),
                            b = canonical(vs[i]);  // reversed
        if (a == b) continue;                      // an edge rounding made zero length
        if (auto it = count.find(key(b, a)); it != count.end() && it->second > 0) {
          if (--it->second == 0) count.erase(it);
        } else {
          ++count[key(a, b)];
        }
      }
    }
  }
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> out;  // start -> ends
  std::vector<std::uint64_t> keys;
  for (const auto& [k, c] : count)
    for (int i = 0; i < c; ++i) keys.push_back(k);
  std::sort(keys.begin(), keys.end());  // a walk that does not depend on hashing
  for (std::uint64_t k : keys) out[static_cast<std::uint32_t>(k >> 32)].push_back(k & 0xffffffffu);
  // Walk closed chains; cut each at repeated vertices into simple loops.
  std::vector<Loop2> loops;
  for (std::uint64_t k : keys) {
    const std::uint32_t start = static_cast<std::uint32_t>(k >> 32);
    if (out[start].empty()) continue;
    std::vector<std::uint32_t> chain{start};
    std::unordered_map<std::uint32_t, std::size_t> at{{start, 0}};
    std::uint32_t v = start;
    do {
      auto& ends = out[v];
      if (ends.empty()) break;  // not closed: cannot happen for a closed result
      const std::uint32_t w = ends.back();
      ends.pop_back();
      if (w != start) {
        if (auto it = at.find(w); it != at.end()) {  // a simple loop closes at w
          const std::size_t from = it->second;  // before the erase below frees *it
          std::vector<std::uint32_t> cut(chain.begin() + static_cast<std::ptrdiff_t>(from),
                                         chain.end());
          for (std::uint32_t c : cut) at.erase(c);
          chain.resize(from);
          loops.push_back(make_loop(m, std::move(cut)));
        }
        at[w] = chain.size();
        chain.push_back(w);
      }
      v = w;
    } while (v != start);
    if (v == start) loops.push_back(make_loop(m, std::move(chain)));
  }
  // Outer loops, largest first; each hole joins the last (smallest) one containing it.
  std::vector<const Loop2*> outers, holes;
  for (const Loop2& l : loops) {
    const int sign = l.p.size() >= 3 ? area_sign(l.p) : 0;
    if (sign != 0) (sign > 0 ? outers : holes).push_back(&l);
  }
  std::stable_sort(outers.begin(), outers.end(),
                   [](const Loop2* a, const Loop2* b) { return a->area > b->area; });
  Shape2D s;
  for (const Loop2* o : outers) s.regions.push_back(Region{{o->p}});
  for (const Loop2* h : holes) {
    for (std::size_t i = outers.size(); i-- > 0;) {
      if (contains(*outers[i], *h)) {
        s.regions[i].loops.push_back(h->p);
        break;
      }
    }
  }
  return s;
}

// ---------------------------------------------------------------- expressions

// `e` with empty operands replaced by the empty set and the rest renumbered into
// `used`; nullopt when the whole expression is empty.
std::optional<Expr> without_empties(const Expr& e, const std::vector<bool>& empty,
                                    std::vector<int>& used) {
  switch (e.kind) {
    case Expr::Kind::kOperand: {
      if (empty[static_cast<std::size_t>(e.operand)]) return std::nullopt;
      auto it = std::find(used.begin(), used.end(), e.operand);
      if (it == used.end()) it = used.insert(used.end(), e.operand);
      return Expr::of(static_cast<int>(it - used.begin()));
    }
    case Expr::Kind::kUnion: {
      std::vector<Expr> kids;
      for (const Expr& c : e.children)
        if (auto k = without_empties(c, empty, used)) kids.push_back(std::move(*k));
      if (kids.empty()) return std::nullopt;
      if (kids.size() == 1) return kids[0];
      return Expr::op(Op::kUnion, std::move(kids));
    }
    case Expr::Kind::kIntersection: {
      std::vector<Expr> kids;
      for (const Expr& c : e.children) {
        auto k = without_empties(c, empty, used);
        if (!k) return std::nullopt;
        kids.push_back(std::move(*k));
      }
      if (kids.empty()) return std::nullopt;
      if (kids.size() == 1) return kids[0];
      return Expr::op(Op::kIntersection, std::move(kids));
    }
    case Expr::Kind::kDifference: {
      if (e.children.empty()) return std::nullopt;
      auto first = without_empties(e.children[0], empty, used);
      if (!first) return std::nullopt;
      std::vector<Expr> kids{std::move(*first)};
      for (std::size_t i = 1; i < e.children.size(); ++i)
        if (auto k = without_empties(e.children[i], empty, used)) kids.push_back(std::move(*k));
      if (kids.size() == 1) return kids[0];
      return Expr::op(Op::kDifference, std::move(kids));
    }
  }
  return std::nullopt;
}

// The Boolean of lifted models, read back on z = 0.
Result<Evaluated2D> evaluate_counted(std::span<const Model* const> models, const Expr& e) {
  auto r = evaluate(models, e);
  if (!r) return r.error();
  return Evaluated2D{read_plane(r->model), r->report.rounding_self_intersections};
}

// Every region of `shape` normalized: the union of its regions, disjoint.
Result<Shape2D> normalized(std::vector<Region> regions) {
  if (regions.empty()) return Shape2D{};
  const Shape2D one[] = {Shape2D{std::move(regions)}};
  auto r = planar_boolean(one, Expr::of(0));
  if (!r) return r.error();
  return std::move(r->shape);
}

}  // namespace

Result<Evaluated2D> evaluate_2d_counted(std::span<const Shape2D> operands, const Expr& expr) {
  if (expr.max_operand() >= static_cast<int>(operands.size()))
    return invalid("2D Boolean: the expression names operand " +
                   std::to_string(expr.max_operand()) + " of " + std::to_string(operands.size()));
  std::vector<bool> empty;
  for (const Shape2D& s : operands) empty.push_back(s.empty());
  std::vector<int> used;
  const std::optional<Expr> e = without_empties(expr, empty, used);
  if (!e) return Evaluated2D{};
  if (e->kind == Expr::Kind::kOperand)
    return Evaluated2D{operands[static_cast<std::size_t>(used[0])], 0};
  std::vector<Shape2D> kept;
  for (int i : used) kept.push_back(operands[static_cast<std::size_t>(i)]);
  auto r = planar_boolean(kept, *e);
  if (!r) {  // name the operand as the caller numbered it
    std::string m = r.error().message;
    const std::string tag = "2D operand ";
    if (m.rfind(tag, 0) == 0) {
      const std::size_t end = m.find(' ', tag.size());
      const int k = std::atoi(m.substr(tag.size(), end - tag.size()).c_str());
      m = tag + std::to_string(used[static_cast<std::size_t>(k)]) + m.substr(end);
    }
    return Error{r.error().code, m};
  }
  return r;
}

Result<Evaluated2D> lifted_boolean(std::span<const Shape2D> operands, const Expr& expr) {
  if (expr.max_operand() >= static_cast<int>(operands.size()))
    return invalid("2D Boolean: the expression names operand " +
                   std::to_string(expr.max_operand()) + " of " + std::to_string(operands.size()));
  std::vector<bool> empty;
  for (const Shape2D& s : operands) empty.push_back(s.empty());
  std::vector<int> used;
  const std::optional<Expr> e = without_empties(expr, empty, used);
  if (!e) return Evaluated2D{};
  if (e->kind == Expr::Kind::kOperand)
    return Evaluated2D{operands[static_cast<std::size_t>(used[0])], 0};
  std::vector<Model> models;
  for (int i : used) {
    auto m = lift(operands[static_cast<std::size_t>(i)].regions, "2D operand " + std::to_string(i));
    if (!m) return m.error();
    models.push_back(std::move(*m));
  }
  std::vector<const Model*> ptrs;
  for (const Model& m : models) ptrs.push_back(&m);
  return evaluate_counted(ptrs, *e);
}

Result<Shape2D> evaluate_2d(std::span<const Shape2D> operands, const Expr& expr) {
  auto r = evaluate_2d_counted(operands, expr);
  if (!r) return r.error();
  return std::move(r->shape);
}

Result<Shape2D> apply_2d(Op op, std::span<const Shape2D> operands) {
  if (operands.empty()) return Shape2D{};
  return evaluate_2d(operands, Expr::over(op, static_cast<int>(operands.size())));
}

// ---------------------------------------------------------------- offset

namespace {

Vec2 add(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
Vec2 scaled(Vec2 a, double s) { return {a.x * s, a.y * s}; }
double cross2(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
double dot2(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }

// The unit normal on the right of a -> b (outward: interiors lie on the left).
Vec2 right_normal(Vec2 a, Vec2 b) {
  const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
  return {dy / len, -dx / len};
}

// A convex piece as a region (counterclockwise), or nothing when it has no area.
void add_piece(std::vector<Region>& pieces, std::vector<Vec2> loop) {
  loop.erase(std::unique(loop.begin(), loop.end()), loop.end());
  while (loop.size() > 1 && loop.front() == loop.back()) loop.pop_back();
  if (loop.size() < 3) return;
  const int s = area_sign(loop);
  if (s == 0) return;
  if (s < 0) std::reverse(loop.begin(), loop.end());
  pieces.push_back(Region{{std::move(loop)}});
}

// The join at vertex v between the edge before it (normal nk) and the edge after it
// (normal nj), on the side the offset moves to, as Clipper makes it (clipper.cpp,
// ClipperOffset::DoRound / DoMiter / DoSquare).
std::vector<Vec2> join_piece(Vec2 v, Vec2 nk, Vec2 nj, double delta, const OffsetOptions& o,
                             int fragments) {
  const double sin_a = cross2(nk, nj), cos_a = dot2(nk, nj);
  const Vec2 first = add(v, scaled(nk, delta)), last = add(v, scaled(nj, delta));
  std::vector<Vec2> loop{v, first};
  switch (o.join) {
    case OffsetJoin::kRound: {
      const double a = std::atan2(sin_a, cos_a);
      const int steps = std::max(
          static_cast<int>(std::lround(fragments / (2 * std::numbers::pi) * std::fabs(a))), 1);
      const double step = (a >= 0 ? 1 : -1) * 2 * std::numbers::pi / fragments;
      for (int i = 1; i < steps; ++i) {
        const double c = std::cos(i * step), s = std::sin(i * step);
        loop.push_back(add(v, scaled({nk.x * c - nk.y * s, nk.x * s + nk.y * c}, delta)));
      }
      break;
    }
    case OffsetJoin::kMiter: {
      const double r = 1 + cos_a;
      constexpr double kMiterLimit = 1e6;  // OpenSCAD's offset(delta) miter limit
      if (r >= 2 / (kMiterLimit * kMiterLimit)) {
        loop.push_back(add(v, scaled(add(nk, nj), delta / r)));
        break;
      }
      [[fallthrough]];  // a spike beyond the limit is squared off, as Clipper does
    }
    case OffsetJoin::kChamfer: {
      const double dx = std::tan(std::atan2(sin_a, cos_a) / 4);
      loop.push_back(add(v, scaled({nk.x - nk.y * dx, nk.y + nk.x * dx}, delta)));
      loop.push_back(add(v, scaled({nj.x + nj.y * dx, nj.y - nj.x * dx}, delta)));
      break;
    }
  }
  loop.push_back(last);
  return loop;
}

// The strips and joins of every loop of a normalized shape.
std::vector<Region> offset_pieces(const Shape2D& shape, const OffsetOptions& o) {
  const double delta = o.amount;
  const int fragments = shape::fragments(std::fabs(delta), o.faceting);
  const int side = delta > 0 ? 1 : -1;
  std::vector<Region> pieces;
  for (const Region& r : shape.regions) {
    for (const auto& loop : r.loops) {
      const std::size_t n = loop.size();
      std::vector<Vec2> normal(n);  // of edge i -> i + 1
      for (std::size_t i = 0; i < n; ++i) normal[i] = right_normal(loop[i], loop[(i + 1) % n]);
      for (std::size_t i = 0; i < n; ++i) {
        const Vec2 a = loop[i], b = loop[(i + 1) % n];
        add_piece(pieces,
                  {a, b, add(b, scaled(normal[i], delta)), add(a, scaled(normal[i], delta))});
        const Vec2 c = loop[(i + 2) % n];
        const int turn = orient2d(a, b, c);
        const Vec2 nk = normal[i], nj = normal[(i + 1) % n];
        if (turn == side) {
          add_piece(pieces, join_piece(b, nk, nj, delta, o, fragments));
        } else if (turn == 0) {  // the two strips' ends may differ by rounding
          add_piece(pieces, {b, add(b, scaled(nk, delta)), add(b, scaled(nj, delta))});
        }
      }
    }
  }
  return pieces;
}

}  // namespace

Result<Shape2D> offset(const Shape2D& shape, const OffsetOptions& options) {
  if (!std::isfinite(options.amount))
    return invalid("offset: the amount is " + shape::format_number(options.amount) +
                   " (must be finite)");
  if (options.amount == 0 || shape.empty()) return shape;
  Shape2D base = shape;
  if (shape.regions.size() > 1) {
    auto n = normalized(shape.regions);
    if (!n) return n.error();
    base = std::move(*n);
  }
  for (Region& r : base.regions)  // interiors on the left of every loop
    for (std::size_t li = 0; li < r.loops.size(); ++li)
      if (area_sign(r.loops[li]) == (li == 0 ? -1 : 1))
        std::reverse(r.loops[li].begin(), r.loops[li].end());
  const std::vector<Region> pieces = offset_pieces(base, options);
  const Shape2D both[] = {std::move(base), Shape2D{pieces}};
  auto r =
      planar_boolean(both, Expr::over(options.amount > 0 ? Op::kUnion : Op::kDifference, 2));
  if (!r) return r.error();
  return std::move(r->shape);
}

// ---------------------------------------------------------------- minkowski

namespace {

bool is_convex(const Shape2D& s) {
  if (s.regions.size() != 1 || s.regions[0].loops.size() != 1) return false;
  const auto& l = s.regions[0].loops[0];
  const std::size_t n = l.size();
  for (std::size_t i = 0; i < n; ++i)
    if (orient2d(l[i], l[(i + 1) % n], l[(i + 2) % n]) < 0) return false;
  return area_sign(l) > 0;
}

Result<Region> hull_of_sums(std::span<const Vec2> a, std::span<const Vec2> b) {
  std::vector<Vec2> sums;
  sums.reserve(a.size() * b.size());
  for (Vec2 p : a)
    for (Vec2 q : b) sums.push_back(add(p, q));
  return shape::convex_hull(sums);
}

Shape2D translated(const Shape2D& s, Vec2 t) {
  Shape2D out = s;
  for (Region& r : out.regions)
    for (auto& loop : r.loops)
      for (Vec2& p : loop) p = add(p, t);
  return out;
}

// Pieces whose union is A + B for convex B: A + b0 and the hull of e + B for every
// boundary edge e of A.
Status add_sum_with_convex(std::vector<Region>& pieces, const Shape2D& a, std::span<const Vec2> b) {
  for (const Region& r : translated(a, b[0]).regions) pieces.push_back(r);
  for (const Region& r : a.regions) {
    for (const auto& loop : r.loops) {
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const Vec2 e[2] = {loop[i], loop[(i + 1) % loop.size()]};
        auto h = hull_of_sums(e, b);
        if (!h) return h.error();
        pieces.push_back(std::move(*h));
      }
    }
  }
  return Status::Ok();
}

Result<Shape2D> minkowski_pair(const Shape2D& a, const Shape2D& b) {
  const bool ca = is_convex(a), cb = is_convex(b);
  if (ca && cb) {
    auto h = hull_of_sums(a.regions[0].loops[0], b.regions[0].loops[0]);
    if (!h) return h.error();
    return shape::shape_of(std::move(*h));
  }
  const Shape2D& big = cb ? a : b;  // the operand summed edge by edge
  const Shape2D& convex = cb ? b : a;
  std::vector<Region> pieces;
  if (ca || cb) {
    if (Status s = add_sum_with_convex(pieces, big, convex.regions[0].loops[0]); !s)
      return s.error();
  } else {
    for (const Region& r : b.regions) {  // B as triangles, each convex
      std::vector<std::vector<Vec3>> loops3;
      for (const auto& loop : r.loops) {
        std::vector<Vec3> l3;
        for (Vec2 p : loop) l3.push_back({p.x, p.y, 0});
        loops3.push_back(std::move(l3));
      }
      std::vector<Vec2> flat;
      for (const auto& loop : r.loops) flat.insert(flat.end(), loop.begin(), loop.end());
      for (const auto& t : io::triangulate_polygon(loops3, {0, 0, 1})) {
        const Vec2 tri[3] = {flat[t[0]], flat[t[1]], flat[t[2]]};
        if (orient2d(tri[0], tri[1], tri[2]) == 0) continue;
        if (Status s = add_sum_with_convex(pieces, a, tri); !s) return s.error();
      }
    }
  }
  return normalized(std::move(pieces));
}

}  // namespace

Result<Shape2D> minkowski_2d(std::span<const Shape2D> operands) {
  if (operands.empty()) return Shape2D{};
  for (const Shape2D& s : operands)
    if (s.empty()) return Shape2D{};
  Shape2D acc = operands[0];
  if (operands.size() == 1) return acc;
  for (std::size_t i = 1; i < operands.size(); ++i) {
    auto next = minkowski_pair(acc, operands[i]);
    if (!next) return next.error();
    acc = std::move(*next);
  }
  return acc;
}

// ---------------------------------------------------------------- projection

Result<Shape2D> projection(const Model& solid, const ProjectionOptions& options) {
  if (solid.num_faces() == 0) return Shape2D{};
  if (options.cut) {
    Vec3 lo = solid.position(*solid.vertices().begin()), hi = lo;
    for (VertexId v : solid.vertices()) {
      const Vec3 p = solid.position(v);
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    if (hi.z <= 0 || lo.z > 0) return Shape2D{};
    // A box from z = 0 to above the solid, wider than it: the solid's part above z = 0.
    const Vec2 a{lo.x - 1, lo.y - 1}, b{hi.x + 1, hi.y + 1};
    MeshInput mesh;
    add_prism(mesh, {{a, {b.x, a.y}, b, {a.x, b.y}}}, 0, hi.z + 1);
    Model slab;
    if (auto built = build_mesh(slab, mesh); !built) return built.error();
    const Model* ms[] = {&solid, &slab};
    // Only the section is read, and the planar Boolean makes it a valid shape, exactly:
    // no rounding check of the 3D result. Read as it is, rounding may have left two
    // of its points a unit apart with their edges touching (example021.scad's
    // slanted sections), which no region may have.
    Options unchecked;
    unchecked.check_rounding = false;
    auto r = evaluate(ms, Expr::over(Op::kIntersection, 2), unchecked);
    if (!r) return r.error();
    return normalized(read_plane(r->model, &r->sources).regions);
  }
  return shadow(solid, false);
}

// The shadow: the union of the faces that look up (outward normal with z > 0), the
// points they cover at least once. With `by_faces` that union of every such face
// (the planar arrangement of all their edges); otherwise, as projection() does it,
// from their boundary alone. A point's cover count is the sum of the winding numbers
// of those faces' loops about it (each looks up: counterclockwise seen from above),
// and winding numbers add as chains do: an edge two of the faces share, run once each
// way, cancels. What is left, the edges of the faces with no neighbour among them
// (the silhouette and the rims of overhangs), winds about each point its cover count,
// and the shadow is where that is positive: the rule planar_boolean reads an operand
// by. A terrain of thousands of faces has a boundary of a few hundred edges.
Result<Shape2D> shadow(const Model& solid, bool by_faces) {
  std::vector<Region> faces;
  std::unordered_map<std::uint64_t, int> net;  // (lower id, higher id): uses lower -> higher minus the reverse
  std::unordered_map<std::uint32_t, Vec2> at;
  for (FaceId f : solid.faces()) {
    const bool front = solid.front_volume(f).is_valid(), back = solid.back_volume(f).is_valid();
    if (front == back) continue;
    Region r;
    std::vector<std::vector<VertexId>> ids;
    for (LoopId l : solid.loops_of(f)) {
      if (solid.is_point_loop(l)) continue;
      std::vector<VertexId> vs = solid.loop_vertices(l);
      if (front) std::reverse(vs.begin(), vs.end());
      std::vector<Vec2> loop;
      for (VertexId v : vs) loop.push_back({solid.position(v).x, solid.position(v).y});
      r.loops.push_back(std::move(loop));
      ids.push_back(std::move(vs));
    }
    // A face that is not vertical projects one to one (its edges stay edges).
    if (r.loops.empty() || area_sign(r.loops[0]) <= 0) continue;
    if (by_faces) {
      faces.push_back(std::move(r));
      continue;
    }
    for (const auto& vs : ids)
      for (std::size_t i = 0; i < vs.size(); ++i) {
        const std::uint32_t u = vs[i].value, v = vs[(i + 1) % vs.size()].value;
        if (u == v) continue;
        at.try_emplace(u, Vec2{solid.position(vs[i]).x, solid.position(vs[i]).y});
        net[(std::uint64_t{std::min(u, v)} << 32) | std::max(u, v)] += u < v ? 1 : -1;
      }
  }
  if (by_faces) return faces.empty() ? Shape2D{} : normalized(std::move(faces));
  // The remaining edges, each as often as it is left over, in cycles: from a vertex,
  // along any unused edge out of it, until a vertex of the walk comes again.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> out;
  std::vector<std::uint64_t> keys;
  for (const auto& [key, n] : net)
    if (n != 0) keys.push_back(key);
  std::sort(keys.begin(), keys.end());  // the same cycles from run to run
  for (std::uint64_t key : keys) {
    const int n = net[key];
    const auto lo = static_cast<std::uint32_t>(key >> 32), hi = static_cast<std::uint32_t>(key);
    for (int k = 0; k < std::abs(n); ++k) out[n > 0 ? lo : hi].push_back(n > 0 ? hi : lo);
  }
  std::vector<std::uint32_t> starts;
  for (const auto& [v, list] : out) starts.push_back(v);
  std::sort(starts.begin(), starts.end());
  Region holes;  // clockwise cycles, read as holes of a region whose outer loop has no area
  std::vector<Region> regions;
  std::vector<std::uint32_t> walk;
  std::unordered_map<std::uint32_t, std::size_t> on_walk;
  // A vertex has as many edges out as in (every face loop is closed), so a walk that
  // reaches a vertex with none left out has closed every cycle it opened.
  const auto emit = [&](std::vector<Vec2> loop) {
    if (loop.size() < 3) return;
    if (area_sign(loop) > 0) {
      regions.push_back(Region{{std::move(loop)}});
    } else {
      holes.loops.push_back(std::move(loop));
    }
  };
  for (const std::uint32_t start : starts) {
    while (!out[start].empty()) {
      walk.assign(1, start);
      on_walk.clear();
      on_walk[start] = 0;
      for (std::uint32_t x = start; !(walk.size() == 1 && out[start].empty());) {
        auto& next = out[x];
        if (next.empty())
          return Error{ErrorCode::kPrecondition, "projection: the boundary of the faces that look up is not closed"};
        const std::uint32_t y = next.back();
        next.pop_back();
        x = y;
        const auto it = on_walk.find(y);
        if (it == on_walk.end()) {
          on_walk[y] = walk.size();
          walk.push_back(y);
          continue;
        }
        // A cycle: the walk from y on; the walk up to y goes on from there.
        const std::size_t from = it->second;
        std::vector<Vec2> loop;
        for (std::size_t k = from; k < walk.size(); ++k) loop.push_back(at.at(walk[k]));
        for (std::size_t k = from + 1; k < walk.size(); ++k) on_walk.erase(walk[k]);
        walk.resize(from + 1);
        emit(std::move(loop));
      }
    }
  }
  if (regions.empty()) return Shape2D{};
  if (!holes.loops.empty()) {
    // Outer loop: a point and back, no area and no winding (planar.h).
    const Vec2 p = holes.loops[0][0], q = holes.loops[0][1];
    holes.loops.insert(holes.loops.begin(), std::vector<Vec2>{p, q, p});
    regions.push_back(std::move(holes));
  }
  return normalized(std::move(regions));
}

}  // namespace cellforge::boolean
