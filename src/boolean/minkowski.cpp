// The Minkowski sum of solids (minkowski.h): hulls of vertex sums for convex cells,
// the boundary-triangle decomposition otherwise, one exact Boolean union at the end.
#include "cellforge/boolean/minkowski.h"

#include <algorithm>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "cellforge/boolean/boolean.h"
#include "cellforge/geom/plane.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/shape/hull.h"
#include "cellforge/topo/builder.h"

namespace cellforge::boolean {

namespace {

Error invalid(std::string message) { return Error{ErrorCode::kInvalidInput, std::move(message)}; }

bool bounds(const Model& m, FaceId f, VolumeId c) {
  return m.front_volume(f) == c || m.back_volume(f) == c;
}

std::vector<Vec3> cell_vertices(const Model& m, VolumeId c) {
  std::unordered_set<std::uint32_t> seen;
  std::vector<Vec3> out;
  for (FaceId f : m.faces()) {
    if (!bounds(m, f, c)) continue;
    for (LoopId l : m.loops_of(f))
      for (VertexId v : m.loop_vertices(l))
        if (seen.insert(v.value).second) out.push_back(m.position(v));
  }
  return out;
}

struct Cell {
  std::vector<Vec3> vertices;
  bool convex = false;
};

std::vector<Cell> cells_of(const Model& m) {
  std::vector<Cell> cells;
  for (VolumeId c : m.volumes()) cells.push_back({cell_vertices(m, c), is_convex_cell(m, c)});
  return cells;
}

bool all_convex(const std::vector<Cell>& cells) {
  for (const Cell& c : cells)
    if (!c.convex) return false;
  return true;
}

// The model's faces and cells again, every position moved by t.
Status add_translated(Model& into, const Model& m, Vec3 t) {
  MeshInput mesh;
  mesh.group_name = "minkowski";
  std::unordered_map<std::uint32_t, std::uint32_t> vid, cid;
  auto cell = [&](VolumeId c) {
    if (!c.is_valid()) return -1;
    auto [it, fresh] = cid.try_emplace(c.value, static_cast<std::uint32_t>(cid.size()));
    return static_cast<int>(it->second);
  };
  for (FaceId f : m.faces()) {
    MeshFace mf;
    mf.front = cell(m.front_volume(f));
    mf.back = cell(m.back_volume(f));
    if (mf.front < 0 && mf.back < 0) continue;
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) continue;
      std::vector<std::uint32_t> loop;
      for (VertexId v : m.loop_vertices(l)) {
        auto [it, fresh] = vid.try_emplace(v.value, static_cast<std::uint32_t>(mesh.positions.size()));
        if (fresh) mesh.positions.push_back(m.position(v) + t);
        loop.push_back(it->second);
      }
      mf.loops.push_back(std::move(loop));
    }
    mesh.faces.push_back(std::move(mf));
  }
  mesh.volumes = static_cast<int>(cid.size());
  auto built = build_mesh(into, mesh);
  if (!built) return built.error();
  return Status::Ok();
}

Status add_hull(Model& into, std::span<const Vec3> a, std::span<const Vec3> b) {
  std::vector<Vec3> sums;
  sums.reserve(a.size() * b.size());
  for (Vec3 p : a)
    for (Vec3 q : b) sums.push_back(p + q);
  auto h = shape::convex_hull(into, sums);
  if (!h) return Error{h.error().code, "minkowski: " + h.error().message};
  return Status::Ok();
}

// The points of face f when it is one exactly planar convex polygon (every corner
// turns the same way or not at all), else nothing.
std::vector<Vec3> convex_face(const Model& m, FaceId f) {
  if (m.inner_loop_count(f) != 0) return {};
  const std::vector<Vec3> p = m.loop_points(m.outer_loop(f));
  const std::size_t n = p.size();
  std::size_t k = 0;  // a corner that spans the plane
  while (k < n && collinear3d(p[k], p[(k + 1) % n], p[(k + 2) % n])) ++k;
  if (k == n) return {};
  const Vec3 a = p[k], b = p[(k + 1) % n], c = p[(k + 2) % n];
  for (const Vec3& q : p)
    if (orient3d(a, b, c, q) != 0) return {};
  const int axis = Plane::through(a, b, c).dominant_axis();
  int turn = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int t = orient2d_projected(p[i], p[(i + 1) % n], p[(i + 2) % n], axis);
    if (t != 0 && turn != 0 && t != turn) return {};
    if (t != 0) turn = t;
  }
  return p;
}

