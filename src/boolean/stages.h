// The Boolean's stages after the arrangement: classification and selection
// (classify.cpp), merging and stitching into a model (output.cpp), and the choice of
// doubles for the rounded points (rounding.cpp).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "boolean/arrangement.h"
#include "cellforge/boolean/boolean.h"
#include "cellforge/topo/builder.h"

namespace cellforge::boolean {

// A face of the result before merging: loops of arrangement points, counterclockwise
// about the result's outward normal, with the global line key of each edge
// (kInvalidIndex where none is known).
enum class FaceKind : std::uint8_t {
  kBoundary,  // the set on one side only: its back (as the loops turn)
  kSheet,     // the set on neither side: a face of no volume (non-regularized)
  kInner,     // the set on both sides: between two cells (Options::cells), or a cut
};

struct OutPoly {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::vector<std::uint32_t>> keys;
  std::uint32_t cluster = kInvalidIndex;  // its plane; kInvalidIndex for a non-planar face
  int normal_sign = 1;                    // +1: outward normal along the cluster's reference
  std::uint32_t tri = 0;                  // the input triangle it lies on (provenance)
  FaceKind kind = FaceKind::kBoundary;
  bool mark = true;                       // whether the face's own points are in the set
};

// An edge of the arrangement's faces (a piece's side, an untouched triangle's edge)
// with its global line key, for the lower-dimensional parts of a non-regularized
// result.
struct OutSide {
  std::uint32_t p, q, key;
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
};
std::vector<SiteVerdict> classify_sites(const Arrangement& a, const Expr& expr,
                                        const std::vector<std::array<std::uint32_t, 2>>& sites,
                                        int threads, bool both_sides = false);

// Stages 5 and 6: one vertex per exact position, every vertex of a line on each edge
// along it, coplanar neighbours and collinear edges merged, coordinates rounded, and
// the faces built into one group with a cell per connected solid.
Result<BooleanResult> build_result(Arrangement& a, Selection selection, const Expr& expr,
                                   const Options& options, Report& report);

// A face of `in` as triangles (indices into in.positions), as io::triangulate_face
// tiles the face it becomes (rounding.cpp).
std::vector<std::array<std::uint32_t, 3>> tile_face(const MeshInput& in, const MeshFace& f);

// Where rounding made two faces' triangles cross, moves the inexact vertices of the
// crossing triangles (inexact[i] for positions[i]) to neighbouring doubles that
// remove crossings, keeping the coordinates that are exact (exact(i, axis): the
// rounded coordinate is the exact one) (rounding.cpp).
void nudge_rounding(MeshInput& in, const std::vector<char>& inexact,
                    const std::function<bool(std::uint32_t, int)>& exact, int threads);

}  // namespace cellforge::boolean
