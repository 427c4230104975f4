// The arrangement of all operands' triangles (stages 1 and 2 of DESIGN.md's
// Boolean) and the exact predicates on its points.
//
// Notation. Input vertices are explicit points (doubles). Triangles that are
// coplanar and overlap with positive area form one *cluster*, cut as one planar
// arrangement so that coincident pieces of different operands are one piece. A
// cluster works in 2D: the coordinates (u, v) are the axes (k+1, k+2) mod 3, k the
// dominant axis of its reference triangle's normal n, so a polygon counterclockwise
// in (u, v) turns counterclockwise about n when n_k > 0. Lines of a cluster are
// A u + B v + C = 0: through two input vertices (an edge), the trace of another
// triangle's plane, or an axis-parallel side of the cluster's bounding box.
//
// Points are homogeneous, (X, Y, Z, W) in 3D and (U, V, W) in a cluster
// (geom/implicit.h):
//   vertex  an input vertex: an explicit point                    (x, y, z, 1)
//   lpi     segment pq meets the plane of a triangle (implicit.h's lpi)
//   cross   two lines of a cluster meet: (U, V, W) = (A1,B1,C1) x (A2,B2,C2),
//           lifted onto the cluster's plane n.P = n.a by P_k = (n.a W - n_u U - n_v V)/n_k
// Every predicate is a sign of a polynomial in these, evaluated on Fp and, only when
// that cannot decide, on Dyadic (filtered.h). Nothing is ever rounded until the
// result is built.
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <shared_mutex>
#include <span>
#include <type_traits>
#include <unordered_map>
#include <utility>
#include <vector>

#include "boolean/flat_map.h"
#include "boolean/parallel.h"
#include "cellforge/geom/bvh.h"
#include "cellforge/geom/implicit.h"
#include "cellforge/geom/memory.h"
#include "cellforge/geom/vec.h"
#include "cellforge/ids.h"

namespace cellforge::boolean {

// 20 bytes: the operand model's face it triangulates is faces[input_face].face.
struct Tri {
  std::array<std::uint32_t, 3> v;  // input vertices, counterclockwise seen from outside
  std::uint32_t operand = 0;
  std::uint32_t input_face = 0;  // index into Arrangement::faces
};

// A face's tiles: the consecutive soup triangles first, first + 1, ... (a face's
// tiles are made together), iterated and indexed as a list of triangle ids.
class TileRange {
 public:
  class iterator {
   public:
    using value_type = std::uint32_t;
    using difference_type = std::ptrdiff_t;
    iterator() = default;
    explicit iterator(std::uint32_t i) : i_(i) {}
    std::uint32_t operator*() const { return i_; }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    iterator operator++(int) { return iterator(i_++); }
    bool operator==(const iterator&) const = default;

   private:
    std::uint32_t i_ = 0;
  };
  // The next tile, which must be triangle first + size().
  void push_back(std::uint32_t t) {
    if (count_ == 0) first_ = t;
    ++count_;
  }
  std::uint32_t operator[](std::size_t k) const { return first_ + static_cast<std::uint32_t>(k); }
  // The same tiles, their list moved `by` places later.
  void shift(std::uint32_t by) { first_ += by; }
  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  iterator begin() const { return iterator(first_); }
  iterator end() const { return iterator(first_ + count_); }

 private:
  std::uint32_t first_ = 0, count_ = 0;
};

// The operand faces' loops of input vertices, all in one table: loop i is
// points[begin[i]] .. points[begin[i + 1]).
class LoopTable {
 public:
  std::uint32_t add(std::span<const std::uint32_t> loop) {
    points_.insert(points_.end(), loop.begin(), loop.end());
    begin_.push_back(static_cast<std::uint32_t>(points_.size()));
    return static_cast<std::uint32_t>(begin_.size() - 2);
  }
  std::span<const std::uint32_t> operator[](std::uint32_t i) const {
    return {points_.data() + begin_[i], begin_[i + 1] - begin_[i]};
  }
  std::uint32_t size() const { return static_cast<std::uint32_t>(begin_.size() - 1); }
  // Another table's loops after these (their numbers shifted by size()).
  void append(const LoopTable& o) {
    const auto base = static_cast<std::uint32_t>(points_.size());
    points_.insert(points_.end(), o.points_.begin(), o.points_.end());
    for (std::size_t i = 1; i < o.begin_.size(); ++i) begin_.push_back(base + o.begin_[i]);
  }
  void clear() {
    std::vector<std::uint32_t>().swap(points_);
    begin_.assign(1, 0);
  }

