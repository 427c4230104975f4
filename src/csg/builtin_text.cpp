// text() and surface(): modules whose geometry comes from outside the script (a font,
// a heightmap file). Both are turned into ordinary tree nodes while the script is
// evaluated — text() into one polygon per glyph, surface() into a polyhedron — so the
// JSON form, the cache keys (which then hold the glyph and height data) and the build
// need nothing of their own.
#include <png.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "interp.h"
#include "text.h"

namespace cellforge::csg {

std::string Interp::script_relative(const std::string& file, SourcePos from) const {
  if (!file.empty() && file[0] == '/') return file;
  const auto it = source_paths_.find(from.file);
  std::string base = it != source_paths_.end() ? it->second : std::string();
  const std::size_t slash = base.find_last_of('/');
  base = slash == std::string::npos ? std::string() : base.substr(0, slash + 1);
  return base + file;
}

bool Interp::text(const Stmt& s, const Args& args, const EnvPtr& env, std::vector<NodePtr>& out) {
  // text, size and font by position; the others by name only, as OpenSCAD has them.
  const Params p(args, {"text", "size", "font"}, s.pos);
  if (!s.children.empty()) warn(s.pos, "text() takes no children (ignored)");
  auto string_arg = [&](const char* key, const char* fallback) {
    const Value& v = p.get(key);
    if (v.is_undef()) return std::string(fallback);
    if (!v.is_string())
      fail(p.pos(key), std::string("text(): ") + key + " must be a string, not " + v.to_echo());
    return v.as_string();
  };
  auto number_arg = [&](const char* key, double fallback) {
    const Value& v = p.get(key);
    if (v.is_undef()) return fallback;
    if (!v.is_number() || !std::isfinite(v.as_number()))
      fail(p.pos(key),
           std::string("text(): ") + key + " must be a finite number, not " + v.to_echo());
    return v.as_number();
  };
  TextParams t;
  t.text = string_arg("text", "");
  t.size = number_arg("size", 10);
  t.font = string_arg("font", "");
  t.direction = string_arg("direction", "");
  t.language = string_arg("language", "en");
  t.script = string_arg("script", "");
  t.halign = string_arg("halign", "left");
  t.valign = string_arg("valign", "baseline");
  t.spacing = number_arg("spacing", 1);
  if (!(std::fabs(t.size) <= 1e6)) fail(p.pos("size"), "text(): size must be at most 10^6");
  // OpenSCAD's curve steps: a fraction of the segments of a circle of radius size.
  const shape::Faceting f = faceting(p, env);
  if (f.fn > 1e6) fail(s.pos, "text(): more than 10^6 segments per circle");
  const int circle = shape::fragments(t.size, f);
  t.segments = std::max(static_cast<int>(std::floor(circle / 8.0)) + 1, 2);
  if (!options_.allow_files) fail(s.pos, "text(): reading fonts is turned off");
  auto r = render_text(t);
  if (!r) fail(s.pos, "text(): " + r.error().message);
  for (const std::string& w : r->warnings) warn(s.pos, "text(): " + w);
  auto group = std::make_shared<Node>();
  group->kind = NodeKind::kGroup;
  group->pos = s.pos;
  for (const auto& glyph : r->glyphs) {
    auto poly = std::make_shared<Node>();
    poly->kind = NodeKind::kPolygon;
    poly->pos = s.pos;
    for (const auto& contour : glyph) {
      std::vector<std::uint32_t> path;
      for (Vec2 v : contour) {
        path.push_back(static_cast<std::uint32_t>(poly->points.size()));
        poly->points.push_back(Vec3{v.x, v.y, 0});
      }
      poly->faces.push_back(std::move(path));
    }
    group->children.push_back(std::move(poly));
  }
  out.push_back(std::move(group));
  return true;
}

namespace {

struct HeightMap {
  std::map<std::pair<int, int>, double> data;  // (row, column) -> height
};

// OpenSCAD's .dat: rows of numbers separated by spaces or tabs; empty lines and
// lines starting with '#' are skipped.
std::string read_dat(const std::string& path, HeightMap& map) {
  std::ifstream in(path);
  if (!in) return "cannot open " + path;
  std::string line;
  int row = 0, number = 0;
  while (std::getline(in, line)) {
    ++number;
    const auto a = line.find_first_not_of(" \t\r");
    if (a == std::string::npos || line[a] == '#') continue;
    std::istringstream tokens(line);
    std::string tok;
    int col = 0;
    while (tokens >> tok) {
      char* end = nullptr;
      const double v = std::strtod(tok.c_str(), &end);
      if (end == tok.c_str() || *end != '\0' || !std::isfinite(v))
        return path + ":" + std::to_string(number) + ": not a number: " + tok;
      map.data[{row, col++}] = v;
    }
    ++row;
  }
  return "";
}

// A PNG as 8-bit RGBA (16-bit channels keep their high byte, palettes and gray are
// expanded, no gamma correction), each pixel's height 100/255 of its luma (Rec. 709
// weights), the image's top row at the largest y — OpenSCAD's reading.
std::string read_png(const std::string& path, bool invert, HeightMap& map) {
  FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) return "cannot open " + path;
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  std::vector<png_byte> pixels;
  std::vector<png_bytep> rows;
  png_uint_32 width = 0, height = 0;
  if (!png || !info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return path + ": not a readable PNG image";
  }
  png_init_io(png, fp);
  png_set_user_limits(png, 20000, 20000);
  png_read_info(png, info);
  width = png_get_image_width(png, info);
  height = png_get_image_height(png, info);
  if (static_cast<double>(width) * height > 25e6) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return path + ": more than 25 million pixels";
  }
  png_set_expand(png);
  png_set_strip_16(png);
  png_set_gray_to_rgb(png);
  png_set_add_alpha(png, 0xFF, PNG_FILLER_AFTER);
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  if (png_get_rowbytes(png, info) != 4 * static_cast<std::size_t>(width)) {
    png_destroy_read_struct(&png, &info, nullptr);
    std::fclose(fp);
    return path + ": unexpected PNG pixel format";
  }
  pixels.resize(4 * static_cast<std::size_t>(width) * height);
  rows.resize(height);
  for (png_uint_32 y = 0; y < height; ++y)
    rows[y] = pixels.data() + 4 * static_cast<std::size_t>(width) * y;
  png_read_image(png, rows.data());
  png_read_end(png, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  std::fclose(fp);
  for (png_uint_32 y = 0; y < height; ++y) {
    for (png_uint_32 x = 0; x < width; ++x) {
      const png_byte* px = rows[y] + 4 * x;
      const double luma = 0.2126 * px[0] + 0.7152 * px[1] + 0.0722 * px[2];
      // OpenSCAD 2021.01 inverts as 1 - luma (not 255 - luma): kept, to agree with it.
      const double z = 100.0 / 255 * (invert ? 1 - luma : luma);
      map.data[{static_cast<int>(height - 1 - y), static_cast<int>(x)}] = z;
    }
  }
  return "";
}

bool is_png_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char sig[8] = {};
  in.read(reinterpret_cast<char*>(sig), 8);
  static const unsigned char kSig[8] = {0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a};
  return in.gcount() == 8 && std::equal(sig, sig + 8, kSig);
}

}  // namespace

