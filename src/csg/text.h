// text(): glyph outlines laid out as OpenSCAD 2021.01 lays them out (private to csg/).
//
// The font is found through fontconfig (a name such as "Liberation Sans:style=Bold"),
// the string shaped by HarfBuzz and the glyph outlines read by FreeType, the same
// libraries and the same calls as OpenSCAD's, so that both programs place the same
// vertices: the face at a fixed character size of 100000/64 points at 100 dpi, loaded
// with FreeType's default hinting; outline coordinates / 1000 and HarfBuzz advances and
// offsets / 1024, both scaled by size / 100; Bezier segments flattened into `segments`
// steps each (OpenSCAD's max(floor(fragments(size) / 8) + 1, 2)); halign from the
// total advance, valign from the grid-fitted glyph boxes; every coordinate then
// truncated toward zero to a multiple of 2^-16, the grid of OpenSCAD's Clipper union of
// the glyphs.
#pragma once

#include <string>
#include <vector>

#include "cellforge/geom/vec.h"
#include "cellforge/result.h"

namespace cellforge::csg {

struct TextParams {
  std::string text;
  double size = 10;
  std::string font;  // "" : OpenSCAD's default, "Liberation Sans"
  std::string halign = "left", valign = "baseline";
  double spacing = 1;
  std::string direction, language = "en", script;  // "" : detected as OpenSCAD does
  int segments = 2;                                // steps per Bezier segment
};

struct TextGlyphs {
  // One entry per glyph with an outline: its contours (closed, no repeated
  // consecutive vertex, the last not equal to the first), in the font's orientation.
  std::vector<std::vector<std::vector<Vec2>>> glyphs;
  std::string font_file;    // the file fontconfig chose
  std::string font_family;  // its family name
  std::vector<std::string> warnings;
};

// kInvalidInput when no font can be loaded; warnings for what OpenSCAD warns about
// (an unknown halign or valign, a font found under another family name).
Result<TextGlyphs> render_text(const TextParams& params);

}  // namespace cellforge::csg