 private:
  std::vector<std::uint32_t> points_;
  std::vector<std::uint32_t> begin_{0};
};

// A face's loops: `count` consecutive loops of a LoopTable from `first`.
struct FaceLoops {
  const LoopTable* table = nullptr;
  std::uint32_t first = 0, count = 0;
  class iterator {
   public:
    using value_type = std::span<const std::uint32_t>;
    using difference_type = std::ptrdiff_t;
    iterator() = default;
    iterator(const LoopTable* t, std::uint32_t i) : t_(t), i_(i) {}
    std::span<const std::uint32_t> operator*() const { return (*t_)[i_]; }
    iterator& operator++() {
      ++i_;
      return *this;
    }
    iterator operator++(int) { return iterator(t_, i_++); }
    bool operator==(const iterator& o) const { return i_ == o.i_; }

   private:
    const LoopTable* t_ = nullptr;
    std::uint32_t i_ = 0;
  };
  std::span<const std::uint32_t> operator[](std::size_t k) const {
    return (*table)[first + static_cast<std::uint32_t>(k)];
  }
  std::size_t size() const { return count; }
  bool empty() const { return count == 0; }
  iterator begin() const { return {table, first}; }
  iterator end() const { return {table, first + count}; }
};

// An operand face as it was: its loops of input vertices (Arrangement::loops_of), and
// whether the Boolean sees it reversed (a face with its cell in front).
struct SoupFace {
  std::uint32_t operand = 0, face = 0;
  std::uint32_t first_loop = 0, loop_count = 0;  // in Arrangement::loop_table
  TileRange tris;
  bool flipped = false;  // the model's face points into its cell: reversed here
  bool sheet = false;    // a face with no cell on either side: it bounds nothing, and
                         // its points are the operand's (non-regularized operations)
  // Every vertex of the loops on the plane of the first triangle, exactly. Decided once
  // here: a faceted curved primitive's quads are planar only in exact arithmetic, so
  // each of their tests goes to the exact stage, and the pair tests, the patch
  // classification and the merge all ask it.
  bool planar = true;
  // Planar, of one loop, strictly convex and winding once, with every tile kept: its
  // tiles meet only in their shared edges and corners, so no pair of them is tested
  // (they are joined as one plane instead).
  bool convex = false;
  // Planar, and its tiles meet only in their shared edges and corners: convex, or
  // certified so (boolean.cpp, simple_face: the loops simple and apart, every tile
  // turning one way). No pair of its tiles is tested.
  bool simple = false;
  // A face of one loop of four vertices (a quad of a faceted curved primitive; the
  // loop is loops_of(f)[0]), and the sign of orient3d over that loop in its order, so
  // that any tile's test of the fourth vertex is a permutation of it (sides_of).
  bool quad = false;
  std::int8_t fold = 0;
};

enum class LineKind : std::uint8_t { kThrough, kTrace, kAxisU, kAxisV };
struct Line {
  LineKind kind = LineKind::kThrough;
  std::uint32_t a = 0, b = 0;  // kThrough: vertices a, b; kTrace: triangle a
  double c = 0;                // kAxisU: u = c; kAxisV: v = c
  Fp A, B, C;                  // the coefficients, filtered
  std::int8_t sign_a = 0, sign_b = 0;  // the signs of A and B, exactly (add_line)
  // 1: the line is u = at, 2: v = at, a double known exactly (an axis line, an edge
  // whose ends share that coordinate, the trace of a plane perpendicular to that
  // axis); 0: neither (add_line). Sides on it then compare one known coordinate.
  std::int8_t fixed = 0;
  double at = 0;
  std::uint32_t key = 0;       // global line key (Arrangement::line_key)
  std::vector<std::uint32_t> points;  // points found on it