Result<Model> united(const Model& pieces) {
  const Model* ms[] = {&pieces};
  auto r = evaluate(ms, Expr::of(0));
  if (!r) return r.error();
  return std::move(r->model);
}

// A + B, where `a` and `b` name the operands in messages.
Result<Model> sum_pair(const Model& a, const Model& b, const std::string& a_name,
                       const std::string& b_name) {
  const std::vector<Cell> ca = cells_of(a), cb = cells_of(b);
  Model pieces;
  if (all_convex(ca) && all_convex(cb)) {
    for (const Cell& x : ca)
      for (const Cell& y : cb)
        if (Status s = add_hull(pieces, x.vertices, y.vertices); !s) return s.error();
    if (ca.size() * cb.size() == 1) return pieces;
    return united(pieces);
  }
  if (!all_convex(ca) && !all_convex(cb))
    return Error{ErrorCode::kUnsupported,
                 "minkowski: neither " + a_name + " nor " + b_name +
                     " is a union of convex cells (the sum of two non-convex solids needs a "
                     "convex decomposition, which is not built)"};
  const bool swap = !all_convex(cb);
  const Model& big = swap ? b : a;  // summed triangle by triangle
  const std::vector<Cell>& convex = swap ? ca : cb;
  std::vector<std::vector<Vec3>> parts;  // of the boundary, each convex
  for (FaceId f : big.faces()) {
    if (!big.front_volume(f).is_valid() && !big.back_volume(f).is_valid()) continue;
    if (std::vector<Vec3> p = convex_face(big, f); !p.empty()) {
      parts.push_back(std::move(p));
      continue;
    }
    for (const auto& t : io::triangulate_face(big, f)) {
      const Vec3 p[3] = {big.position(t[0]), big.position(t[1]), big.position(t[2])};
      if (!collinear3d(p[0], p[1], p[2])) parts.push_back({p[0], p[1], p[2]});
    }
  }
  for (const Cell& y : convex) {
    if (Status s = add_translated(pieces, big, y.vertices[0]); !s) return s.error();
    for (const auto& t : parts)
      if (Status s = add_hull(pieces, t, y.vertices); !s) return s.error();
  }
  return united(pieces);
}

}  // namespace

bool is_convex_cell(const Model& m, VolumeId c) {
  std::vector<VertexId> vs;
  {
    std::unordered_set<std::uint32_t> seen;
    for (FaceId f : m.faces())
      if (bounds(m, f, c))
        for (LoopId l : m.loops_of(f))
          for (VertexId v : m.loop_vertices(l))
            if (seen.insert(v.value).second) vs.push_back(v);
  }
  for (FaceId f : m.faces()) {
    if (!bounds(m, f, c)) continue;
    if (m.inner_loop_count(f) != 0) return false;
    std::vector<VertexId> loop = m.loop_vertices(m.outer_loop(f));
    if (m.front_volume(f) == c) std::reverse(loop.begin(), loop.end());  // c behind
    const std::unordered_set<std::uint32_t> own = [&] {
      std::unordered_set<std::uint32_t> o;
      for (VertexId v : loop) o.insert(v.value);
      return o;
    }();
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3 a = m.position(loop[(i + n - 1) % n]), b = m.position(loop[i]),
                 d = m.position(loop[(i + 1) % n]);
      if (collinear3d(a, b, d)) continue;
      for (VertexId v : vs)
        if (!own.count(v.value) && orient3d(a, b, d, m.position(v)) > 0) return false;
    }
  }
  return true;
}

Result<Model> minkowski(std::span<const Model* const> operands) {
  if (operands.empty()) return invalid("minkowski: no operands");
  for (std::size_t i = 0; i < operands.size(); ++i)
    if (operands[i]->num_volumes() == 0)
      return invalid("minkowski: operand " + std::to_string(i) + " holds no solid (no cell)");
  if (operands.size() == 1) return united(*operands[0]);
  Result<Model> acc = sum_pair(*operands[0], *operands[1], "operand 0", "operand 1");
  for (std::size_t i = 2; i < operands.size() && acc; ++i)
    acc = sum_pair(*acc, *operands[i], "the sum of operands 0.." + std::to_string(i - 1),
                   "operand " + std::to_string(i));
  return acc;
}

}  // namespace cellforge::boolean
