// The models of the structure comparison (issue 6), as bulk-builder input: the
// solids, the non-manifold fixtures, OpenSCAD-style spheres and large closed
// triangle meshes. Faces are outward and counterclockwise seen from the front;
// solids bound volume 0 (behind their faces).
#pragma once

#include <cstdint>

#include "cellforge/topo/builder.h"

namespace cellforge::compare {

MeshInput cube_model();              // [0,1]^3
MeshInput cube_with_hole_model();    // [0,3]^3 with the square hole [1,2]^2 through it along z
MeshInput two_cubes_edge_model();    // [0,1]^3 and [1,2]x[1,2]x[0,1], two volumes, one edge
MeshInput two_cubes_vertex_model();  // [0,1]^3 and [1,2]^3, two volumes, one vertex
MeshInput book_model();              // three unit square sheets on the spine (0,0,0)-(0,0,1)

// OpenSCAD's sphere(r, $fn = fn): rings = (fn + 1) / 2, ring i at polar angle
// 180 * (i + 0.5) / rings degrees with fn points from azimuth 0; an fn-gon cap on
// the first and last ring and quads between rings.
MeshInput sphere_model(int fn, double r = 1);

// A torus grid of n x m quads, each split into two triangles (2nm faces, closed,
// genus 1). With a nonzero seed each quad's diagonal is chosen at random and the
// vertices are pushed radially by up to 10% of the tube radius: a random closed
// triangle mesh with vertex degrees from 4 to 8.
MeshInput torus_model(int n, int m, std::uint32_t seed = 0);

}  // namespace cellforge::compare
