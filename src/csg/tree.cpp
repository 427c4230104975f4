// build(): the CSG tree to a Model. Each run of set operations, with the transforms
// and colors in it pushed down to its leaves, is one n-ary boolean::evaluate. Leaves
// are primitives, imports, sweeps and resize (a sweep or resize builds its own
// subtree first). 2D subtrees are kept as expressions over regions and evaluated by
// the planar 2D Booleans (boolean/ops2d.h) where a 2D shape is needed; a sweep of a
// set operation sweeps the evaluated profile's disjoint regions. When the sweep refuses
// such a region (one touching itself), a straight linear_extrude (no twist, equal x and
// y scale) of a 2D union, difference or intersection is that set operation of the
// extruded regions, exactly, and the same holds for rotate_extrude of a union when every
// region is turned with the same segments.
#include "cellforge/csg/tree.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "cache.h"
#include "cellforge/boolean/boolean.h"
#include "cellforge/boolean/minkowski.h"
#include "cellforge/boolean/ops2d.h"
#include "cellforge/csg/tree_json.h"
#include "cellforge/geom/bvh.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/geom/workers.h"
#include "cellforge/io/mesh_io.h"
#include "cellforge/shape/hull.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/region.h"
#include "cellforge/shape/resize.h"
#include "cellforge/shape/shape2d.h"
#include "cellforge/topo/builder.h"
#include "cellforge/topo/parts.h"
#include "fill.h"
#include "import2d.h"
#include "tree_private.h"

namespace cellforge::csg {

namespace {

constexpr const char* kNames[] = {
    "group",      "union",      "difference", "intersection",   "cube",           "sphere",
    "cylinder",   "polyhedron", "import",     "square",         "circle",         "polygon",
    "multmatrix", "resize",     "color",      "linear_extrude", "rotate_extrude", "hull",
    "minkowski",  "offset",     "projection"};

}  // namespace

const char* node_name(NodeKind k) { return kNames[static_cast<int>(k)]; }

std::optional<NodeKind> node_kind(const std::string& name) {
  for (int i = 0; i < static_cast<int>(std::size(kNames)); ++i) {
    if (name == kNames[i]) return static_cast<NodeKind>(i);
  }
  return std::nullopt;
}

Model copy_transformed(const Model& src, const shape::Transform& t) {
  Model out;
  copy_into(out, src, t);
  return out;
}

std::vector<FaceId> copy_into(Model& out, const Model& src, const shape::Transform& t) {
  std::vector<FaceId> faces(src.face_slots());
  const bool flip = t.determinant() < 0;
  // Not mirrored: the records copied as they are, the points moved, the property
  // tables carried (example020.scad's copies: 51 M instructions through the builder,
  // 24 M so). A mirror needs its loops reversed: the builder, below.
  if (!flip) {
    const bool still = is_identity(t);
    auto ids = append(out, src, [&](Vec3 p) { return still ? p : t.apply(p); });
    if (ids) return std::move(ids->faces);
  }
  // Source id -> index in the group's mesh, by slot (every part of a build is copied
  // at least once: maps by slot and the group index keep it linear).
  constexpr std::uint32_t kNone = UINT32_MAX;
  std::vector<std::uint32_t> vertex(src.vertex_slots(), kNone), volume;
  for (GroupId g : src.groups()) {
    MeshInput mesh;
    std::vector<FaceId> face_ids;
    mesh.group_name = src.name(g);
    mesh.positions.reserve(src.num_vertices(g));
    for (VertexId v : src.vertices(g)) {
      vertex[v.value] = static_cast<std::uint32_t>(mesh.positions.size());
      mesh.positions.push_back(t.apply(src.position(v)));
    }
    for (VolumeId c : src.volumes(g)) {
      if (volume.size() <= c.value) volume.resize(c.value + 1, kNone);
      volume[c.value] = static_cast<std::uint32_t>(mesh.volumes++);
    }
    mesh.faces.reserve(src.num_faces(g));
    face_ids.reserve(src.num_faces(g));
    for (FaceId f : src.faces(g)) {
      MeshFace face;
      for (LoopId l : src.loops_of(f)) {
        if (src.is_point_loop(l)) continue;
        face.loops.emplace_back();
        for (VertexId v : src.loop_vertices(l)) face.loops.back().push_back(vertex[v.value]);
        if (flip) std::reverse(face.loops.back().begin(), face.loops.back().end());
      }
      if (src.front_volume(f).is_valid()) face.front = static_cast<int>(volume[src.front_volume(f).value]);
      if (src.back_volume(f).is_valid()) face.back = static_cast<int>(volume[src.back_volume(f).value]);
      mesh.faces.push_back(std::move(face));
      face_ids.push_back(f);
    }
    for (EdgeId e : src.edges(g)) {
      if (src.is_wire(e)) mesh.wires.push_back({vertex[src.start_of(e).value], vertex[src.end_of(e).value]});
    }
    auto built = build_mesh(out, mesh);
    if (!built) continue;  // the source was built by build_mesh too; this cannot fail
    for (const auto& a : src.attributes(g)) out.set_attribute(built->group, a.key, a.value);
    for (std::size_t i = 0; i < face_ids.size(); ++i) faces[face_ids[i].value] = built->faces[i];
  }
  return faces;
}

bool is_identity(const shape::Transform& t) {
  const shape::Transform i = shape::Transform::identity();
  return t.m == i.m;
}

namespace {

bool is_2d_file(const std::string& path) {
  std::string ext = path.substr(
      path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".dxf" || ext == ".svg";
}

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct BuildError {
  SourcePos pos;
  std::string message;
};

using Color = std::optional<std::array<double, 4>>;

// A subtree combined in its own frame before it was moved (turned off the axes): its
// model there, its faces' colors, and the move.
struct Framed {
  Model model;
  std::vector<Color> face_colors;
  shape::Transform to_world;
};

struct Leaf {
  Model model;
  Color color;
  std::vector<Color> face_colors;  // by face, where the leaf is a combined subtree
  std::shared_ptr<const Framed> frame;  // where the leaf is a turned subtree
  Color color_of(std::uint32_t face) const { return face < face_colors.size() ? face_colors[face] : color; }
};

// copy_into (moved by t) with the faces' colors (by source face) carried to
// out_colors, when given, grown to out's faces.
void copy_colored(Model& out, std::vector<Color>* out_colors, const Model& m, const std::vector<Color>& colors,
                  const shape::Transform& t = shape::Transform::identity()) {
  const std::vector<FaceId> ids = copy_into(out, m, t);
  if (!out_colors) return;
  out_colors->resize(out.face_slots());
  for (FaceId f : m.faces())
    if (ids[f.value].is_valid() && f.value < colors.size()) (*out_colors)[ids[f.value].value] = colors[f.value];
}

// The inverse of an invertible affine map (the linear part by its adjugate).
shape::Transform inverse(const shape::Transform& t) {
  const auto& a = t.m;
  const double det = t.determinant();
  shape::Transform r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      r.m[i][j] = (a[i1][j1] * a[i2][j2] - a[i1][j2] * a[i2][j1]) / det;
    }
  for (int i = 0; i < 3; ++i)
    r.m[i][3] = -(r.m[i][0] * a[0][3] + r.m[i][1] * a[1][3] + r.m[i][2] * a[2][3]);
  return r;
}

// A subtree built once: its model and the color of each face.
struct Built {
  Model model;
  std::vector<Color> face_colors;
};

// Values made once by key, whatever the thread: the first to ask makes one (`made`),
// the others wait for it and get a copy. A make() that throws throws for all of them.
// No wait can close a cycle: a subtree waits only for smaller subtrees.
template <class V>
class OnceMap {
 public:
  template <class Make>
  V get(const std::string& key, Make&& make, bool& made) {
    std::promise<V> promise;
    std::shared_future<V> future;
    {
      std::lock_guard hold(lock_);
      auto [it, inserted] = map_.try_emplace(key);
      if (inserted) it->second = promise.get_future().share();
      future = it->second;
      made = inserted;
    }
    if (made) {
      try {
        promise.set_value(make());
      } catch (...) {
        promise.set_exception(std::current_exception());
      }
    }
    return future.get();
  }

