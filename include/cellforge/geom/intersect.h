// Exact intersection tests between segments and triangles, in the plane and in space.
// Every test treats its segments and triangles as closed point sets (touching counts)
// and is decided by the exact predicates of predicates.h alone.
#pragma once

#include "cellforge/geom/predicates.h"
#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

// p lies on the closed segment ab (a == b: p == a).
bool point_on_segment(Vec2 a, Vec2 b, Vec2 p);

// The closed segments ab and cd share a point.
bool segments_meet(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// Consecutive edges ab and bc of a polygon meet in more than b: the turn at b is a
// reversal (c runs back along ab), or one edge covers the other's far end.
bool edges_fold_back(Vec2 a, Vec2 b, Vec2 c);

// p lies in the closed triangle t, of either orientation.
bool point_in_triangle(const Vec2 t[3], Vec2 p);

// The closed triangles a and b of one plane share a point.
bool triangles_meet(const Vec2 a[3], const Vec2 b[3]);

// The closed segment pq meets the closed triangle t in space (t not degenerate, or at
// least not projecting to a line along the dominant axis of its normal when pq lies
// in its plane).
bool segment_meets_triangle(Vec3 p, Vec3 q, const Vec3 t[3]);

// Triangles a and b in space that each cross the other's plane with no corner in it
// (sa: the sides of a's corners against b's plane, orient3d(b..., a[i]); sb: b's
// against a's; each has both signs and no zero) are apart: their traces on the line of
// the two planes do not overlap. Two orientations of input points decide it (Guigue and
// Devillers' test); false when the triangles meet, touching included.
bool straddling_triangles_apart(const Vec3 a[3], const Vec3 b[3], const int sa[3], const int sb[3]);

// The closed triangles a and b in space share a point. A degenerate triangle (three
// collinear points) is the segment or point it covers, against a triangle that is not;
// two degenerate triangles, or a degenerate one in the other's plane, are reported
// as not meeting when their rounded normal is zero: callers report degeneracy on its own.
bool triangles_meet(const Vec3 a[3], const Vec3 b[3]);

}  // namespace cellforge::inline geom