bool Interp::surface(const Stmt& s, const Args& args, std::vector<NodePtr>& out) {
  const Params p(args, {"file", "center", "convexity"}, s.pos);
  if (!s.children.empty()) warn(s.pos, "surface() takes no children (ignored)");
  const Value& file = p.get("file");
  if (!file.is_string()) fail(p.pos("file"), "surface(): file must be a string");
  if (!options_.allow_files) fail(s.pos, "surface(): reading files is turned off");
  const std::string path = script_relative(file.as_string(), s.pos);
  const bool center = p.get("center").is_bool() && p.get("center").truthy();
  const bool invert = p.get("invert").is_bool() && p.get("invert").truthy();
  HeightMap map;
  const std::string err = is_png_file(path) ? read_png(path, invert, map) : read_dat(path, map);
  if (!err.empty()) fail(p.pos("file"), "surface(): " + err);
  int lines = 0, columns = 0;
  double base = 0;  // one below the lowest height, and not above 0
  for (const auto& [rc, v] : map.data) {
    lines = std::max(lines, rc.first + 1);
    columns = std::max(columns, rc.second + 1);
    base = std::min(base, v - 1);
  }
  if (lines < 2 || columns < 2) {
    fail(p.pos("file"), "surface(): " + path + " has " + std::to_string(lines) + " rows and " +
                            std::to_string(columns) + " columns; a solid needs at least 2 of each");
  }
  if (static_cast<double>(lines) * columns > 25e6)
    fail(p.pos("file"), "surface(): more than 25 million heights in " + path);
  auto height = [&](int i, int j) {
    const auto it = map.data.find({i, j});
    return it == map.data.end() ? 0.0 : it->second;  // a short row is padded with 0
  };
  const double ox = center ? -(columns - 1) / 2.0 : 0;
  const double oy = center ? -(lines - 1) / 2.0 : 0;
  auto node = std::make_shared<Node>();
  node->kind = NodeKind::kPolyhedron;
  node->pos = s.pos;
  auto& pts = node->points;
  auto& faces = node->faces;
  // Top grid points (row i, column j), then the cell centres, then the bottom ring.
  auto top = [&](int i, int j) { return static_cast<std::uint32_t>(i * columns + j); };
  for (int i = 0; i < lines; ++i)
    for (int j = 0; j < columns; ++j) pts.push_back(Vec3{ox + j, oy + i, height(i, j)});
  const auto centres = static_cast<std::uint32_t>(pts.size());
  auto centre = [&](int i, int j) {  // of the cell whose far corner is (i, j)
    return centres + static_cast<std::uint32_t>((i - 1) * (columns - 1) + (j - 1));
  };
  for (int i = 1; i < lines; ++i) {
    for (int j = 1; j < columns; ++j) {
      const double vx =
          (height(i - 1, j - 1) + height(i - 1, j) + height(i, j - 1) + height(i, j)) / 4;
      pts.push_back(Vec3{ox + j - 0.5, oy + i - 0.5, vx});
    }
  }
  std::map<std::pair<int, int>, std::uint32_t> bottom;
  auto low = [&](int i, int j) {
    auto [it, fresh] = bottom.emplace(std::pair{i, j}, static_cast<std::uint32_t>(pts.size()));
    if (fresh) pts.push_back(Vec3{ox + j, oy + i, base});
    return it->second;
  };
  // Faces counterclockwise seen from outside, reversed at the end (polyhedron()'s
  // clockwise order). Each cell is four triangles about its centre.
  std::vector<std::vector<std::uint32_t>> ccw;
  for (int i = 1; i < lines; ++i) {
    for (int j = 1; j < columns; ++j) {
      const std::uint32_t c = centre(i, j);
      ccw.push_back({top(i - 1, j - 1), top(i - 1, j), c});
      ccw.push_back({top(i - 1, j), top(i, j), c});
      ccw.push_back({top(i, j), top(i, j - 1), c});
      ccw.push_back({top(i, j - 1), top(i - 1, j - 1), c});
    }
  }
  const int last_row = lines - 1, last_col = columns - 1;
  for (int i = 1; i < lines; ++i) {
    ccw.push_back({low(i - 1, 0), top(i - 1, 0), top(i, 0), low(i, 0)});
    ccw.push_back({low(i, last_col), top(i, last_col), top(i - 1, last_col), low(i - 1, last_col)});
  }
  for (int j = 1; j < columns; ++j) {
    ccw.push_back({low(0, j), top(0, j), top(0, j - 1), low(0, j - 1)});
    ccw.push_back({low(last_row, j - 1), top(last_row, j - 1), top(last_row, j), low(last_row, j)});
  }
  // The bottom, seen from below: round the boundary clockwise seen from above.
  std::vector<std::uint32_t> ring;
  for (int j = 0; j < last_col; ++j) ring.push_back(low(0, j));
  for (int i = 0; i < last_row; ++i) ring.push_back(low(i, last_col));
  for (int j = last_col; j > 0; --j) ring.push_back(low(last_row, j));
  for (int i = last_row; i > 0; --i) ring.push_back(low(i, 0));
  std::reverse(ring.begin(), ring.end());
  ccw.push_back(std::move(ring));
  for (auto& f : ccw) {
    std::reverse(f.begin(), f.end());
    faces.push_back(std::move(f));
  }
  out.push_back(std::move(node));
  return true;
}

}  // namespace cellforge::csg
