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
struct OutPoly {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::vector<std::uint32_t>> keys;
  std::uint32_t cluster = kInvalidIndex;  // its plane; kInvalidIndex for a non-planar face
  int normal_sign = 1;                    // +1: outward normal along the cluster's reference
  std::uint32_t tri = 0;                  // the input triangle it lies on (provenance)
};

// Stages 3 and 4: winding numbers of every piece's two sides by exact ray casting,
// the expression on them, and the kept pieces as faces.
// On `threads` threads (0: all); the same result at any count.
std::vector<OutPoly> classify_and_select(const Arrangement& a, const Expr& expr, Report& report,
                                         int threads = 1);

// Stages 5 and 6: one vertex per exact position, every vertex of a line on each edge
// along it, coplanar neighbours and collinear edges merged, coordinates rounded, and
// the faces built into one group with a cell per connected solid.
Result<BooleanResult> build_result(Arrangement& a, std::vector<OutPoly> polys, Report& report,
                                   int threads = 1);

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