 private:
  std::mutex lock_;
  std::unordered_map<std::string, std::shared_future<V>> map_;
};

// Whether a transform maps the axes to the axes (scaled, permuted, mirrored): faces
// the subtree meant to lie in one axis plane stay in one plane when their vertices
// are moved and rounded. A rotation off the axes moves them to planes a hair apart.
bool keeps_axes(const shape::Transform& t) {
  for (int r = 0; r < 3; ++r) {
    int nonzero = 0;
    for (int c = 0; c < 3; ++c) nonzero += t.m[r][c] != 0;
    if (nonzero != 1) return false;
  }
  return true;
}

// Whether t is a signed permutation of the axes with no translation: it moves every
// double point to a double point exactly.
bool permutes_axes(const shape::Transform& t) {
  if (!keeps_axes(t)) return false;
  for (int r = 0; r < 3; ++r) {
    if (t.m[r][3] != 0) return false;
    for (int c = 0; c < 3; ++c)
      if (t.m[r][c] != 0 && std::abs(t.m[r][c]) != 1) return false;
  }
  return true;
}

// A 2D subtree: regions (already transformed into the plane) combined by set operations.
struct Shape2 {
  boolean::Expr expr;
  std::vector<shape::Region> regions;
};

class Builder {
 public:
  Builder(const BuildOptions& o, const Node& root) : options_(o), cache_(o.cache_dir), keys_(root) {}

  BuildOutput run(const Node& root) {
    BuildOutput out;
    const int d = dimension(root);
    if (d == 2) {
      auto s = collect2(root, shape::Transform::identity());
      out.dimension = s ? 2 : 0;
      if (s) {
        // Messages about the whole result name its first object.
        const auto first = active_children(root);
        const shape::Shape2D flat =
            to_shape(*s, root.pos.line == 0 && !first.empty() ? *first[0] : root);
        for (const shape::Region& r : flat.regions) {
          auto g = shape::make_region_face(out.model, r);
          if (!g) fail(root.pos, g.error().message);
        }
        if (flat.empty()) out.dimension = 0;
      }
      out.stats = stats_;
      return out;
    }
    if (root.kind == NodeKind::kGroup) {
      run_parts(root, out);
      out.stats = stats_;
      return out;
    }
    std::vector<Leaf> leaves;
    auto expr = collect3(root, shape::Transform::identity(), std::nullopt, leaves);
    if (!expr) {
      out.dimension = 0;
      out.stats = stats_;
      return out;
    }
    out.model = combine(*expr, leaves, root.pos, &out.face_colors);
    out.stats = stats_;
    return out;
  }

  struct Part {
    Model model;
    std::vector<Color> colors;
    Vec3 lo, hi;
  };

  // One top-level part: from the cache by its content key when it is there, else its
  // geometry (built once in this build: a projection of the same subtree elsewhere
  // finds it) colored as the color nodes above it say.
  Part build_part(const Node& c) {
    Part p;
    const std::string key = keys_(c);
    if (cache_.load(key, p.model, p.colors)) {
      tally([&](BuildStats& s) { ++s.cache_hits; });
    } else {
      tally([&](BuildStats& s) { ++s.cache_misses; });
      const Node& core = geometry_core(c);
      Built b;
      if (combines_solids(core)) {
        b = with_color(subtree(core, c.pos), color_above(c));
      } else {
        std::vector<Leaf> leaves;
        auto expr = collect3(c, shape::Transform::identity(), std::nullopt, leaves);
        if (expr) b.model = combine(*expr, leaves, c.pos, &b.face_colors);
      }
      p.model = std::move(b.model);
      p.colors = std::move(b.face_colors);
      cache_.store(key, p.model, p.colors);
    }
    if (p.model.num_faces() == 0) return p;
    Box box;  // of its points, as mass_properties gives it, without the sums
    for (VertexId v : p.model.vertices()) box.add(p.model.position(v));
    p.lo = box.lo;
    p.hi = box.hi;
    return p;
  }