  static Line make(LineKind kind, std::uint32_t a, std::uint32_t b = 0, double c = 0) {
    Line l;
    l.kind = kind;
    l.a = a;
    l.b = b;
    l.c = c;
    return l;
  }
};

enum class PointKind : std::uint8_t { kVertex, kLpi, kCross, kMeet };
struct PointDef {
  PointKind kind = PointKind::kVertex;
  std::uint32_t a = 0, b = 0, c = 0;  // vertex a | lpi p=a q=b plane of triangle c |
                                      // cross: cluster a, lines b, c |
                                      // meet: segment ab and Arrangement::meets[c]
};

// A wire edge of an operand (p != q), or an isolated point (p == q): input vertices.
struct WireSeg {
  std::uint32_t p = 0, q = 0, operand = 0;
};

struct Piece {
  std::vector<std::uint32_t> pts;    // counterclockwise in the cluster's (u, v)
  std::vector<std::uint32_t> lines;  // lines[i] carries the edge pts[i] -> pts[i+1]
  Box box2;                          // (u, v) bounds, z unused
};

struct Constraint {
  std::uint32_t other_cluster;  // the trace of that cluster's plane
  std::uint32_t other_tri;
  std::uint32_t p, q;  // where the other triangle meets this plane
  std::uint32_t tri;   // this cluster's triangle that the other one met
};

// What a cut cluster holds. Most clusters (one per input triangle) are near nothing and
// hold none of it: one pointer for all four lists, made on the first push_back.
struct ClusterCuts {
  std::vector<std::uint32_t> tris;  // the cluster's triangles, when it has several
  std::vector<Constraint> constraints;
  std::vector<std::uint32_t> touch_points;  // input vertices touching it inside
  std::vector<Line> lines;
  std::vector<Piece> pieces;
};

// One of a cluster's lists, seen through the cluster's block (Cluster::lines() ...):
// reading never makes the block, push_back does.
template <class T, std::vector<T> ClusterCuts::*kList, bool kConst>
class CutList {
  using Block = std::conditional_t<kConst, const std::unique_ptr<ClusterCuts>, std::unique_ptr<ClusterCuts>>;
  using Elem = std::conditional_t<kConst, const T, T>;

 public:
  explicit CutList(Block& block) : block_(&block) {}
  std::size_t size() const { return list() ? list()->size() : 0; }
  bool empty() const { return size() == 0; }
  Elem* begin() const { return list() ? list()->data() : nullptr; }
  Elem* end() const { return list() ? list()->data() + list()->size() : nullptr; }
  Elem* data() const { return begin(); }
  Elem& operator[](std::size_t i) const { return (*list())[i]; }
  Elem& back() const { return list()->back(); }
  void push_back(T x) const
    requires(!kConst)
  {
    if (!*block_) *block_ = std::make_unique<ClusterCuts>();
    ((**block_).*kList).push_back(std::move(x));
  }
  void release() const
    requires(!kConst)
  {
    if (*block_) std::vector<T>().swap((**block_).*kList);
  }

 private:
  auto* list() const { return *block_ ? &((**block_).*kList) : nullptr; }
  Block* block_;
};

// 24 bytes a recorded cluster (the triangles along the intersection curves, those
// in one plane with another, those something touches; the rest are lone, unrecorded).
struct Cluster {
  // Its triangles: one, the common case, held in place; several in the block.
  std::span<const std::uint32_t> tris() const {
    return n_tris_ <= 1 ? std::span<const std::uint32_t>(&first_tri_, n_tris_) : std::span<const std::uint32_t>(cuts->tris);
  }
  void add_tri(std::uint32_t t) {
    if (n_tris_ == 0) {
      first_tri_ = t;
    } else {
      if (!cuts) cuts = std::make_unique<ClusterCuts>();
      if (cuts->tris.empty()) cuts->tris.push_back(first_tri_);
      cuts->tris.push_back(t);
    }
    ++n_tris_;
  }
  std::uint32_t ref = 0;     // reference triangle (its plane)
  std::int8_t k = 2;         // dominant axis of the reference normal
  std::int8_t nk_sign = 1;   // sign of the reference normal's component k
  bool touched = false;      // cut by anything, or several triangles
  std::unique_ptr<ClusterCuts> cuts;

