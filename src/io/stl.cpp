// STL, binary and ASCII. Which one a file is follows from its content: binary when
// the size is exactly 84 + 50 * (the triangle count in bytes 80..83), ASCII when it
// starts with "solid" and is text; anything else is an error that says why.
#include <cmath>
#include <cstring>

#include "io/formats.h"
#include "io/text.h"
#include "io/weld.h"

namespace cellforge::io {

namespace {

constexpr std::size_t kHeader = 84, kRecord = 50;

std::uint32_t read_u32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | std::uint32_t{p[1]} << 8 | std::uint32_t{p[2]} << 16 |
         std::uint32_t{p[3]} << 24;
}

float read_f32(const std::uint8_t* p) {
  const std::uint32_t u = read_u32(p);
  float f;
  std::memcpy(&f, &u, sizeof f);
  return f;
}

Result<PolygonSoup> parse_binary(std::span<const std::uint8_t> bytes) {
  const std::size_t n = read_u32(bytes.data() + 80);
  PolygonSoup soup;
  soup.polygons.reserve(n);  // checked: the size is exactly 84 + 50 n
  soup.positions.reserve(n / 2 + 3);
  PositionIndex interner(soup.positions);
  interner.reserve(n / 2 + 3);
  for (std::size_t t = 0; t < n; ++t) {
    const std::uint8_t* rec = bytes.data() + kHeader + kRecord * t;
    std::vector<std::uint32_t> tri(3);
    for (int k = 0; k < 3; ++k) {
      const std::uint8_t* c = rec + 12 + 12 * k;
      const Vec3 p{read_f32(c), read_f32(c + 4), read_f32(c + 8)};
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        return byte_error("stl", static_cast<std::size_t>(c - bytes.data()),
                          "triangle " + std::to_string(t) + " vertex " + std::to_string(k) +
                              " has a non-finite coordinate (NaN or Inf)");
      }
      tri[k] = interner.add(p);
    }
    soup.polygons.push_back(std::move(tri));
  }
  return soup;
}

