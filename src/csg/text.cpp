// text(): fontconfig finds the font, HarfBuzz shapes the string, FreeType gives the
// glyph outlines (text.h says which calls and scales, OpenSCAD 2021.01's).
#include "text.h"

#include <fontconfig/fontconfig.h>
#include <ft2build.h>
#include <hb-ft.h>
#include <hb.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <utility>

#include FT_FREETYPE_H
#include FT_GLYPH_H
#include FT_OUTLINE_H

#include "cellforge/csg/source.h"
#include "cellforge/geom/shared_library.h"

namespace cellforge::csg {

namespace {

// FreeType, HarfBuzz and fontconfig are loaded by the first text() (dlopen of
// libfreetype.so.6, libharfbuzz.so.0 and libfontconfig.so.1, Debian's libfreetype6,
// libharfbuzz0b and libfontconfig1) rather than linked: linked, they added about 6 ms
// to the start of every run of cellforge, a third of a small file's build. The
// functions keep their names, as members of one table.
#define CELLFORGE_FREETYPE_FUNCTIONS(X) \
  X(FT_Done_Face) \
  X(FT_Done_Glyph) \
  X(FT_Get_Glyph) \
  X(FT_Glyph_Get_CBox) \
  X(FT_Init_FreeType) \
  X(FT_Load_Glyph) \
  X(FT_New_Face) \
  X(FT_Outline_Decompose) \
  X(FT_Set_Char_Size)
#define CELLFORGE_HARFBUZZ_FUNCTIONS(X) \
  X(hb_buffer_add_utf8) \
  X(hb_buffer_create) \
  X(hb_buffer_destroy) \
  X(hb_buffer_get_direction) \
  X(hb_buffer_get_glyph_infos) \
  X(hb_buffer_get_glyph_positions) \
  X(hb_buffer_set_direction) \
  X(hb_buffer_set_language) \
  X(hb_buffer_set_script) \
  X(hb_direction_from_string) \
  X(hb_direction_to_string) \
  X(hb_font_destroy) \
  X(hb_ft_font_create) \
  X(hb_language_from_string) \
  X(hb_script_from_string) \
  X(hb_script_get_horizontal_direction) \
  X(hb_script_to_iso15924_tag) \
  X(hb_shape) \
  X(hb_tag_to_string) \
  X(hb_unicode_funcs_get_default) \
  X(hb_unicode_script)
#define CELLFORGE_FONTCONFIG_FUNCTIONS(X) \
  X(FcConfigSubstitute) \
  X(FcDefaultSubstitute) \
  X(FcFontMatch) \
  X(FcInitLoadConfigAndFonts) \
  X(FcNameParse) \
  X(FcPatternAddBool) \
  X(FcPatternDestroy) \
  X(FcPatternGetInteger) \
  X(FcPatternGetString)

struct FontLibs {
#define CELLFORGE_FONT_MEMBER(f) decltype(&::f) f = nullptr;
  CELLFORGE_FREETYPE_FUNCTIONS(CELLFORGE_FONT_MEMBER)
  CELLFORGE_HARFBUZZ_FUNCTIONS(CELLFORGE_FONT_MEMBER)
  CELLFORGE_FONTCONFIG_FUNCTIONS(CELLFORGE_FONT_MEMBER)
#undef CELLFORGE_FONT_MEMBER
};

// The table, loaded once; nullptr with the reason in `why` when a library cannot be.
const FontLibs* load_font_libs(std::string& why) {
  static const std::pair<const FontLibs*, std::string> loaded = []() -> std::pair<const FontLibs*, std::string> {
    static FontLibs table;
    SharedLibrary freetype("libfreetype.so.6"), harfbuzz("libharfbuzz.so.0"), fontconfig("libfontconfig.so.1");
#define CELLFORGE_FONT_LOAD(lib, f) table.f = reinterpret_cast<decltype(&::f)>(lib.symbol(#f));
#define CELLFORGE_FREETYPE_LOAD(f) CELLFORGE_FONT_LOAD(freetype, f)
#define CELLFORGE_HARFBUZZ_LOAD(f) CELLFORGE_FONT_LOAD(harfbuzz, f)
#define CELLFORGE_FONTCONFIG_LOAD(f) CELLFORGE_FONT_LOAD(fontconfig, f)
    CELLFORGE_FREETYPE_FUNCTIONS(CELLFORGE_FREETYPE_LOAD)
    CELLFORGE_HARFBUZZ_FUNCTIONS(CELLFORGE_HARFBUZZ_LOAD)
    CELLFORGE_FONTCONFIG_FUNCTIONS(CELLFORGE_FONTCONFIG_LOAD)
#undef CELLFORGE_FONT_LOAD
#undef CELLFORGE_FREETYPE_LOAD
#undef CELLFORGE_HARFBUZZ_LOAD
#undef CELLFORGE_FONTCONFIG_LOAD
    std::string problems;
    for (const SharedLibrary* lib : {&freetype, &harfbuzz, &fontconfig})
      if (!lib->problems().empty()) problems += (problems.empty() ? "" : "; ") + lib->problems();
    if (!problems.empty()) return {nullptr, "text() cannot load its font libraries: " + problems};
    return {&table, ""};
  }();
  why = loaded.second;
  return loaded.first;
}

// The loaded table: every caller is past fonts(), which loaded it.
const FontLibs& lib() {
  static std::string why;
  static const FontLibs* table = load_font_libs(why);
  return *table;
}

// FreeType's library and fontconfig's configuration are shared by every text() call
// and used under one lock (neither is safe to use from several threads at once).
struct Fonts {
  std::mutex lock;
  FT_Library library = nullptr;
  FcConfig* config = nullptr;
  bool ok = false;

