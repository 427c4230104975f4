// OFF (Object File Format): "OFF", the counts "nv nf ne", nv vertex lines (x y z,
// anything after the third number ignored, so COFF/NOFF colours and normals pass),
// nf face lines "n i0 ... i(n-1)", optionally followed by the face's colour "r g b"
// or "r g b a" (integers 0..255, or numbers 0..1 when one has a point or an
// exponent; anything else after the indices is ignored). Counts are
// checked against the file: a count larger than the lines that follow is an
// error, and so are lines after the last face.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

namespace {

using Line = std::vector<std::pair<std::string_view, TextPos>>;

// The next non-empty line's tokens (empty at the end of the text).
Line next_line(Tokenizer& tok, std::string_view& pending) {
  Line line;
  if (pending.empty()) return line;
  line.push_back({pending, tok.pos()});
  for (pending = tok.next(); !pending.empty() && !tok.line_start(); pending = tok.next())
    line.push_back({pending, tok.pos()});
  return line;
}

}  // namespace

Result<PolygonSoup> parse_off(std::string_view text) {
  if (Status s = check_not_blank("off", text); !s) return s.error();
  if (Status s = check_utf8("off", text); !s) return s.error();
  Tokenizer tok(text, true);
  std::string_view pending = tok.next();
  Line line = next_line(tok, pending);
  const std::string_view magic = line.empty() ? std::string_view() : line[0].first;
  if (magic != "OFF" && magic != "COFF" && magic != "NOFF" && magic != "CNOFF") {
    return parse_error("off", line.empty() ? TextPos{} : line[0].second,
                       "expected 'OFF', found " + quote(magic));
  }
  line.erase(line.begin());
  if (line.empty()) line = next_line(tok, pending);  // counts on their own line
  if (line.size() < 2) return parse_error("off", tok.pos(), "expected the counts 'nv nf ne'");
  std::int64_t nv, nf;
  if (!parse_int64(line[0].first, nv) || nv < 0)
    return parse_error("off", line[0].second, "bad vertex count " + quote(line[0].first));
  if (!parse_int64(line[1].first, nf) || nf < 0)
    return parse_error("off", line[1].second, "bad face count " + quote(line[1].first));
  // Each vertex takes at least 6 bytes ("0 0 0\n") and each face 8 ("3 0 1 2\n").
  if (nv > static_cast<std::int64_t>(text.size() / 6) ||
      nf > static_cast<std::int64_t>(text.size() / 8)) {
    return parse_error("off", line[0].second,
                       "counts " + std::to_string(nv) + " vertices, " + std::to_string(nf) +
                           " faces cannot fit in a file of " + std::to_string(text.size()) +
                           " bytes");
  }
  PolygonSoup soup;
  soup.positions.reserve(static_cast<std::size_t>(nv));
  soup.polygons.reserve(static_cast<std::size_t>(nf));
  for (std::int64_t i = 0; i < nv; ++i) {
    line = next_line(tok, pending);
    if (line.empty()) {
      return parse_error(
          "off", tok.pos(),
          "file ends after " + std::to_string(i) + " of " + std::to_string(nv) + " vertices");
    }
    if (line.size() < 3) return parse_error("off", line[0].second, "vertex needs 3 coordinates");
    double c[3];
    for (int k = 0; k < 3; ++k) {
      if (!parse_double(line[k].first, c[k]))
        return parse_error("off", line[k].second,
                           "expected a number, found " + quote(line[k].first));
      if (!std::isfinite(c[k]))
        return parse_error("off", line[k].second, "non-finite coordinate " + quote(line[k].first));
    }
    soup.positions.push_back({c[0], c[1], c[2]});
  }
  for (std::int64_t i = 0; i < nf; ++i) {
    line = next_line(tok, pending);
    if (line.empty()) {
      return parse_error(
          "off", tok.pos(),
          "file ends after " + std::to_string(i) + " of " + std::to_string(nf) + " faces");
    }
    std::int64_t n;
    if (!parse_int64(line[0].first, n) || n < 3)
      return parse_error("off", line[0].second,
                         "bad face vertex count " + quote(line[0].first) + " (at least 3)");
    if (n + 1 > static_cast<std::int64_t>(line.size())) {
      return parse_error("off", line[0].second,
                         "face declares " + std::to_string(n) + " vertices but the line has " +
                             std::to_string(line.size() - 1) + " numbers");
    }
    std::vector<std::uint32_t> poly;
    poly.reserve(static_cast<std::size_t>(n));
    for (std::int64_t k = 1; k <= n; ++k) {
      std::int64_t idx;
      if (!parse_int64(line[k].first, idx))
        return parse_error("off", line[k].second,
                           "expected an index, found " + quote(line[k].first));
      if (idx < 0 || idx >= nv)
        return parse_error(
            "off", line[k].second,
            "index " + std::to_string(idx) + " out of range (" + std::to_string(nv) + " vertices)");
      poly.push_back(static_cast<std::uint32_t>(idx));
    }
    soup.polygons.push_back(std::move(poly));
    if (line.size() >= static_cast<std::size_t>(n) + 4) {  // a colour
      const std::size_t at = static_cast<std::size_t>(n) + 1, count = std::min<std::size_t>(4, line.size() - at);
      float c[4] = {1, 1, 1, 1};
      bool ok = true, fraction = false;
      for (std::size_t k = 0; k < count; ++k) {
        double x;
        ok = ok && parse_double(line[at + k].first, x) && std::isfinite(x) && x >= 0;
        if (ok) c[k] = static_cast<float>(x);
        fraction = fraction || line[at + k].first.find_first_of(".eE") != std::string_view::npos;
      }
      if (ok) {
        if (!fraction)
          for (float& x : c) x = std::min(x, 255.0f) / 255.0f;
        if (!fraction && count == 3) c[3] = 1;
        soup.colours.resize(soup.polygons.size(), Colour{});
        soup.colours.back() = {c[0], c[1], c[2], c[3]};
      }
    }
  }
  if (!soup.colours.empty()) soup.colours.resize(soup.polygons.size(), Colour{});
  line = next_line(tok, pending);
  if (!line.empty())
    return parse_error("off", line[0].second,
                       "data after the " + std::to_string(nf) + " declared faces");
  return soup;
}

Result<std::string> write_off(const Model& m, const WriteOptions& options) {
  const TriangleMesh mesh = triangle_mesh(m, false);
  const auto polygons = export_polygons(m, mesh, options.triangulate);
  std::string out = "OFF\n" + std::to_string(mesh.positions.size()) + ' ' +
                    std::to_string(polygons.size()) + " 0\n";  // ne: unused by readers
  char buf[96];
  for (const Vec3& p : mesh.positions) {
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    out += buf;
  }
  for (const auto& poly : polygons) {
    out += std::to_string(poly.size());
    for (std::uint32_t i : poly) out += ' ' + std::to_string(i);
    out += '\n';
  }
  return out;
}

}  // namespace cellforge::io