bool starts_with_solid(std::span<const std::uint8_t> bytes) {
  std::size_t i = 0;
  while (i < bytes.size() &&
         (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\r' || bytes[i] == '\n'))
    ++i;
  return bytes.size() - i >= 5 && std::memcmp(bytes.data() + i, "solid", 5) == 0;
}

Result<PolygonSoup> parse_ascii(std::string_view text) {
  if (Status s = check_utf8("stl", text); !s) return s.error();
  Tokenizer tok(text, false);
  PolygonSoup soup;
  PositionIndex interner(soup.positions);
  const auto expect = [&](std::string_view word) -> Status {
    const std::string_view t = tok.next();
    if (t == word) return Status::Ok();
    return parse_error("stl", tok.pos(),
                       "expected '" + std::string(word) + "', found " +
                           (t.empty() ? std::string("end of file") : quote(t)));
  };
  if (Status s = expect("solid"); !s) return s.error();
  // The name runs to the end of the line.
  std::string_view t = tok.next();
  while (!t.empty() && !tok.line_start()) {
    if (t == "facet" || t == "endsolid") break;
    soup.name += (soup.name.empty() ? "" : " ") + std::string(t);
    t = tok.next();
  }
  while (true) {
    if (t == "endsolid") return soup;
    if (t != "facet") {
      return parse_error("stl", tok.pos(),
                         "expected 'facet' or 'endsolid', found " +
                             (t.empty() ? std::string("end of file") : quote(t)));
    }
    if (Status s = expect("normal"); !s) return s.error();
    double ignored;
    for (int k = 0; k < 3; ++k) {
      t = tok.next();
      if (!parse_double(t, ignored)) return parse_error("stl", tok.pos(), "bad normal " + quote(t));
    }
    if (Status s = expect("outer"); !s) return s.error();
    if (Status s = expect("loop"); !s) return s.error();
    std::vector<std::uint32_t> poly;
    while (true) {
      t = tok.next();
      if (t == "endloop") break;
      if (t != "vertex") {
        return parse_error("stl", tok.pos(),
                           "expected 'vertex' or 'endloop', found " +
                               (t.empty() ? std::string("end of file") : quote(t)));
      }
      double c[3];
      for (double& x : c) {
        t = tok.next();
        if (!parse_double(t, x)) {
          return parse_error(
              "stl", tok.pos(),
              "expected a number, found " + (t.empty() ? std::string("end of file") : quote(t)));
        }
        if (!std::isfinite(x)) {
          return parse_error("stl", tok.pos(), "non-finite coordinate " + quote(t));
        }
      }
      poly.push_back(interner.add({c[0], c[1], c[2]}));
    }
    if (poly.size() < 3) {
      return parse_error("stl", tok.pos(),
                         "facet has " + std::to_string(poly.size()) + " vertices (at least 3)");
    }
    soup.polygons.push_back(std::move(poly));
    if (Status s = expect("endfacet"); !s) return s.error();
    t = tok.next();
  }
}

}  // namespace

Result<PolygonSoup> parse_stl(std::span<const std::uint8_t> bytes) {
  if (Status s =
          check_not_blank("stl", {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
      !s)
    return s.error();
  const bool solid = starts_with_solid(bytes);
  if (bytes.size() >= kHeader) {
    const std::uint64_t n = read_u32(bytes.data() + 80);
    const std::uint64_t expected = kHeader + kRecord * n;
    if (expected == bytes.size()) return parse_binary(bytes);
    // A header that starts with "solid" is common in binary files; only text that
    // contains no NUL byte is taken as ASCII.
    const bool text = solid && std::memchr(bytes.data(), 0, bytes.size()) == nullptr;
    if (!text) {
      return byte_error("stl", 80,
                        "binary STL header declares " + std::to_string(n) + " triangles (" +
                            std::to_string(expected) + " bytes) but the file has " +
                            std::to_string(bytes.size()) + " bytes (" +
                            (expected > bytes.size() ? "truncated" : "trailing data") + ")");
    }
  } else if (!solid) {
    return byte_error("stl", bytes.size(),
                      "file of " + std::to_string(bytes.size()) +
                          " bytes is neither ASCII STL (no 'solid') nor binary STL (84-byte "
                          "header)");
  }
  return parse_ascii(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

namespace {

void put_u32(std::string& out, std::uint32_t v) {
  for (int k = 0; k < 4; ++k) out += static_cast<char>((v >> (8 * k)) & 0xFF);
}

void put_f32(std::string& out, double d) {
  const float f = static_cast<float>(d);
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  put_u32(out, u);
}

}  // namespace

std::string write_stl(const TriangleMesh& mesh, bool binary, const std::string& name) {
  std::string out;
  if (binary) {
    out.reserve(kHeader + kRecord * mesh.triangles.size());
    std::string header = "binary STL written by cellforge " + name;
    header.resize(80, ' ');
    out += header;
    put_u32(out, static_cast<std::uint32_t>(mesh.triangles.size()));
    for (const auto& t : mesh.triangles) {
      const Vec3 n = triangle_normal(mesh, t);
      put_f32(out, n.x), put_f32(out, n.y), put_f32(out, n.z);
      for (std::uint32_t i : t) {
        const Vec3 p = mesh.positions[i];
        put_f32(out, p.x), put_f32(out, p.y), put_f32(out, p.z);
      }
      out += '\0', out += '\0';
    }
    return out;
  }
  char buf[160];
  std::string solid_name = name.empty() ? "cellforge" : name;
  for (char& c : solid_name)
    if (c == '\n' || c == '\r') c = ' ';
  out += "solid " + solid_name + "\n";
  for (const auto& t : mesh.triangles) {
    const Vec3 n = triangle_normal(mesh, t);
    std::snprintf(buf, sizeof buf, "  facet normal %.9g %.9g %.9g\n    outer loop\n", n.x, n.y,
                  n.z);
    out += buf;
    for (std::uint32_t i : t) {
      const Vec3 p = mesh.positions[i];
      std::snprintf(buf, sizeof buf, "      vertex %.17g %.17g %.17g\n", p.x, p.y, p.z);
      out += buf;
    }
    out += "    endloop\n  endfacet\n";
  }
  out += "endsolid " + solid_name + "\n";
  return out;
}

}  // namespace cellforge::io
