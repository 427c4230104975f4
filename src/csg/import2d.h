// import() of 2D files: DXF and SVG outlines as closed paths (private to csg/), to be
// filled even-odd as OpenSCAD fills them.
//
// DXF: the ENTITIES section's LINE, LWPOLYLINE (without bulges), POLYLINE with its
// VERTEXes, CIRCLE and ARC, of one layer or all; DIMENSION, TEXT, MTEXT and POINT
// entities carry no outline and are passed over; any other entity is an error naming
// FILE:LINE. As OpenSCAD's reader does, every point is read as (p - origin) * scale
// and put on a grid of 1/1024 (a point next to one already on the grid joins it), so
// that the ends of lines and arcs written separately meet; circles and arcs have
// OpenSCAD's number of segments (fragments(r), an arc its share of them). The
// segments are then joined at shared points into closed paths; a path that branches
// or stays open is an error naming a point on it.
//
// SVG: path (M L H V C S Q T A Z, absolute and relative), polygon, polyline, rect,
// circle, ellipse and line elements, in groups, with transform attributes
// (matrix, translate, scale, rotate, skewX, skewY); the y axis turned up and the user
// units read as OpenSCAD 2021.01 reads them. Curves and arcs are flattened as
// OpenSCAD's importer flattens them. Other elements that draw (text, image, use) are
// errors naming FILE:LINE.
#pragma once

#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"
#include "cellforge/shape/faceting.h"

namespace cellforge::csg {

struct Import2DOptions {
  std::string layer;  // DXF: "" reads every layer
  Vec2 origin{0, 0};
  double scale = 1;
  shape::Faceting faceting;
};

// Closed paths (no repeated closing vertex). Errors: kIo (unreadable file) or
// kInvalidInput / kUnsupported with FILE:LINE.
Result<std::vector<std::vector<Vec2>>> read_dxf(const std::string& path,
                                                const Import2DOptions& options);
Result<std::vector<std::vector<Vec2>>> read_svg(const std::string& path,
                                                const Import2DOptions& options);

}  // namespace cellforge::csg