  // The top-level parts (the root's children, and the children of unions among them)
  // are built each on its own (build_part; several at once, on threads of their own:
  // a part's Boolean then takes the worker threads, geom/workers.h, when no other has
  // them) — then parts whose boxes are apart are put side by side (their union,
  // exactly, without a Boolean) and others united by one more Boolean. Separate parts
  // are the common case of a file with many parts, and one arrangement per part is
  // faster than one for all of them. What is built does not depend on the threads:
  // each part is its subtree's, and they are put together in order.
  void run_parts(const Node& root, BuildOutput& out) {
    std::vector<Part> parts;
    std::vector<const Node*> pieces;
    std::function<void(const Node&)> split = [&](const Node& n) {
      for (const Node* c : active_children(n)) {
        if (c->kind == NodeKind::kGroup || c->kind == NodeKind::kUnion) {
          split(*c);
        } else {
          pieces.push_back(c);
        }
      }
    };
    split(root);
    const std::size_t n = pieces.size();
    std::vector<Part> built(n);
    std::vector<std::exception_ptr> errors(n);
    std::atomic<std::size_t> next{0};
    std::atomic<bool> failed{false};
    std::mutex progress_lock;
    std::size_t finished = 0;
    if (options_.progress) options_.progress(0, n);
    // Parts taken in order; after a failure no new one is started, so the first
    // failing part by order is among those that ran (its error is the one reported).
    auto work = [&] {
      for (std::size_t i = next++; i < n && !failed; i = next++) {
        try {
          built[i] = build_part(*pieces[i]);
        } catch (...) {
          errors[i] = std::current_exception();
          failed = true;
        }
        if (options_.progress) {
          std::lock_guard hold(progress_lock);
          options_.progress(++finished, n);
        }
      }
    };
    const int want = options_.threads > 0 ? options_.threads : geom::worker_capacity();
    const std::size_t threads = std::min<std::size_t>(n, static_cast<std::size_t>(want));
    std::vector<std::thread> others;
    for (std::size_t k = 1; k < threads; ++k) others.emplace_back(work);
    work();
    for (std::thread& t : others) t.join();
    for (const std::exception_ptr& e : errors)
      if (e) std::rethrow_exception(e);
    for (Part& p : built)
      if (p.model.num_faces() != 0) parts.push_back(std::move(p));
    if (parts.empty()) {
      out.dimension = 0;
      return;
    }
    if (parts.size() == 1) {
      out.model = std::move(parts[0].model);
      out.face_colors = std::move(parts[0].colors);
      return;
    }
    // Parts whose boxes are apart, or that are apart though their boxes meet (exactly:
    // meeting_clusters), are put side by side; each cluster of parts that meet is
    // united by one more Boolean.
    std::vector<std::uint32_t> cluster(parts.size());
    std::vector<const Model*> all;
    for (std::size_t i = 0; i < parts.size(); ++i) {
      cluster[i] = static_cast<std::uint32_t>(i);
      all.push_back(&parts[i].model);
    }
    bool boxes_apart = true;
    for (std::size_t i = 0; i < parts.size() && boxes_apart; ++i) {
      for (std::size_t j = i + 1; j < parts.size() && boxes_apart; ++j) {
        bool separated = false;
        for (int k = 0; k < 3; ++k) {
          separated |= parts[i].hi[k] < parts[j].lo[k] || parts[j].hi[k] < parts[i].lo[k];
        }
        boxes_apart = separated;
      }
    }
    if (!boxes_apart) cluster = meeting_clusters(all);
    if (std::any_of(cluster.begin(), cluster.end(), [&](std::uint32_t c) { return c != cluster[0]; }))
      tally([&](BuildStats& s) { ++s.parts_apart; });
    std::vector<std::vector<std::size_t>> members(parts.size());  // by cluster
    for (std::size_t i = 0; i < parts.size(); ++i) members[cluster[i]].push_back(i);
    for (std::size_t c = 0; c < parts.size(); ++c) {
      if (members[c].empty()) continue;
      if (members[c].size() == 1) {
        copy_colored(out.model, &out.face_colors, parts[c].model, parts[c].colors);
        continue;
      }
      std::vector<const Model*> operands;
      for (std::size_t i : members[c]) operands.push_back(&parts[i].model);
      const auto start = Clock::now();
      auto r = boolean::apply(boolean::Op::kUnion, operands, boolean_options(operands));
      count_boolean(start, operands.size(), false, r ? &r->report : nullptr);
      if (!r) fail(root.pos, "the Boolean operation failed: " + r.error().message);
      std::vector<Color> colors(r->model.face_slots(), std::nullopt);
      for (std::size_t f = 0; f < r->sources.size() && f < colors.size(); ++f) {
        const auto& src = r->sources[f];
        if (src.operand < 0) continue;
        const Part& p = parts[members[c][static_cast<std::size_t>(src.operand)]];
        if (src.face < p.colors.size()) colors[f] = p.colors[src.face];
      }
      if (members[c].size() == parts.size()) {
        out.model = std::move(r->model);
        out.face_colors = std::move(colors);
      } else {
        copy_colored(out.model, &out.face_colors, r->model, colors);
      }
    }
  }

  [[noreturn]] void fail(SourcePos pos, const std::string& message) const {
    throw BuildError{pos, message};
  }

  // 3: solids, 2: planar shapes, 0: nothing (or only background).
  int dimension(const Node& n) const {
    switch (n.kind) {
      case NodeKind::kCube:
      case NodeKind::kSphere:
      case NodeKind::kCylinder:
      case NodeKind::kPolyhedron:
      case NodeKind::kLinearExtrude:
      case NodeKind::kRotateExtrude:
        return 3;
      case NodeKind::kSquare:
      case NodeKind::kCircle:
      case NodeKind::kPolygon:
      case NodeKind::kProjection:
      case NodeKind::kOffset:
        return 2;
      case NodeKind::kImport:
        return is_2d_file(n.path) ? 2 : 3;
      default: {
        int d = 0;
        for (const NodePtr& c : n.children) {
          if (c->background) continue;
          const int cd = dimension(*c);
          if (cd == 0) continue;
          if (d != 0 && cd != d) {
            fail(c->pos, std::string("a ") + (cd == 2 ? "2D" : "3D") + " object among " +
                             (d == 2 ? "2D" : "3D") + " ones in " + node_name(n.kind) +
                             "() (OpenSCAD ignores it; mixing dimensions is refused here)");
          }
          d = cd;
        }
        return d;
      }
    }
  }

  std::vector<const Node*> active_children(const Node& n) const {
    std::vector<const Node*> out;
    for (const NodePtr& c : n.children) {
      if (!c->background) out.push_back(c.get());
    }
    return out;
  }

  // ---- 3D: the set-operation expression over leaves
  std::optional<boolean::Expr> collect3(const Node& n, const shape::Transform& t,
                                        const Color& color, std::vector<Leaf>& leaves) {
    switch (n.kind) {
      case NodeKind::kGroup:
      case NodeKind::kUnion:
      case NodeKind::kDifference:
      case NodeKind::kIntersection: {
        std::vector<std::optional<boolean::Expr>> parts;
        for (const Node* c : active_children(n)) parts.push_back(collect3(*c, t, color, leaves));
        return set_op(n.kind, std::move(parts));
      }
      case NodeKind::kMultmatrix: {
        const shape::Transform inner = t * n.matrix;
        // Off the axes, a subtree that combines solids is combined in its own frame and
        // its result moved (rounded once), as OpenSCAD evaluates it: moving each leaf
        // would round the faces it puts side by side in one plane (cubes stacked, a
        // Menger sponge's bars) to planes a hair apart, and the Boolean would then
        // resolve every sliver between them exactly (example024: minutes, not a second).
        if (!keeps_axes(n.matrix) && combines_solids(n)) {
          if (inner.determinant() == 0) return std::nullopt;  // flattened: nothing
          Built b = build_children_colored(n, color);
          if (b.model.num_faces() == 0) return std::nullopt;
          Leaf leaf{Model(), color, {}, nullptr};
          const std::vector<FaceId> ids = copy_into(leaf.model, b.model, inner);
          leaf.face_colors.assign(leaf.model.face_slots(), color);
          for (std::size_t f = 0; f < ids.size(); ++f)
            if (ids[f].is_valid() && f < b.face_colors.size()) leaf.face_colors[ids[f].value] = b.face_colors[f];
          leaf.frame = std::make_shared<const Framed>(Framed{std::move(b.model), std::move(b.face_colors), inner});
          leaves.push_back(std::move(leaf));
          return boolean::Expr::of(static_cast<int>(leaves.size() - 1));
        }
        std::vector<std::optional<boolean::Expr>> parts;
        for (const Node* c : active_children(n))
          parts.push_back(collect3(*c, inner, color, leaves));
        return set_op(NodeKind::kGroup, std::move(parts));
      }
      case NodeKind::kColor: {
        std::vector<std::optional<boolean::Expr>> parts;
        for (const Node* c : active_children(n)) parts.push_back(collect3(*c, t, n.color, leaves));
        return set_op(NodeKind::kGroup, std::move(parts));
      }
      default:
        break;
    }
    const auto start = Clock::now();
    Model m = memo_leaf(n);
    tally([&](BuildStats& s) {
      s.leaf_seconds += seconds_since(start);
      ++s.leaves;
    });
    if (m.num_faces() == 0) return std::nullopt;
    if (m.num_volumes() == 0) fail(n.pos, std::string(node_name(n.kind)) + "() made no solid");
    if (!is_identity(t)) {
      if (t.determinant() == 0) return std::nullopt;  // flattened to nothing, as OpenSCAD
      m = copy_transformed(m, t);
    }
    leaves.push_back(Leaf{std::move(m), color, {}, nullptr});
    return boolean::Expr::of(static_cast<int>(leaves.size() - 1));
  }