  template <class T, std::vector<T> ClusterCuts::*kList>
  using List = CutList<T, kList, false>;
  template <class T, std::vector<T> ClusterCuts::*kList>
  using ConstList = CutList<T, kList, true>;
  List<Constraint, &ClusterCuts::constraints> constraints() { return List<Constraint, &ClusterCuts::constraints>(cuts); }
  ConstList<Constraint, &ClusterCuts::constraints> constraints() const {
    return ConstList<Constraint, &ClusterCuts::constraints>(cuts);
  }
  List<std::uint32_t, &ClusterCuts::touch_points> touch_points() {
    return List<std::uint32_t, &ClusterCuts::touch_points>(cuts);
  }
  ConstList<std::uint32_t, &ClusterCuts::touch_points> touch_points() const {
    return ConstList<std::uint32_t, &ClusterCuts::touch_points>(cuts);
  }
  List<Line, &ClusterCuts::lines> lines() { return List<Line, &ClusterCuts::lines>(cuts); }
  ConstList<Line, &ClusterCuts::lines> lines() const { return ConstList<Line, &ClusterCuts::lines>(cuts); }
  List<Piece, &ClusterCuts::pieces> pieces() { return List<Piece, &ClusterCuts::pieces>(cuts); }
  ConstList<Piece, &ClusterCuts::pieces> pieces() const { return ConstList<Piece, &ClusterCuts::pieces>(cuts); }

 private:
  std::uint32_t first_tri_ = 0, n_tris_ = 0;
};

// A point strictly inside a piece: the centroid of three of its vertices that do
// not lie on one line.
struct RepPoint {
  std::uint32_t cluster;
  std::array<std::uint32_t, 3> p;
};

// Every edge of every triangle, grouped by edge: the uses of edge {p, q} (p < q) lie
// in p's row, ordered by q, then by triangle. 8 bytes a use and 4 a point, made
// without a second copy (counted into place), where a sorted list of 64-bit keys
// took 16 a use and a copy to sort.
class EdgeUseTable {
 public:
  struct Use {
    std::uint32_t q;    // the edge's larger end
    std::uint32_t bits;  // triangle << 1 | forward (the triangle runs p -> q)
    std::uint32_t tri() const { return bits >> 1; }
    bool forward() const { return (bits & 1) != 0; }
  };
  EdgeUseTable() = default;
  // The edges of triangles (ids: triangles).
  EdgeUseTable(std::span<const Tri> tris, std::size_t n_points, int threads = 1);
  // The edges that edges_of(lo, hi, emit) gives for the ids in [lo, hi), by emit(p, q,
  // id) (p != q, both below n_points; id below 2^31) in increasing id: called twice on
  // each of up to `threads` ranges of [0, n_ids), on threads, to count and to fill.
  // Range k's uses of a row go after those of the ranges before it, so a row lists its
  // uses in id order (then sorted by q, stably): the same table at any thread count.
  template <class EdgesOf>
  EdgeUseTable(std::size_t n_points, std::size_t n_ids, EdgesOf&& edges_of, int threads = 1)
      : start_(n_points + 1, 0) {
    // At most eight ranges: each keeps a count a point (a many-core machine would
    // otherwise hold hundreds of MB of them for a big table).
    const std::size_t parts = std::max<std::size_t>(
        1, std::min<std::size_t>({static_cast<std::size_t>(thread_count(threads)), 8, n_ids / 4096}));
    auto range = [&](std::size_t k) { return std::pair{n_ids * k / parts, n_ids * (k + 1) / parts}; };
    // at[k][v]: range k's uses of row v, counted, then where the next one goes.
    std::vector<std::vector<std::uint32_t>> at(parts, std::vector<std::uint32_t>(n_points, 0));
    on_threads(parts, [&](std::size_t k) {
      const auto [lo, hi] = range(k);
      std::vector<std::uint32_t>& count = at[k];
      edges_of(lo, hi, [&](std::uint32_t p, std::uint32_t q, std::uint32_t) { ++count[std::min(p, q)]; });
    });
    for (std::size_t v = 0; v < n_points; ++v) {
      std::uint32_t next = start_[v];
      for (std::size_t k = 0; k < parts; ++k) next += std::exchange(at[k][v], next);
      start_[v + 1] = next;
    }
    uses_.resize(start_[n_points]);
    on_threads(parts, [&](std::size_t k) {
      const auto [lo, hi] = range(k);
      std::vector<std::uint32_t>& next = at[k];
      edges_of(lo, hi, [&](std::uint32_t p, std::uint32_t q, std::uint32_t id) {
        uses_[next[std::min(p, q)]++] = {std::max(p, q), id << 1 | (p < q ? 1u : 0u)};
      });
    });
    at.clear();
    sort_rows(threads);
  }

