// The Boolean's stages after the arrangement: classification and selection
// (classify.cpp), merging and stitching into a model (output.cpp), and the choice of
// doubles for the rounded points (rounding.cpp).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "boolean/arrangement.h"
#include "cellforge/geom/bvh.h"
#include "cellforge/boolean/boolean.h"
#include "cellforge/topo/builder.h"

namespace cellforge::boolean {

// Whether the tiles of a planar face (its triangles `tiles` of `tris`, its loops
// `loops`) meet only in the edges and corners they share, so that no pair of them need
// be tested: every tile turns one way; its edges pair up inside or run the loops; the
// loops are simple and apart; exactly one loop turns the tiles' way. Then the tiles
// over a point number the loops' winding about it, 0 or 1 (boolean.cpp).
bool simple_face(const std::vector<Vec3>& pos, const FaceLoops& loops, std::span<const Tri> tris,
                 const TileRange& tiles);

// A face of the result before merging: loops of arrangement points, counterclockwise
// about the result's outward normal, with the global line key of each edge
// (kInvalidIndex where none is known).
enum class FaceKind : std::uint8_t {
  kBoundary,  // the set on one side only: its back (as the loops turn)
  kSheet,     // the set on neither side: a face of no volume (non-regularized)
  kInner,     // the set on both sides: between two cells (Options::cells), or a cut
};

// Where an OutPoly's loops are: made (in `loops`), or still those of input face
// faces[tris[tri].input_face] or of input triangle tri, reversed when normal_sign < 0,
// to be made by build_result once the arrangement's pieces are freed (the selection
// then holds no lists for the faces nothing cut while the classification peaks).
enum class LoopSource : std::uint8_t { kMade, kFace, kTriangle };

// An OutPoly's line keys, by loop, by edge: one pointer, null for the many faces that
// keep none (an OutPoly is 48 bytes, not 64: 34 MB of them for two spheres of 10^6
// triangles took a mapping of their own, fresh pages, where 25 MB come from the heap).
class LoopKeys {
 public:
  LoopKeys() = default;
  LoopKeys(const LoopKeys& o)
      : lists_(o.lists_ ? std::make_unique<std::vector<std::vector<std::uint32_t>>>(*o.lists_) : nullptr) {}
  LoopKeys& operator=(const LoopKeys& o) {
    if (this != &o) *this = LoopKeys(o);
    return *this;
  }
  LoopKeys(LoopKeys&&) noexcept = default;
  LoopKeys& operator=(LoopKeys&&) noexcept = default;
  bool empty() const { return !lists_ || lists_->empty(); }
  std::vector<std::uint32_t>& operator[](std::size_t l) { return (*lists_)[l]; }
  const std::vector<std::uint32_t>& operator[](std::size_t l) const { return (*lists_)[l]; }
  void push_back(std::vector<std::uint32_t> keys) {
    if (!lists_) lists_ = std::make_unique<std::vector<std::vector<std::uint32_t>>>();
    lists_->push_back(std::move(keys));
  }
  void clear() { lists_.reset(); }