  // Empty parts dropped: a union of nothing is nothing, an intersection with nothing is
  // nothing, a difference from nothing is nothing.
  static std::optional<boolean::Expr> set_op(NodeKind k,
                                             std::vector<std::optional<boolean::Expr>> parts) {
    std::vector<boolean::Expr> kept;
    if (k == NodeKind::kIntersection) {
      for (auto& p : parts) {
        if (!p) return std::nullopt;
        kept.push_back(std::move(*p));
      }
    } else if (k == NodeKind::kDifference) {
      if (parts.empty() || !parts[0]) return std::nullopt;
      for (auto& p : parts) {
        if (p) kept.push_back(std::move(*p));
      }
    } else {
      for (auto& p : parts) {
        if (p) kept.push_back(std::move(*p));
      }
    }
    if (kept.empty()) return std::nullopt;
    if (kept.size() == 1) return std::move(kept[0]);
    const boolean::Op op = k == NodeKind::kIntersection ? boolean::Op::kIntersection
                           : k == NodeKind::kDifference ? boolean::Op::kDifference
                                                        : boolean::Op::kUnion;
    // Nested runs of the same associative operation become one node.
    std::vector<boolean::Expr> flat;
    const auto kind = op == boolean::Op::kUnion ? boolean::Expr::Kind::kUnion
                                                : boolean::Expr::Kind::kIntersection;
    for (auto& e : kept) {
      if (op != boolean::Op::kDifference && e.kind == kind) {
        for (auto& c : e.children) flat.push_back(std::move(c));
      } else {
        flat.push_back(std::move(e));
      }
    }
    return boolean::Expr::op(op, std::move(flat));
  }

  Model combine(const boolean::Expr& expr, std::vector<Leaf>& leaves, SourcePos pos,
                std::vector<Color>* face_colors, bool split_apart = true) {
    if (split_apart && expr.kind == boolean::Expr::Kind::kUnion && expr.children.size() > 1) {
      if (auto apart = combine_apart(expr, leaves, pos, face_colors)) return std::move(*apart);
    }
    if (expr.kind == boolean::Expr::Kind::kOperand) {
      Leaf& l = leaves[static_cast<std::size_t>(expr.operand)];
      if (face_colors) {
        face_colors->resize(l.model.face_slots());
        for (std::uint32_t f = 0; f < face_colors->size(); ++f) (*face_colors)[f] = l.color_of(f);
      }
      return std::move(l.model);
    }
    if (auto framed = combine_framed(expr, leaves, pos, face_colors)) return std::move(*framed);
    std::vector<const Model*> operands;
    for (const Leaf& l : leaves) operands.push_back(&l.model);
    const auto start = Clock::now();
    auto r = boolean::evaluate(operands, expr, boolean_options(operands));
    count_boolean(start, operands.size(), false, r ? &r->report : nullptr);
    if (!r) fail(pos, "the Boolean operation failed: " + r.error().message);
    if (face_colors) {
      face_colors->assign(r->model.face_slots(), std::nullopt);
      for (std::size_t f = 0; f < r->sources.size() && f < face_colors->size(); ++f) {
        const int op = r->sources[f].operand;
        if (op >= 0 && static_cast<std::size_t>(op) < leaves.size())
          (*face_colors)[f] = leaves[static_cast<std::size_t>(op)].color_of(r->sources[f].face);
      }
    }
    return std::move(r->model);
  }