  std::size_t size() const { return uses_.size(); }
  std::size_t rows() const { return start_.empty() ? 0 : start_.size() - 1; }
  // f(p, q, uses) for every edge, by p, then q.
  template <class F>
  void each_edge(F&& f) const {
    each_edge_from(0, rows(), f);
  }
  // The same for the edges whose smaller end p is in [lo, hi): ranges of rows for
  // threads.
  template <class F>
  void each_edge_from(std::size_t lo, std::size_t hi, F&& f) const {
    for (auto p = static_cast<std::uint32_t>(lo); p < hi; ++p)
      for (std::uint32_t i = start_[p], end = start_[p + 1]; i < end;) {
        std::uint32_t j = i + 1;
        while (j < end && uses_[j].q == uses_[i].q) ++j;
        f(p, uses_[i].q, std::span<const Use>(uses_.data() + i, j - i));
        i = j;
      }
  }
  // What f(p, q, uses, out) pushes into `out` for every edge, found on `threads`
  // threads by ranges of rows and joined in the edges' order (the same list at any
  // count).
  template <class T, class F>
  std::vector<T> gather(int threads, F&& f) const {
    const std::vector<std::vector<T>> parts =
        parallel_ranges<std::vector<T>>(rows(), threads, [&](std::size_t lo, std::size_t hi, std::vector<T>& out) {
          each_edge_from(lo, hi, [&](std::uint32_t p, std::uint32_t q, std::span<const Use> uses) { f(p, q, uses, out); });
        });
    std::vector<T> all;
    for (const std::vector<T>& part : parts) all.insert(all.end(), part.begin(), part.end());
    return all;
  }
  // The uses of edge {p, q} (either order); empty when no triangle has it.
  std::span<const Use> uses(std::uint32_t p, std::uint32_t q) const;
  void clear() {
    std::vector<std::uint32_t>().swap(start_);
    RawVector<Use>().swap(uses_);
  }

 private:
  void sort_rows(int threads);  // each row by q, stably
  std::vector<std::uint32_t> start_;  // by point: its row uses_[start_[p]] .. uses_[start_[p + 1]]
  RawVector<Use> uses_;
};

// Which operands' triangles certainly form one closed surface embedded in space,
// decided by exact predicates: closed and oriented, star-shaped from a point that
// every triangle's plane has on one side, covering the directions from it once.
// Spheres, cylinders, cubes and every convex part pass. Then two of its triangles meet
// only in the corners and edges they share, and no pair of them need be tested.
// `candidates`: by operand, whether to try (its faces all bound one cell on one side:
// no sheet, wire or point). `joins` gets the certified operands' pairs of triangles
// from different faces that share an edge and lie in one plane. `edges`: the
// triangles' edge uses.
std::vector<char> embedded_operands(const std::vector<Vec3>& pos, std::span<const Tri> tris,
                                    const EdgeUseTable& edges, const std::vector<char>& candidates,
                                    int threads, std::vector<std::array<std::uint32_t, 2>>& joins);

struct SplitScratch;  // split.cpp

class Arrangement {
 public:
  // embedded: by operand, whether its own triangles are known to meet only in the
  // corners and edges they share (embedded_operands), so that no pair of them is
  // tested; plane_joins: pairs of those triangles that lie in one plane; edges: the
  // triangles' edge uses. The tree of the triangles' boxes is built on `threads`.
  Arrangement(std::vector<Vec3> positions, std::vector<Tri> tris, std::vector<SoupFace> faces,
              LoopTable loops, std::uint32_t operands, std::vector<WireSeg> wires,
              std::vector<char> embedded, std::vector<std::array<std::uint32_t, 2>> plane_joins,
              EdgeUseTable edges, int threads = 1);

  // Stage 1: candidate pairs, exact tests, clusters and their constraints.
  // Stage 1 on `threads` threads (0: all); the same result at any count.
  void intersect(int threads = 1);
  // Stage 2: each cluster cut into pieces: along its segments alone (split.cpp), or,
  // where that would make a face pass a point twice or segment_split is off, into
  // convex pieces along the segments' whole lines.
  void split();
  bool segment_split = true;
  std::size_t convex_splits = 0;  // clusters cut the convex way
  // The operands' wire edges cut where they cross a face, an edge or another wire, or
  // pass through a vertex (wire_pieces); points on input edges are recorded there.
  void split_wires();
  // Frees what only stages 1 to 4 read (the pieces, the constraints, the triangles'
  // boxes and tree), before the result is built; with keep_tree, the triangles' boxes
  // and tree and their edge uses stay (for classify_sites and only_operand_near).
  void release_pieces(bool keep_tree = false);
  // Frees the input faces' loops, once the result's faces that copy them are made.
  void release_loops();
  // Frees everything: a regularized result's faces, points and sources are made.
  void release_all();

