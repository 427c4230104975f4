// The 3-cells of an imported group (VolumeMode::kAuto), decided on the built
// topology, where the radial order around every edge is known exactly.
//
// Face sides are joined across each wedge between radially consecutive faces into
// classes; each class bounds one region locally, and its sides, each taken with its
// face's orientation reversed when the side is a front, form a closed surface around
// that region. By the exact sign of that surface's volume (geom/volume.h):
//   > 0  the class is the outer boundary of a bounded region; the region is a cell
//        when more of its sides are backs than fronts (the faces point away from it),
//        else it is void (an inside-out shell, the inside of a cavity);
//   < 0  the class is an inner boundary (a cavity's wall, or the outside of a solid):
//        its region is the one of the innermost outer boundary that contains it
//        (geom/winding.h), or the unbounded void when none does;
//   = 0  a sheet or a zero-thickness pair on its own: void.
// So a cube with an inward-facing spherical cavity is one cell bounded by both
// shells, two cubes exported with their common face twice (back to back) are two
// cells with a zero-thickness gap between them, and an open sheet has no cell.
#pragma once
#include <functional>

#include <cstddef>

#include "cellforge/result.h"
#include "cellforge/topo/model.h"

namespace cellforge::io {

// Makes the cells of group g, whose faces have no volumes yet; returns how many.
// With `side_in`, which regions are cells is given rather than inferred from the
// faces' orientation: side_in(f, front) tells whether the region on that side of face
// f is a cell (a Boolean's selection knows it); a region whose outer boundary has
// positive volume and is in becomes a cell, and its inner boundaries join it.
Result<std::size_t> make_region_volumes(Model& m, GroupId g,
                                        const std::function<bool(FaceId, bool front)>& side_in = {});

}  // namespace cellforge::io