  // A Boolean whose operands are mostly one subtree turned off the axes (a rotated
  // Menger sponge cut by a box: example024.scad) is evaluated in that subtree's frame,
  // the other operands moved there, and its result moved back: the turned subtree's
  // faces, a rounding off planar once moved and then resolved against each other
  // exactly, stay in their planes, and only the few faces of the others are rounded
  // in between. Nothing when no turned subtree holds more than half the faces.
  std::optional<Model> combine_framed(const boolean::Expr& expr, std::vector<Leaf>& leaves, SourcePos pos,
                                      std::vector<Color>* face_colors) {
    std::size_t big = leaves.size(), big_faces = 0, total = 0;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      const std::size_t faces = leaves[i].model.num_faces();
      total += faces;
      if (leaves[i].frame && faces > big_faces) big = i, big_faces = faces;
    }
    if (big == leaves.size() || 2 * big_faces <= total) return std::nullopt;
    // The others, turned into the frame, would meet each other a rounding off their
    // planes: only others whose boxes are apart.
    std::vector<Box> boxes;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      if (i == big) continue;
      Box b;
      for (VertexId v : leaves[i].model.vertices()) b.add(leaves[i].model.position(v));
      for (const Box& o : boxes)
        if (o.overlaps(b)) return std::nullopt;
      boxes.push_back(b);
    }
    const Framed& frame = *leaves[big].frame;
    const shape::Transform to_frame = inverse(frame.to_world);
    std::vector<Model> moved(leaves.size());
    std::vector<std::vector<FaceId>> moved_ids(leaves.size());  // frame face -> leaf face
    std::vector<const Model*> operands;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      if (i == big) {
        operands.push_back(&frame.model);
        continue;
      }
      const std::vector<FaceId> ids = copy_into(moved[i], leaves[i].model, to_frame);
      moved_ids[i].assign(moved[i].face_slots(), FaceId());
      for (std::size_t f = 0; f < ids.size(); ++f)
        if (ids[f].is_valid()) moved_ids[i][ids[f].value] = FaceId(static_cast<std::uint32_t>(f));
      operands.push_back(&moved[i]);
    }
    const auto start = Clock::now();
    auto r = boolean::evaluate(operands, expr, boolean_options(operands));
    count_boolean(start, operands.size(), true, r ? &r->report : nullptr);
    if (!r) fail(pos, "the Boolean operation failed: " + r.error().message);
    Model out;
    const std::vector<FaceId> ids = copy_into(out, r->model, frame.to_world);
    if (face_colors) {
      face_colors->assign(out.face_slots(), std::nullopt);
      for (std::size_t f = 0; f < r->sources.size() && f < ids.size(); ++f) {
        const int op = r->sources[f].operand;
        if (op < 0 || !ids[f].is_valid()) continue;
        const auto i = static_cast<std::size_t>(op);
        const std::uint32_t face = r->sources[f].face;
        Color c;
        if (i == big) {
          c = face < frame.face_colors.size() ? frame.face_colors[face] : leaves[i].color;
        } else if (face < moved_ids[i].size() && moved_ids[i][face].is_valid()) {
          c = leaves[i].color_of(moved_ids[i][face].value);
        } else {
          c = leaves[i].color;
        }
        (*face_colors)[ids[f].value] = c;
      }
    }
    return out;
  }

  // A union whose terms fall into clusters that are apart (meeting_clusters: no
  // surfaces meet, none inside another; a term stands for its leaves, since what it
  // makes lies within them): each cluster is combined alone and the results are put
  // side by side. Nothing when the terms make one cluster.
  std::optional<Model> combine_apart(const boolean::Expr& expr, std::vector<Leaf>& leaves,
                                     SourcePos pos, std::vector<Color>* face_colors) {
    constexpr std::uint32_t kNone = 0xffffffffu;
    std::vector<std::uint32_t> term_of(leaves.size(), kNone);
    UnionFind terms(expr.children.size());  // terms sharing a leaf are one
    std::function<void(const boolean::Expr&, std::uint32_t)> mark = [&](const boolean::Expr& e, std::uint32_t t) {
      if (e.kind == boolean::Expr::Kind::kOperand) {
        std::uint32_t& at = term_of[static_cast<std::size_t>(e.operand)];
        if (at != kNone) terms.unite_to_smaller(at, t);
        at = t;
      }
      for (const boolean::Expr& c : e.children) mark(c, t);
    };
    for (std::size_t t = 0; t < expr.children.size(); ++t) mark(expr.children[t], static_cast<std::uint32_t>(t));
    std::vector<const Model*> models;
    std::vector<std::uint32_t> together;
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      if (term_of[i] == kNone) return std::nullopt;  // a leaf the union does not name
      models.push_back(&leaves[i].model);
      together.push_back(terms.find(term_of[i]));
    }
    const std::vector<std::uint32_t> cluster = meeting_clusters(models, together);
    if (std::all_of(cluster.begin(), cluster.end(), [&](std::uint32_t c) { return c == cluster[0]; }))
      return std::nullopt;
    tally([&](BuildStats& s) { ++s.parts_apart; });
    // The leaves and terms of each cluster (named by its smallest leaf), the leaves
    // renumbered in order within it; a term's leaves are all in one cluster.
    std::vector<std::vector<std::size_t>> members(leaves.size()), own_terms(leaves.size());
    std::vector<int> local(leaves.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) {
      local[i] = static_cast<int>(members[cluster[i]].size());
      members[cluster[i]].push_back(i);
    }
    std::vector<std::uint32_t> term_cluster(expr.children.size());
    for (std::size_t i = 0; i < leaves.size(); ++i) term_cluster[term_of[i]] = cluster[i];
    for (std::size_t t = 0; t < expr.children.size(); ++t) own_terms[term_cluster[t]].push_back(t);
    std::function<boolean::Expr(const boolean::Expr&)> renumber = [&](const boolean::Expr& e) {
      boolean::Expr r{e.kind, e.kind == boolean::Expr::Kind::kOperand ? local[static_cast<std::size_t>(e.operand)] : 0, {}};
      for (const boolean::Expr& k : e.children) r.children.push_back(renumber(k));
      return r;
    };
    Model out;
    if (face_colors) face_colors->clear();
    for (std::size_t c = 0; c < leaves.size(); ++c) {
      if (members[c].empty()) continue;
      std::vector<Leaf> own;
      for (std::size_t i : members[c]) own.push_back(std::move(leaves[i]));
      std::vector<boolean::Expr> terms_here;
      for (std::size_t t : own_terms[c]) terms_here.push_back(renumber(expr.children[t]));
      const boolean::Expr sub = terms_here.size() == 1 ? terms_here[0] : boolean::Expr{boolean::Expr::Kind::kUnion, 0, std::move(terms_here)};
      std::vector<Color> colors;
      const Model m = combine(sub, own, pos, face_colors ? &colors : nullptr, false);
      copy_colored(out, face_colors, m, colors);
    }
    return out;
  }

  template <class T>
  void check(const Result<T>& r, const Node& n) const {
    if (!r) fail(n.pos, std::string(node_name(n.kind)) + "(): " + r.error().message);
  }

  // More than a million segments per circle is refused before the faceting rule
  // turns it into an int (and before building it would run out of memory).
  void check_segments(const Node& n, double r, const shape::Faceting& f) const {
    constexpr double kMax = 1e6;
    const double fa = std::max(f.fa, shape::kMinimumFaFs), fs = std::max(f.fs, shape::kMinimumFaFs);
    const double segments = f.fn > 0 ? f.fn : std::min(360.0 / fa, std::fabs(r) * 2 * M_PI / fs);
    if (std::isfinite(f.fn) && !(segments <= kMax)) {
      fail(n.pos, std::string(node_name(n.kind)) + "(): more than 10^6 segments per circle");
    }
  }

  Model leaf3(const Node& n) {
    Model m;
    if (n.kind == NodeKind::kSphere) check_segments(n, n.r, n.faceting);
    if (n.kind == NodeKind::kCylinder) check_segments(n, std::max(n.r1, n.r2), n.faceting);
    switch (n.kind) {
      case NodeKind::kCube:
        if (n.size.x == 0 || n.size.y == 0 || n.size.z == 0) return m;
        check(shape::make_cube(m, {.size = n.size, .center = n.center}), n);
        return m;
      case NodeKind::kSphere:
        if (n.r == 0) return m;
        check(shape::make_sphere(m, {.r = n.r, .faceting = n.faceting}), n);
        return m;
      case NodeKind::kCylinder:
        if (n.h == 0 || (n.r1 == 0 && n.r2 == 0)) return m;
        check(
            shape::make_cylinder(
                m, {.h = n.h, .r1 = n.r1, .r2 = n.r2, .center = n.center, .faceting = n.faceting}),
            n);
        return m;
      case NodeKind::kPolyhedron:
        check(shape::make_polyhedron(m, {.points = n.points, .faces = n.faces, .clockwise = true}),
              n);
        return m;
      case NodeKind::kImport: {
        auto r = io::read_file(m, n.path);
        check(r, n);
        return m;
      }
      case NodeKind::kLinearExtrude:
      case NodeKind::kRotateExtrude:
        return extrude(n);
      case NodeKind::kResize:
        return resize(n);
      case NodeKind::kHull:
        return hull3(n);
      case NodeKind::kMinkowski:
        return minkowski3(n);
      default:
        fail(n.pos, std::string(node_name(n.kind)) + "() is a 2D object where a 3D one is needed");
    }
  }

  // The children of n built into one model (a subtree of its own); the same subtree
  // met again in this build (GEB.scad's letters, built as a part and projected) is
  // built once.
  Model build_children(const Node& n) { return build_children_colored(n, std::nullopt).model; }

  // A Boolean of small operands stays on one thread: starting threads for each of its
  // stages costs more than they save (CSG.scad's cube and sphere: 43 -> 46 ms).
  boolean::Options boolean_options(const std::vector<const Model*>& operands) const {
    constexpr std::size_t kVerticesForThreads = 2000;  // about twice as many triangles
    std::size_t vertices = 0;
    for (const Model* m : operands) vertices += m->num_vertices();
    boolean::Options o;
    o.threads = vertices >= kVerticesForThreads ? options_.threads : 1;
    return o;
  }

  // The same with the color of each face (`color` where the subtree gives none).
  Built build_children_colored(const Node& n, const Color& color) {
    Node group;
    group.kind = NodeKind::kGroup;
    group.children = n.children;
    return with_color(with_color(subtree(geometry_core(group), n.pos), color_above(group)), color);
  }

  // A subtree built whole, with the colors of its own color nodes (none for faces
  // outside them), once per build by content key: the first to ask builds it, on
  // whatever thread, and the others wait for it.
  Built subtree(const Node& n, SourcePos pos) {
    return memoized(subtree_memo_, n, [&] {
      Built out;
      // Under quarter turns and mirrors in the axes' planes, nothing added (a signed
      // permutation of the axes: every point moves exactly), the subtree is combined in
      // its own frame, once however many ways it is turned (GEB.scad's letters, built
      // as a part and projected from three sides), and its result moved: the same solid
      // as combining the moved leaves would give, but for the diagonal that splits a
      // quad that is not exactly planar (a sphere's), which follows the quad's corner
      // order and so may differ in a mirror image.
      if (n.kind == NodeKind::kMultmatrix && permutes_axes(n.matrix)) {
        Node group;
        group.kind = NodeKind::kGroup;
        group.children = n.children;
        const Node& core = geometry_core(group);
        if (combines_solids(core)) {
          const Built inner = with_color(subtree(core, pos), color_above(group));
          copy_colored(out.model, &out.face_colors, inner.model, inner.face_colors, n.matrix);
          return out;
        }
      }
      std::vector<Leaf> leaves;
      auto expr = collect3(n, shape::Transform::identity(), std::nullopt, leaves);
      if (expr) out.model = combine(*expr, leaves, pos, &out.face_colors);
      return out;
    });
  }

  // b with `color` on the faces that have none (a color node above the subtree:
  // OpenSCAD's inner colors win).
  static Built with_color(Built b, const Color& color) {
    if (!color) return b;
    b.face_colors.resize(b.model.face_slots());
    for (Color& c : b.face_colors)
      if (!c) c = color;
    return b;
  }

  // The color that the color nodes between n and its geometry_core give (the innermost).
  Color color_above(const Node& n) const {
    Color color;
    const Node* c = &n;
    const Node* core = &geometry_core(n);
    while (c != core) {
      if (c->kind == NodeKind::kColor) color = c->color;
      c = active_children(*c)[0];
    }
    return color;
  }

  // Whether a set operation (explicit, or a group's implicit union) combines two or
  // more solids somewhere below n.
  bool combines_solids(const Node& n) const {
    switch (n.kind) {
      case NodeKind::kGroup:
      case NodeKind::kUnion:
      case NodeKind::kDifference:
      case NodeKind::kIntersection:
      case NodeKind::kMultmatrix:
      case NodeKind::kColor: {
        const auto kids = active_children(n);
        if (kids.size() >= 2 && n.kind != NodeKind::kMultmatrix && n.kind != NodeKind::kColor) return true;
        for (const Node* c : kids)
          if (combines_solids(*c)) return true;
        return false;
      }
      default:
        return false;
    }
  }

  // The node whose geometry n is: through colors and groups of one child, which
  // change no point of it.
  const Node& geometry_core(const Node& n) const {
    const Node* c = &n;
    for (;;) {
      if (c->kind != NodeKind::kColor && c->kind != NodeKind::kGroup) return *c;
      const auto kids = active_children(*c);
      if (kids.size() != 1) return *c;
      c = kids[0];
    }
  }

  // A leaf that takes more than a primitive's work (an extrusion, a hull, an import),
  // built once per build whatever the number of places it is used (in its own frame;
  // each place moves a copy).
  Model memo_leaf(const Node& n) {
    const bool primitive =
        n.kind == NodeKind::kCube || n.kind == NodeKind::kSphere || n.kind == NodeKind::kCylinder;
    if (primitive) return leaf3(n);
    return memoized(leaf_memo_, n, [&] { return leaf3(n); });
  }

  Model resize(const Node& n) {
    Model sub = build_children(n);
    if (sub.num_faces() == 0) return sub;
    const shape::MassProperties mp = shape::mass_properties(sub);
    auto f =
        shape::resize_factors(mp.bbox_max - mp.bbox_min, {.size = n.size, .autosize = n.auto_size});
    check(f, n);
    return copy_transformed(sub, shape::Transform::scale(*f));
  }

  Model hull3(const Node& n) {
    std::vector<Leaf> leaves;
    Node group;
    group.kind = NodeKind::kGroup;
    group.children = n.children;
    // The hull of a union is the hull of all the vertices: no Boolean is needed.
    collect3(group, shape::Transform::identity(), std::nullopt, leaves);
    std::vector<Vec3> points;
    for (const Leaf& l : leaves) {
      for (Vec3 p : shape::vertex_positions(l.model)) points.push_back(p);
    }
    Model m;
    if (points.empty()) return m;
    check(shape::convex_hull(m, points), n);
    return m;
  }

  Model minkowski3(const Node& n) {
    std::vector<Model> parts;
    for (const Node* c : active_children(n)) {
      Node one;
      one.kind = NodeKind::kGroup;
      one.children = {std::make_shared<Node>(*c)};
      Model m = build_children(one);
      if (m.num_faces() == 0) return Model();
      parts.push_back(std::move(m));
    }
    if (parts.empty()) return Model();
    std::vector<const Model*> operands;
    for (const Model& m : parts) operands.push_back(&m);
    auto r = boolean::minkowski(operands);
    check(r, n);
    return std::move(*r);
  }

  // A 2D subtree as one shape: its set operations evaluated (2D Booleans).
  shape::Shape2D to_shape(const Shape2& s, const Node& at) {
    if (s.expr.kind == boolean::Expr::Kind::kOperand)
      return shape::shape_of(s.regions[static_cast<std::size_t>(s.expr.operand)]);
    std::vector<shape::Shape2D> operands;
    for (const shape::Region& r : s.regions) operands.push_back(shape::shape_of(r));
    const auto start = Clock::now();
    auto r = boolean::evaluate_2d(operands, s.expr);
    count_boolean(start, 0);
    check(r, at);
    return std::move(*r);
  }

  // A shape (disjoint regions) as a Shape2: the union of its regions.
  static std::optional<Shape2> from_shape(shape::Shape2D shape) {
    if (shape.empty()) return std::nullopt;
    Shape2 s;
    std::vector<boolean::Expr> parts;
    for (auto& r : shape.regions) {
      parts.push_back(boolean::Expr::of(static_cast<int>(s.regions.size())));
      s.regions.push_back(std::move(r));
    }
    s.expr = parts.size() == 1 ? std::move(parts[0])
                               : boolean::Expr::op(boolean::Op::kUnion, std::move(parts));
    return s;
  }

  std::optional<Shape2> children2(const Node& n, const shape::Transform& t) {
    Node group;
    group.kind = NodeKind::kGroup;
    group.children = n.children;
    return collect2(group, t);
  }

  // ---- 2D
  std::optional<Shape2> collect2(const Node& n, const shape::Transform& t) {
    switch (n.kind) {
      case NodeKind::kGroup:
      case NodeKind::kUnion:
      case NodeKind::kDifference:
      case NodeKind::kIntersection:
      case NodeKind::kMultmatrix:
      case NodeKind::kColor: {
        const shape::Transform inner = n.kind == NodeKind::kMultmatrix ? t * n.matrix : t;
        Shape2 all;
        std::vector<std::optional<boolean::Expr>> parts;
        for (const Node* c : active_children(n)) {
          auto s = collect2(*c, inner);
          if (!s) {
            parts.push_back(std::nullopt);
            continue;
          }
          const int offset = static_cast<int>(all.regions.size());
          for (auto& r : s->regions) all.regions.push_back(std::move(r));
          shift(s->expr, offset);
          parts.push_back(std::move(s->expr));
        }
        const NodeKind k = n.kind == NodeKind::kMultmatrix || n.kind == NodeKind::kColor
                               ? NodeKind::kGroup
                               : n.kind;
        auto e = set_op(k, std::move(parts));
        if (!e) return std::nullopt;
        all.expr = std::move(*e);
        return all;
      }
      default:
        break;
    }
    if (n.kind == NodeKind::kHull || n.kind == NodeKind::kMinkowski ||
        n.kind == NodeKind::kOffset || n.kind == NodeKind::kProjection ||
        n.kind == NodeKind::kResize) {
      return operation2(n, t);
    }
    if (n.kind == NodeKind::kImport) {
      const Import2DOptions o{.layer = n.layer,
                              .origin = Vec2{n.origin.x, n.origin.y},
                              .scale = n.import_scale,
                              .faceting = n.faceting};
      std::string ext = n.path.substr(std::min(n.path.size(), n.path.find_last_of('.')));
      for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
      if (ext != ".svg") {
        auto paths = read_dxf(n.path, o);
        check(paths, n);
        return paths_2d(*paths, t, n);
      }
      // SVG: each shape filled even-odd, the shapes united.
      auto shapes = read_svg(n.path, o);
      check(shapes, n);
      Shape2 all;
      std::vector<boolean::Expr> parts;
      for (const auto& shape : *shapes) {
        auto s = paths_2d(shape, t, n);
        if (!s) continue;
        shift(s->expr, static_cast<int>(all.regions.size()));
        for (auto& r : s->regions) all.regions.push_back(std::move(r));
        parts.push_back(std::move(s->expr));
      }
      if (parts.empty()) return std::nullopt;
      all.expr = parts.size() == 1 ? std::move(parts[0])
                                   : boolean::Expr::op(boolean::Op::kUnion, std::move(parts));
      return all;
    }
    Result<shape::Region> region = Error{ErrorCode::kUnsupported, ""};
    switch (n.kind) {
      case NodeKind::kSquare:
        if (n.size.x == 0 || n.size.y == 0) return std::nullopt;
        region = shape::rectangle(Vec2{n.size.x, n.size.y}, n.center);
        break;
      case NodeKind::kCircle:
        if (n.r == 0) return std::nullopt;
        check_segments(n, n.r, n.faceting);
        region = shape::circle(n.r, n.faceting);
        break;
      case NodeKind::kPolygon: {
        std::vector<std::vector<std::uint32_t>> paths = n.faces;
        if (paths.empty()) {
          paths.emplace_back();
          for (std::uint32_t i = 0; i < n.points.size(); ++i) paths[0].push_back(i);
        }
        if (paths[0].size() < 3) return std::nullopt;
        std::vector<std::vector<Vec2>> loops;
        for (const auto& path : paths) {
          loops.emplace_back();
          for (std::uint32_t i : path) loops.back().push_back(Vec2{n.points[i].x, n.points[i].y});
        }
        if (loops.size() == 1) {
          region = shape::polygon(loops[0]);
          break;
        }
        return paths_2d(loops, t, n);
      }
      default:
        fail(n.pos, std::string(node_name(n.kind)) + "() is a 3D object where a 2D one is needed");
    }
    check(region, n);
    shape::Region r = std::move(*region);
    if (!is_identity(t)) {
      const auto& m = t.m;
      if (m[2][0] != 0 || m[2][1] != 0) {
        fail(n.pos,
             "a 2D object moved out of the xy plane (only transforms within it are "
             "supported for 2D)");
      }
      const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
      if (det == 0) return std::nullopt;
      for (auto& l : r.loops) {
        for (Vec2& p : l)
          p = Vec2{m[0][0] * p.x + m[0][1] * p.y + m[0][3],
                   m[1][0] * p.x + m[1][1] * p.y + m[1][3]};
      }
      if (det < 0) {
        std::vector<std::vector<Vec2>> holes(r.loops.begin() + 1, r.loops.end());
        auto again = shape::polygon(r.loops[0], std::move(holes));
        check(again, n);
        r = std::move(*again);
      }
    }
    Shape2 s;
    s.regions.push_back(std::move(r));
    s.expr = boolean::Expr::of(0);
    return s;
  }

  // Closed paths filled even-odd, as OpenSCAD fills polygon() paths and imported
  // outlines: read off the nesting when no two paths meet (fill.h), otherwise the
  // symmetric difference of the paths' polygons, one path at a time (2D Booleans).
  std::optional<Shape2> paths_2d(const std::vector<std::vector<Vec2>>& loops,
                                 const shape::Transform& t, const Node& n) {
    shape::Shape2D fill;
    if (auto nested = fill_nested(loops)) {
      fill.regions = std::move(*nested);
    } else {
      std::optional<shape::Shape2D> acc;
      for (const auto& loop : loops) {
        if (loop.size() < 3) continue;
        auto one = shape::polygon(loop);
        check(one, n);
        if (!acc) {
          acc = shape::shape_of(std::move(*one));
          continue;
        }
        const shape::Shape2D pair[2] = {std::move(*acc), shape::shape_of(std::move(*one))};
        using boolean::Expr;
        const Expr either = Expr::op(boolean::Op::kUnion, {Expr::of(0), Expr::of(1)});
        const Expr both = Expr::op(boolean::Op::kIntersection, {Expr::of(0), Expr::of(1)});
        const auto start = Clock::now();
        auto x = boolean::evaluate_2d(pair, Expr::op(boolean::Op::kDifference, {either, both}));
        count_boolean(start, 0);
        check(x, n);
        acc = std::move(*x);
      }
      if (!acc) return std::nullopt;
      fill = std::move(*acc);
    }
    if (fill.empty()) return std::nullopt;
    if (!is_identity(t)) {
      if (t.m[2][0] != 0 || t.m[2][1] != 0) {
        fail(n.pos,
             "a 2D object moved out of the xy plane (only transforms within it are "
             "supported for 2D)");
      }
      if (t.m[0][0] * t.m[1][1] - t.m[0][1] * t.m[1][0] == 0) return std::nullopt;
      auto moved = shape::transformed(fill, t);
      check(moved, n);
      fill = std::move(*moved);
    }
    return from_shape(std::move(fill));
  }

  // hull, minkowski, offset, projection and resize of 2D children (projection: of 3D
  // ones), in the children's own frame, then moved by t.
  std::optional<Shape2> operation2(const Node& n, const shape::Transform& t) {
    shape::Shape2D result;
    if (n.kind == NodeKind::kProjection) {
      Node group;
      group.kind = NodeKind::kGroup;
      group.children = n.children;
      if (dimension(group) == 2) fail(n.pos, "projection() of a 2D object");
      Model m = build_children(n);
      if (m.num_faces() == 0) return std::nullopt;
      auto r = boolean::projection(m, {.cut = n.cut});
      check(r, n);
      result = std::move(*r);
    } else if (n.kind == NodeKind::kMinkowski) {
      std::vector<shape::Shape2D> parts;
      for (const Node* c : active_children(n)) {
        auto s = collect2(*c, shape::Transform::identity());
        if (!s) return std::nullopt;
        parts.push_back(to_shape(*s, n));
      }
      if (parts.empty()) return std::nullopt;
      auto r = boolean::minkowski_2d(parts);
      check(r, n);
      result = std::move(*r);
    } else {
      auto s = children2(n, shape::Transform::identity());
      if (!s) return std::nullopt;
      if (n.kind == NodeKind::kHull) {
        std::vector<Vec2> points;
        for (const auto& reg : s->regions) {
          for (const auto& l : reg.loops) points.insert(points.end(), l.begin(), l.end());
        }
        auto r = shape::convex_hull(points);
        check(r, n);
        result = shape::shape_of(std::move(*r));
      } else if (n.kind == NodeKind::kOffset) {
        const boolean::OffsetJoin join = n.round     ? boolean::OffsetJoin::kRound
                                         : n.chamfer ? boolean::OffsetJoin::kChamfer
                                                     : boolean::OffsetJoin::kMiter;
        auto r = boolean::offset(to_shape(*s, n),
                                 {.amount = n.delta, .join = join, .faceting = n.faceting});
        check(r, n);
        result = std::move(*r);
      } else {
        auto r = shape::resized(to_shape(*s, n), {.size = n.size, .autosize = n.auto_size});
        check(r, n);
        result = std::move(*r);
      }
    }
    if (!is_identity(t)) {
      auto moved = shape::transformed(result, t);
      check(moved, n);
      result = std::move(*moved);
    }
    return from_shape(std::move(result));
  }

  static void shift(boolean::Expr& e, int offset) {
    if (e.kind == boolean::Expr::Kind::kOperand) {
      e.operand += offset;
      return;
    }
    for (auto& c : e.children) shift(c, offset);
  }

  static bool union_only(const boolean::Expr& e) {
    if (e.kind == boolean::Expr::Kind::kOperand) return true;
    if (e.kind != boolean::Expr::Kind::kUnion) return false;
    for (const auto& c : e.children) {
      if (!union_only(c)) return false;
    }
    return true;
  }

  Model extrude(const Node& n) {
    Node group;
    group.kind = NodeKind::kGroup;
    group.children = n.children;
    if (dimension(group) == 3) fail(n.pos, std::string(node_name(n.kind)) + "() of a 3D object");
    auto s = collect2(group, shape::Transform::identity());
    if (!s) return Model();
    bool several = s->regions.size() > 1;
    // A set operation of regions extrudes as that set operation of the extrusions when
    // the sweep maps every plane section the same way (straight linear_extrude; a
    // rotate_extrude of a union with shared segments); otherwise it is evaluated in 2D.
    const bool distributes = n.kind == NodeKind::kLinearExtrude
                                 ? n.linear.twist == 0 && n.linear.scale_x == n.linear.scale_y
                                 : union_only(s->expr);
    if (several && !distributes) {
      s = from_shape(to_shape(*s, n));
      if (!s) return Model();
      several = s->regions.size() > 1;
    } else if (several) {
      // The 2D Boolean is cheap (planar.cpp): the profile evaluated first and its
      // disjoint regions swept is the same solid as the set operation of the swept
      // regions, without a 3D Boolean. A region the sweep refuses (a hole touching its
      // outer loop) falls back to the 3D route.
      auto flat = from_shape(to_shape(*s, n));
      if (!flat) return Model();
      if (auto m = sweep(n, *flat, false)) return std::move(*m);
    }
    return *sweep(n, *s, true);
  }

  // The regions of s swept as n says and combined by s's expression; with strict, a
  // sweep's error is the build's, otherwise it gives nullopt.
  std::optional<Model> sweep(const Node& n, const Shape2& s, bool strict) {
    const bool several = s.regions.size() > 1;
    std::vector<Leaf> leaves(s.regions.size());
    auto swept = [&](const auto& r) {
      if (strict) check(r, n);
      return r.ok();
    };
    if (n.kind == NodeKind::kLinearExtrude) {
      if (n.linear.height <= 0) return Model();
      shape::LinearExtrudeOptions o = n.linear;
      if (o.scale_x < 0 || o.scale_y < 0)
        fail(n.pos, "linear_extrude(): scale must not be negative");
      if (several && o.slices == 0) {
        // OpenSCAD's slice count is the whole profile's.
        shape::Region all;
        for (const auto& reg : s.regions)
          all.loops.insert(all.loops.end(), reg.loops.begin(), reg.loops.end());
        o.slices = shape::extrude_slices(all, o);
      }
      for (std::size_t i = 0; i < s.regions.size(); ++i) {
        if (!swept(shape::linear_extrude(leaves[i].model, s.regions[i], o))) return std::nullopt;
      }
    } else {
      shape::RotateExtrudeOptions o = n.rotate;
      if (o.angle == 0) return Model();
      o.angle = std::clamp(o.angle, -360.0, 360.0);
      double r = 0;
      for (const auto& reg : s.regions) {
        for (const auto& l : reg.loops) {
          for (Vec2 p : l) r = std::max(r, std::fabs(p.x));
        }
      }
      check_segments(n, r, n.rotate.faceting);
      if (several) {
        // The same segments for every region: those of the whole profile.
        o.faceting =
            shape::Faceting{.fn = static_cast<double>(shape::fragments(r, n.rotate.faceting))};
      }
      for (std::size_t i = 0; i < s.regions.size(); ++i) {
        if (!swept(shape::rotate_extrude(leaves[i].model, s.regions[i], o))) return std::nullopt;
      }
    }
    return combine(s.expr, leaves, n.pos, nullptr);
  }

  template <class F>
  void tally(F&& f) {
    std::lock_guard hold(stats_lock_);
    f(stats_);
  }

  // A Boolean (3D, or 2D with no operands counted) that took from `start` to now.
  // `report`: a 3D Boolean's, listed in BuildStats::boolean_list.
  void count_boolean(Clock::time_point start, std::size_t operands, bool in_frame = false,
                     const boolean::Report* report = nullptr) {
    const double seconds = seconds_since(start);
    tally([&](BuildStats& s) {
      s.boolean_seconds += seconds;
      ++s.booleans;
      s.booleans_in_frame += in_frame;
      s.boolean_operands += operands;
      if (!report) return;
      const boolean::StageTimes& t = report->seconds;
      s.boolean_list.push_back({operands, report->input_triangles, report->candidate_pairs,
                                report->intersecting_pairs, report->pieces, report->rays,
                                report->implicit_points, t.soup, t.intersect, t.split, t.classify,
                                t.output, t.check, seconds});
    });
  }

  // n's value from `memo` by its content key, made by make() the first time in this
  // build (any other time counts as a memo hit).
  template <class V, class Make>
  V memoized(OnceMap<V>& memo, const Node& n, Make&& make) {
    bool made = false;
    V v = memo.get(keys_(n), std::forward<Make>(make), made);
    if (!made) tally([&](BuildStats& s) { ++s.memo_hits; });
    return v;
  }

  const BuildOptions& options_;
  DiskCache cache_;
  ContentKeys keys_;
  std::mutex stats_lock_;
  BuildStats stats_;
  // Within one build, by content key: leaves, and subtrees built whole (their
  // geometry and their own colors; a color from above is the caller's).
  OnceMap<Model> leaf_memo_;
  OnceMap<Built> subtree_memo_;
};

}  // namespace

Result<BuildOutput> build(const Node& root, const BuildOptions& options) {
  Builder b(options, root);
  try {
    BuildOutput out = b.run(root);
    std::vector<BooleanStats>& list = out.stats.boolean_list;
    const auto key = [](const BooleanStats& x) {
      return std::tuple(x.triangles, x.operands, x.candidate_pairs, x.pieces, x.points);
    };
    std::stable_sort(list.begin(), list.end(),
                     [&](const BooleanStats& x, const BooleanStats& y) { return key(x) > key(y); });
    return out;
  } catch (const BuildError& e) {
    return Error{ErrorCode::kInvalidInput,
                 options.sources ? options.sources->format(e.pos, e.message) : e.message};
  }
}

}  // namespace cellforge::csg