  // ---- data
  std::vector<Vec3> pos;
  std::vector<Tri> tris;
  // By triangle, for the tiles of a quad: the quad's fourth vertex and its side of the
  // tile's plane (sides_of); kInvalidIndex elsewhere. Set by intersect(), which frees them
  // at its end.
  std::vector<std::uint32_t> quad_other;
  std::vector<std::int8_t> quad_side;
  // By triangle: bit e set when its edge e (v[e] -> v[e + 1]) is a diagonal of its
  // planar face with the face's other tile at that edge in the same cluster. The split
  // makes no segment of it (pieces run across it), and covers() counts a point on it
  // as inside. Set by split().
  std::vector<std::uint8_t> open_edges;
  std::vector<SoupFace> faces;
  LoopTable loop_table;  // the faces' loops
  FaceLoops loops_of(const SoupFace& f) const { return {&loop_table, f.first_loop, f.loop_count}; }
  std::vector<WireSeg> wires;        // the operands' wire edges and isolated points
  std::vector<WireSeg> wire_pieces;  // after split_wires: points (p == q) stay
  std::vector<Box> wire_boxes;
  Bvh wire_bvh;
  // kMeet points: where segment (a, b) of the point meets segment (s, t) lying in one
  // plane with it, computed in the projection along axis k: {s, t, k}.
  std::vector<std::array<std::uint32_t, 3>> meets;
  std::uint32_t operands = 0;
  std::vector<char> embedded;  // by operand (constructor)
  std::vector<std::array<std::uint32_t, 2>> plane_joins;
  EdgeUseTable edge_uses;  // of tris
  Bvh bvh;  // over the triangles' boxes (bvh.box(t))
  // By triangle: its cluster. A triangle that nothing cuts, touches or lies in one
  // plane with (most triangles of big operands: all but those along the intersection
  // curves) is a cluster of its own with no record, kLoneCluster | t; the records are
  // those of the other clusters, clusters[ci]. A record a triangle cost 28 bytes (the
  // Cluster and plane_of), 56 MB for two spheres of 10^6 triangles.
  std::vector<std::uint32_t> cluster_of;
  // By recorded cluster: the first cluster found to lie in the same plane (coplanar
  // triangles that were tested as a pair, such as the two halves of a planar quad).
  // Points are keyed by plane rather than cluster, so that one point has one id.
  std::vector<std::uint32_t> plane_of;
  std::vector<Cluster> clusters;
  static constexpr std::uint32_t kLoneCluster = 1u << 31;  // triangles: fewer than 2^31
  static bool is_lone(std::uint32_t ci) { return ci != kInvalidIndex && (ci & kLoneCluster) != 0; }
  std::uint32_t plane_key(std::uint32_t ci) const { return is_lone(ci) ? ci : plane_of[ci]; }
  std::uint32_t cluster_ref(std::uint32_t ci) const { return is_lone(ci) ? ci & ~kLoneCluster : clusters[ci].ref; }
  bool cluster_touched(std::uint32_t ci) const { return !is_lone(ci) && clusters[ci].touched; }
  // Cluster ci: its record, or for a lone triangle's id one made in `scratch`.
  const Cluster& cluster(std::uint32_t ci, Cluster& scratch) const;
  // The cluster's axis k and the sign of its reference normal's k component.
  void orient_cluster(Cluster& c) const;
  std::vector<PointDef> points;  // ids below pos.size() are the input vertices
  std::vector<H3<Fp>> h3f;       // by point id - pos.size()
  std::vector<H2<Fp>> h2f;       // home-cluster coordinates of cross points (else unused)
  // Points found on input edges by the pair tests (vertex on an edge).
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edge_points;  // (line key, point)
  // Input edges {min, max} (as one 64-bit key) that lie in the plane of another
  // triangle and run inside it or belong to another operand: the surface may pass from
  // one side of that plane to the other across the edge, so untouched triangles are
  // not joined into one patch there (classify.cpp). Sorted, no repeats.
  std::vector<std::uint64_t> contact_edges;
  bool is_contact_edge(std::uint32_t p, std::uint32_t q) const;
  // By triangle: whether a triangle of another operand came near it (their boxes met).
  // Set by intersect().
  std::vector<char> near_other;
  // By input vertex: the operand of its triangles when none of them came near another
  // operand's (nothing of another operand reaches the vertex, nor the triangles' edges
  // at it), else kInvalidIndex (and for a vertex of no triangle). Set by
  // find_alone_vertices(), which the non-regularized output calls.
  std::vector<std::uint32_t> alone_in;
  void find_alone_vertices();
  // Whether pq is an edge of a triangle (a search of the edge uses, which
  // release_pieces keeps only with keep_tree).
  bool is_triangle_edge(std::uint32_t p, std::uint32_t q) const;