 private:
  std::unique_ptr<std::vector<std::vector<std::uint32_t>>> lists_;
};

struct OutPoly {
  std::vector<std::vector<std::uint32_t>> loops;
  // By loop, by edge; empty when the loops are an input face's or triangle's, whose
  // edges' keys are Arrangement::find_edge_key of their ends (input vertices, which
  // stay their own representatives): no lists for the faces nothing cut.
  LoopKeys keys;
  std::uint32_t cluster = kInvalidIndex;  // its plane; kInvalidIndex for a non-planar face
  std::int8_t normal_sign = 1;            // +1: outward normal along the cluster's reference
  std::uint32_t tri = 0;                  // the input triangle it lies on (provenance)
  FaceKind kind = FaceKind::kBoundary;
  bool mark = true;                       // whether the face's own points are in the set
  LoopSource source = LoopSource::kMade;
};

// An edge of the arrangement's faces (a piece's side, an untouched triangle's edge)
// with its global line key, for the lower-dimensional parts of a non-regularized
// result. `settled`: the operand whose face it bounds, when that face is dropped and
// the set is the same on its front, its back and on it, the operand's membership
// differing between the two sides: then the set does not depend on that operand's
// membership there, and wherever no other operand's element comes near the side, every
// point around it and on it has that verdict (nothing of the lower-dimensional parts
// lies there, and no ray need tell). kInvalidIndex otherwise.
struct OutSide {
  std::uint32_t p, q, key;
  std::uint32_t settled = kInvalidIndex;
};

struct Selection {
  std::vector<OutPoly> polys;
  std::vector<OutSide> sides;  // Options::keep_lower_dim only
};

// Stages 3 and 4: winding numbers of every piece's two sides by exact ray casting,
// the expression on them, and the kept pieces as faces.
// On `threads` threads (0: all); the same result at any count.
Selection classify_and_select(const Arrangement& a, const Expr& expr, const Options& options,
                              Report& report);

// For non-regularized results: at each site (p, q) of the arrangement, a point (p == q)
// or the open segment pq (sampled at (p + 2q) / 3), whether it is in the set, and
// whether the points next to it are (where no face separates them, the region around).
// With both_sides, also whether it lies on a face between points in and out of the set
// (next to it on two sides along some axis, the verdicts differ): five more rays.
struct SiteVerdict {
  bool in = false, around = false, on_face = false;
  std::int8_t axis = 2;  // the axis of the ray that gave `around` (+axis)
};
// The ray of each site runs up `axes[k]` when given, else up the axis along which the
// site is nearest the top of the operands' bounding box (fewest triangles to cross,
// most often): `in` does not depend on it, `around` is taken on that ray's side. With
// `both_sides`, the rays along the five other directions tell `on_face`.
std::vector<SiteVerdict> classify_sites(const Arrangement& a, const Expr& expr,
                                        const std::vector<std::array<std::uint32_t, 2>>& sites,
                                        int threads, bool both_sides = false,
                                        const std::vector<std::int8_t>& axes = {});

// Stages 5 and 6: one vertex per exact position, every vertex of a line on each edge
// along it, coplanar neighbours and collinear edges merged, coordinates rounded, and
// the faces built into one group with a cell per connected solid.
Result<BooleanResult> build_result(Arrangement& a, Selection selection, const Expr& expr,
                                   const Options& options, Report& report);

// Boxes of triangles for the rounding checks (rounding.cpp): a triangle much longer
// than the typical one (a sliver of a face with many holes) takes the boxes of the
// pieces left by halving its longest edge until each is about typical, so that a few
// slivers across a part do not make every query visit most of the tree. Every box is
// grown by a few units in the last place (a vertex may move that much, and the
// pieces' corners are rounded).
class TriangleBoxes {
 public:
  // The tree built on `threads` (the same at any count).
  explicit TriangleBoxes(const std::vector<std::array<Vec3, 3>>& tris, int threads = 1);
  // Calls f(j) once for each triangle j with a box meeting one of triangle i's.
  template <class F>
  void near(std::uint32_t i, std::vector<std::uint32_t>& scratch, F&& f) const {
    scratch.clear();
    for (std::uint32_t k = begin_[i]; k < begin_[i + 1]; ++k) collect(boxes_[k], scratch);
    finish(scratch, f);
  }
  // Every pair of triangles i < j with boxes that meet, as i << 32 | j, ascending
  // (the pieces of one triangle are never paired with each other: one walk of the
  // tree for all pairs, where near() for every triangle walks it once a piece).
  // Only the pairs for which keep(i, j) is true, when keep is given: it is asked as
  // each pair is found, so that the pairs it drops are neither stored nor sorted (a
  // check's pairs of neighbours, most of what the tree finds).
  using Keep = std::function<bool(std::uint32_t, std::uint32_t)>;
  std::vector<std::uint64_t> pairs(int threads, const Keep& keep = nullptr) const;
  // The pairs with at least one marked triangle (marked[i] is 0 or 1), ascending: from
  // every pair when most are marked, else from near() of each marked one (a check of
  // a result with few rounded vertices walks the tree for those alone).
  std::vector<std::uint64_t> pairs_with(const std::vector<char>& marked, int threads, const Keep& keep = nullptr) const;
  // Calls f(j) once for each triangle j with a box meeting `box`.
  template <class F>
  void near(const Box& box, std::vector<std::uint32_t>& scratch, F&& f) const {
    scratch.clear();
    collect(box, scratch);
    finish(scratch, f);
  }

 private:
  void collect(const Box& box, std::vector<std::uint32_t>& out) const {
    bvh_.query([&](const auto& b) { return b.overlaps(box); }, [&](std::uint32_t k) { out.push_back(owner_[k]); });
  }
  template <class F>
  static void finish(std::vector<std::uint32_t>& found, F& f) {
    std::sort(found.begin(), found.end());
    found.erase(std::unique(found.begin(), found.end()), found.end());
    for (std::uint32_t j : found) f(j);
  }
  std::vector<Box> boxes_;            // by piece
  std::vector<std::uint32_t> owner_;  // by piece: its triangle
  std::vector<std::uint32_t> begin_;  // by triangle: its pieces begin_[i] .. begin_[i + 1]
  Bvh bvh_;
};

// A face of `in` as triangles (indices into in.positions), as io::triangulate_face
// tiles the face it becomes (rounding.cpp).
std::vector<std::array<std::uint32_t, 3>> tile_face(const MeshInput& in, const MeshFace& f);

// Where rounding made two faces' triangles cross, moves the inexact vertices of the
// crossing triangles (inexact[i] for positions[i]) to neighbouring doubles that
// remove crossings, keeping the coordinates that are exact (exact(i, axis): the
// rounded coordinate is the exact one) (rounding.cpp).
// Returns whether its last full check found no crossing left (false when it stopped
// after moving vertices without checking again, or with crossings it could not remove).
bool nudge_rounding(MeshInput& in, const std::vector<char>& inexact,
                    const std::function<bool(std::uint32_t, int)>& exact, int threads);

// Report::rounding_self_intersections until something has counted them: evaluate sets
// it before build_result, which sets 0 when nudge_rounding's last check was clean;
// otherwise evaluate checks the built model's own triangulation.
inline constexpr std::size_t kRoundingUnchecked = static_cast<std::size_t>(-1);

}  // namespace cellforge::boolean