  std::string why;  // when the libraries could not be loaded

  Fonts() {
    if (load_font_libs(why) == nullptr) return;
    ok = lib().FT_Init_FreeType(&library) == 0;
    config = lib().FcInitLoadConfigAndFonts();
    ok = ok && config != nullptr;
  }
};

Fonts& fonts() {
  static Fonts f;  // lives to the end of the process: faces may be cached by callers
  return f;
}

// The outline units: the face is set to 100000/64 points at 100 dpi, its coordinates
// read / 1000 and HarfBuzz's positions / 1024, then all scaled by size / 100.
constexpr FT_F26Dot6 kCharSize = 100000;
constexpr double kOutlineScale = 1000;
constexpr double kPositionScale = 64.0 * 16.0;

struct Outliner {
  int segments = 2;
  Vec2 pen{0, 0};
  std::vector<std::vector<Vec2>> contours;  // in outline units, offsets not applied

  static Vec2 at(const FT_Vector* v) { return Vec2{v->x / kOutlineScale, v->y / kOutlineScale}; }
  void add(Vec2 v) { contours.back().push_back(v); }

  static int move_to(const FT_Vector* to, void* user) {
    auto* o = static_cast<Outliner*>(user);
    o->contours.emplace_back();
    o->pen = at(to);
    o->add(o->pen);
    return 0;
  }
  static int line_to(const FT_Vector* to, void* user) {
    auto* o = static_cast<Outliner*>(user);
    if (o->contours.empty()) o->contours.emplace_back();
    o->pen = at(to);
    o->add(o->pen);
    return 0;
  }
  // Bezier curves in `segments` equal parameter steps, the end point included.
  static int conic_to(const FT_Vector* control, const FT_Vector* to, void* user) {
    auto* o = static_cast<Outliner*>(user);
    if (o->contours.empty()) o->contours.emplace_back();
    const Vec2 p0 = o->pen, c = at(control), p1 = at(to);
    for (int i = 1; i <= o->segments; ++i) {
      const double a = i * (1.0 / o->segments);
      const double b = 1 - a;
      o->add(Vec2{p0.x * std::pow(b, 2) + c.x * 2 * b * a + p1.x * std::pow(a, 2),
                  p0.y * std::pow(b, 2) + c.y * 2 * b * a + p1.y * std::pow(a, 2)});
    }
    o->pen = p1;
    return 0;
  }
  static int cubic_to(const FT_Vector* c1v, const FT_Vector* c2v, const FT_Vector* to, void* user) {
    auto* o = static_cast<Outliner*>(user);
    if (o->contours.empty()) o->contours.emplace_back();
    const Vec2 p0 = o->pen, c1 = at(c1v), c2 = at(c2v), p1 = at(to);
    for (int i = 1; i <= o->segments; ++i) {
      const double a = i * (1.0 / o->segments);
      const double b = 1 - a;
      o->add(Vec2{p0.x * std::pow(b, 3) + c1.x * 3 * std::pow(b, 2) * a +
                      c2.x * 3 * b * std::pow(a, 2) + p1.x * std::pow(a, 3),
                  p0.y * std::pow(b, 3) + c1.y * 3 * std::pow(b, 2) * a +
                      c2.y * 3 * b * std::pow(a, 2) + p1.y * std::pow(a, 3)});
    }
    o->pen = p1;
    return 0;
  }
};

// OpenSCAD unites the glyphs with Clipper on integer coordinates of 2^16 per unit,
// converted by truncation toward zero; the same grid here makes both programs' text
// the same to the last bit rather than to 2^-16.
double on_grid(double x) { return std::trunc(x * 65536.0) / 65536.0; }

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  const auto b = s.find_last_not_of(" \t\r\n");
  return s.substr(a, b - a + 1);
}

// UTF-8 to code points; false on a malformed sequence.
bool decode_utf8(const std::string& s, std::vector<std::uint32_t>& out) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    const int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (n < 0 || i + n >= s.size() + (n == 0)) return false;
    std::uint32_t cp = n == 0 ? c : n == 1 ? (c & 0x1Fu) : n == 2 ? (c & 0x0Fu) : (c & 0x07u);
    for (int k = 1; k <= n; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 2) return false;
      cp = (cp << 6) | (d & 0x3Fu);
    }
    out.push_back(cp);
    i += n + 1;
  }
  return true;
}