  // Global line keys: an input edge {p, q}, a pair of clusters {c1, c2} (the line
  // where their planes meet), or a fresh key for a bounding-box side. Keys of lines
  // found to coincide are joined (line_union).
  std::uint32_t edge_key(std::uint32_t p, std::uint32_t q);
  std::uint32_t pair_key(std::uint32_t c1, std::uint32_t c2);
  std::uint32_t fresh_key();
  std::uint32_t line_root(std::uint32_t key);
  void line_union(std::uint32_t a, std::uint32_t b);
  std::uint32_t find_edge_key(std::uint32_t p, std::uint32_t q) const;  // kInvalid if none
  FlatMap<std::uint64_t, std::uint32_t> key_ids;
  // By input vertex: whether an edge key names an edge at it (most have none, and
  // find_edge_key then answers without a lookup).
  std::vector<char> has_edge_key;
  std::vector<std::uint32_t> key_parent;

  std::size_t pairs_tested = 0, pairs_hit = 0;
  // Exact homogeneous coordinates of points that needed them, computed once; the lock
  // lets stages on threads share it.
  mutable std::unordered_map<std::uint32_t, H3<Dyadic>> exact3;
  // Their double-double coordinates, for points the filter left undecided (a point on a
  // line or plane by coincidence is asked again and again): under the same lock.
  mutable std::unordered_map<std::uint32_t, H3<Dd>> near3;
  // The same for crossing points in their own cluster's projection (point2).
  mutable std::unordered_map<std::uint32_t, H2<Dd>> near2;
  mutable std::unordered_map<std::uint32_t, H2<Dyadic>> exact2;
  mutable std::unique_ptr<std::shared_mutex> exact3_lock = std::make_unique<std::shared_mutex>();

  // ---- exact evaluation
  template <class T>
  H3<T> point3(std::uint32_t p) const;
  template <class T>
  H2<T> point2(const Cluster& c, std::uint32_t p) const;
  template <class T>
  std::array<T, 3> coeffs(const Cluster& c, const Line& l) const;
  template <class T>
  H3<T> rep3(const RepPoint& r) const;

