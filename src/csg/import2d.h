// import() of 2D files: DXF and SVG outlines as closed paths (private to csg/), to be
// filled even-odd as OpenSCAD fills them.
//
// DXF: the ENTITIES section's LINE, LWPOLYLINE (without bulges), POLYLINE with its
// VERTEXes, CIRCLE, ARC and INSERT (a block of the BLOCKS section, scaled, turned and
// moved), of one layer or all; DIMENSION, TEXT, MTEXT and POINT entities carry no
// outline and are passed over; any other entity is an error naming FILE:LINE. As OpenSCAD's reader
// does, every point is read as (p - origin) * scale and put on a grid of 1/1024 (a point next to
// one already on the grid joins it), so that the ends of lines and arcs written separately meet;
// circles and arcs have OpenSCAD's number of segments (fragments(r), an arc its share of them). The
// segments are then joined at shared points into paths; an open path is closed by a
// segment from its end back to its start (as OpenSCAD closes it), and paths that
// branch are an error naming the point.
//
// SVG: path (M L H V Z and the curves C S Q T, absolute and relative; curves in 20
// equal parameter steps), polygon, rect and circle and ellipse (40 segments), in
// groups, with transform attributes (matrix, translate, scale, rotate, skewX, skewY);
// defs, clipPath, mask, symbol... are not drawn. Units as OpenSCAD 2021.01 reads them:
// width and height in millimetres (a bare number is a point, 25.4/72 mm; px is 1/96
// in); with a viewBox, x' = (x - vx) * width / vw and y' = height - (y + vy) * height
// / vh (its y offset counted with that sign, as 2021.01 does), otherwise x' = x and
// y' = height - y. Arcs (A), rounded rects, stroked shapes (fill none), polyline,
// line, text, image, use and nested svg elements are errors naming FILE:LINE.
#pragma once

#include <array>
#include <optional>
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
// dxf_dim(): the DIMENSION entities of the ENTITIES section, of the layer (every layer
// when it is ""), in file order. Points 0, 3, 4 and 5 (groups 10-15/20-25) are read as
// (p - origin) * scale, the offsets 1, 2 and 6 as p * scale, as OpenSCAD reads them.
struct DxfDimension {
  std::string name;  // group 1, the dimension's text
  int type = 0;      // group 70
  double angle = 0;  // group 50, degrees
  std::array<Vec2, 7> points{};
  std::size_t line = 0;  // of the entity
};
Result<std::vector<DxfDimension>> read_dxf_dimensions(const std::string& path,
                                                      const Import2DOptions& options);
// What OpenSCAD's dxf_dim() measures: by type & 7, 0 the distance along the angle
// between points 3 and 4, 1 their distance, 2 the angle between the lines 5-0 and 3-4
// (degrees), 3 and 4 the distance from point 0 to 5, 6 point 3's x (flag 64) or y;
// none for 5 (angular by three points), which OpenSCAD does not measure either.
std::optional<double> dimension_value(const DxfDimension& d);
// dxf_cross(): where the lines through the first two lone segments of the layer (each
// joined to no other segment) cross; none when there are fewer or they are parallel.
Result<std::optional<Vec2>> read_dxf_cross(const std::string& path, const Import2DOptions& options);

// SVG: per drawn element (shape), its closed subpaths; OpenSCAD fills each shape's
// subpaths even-odd and unites the shapes.
Result<std::vector<std::vector<std::vector<Vec2>>>> read_svg(const std::string& path,
                                                             const Import2DOptions& options);

}  // namespace cellforge::csg