bool is_ignored_script(hb_script_t s) {
  return s == HB_SCRIPT_COMMON || s == HB_SCRIPT_INHERITED || s == HB_SCRIPT_UNKNOWN ||
         s == HB_SCRIPT_INVALID;
}

// OpenSCAD's detection: the script of the string's letters when they agree (a given
// script wins), the direction of that script unless one is given.
void detect_properties(TextParams& p) {
  hb_script_t script = lib().hb_script_from_string(p.script.c_str(), -1);
  if (script == HB_SCRIPT_INVALID) {
    std::vector<std::uint32_t> cps;
    decode_utf8(p.text, cps);
    for (std::uint32_t cp : cps) {
      const hb_script_t s = lib().hb_unicode_script(lib().hb_unicode_funcs_get_default(), cp);
      if (is_ignored_script(s)) continue;
      if (script == HB_SCRIPT_INVALID) {
        script = s;
      } else if (script != s && script != HB_SCRIPT_UNKNOWN) {
        script = HB_SCRIPT_UNKNOWN;
      }
    }
  }
  if (!is_ignored_script(script)) {
    char tag[5] = {0, 0, 0, 0, 0};
    lib().hb_tag_to_string(lib().hb_script_to_iso15924_tag(script), tag);
    p.script = tag;
  }
  hb_direction_t d = lib().hb_direction_from_string(p.direction.c_str(), -1);
  if (d == HB_DIRECTION_INVALID) d = lib().hb_script_get_horizontal_direction(script);
  p.direction = lib().hb_direction_to_string(d);
}

struct FaceHolder {
  FT_Face face = nullptr;
  ~FaceHolder() {
    if (face) lib().FT_Done_Face(face);
  }
};

struct GlyphHolder {
  std::vector<FT_Glyph> glyphs;
  ~GlyphHolder() {
    for (FT_Glyph g : glyphs) lib().FT_Done_Glyph(g);
  }
};

}  // namespace