  // ---- predicates
  int w3_sign(std::uint32_t p) const;                   // sign of W in 3D
  int w2_sign(const Cluster& c, std::uint32_t p) const;  // sign of W in the cluster
  int side(const Cluster& c, const Line& l, std::uint32_t p) const;
  // Order of p and q along l (direction (B, -A)): -1 when p comes first.
  int along(const Cluster& c, const Line& l, std::uint32_t p, std::uint32_t q) const;
  int orient2(const Cluster& c, std::uint32_t p, std::uint32_t q, std::uint32_t r) const;
  // Sign of A_m B_l - B_m A_l: how m's side of a point changes as it moves along l's
  // direction (B, -A); 0 when the lines are parallel.
  int turn(const Cluster& c, const Line& l, const Line& m) const;
  // sign(coordinate axis of p - coordinate axis of q)
  int compare3(std::uint32_t p, std::uint32_t q, int axis) const;
  // Whether coordinate `axis` of p is a double known from how p was made, without
  // arithmetic (an input vertex; a point of a segment, line or plane on which that
  // coordinate is constant), and then x is it.
  bool known_coordinate(std::uint32_t p, int axis, double& x) const;
  bool equal3(std::uint32_t p, std::uint32_t q) const;
  bool collinear3(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  // The input vertices known to lie on triangle t's plane without arithmetic: the four
  // corners of the planar quad it tiles, else its own three.
  std::span<const std::uint32_t> plane_vertices(const Tri& t) const;
  // Side of point p of the plane of input triangle t: sign n_t . (p - t0).
  // +1 when triangle t of cluster c turns the way c's reference does in c's (u, v),
  // -1 when it is reversed (decided when asked: one sign a cluster triangle rarely needs).
  int tri_sign(const Cluster& c, std::uint32_t t) const;
  int plane_side(std::uint32_t t, std::uint32_t p) const;

  // Approximate position (for boxes and output): value and error per coordinate.
  Vec3 approx3(std::uint32_t p, double* err = nullptr) const;
  // Whether p's position in the result (approx3, with the coordinates known_coordinate
  // gives) is known to be exact: always for input vertices; for implicit points when
  // each coordinate is known so, or the filter's arithmetic was exact and its quotient is.
  bool rounds_exactly(std::uint32_t p) const;
  // Whether coordinate `axis` of point p is exactly the double x (an exact test).
  bool coordinate_is(std::uint32_t p, int axis, double x) const;
  void approx2(const Cluster& c, std::uint32_t p, double& u, double& v, double& err) const;

 private:
  std::uint32_t new_point(PointDef def, const Cluster* home);
  struct PairEvents;
  void test_pair(std::uint32_t i, std::uint32_t j, PairEvents& ev) const;
  std::uint32_t lpi_point(std::uint32_t p, std::uint32_t q, std::uint32_t cluster);
  // Where lines li and m of cluster ci cross: an edge's line and another plane's trace
  // meet where the edge's segment meets that plane, an lpi point of lower degree than
  // the crossing of two lines lifted onto the plane, and shared with every other
  // cluster that finds it.
  std::uint32_t crossing_point(std::uint32_t ci, std::uint32_t li, std::uint32_t m);
  std::uint32_t add_line(Cluster& c, Line l);
  // Cluster c's line through input vertices p and q (an edge's), made once: `made`
  // maps edge keys to the lines made so far.
  std::uint32_t edge_line(Cluster& c, FlatMap<std::uint32_t, std::uint32_t>& made, std::uint32_t p,
                          std::uint32_t q);
  void add_pair(std::uint32_t t, std::uint32_t b);
  // Whether side pq of triangle t may be a diagonal of t's face (a side of no loop of
  // a planar face of several tiles), which the split leaves open (open_edges).
  bool may_be_diagonal(const Tri& t, std::uint32_t p, std::uint32_t q) const;
  bool segment_enters(const Tri& x, std::uint32_t p, std::uint32_t q, bool closed = false) const;
  // orient3d of y's corners against x's plane, into o (the plane set up once).
  void sides_of(const Tri& x, const Tri& y, int o[3]) const;
  void split_cluster(std::uint32_t ci);
  // Stage 2 by segments (split.cpp): cluster ci's faces cut along its segments alone,
  // into simple polygons that need not be convex. False, with the cluster as it was
  // (its lines' point lists emptied), where a face would pass a point twice; the
  // convex split (split_cluster) is then used.
  bool split_cluster_graph(std::uint32_t ci, SplitScratch& scratch);
  void mark_open_edges(const Cluster& c);  // sets open_edges for c's triangles
  bool split_piece(Cluster& c, std::uint32_t ci, std::size_t pi, std::uint32_t li,
                   std::uint32_t s0, std::uint32_t s1, std::vector<Piece>& out,
                   std::unordered_map<std::uint64_t, std::uint32_t>& crossings);
  void piece_box(const Cluster& c, Piece& p) const;

  // The point where segment pq meets the plane of a cluster, by ((p, q), cluster):
  // one segment may cross the planes of very many clusters (a plate's edge and the
  // planes of the cylinders through it).
  struct LpiKey {
    std::uint64_t segment;
    std::uint32_t cluster;
    bool operator==(const LpiKey&) const = default;
  };
  struct LpiKeyHash {
    std::size_t operator()(const LpiKey& k) const {
      std::uint64_t h = (k.segment ^ (static_cast<std::uint64_t>(k.cluster) << 1)) * 0x9E3779B97F4A7C15ull;
      return static_cast<std::size_t>(h ^ (h >> 32));
    }
  };
  std::unordered_map<LpiKey, std::uint32_t, LpiKeyHash> lpi_ids_;
};

}  // namespace cellforge::boolean
