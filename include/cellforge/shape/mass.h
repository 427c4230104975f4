// Mass properties of a group or of one cell, from its polygon faces by the divergence
// theorem: each face contributes the signed volume of the cone from a reference point
// to the face (fan triangles of each loop), so the result is exact for the polyhedron
// up to rounding. A cell's volume counts the faces that have it behind them minus the
// faces that have it in front. Sheets (faces without cells) report area only.
#pragma once

#include "cellforge/geom/vec.h"
#include "cellforge/topo/model.h"

namespace cellforge::shape {

struct MassProperties {
  bool solid = false;  // some face bounds a cell; else volume is 0 and the centroid is
                       // the centroid of the area
  double volume = 0;
  double area = 0;          // every face once, inner loops subtracted
  Vec3 centroid;            // of the volume (solid) or of the area (sheet)
  Vec3 bbox_min, bbox_max;  // of the vertices; both zero for an empty group
};

// The whole model (every group), one group, or one cell.
MassProperties mass_properties(const Model& m);
MassProperties mass_properties(const Model& m, GroupId g);
MassProperties mass_properties(const Model& m, VolumeId c);

}  // namespace cellforge::shape