Result<TextGlyphs> render_text(const TextParams& given) {
  Fonts& f = fonts();
  std::lock_guard<std::mutex> guard(f.lock);
  if (!f.why.empty()) return Error{ErrorCode::kUnsupported, f.why};
  if (!f.ok) return Error{ErrorCode::kUnsupported, "FreeType or fontconfig failed to start"};
  TextGlyphs out;
  TextParams p = given;
  detect_properties(p);

  // fontconfig: the name as a pattern, outline (scalable) fonts only.
  const std::string name = trim(p.font).empty() ? "Liberation Sans:style=Regular" : trim(p.font);
  FcPattern* pattern = lib().FcNameParse(reinterpret_cast<const FcChar8*>(name.c_str()));
  if (!pattern) return Error{ErrorCode::kInvalidInput, "font \"" + name + "\" is not a font name"};
  lib().FcPatternAddBool(pattern, FC_OUTLINE, FcTrue);
  lib().FcPatternAddBool(pattern, FC_SCALABLE, FcTrue);
  lib().FcConfigSubstitute(f.config, pattern, FcMatchPattern);
  lib().FcDefaultSubstitute(pattern);
  FcResult fr;
  FcPattern* match = lib().FcFontMatch(f.config, pattern, &fr);
  std::string requested_family;
  FcChar8* value = nullptr;
  if (lib().FcPatternGetString(pattern, FC_FAMILY, 0, &value) == FcResultMatch)
    requested_family = reinterpret_cast<const char*>(value);
  lib().FcPatternDestroy(pattern);
  if (!match) return Error{ErrorCode::kInvalidInput, "no font matches \"" + name + "\""};
  int index = 0;
  if (lib().FcPatternGetString(match, FC_FILE, 0, &value) == FcResultMatch)
    out.font_file = reinterpret_cast<const char*>(value);
  lib().FcPatternGetInteger(match, FC_INDEX, 0, &index);
  if (lib().FcPatternGetString(match, FC_FAMILY, 0, &value) == FcResultMatch)
    out.font_family = reinterpret_cast<const char*>(value);
  lib().FcPatternDestroy(match);
  if (out.font_file.empty())
    return Error{ErrorCode::kInvalidInput, "no font file matches \"" + name + "\""};
  if (!trim(p.font).empty() && !requested_family.empty() &&
      lower(requested_family) != lower(out.font_family)) {
    out.warnings.push_back("font \"" + requested_family +
                           "\" is not installed; fontconfig chose \"" + out.font_family + "\" (" +
                           out.font_file + ")");
  }

  FaceHolder face;
  if (lib().FT_New_Face(f.library, out.font_file.c_str(), index, &face.face) != 0) {
    face.face = nullptr;
    return Error{ErrorCode::kInvalidInput, "FreeType cannot read the font file " + out.font_file};
  }
  if (lib().FT_Set_Char_Size(face.face, 0, kCharSize, 100, 100) != 0)
    return Error{ErrorCode::kInvalidInput, "cannot set the size of font " + out.font_file};
  bool symbol_font = false;
  for (int i = 0; i < face.face->num_charmaps; ++i) {
    const FT_CharMap cm = face.face->charmaps[i];
    symbol_font |= cm->platform_id == 3 && cm->encoding_id == 0;
  }

  hb_font_t* hb_font = lib().hb_ft_font_create(face.face, nullptr);
  hb_buffer_t* buf = lib().hb_buffer_create();
  lib().hb_buffer_set_direction(buf, lib().hb_direction_from_string(p.direction.c_str(), -1));
  lib().hb_buffer_set_script(buf, lib().hb_script_from_string(p.script.c_str(), -1));
  lib().hb_buffer_set_language(buf, lib().hb_language_from_string(p.language.c_str(), -1));
  if (symbol_font) {
    // Symbol fonts map their glyphs into the private use area: characters below 0x100
    // move to page 0xf000, as OpenSCAD does.
    std::vector<std::uint32_t> cps;
    if (decode_utf8(p.text, cps)) {
      std::string mapped;
      for (std::uint32_t c : cps) append_utf8(mapped, c < 0x100 ? 0xF000 + c : c);
      lib().hb_buffer_add_utf8(buf, mapped.c_str(), static_cast<int>(mapped.size()), 0,
                         static_cast<int>(mapped.size()));
    } else {
      out.warnings.push_back("text with invalid UTF-8 is ignored");
    }
  } else {
    lib().hb_buffer_add_utf8(buf, p.text.c_str(), static_cast<int>(p.text.size()), 0,
                       static_cast<int>(p.text.size()));
  }
  lib().hb_shape(hb_font, buf, nullptr, 0);
  unsigned count = 0;
  hb_glyph_info_t* info = lib().hb_buffer_get_glyph_infos(buf, &count);
  hb_glyph_position_t* pos = lib().hb_buffer_get_glyph_positions(buf, &count);
  const bool horizontal = HB_DIRECTION_IS_HORIZONTAL(lib().hb_buffer_get_direction(buf));

  struct Placed {
    FT_Glyph glyph;
    double x_offset, y_offset, x_advance, y_advance;
  };
  std::vector<Placed> placed;
  GlyphHolder held;
  for (unsigned i = 0; i < count; ++i) {
    if (lib().FT_Load_Glyph(face.face, info[i].codepoint, FT_LOAD_DEFAULT) != 0) continue;
    FT_Glyph g = nullptr;
    if (lib().FT_Get_Glyph(face.face->glyph, &g) != 0) continue;
    held.glyphs.push_back(g);
    placed.push_back(Placed{g, pos[i].x_offset / kPositionScale, pos[i].y_offset / kPositionScale,
                            pos[i].x_advance / kPositionScale, pos[i].y_advance / kPositionScale});
  }
  lib().hb_buffer_destroy(buf);
  lib().hb_font_destroy(hb_font);

  double width = 0, ascend = 0, descend = 0;
  for (const Placed& g : placed) {
    FT_BBox box;
    lib().FT_Glyph_Get_CBox(g.glyph, FT_GLYPH_BBOX_GRIDFIT, &box);
    if (horizontal) {
      ascend = std::max(ascend, std::max(0.0, box.yMax / kPositionScale));
      descend = std::max(descend, std::max(0.0, -box.yMin / kPositionScale));
      width += g.x_advance * p.spacing;
    } else {
      width = std::max(width, (box.xMax - box.xMin) / kPositionScale);
      ascend += g.y_advance * p.spacing;
    }
  }
  double x0 = 0, y0 = 0;
  if (p.halign == "right") {
    x0 = -width;
  } else if (p.halign == "center") {
    x0 = -width / 2.0;
  } else if (p.halign != "left") {
    out.warnings.push_back("unknown halign \"" + p.halign +
                           "\" (use \"left\", \"right\" or \"center\"): left");
  }
  if (p.valign == "top") {
    y0 = -ascend;
  } else if (p.valign == "center") {
    y0 = descend / 2.0 - ascend / 2.0;
  } else if (p.valign == "bottom") {
    y0 = descend;
  } else if (p.valign != "baseline") {
    out.warnings.push_back("unknown valign \"" + p.valign +
                           "\" (use \"baseline\", \"bottom\", \"top\" or \"center\"): baseline");
  }

  const double k = p.size / 100.0;
  constexpr double kMaxPoints = 2e7;
  double total_points = 0;
  double adv_x = 0, adv_y = 0;
  FT_Outline_Funcs funcs{};
  funcs.move_to = &Outliner::move_to;
  funcs.line_to = &Outliner::line_to;
  funcs.conic_to = &Outliner::conic_to;
  funcs.cubic_to = &Outliner::cubic_to;
  for (const Placed& g : placed) {
    if (g.glyph->format == FT_GLYPH_FORMAT_OUTLINE) {
      Outliner o;
      o.segments = std::max(1, p.segments);
      FT_Outline outline = reinterpret_cast<FT_OutlineGlyph>(g.glyph)->outline;
      // Every curve becomes `segments` points: refuse before the outlines fill memory.
      total_points += static_cast<double>(outline.n_points) * o.segments;
      if (total_points > kMaxPoints) {
        return Error{ErrorCode::kInvalidInput,
                     "more than 2*10^7 outline points (the text, $fn and the font make " +
                         std::to_string(static_cast<long long>(total_points)) + " at least)"};
      }
      lib().FT_Outline_Decompose(&outline, &funcs, &o);
      const double ox = x0 + g.x_offset, oy = y0 + g.y_offset;
      std::vector<std::vector<Vec2>> contours;
      for (const auto& c : o.contours) {
        std::vector<Vec2> loop;
        for (Vec2 v : c) {
          const Vec2 q{on_grid(k * (v.x + ox + adv_x)), on_grid(k * (v.y + oy + adv_y))};
          if (!loop.empty() && loop.back().x == q.x && loop.back().y == q.y) continue;
          loop.push_back(q);
        }
        while (loop.size() > 1 && loop.back().x == loop.front().x &&
               loop.back().y == loop.front().y)
          loop.pop_back();
        if (loop.size() >= 3) contours.push_back(std::move(loop));
      }
      if (!contours.empty()) out.glyphs.push_back(std::move(contours));
    }
    adv_x += g.x_advance * p.spacing;
    adv_y += g.y_advance * p.spacing;
  }
  return out;
}

}  // namespace cellforge::csg
