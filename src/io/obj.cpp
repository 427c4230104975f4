// Wavefront OBJ: `v` positions, `f` polygons (v, v/vt, v//vn, v/vt/vn; negative
// indices count back from the latest vertex), `l` polylines as wire edges, `p`
// points; the first `o` (or `g`) names the object. Other statements (vt, vn,
// usemtl, s, ...) are read past. Indices must name vertices defined above them.
#include <cmath>
#include <cstdio>

#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

namespace {

struct ObjState {
  PolygonSoup soup;
  std::int64_t texcoords = 0, normals = 0;
};

// Resolves an OBJ index (1-based, or negative from the end) against `count`.
bool resolve(std::int64_t i, std::int64_t count, std::int64_t& out) {
  if (i > 0 && i <= count) {
    out = i - 1;
    return true;
  }
  if (i < 0 && -i <= count) {
    out = count + i;
    return true;
  }
  return false;
}

}  // namespace

Result<PolygonSoup> parse_obj(std::string_view text) {
  if (Status s = check_not_blank("obj", text); !s) return s.error();
  if (Status s = check_utf8("obj", text); !s) return s.error();
  Tokenizer tok(text, true);
  ObjState st;
  PolygonSoup& soup = st.soup;
  std::string_view t = tok.next();
  while (!t.empty()) {
    const TextPos at = tok.pos();
    const std::string_view keyword = t;
    // The statement's arguments: the tokens up to the end of the line.
    std::vector<std::pair<std::string_view, TextPos>> args;
    for (t = tok.next(); !t.empty() && !tok.line_start(); t = tok.next())
      args.push_back({t, tok.pos()});
    if (keyword == "v") {
      if (args.size() < 3) return parse_error("obj", at, "'v' needs 3 coordinates");
      double c[3];
      for (int k = 0; k < 3; ++k) {
        if (!parse_double(args[k].first, c[k]))
          return parse_error("obj", args[k].second,
                             "expected a number, found " + quote(args[k].first));
        if (!std::isfinite(c[k]))
          return parse_error("obj", args[k].second,
                             "non-finite coordinate " + quote(args[k].first));
      }
      if (soup.positions.size() >= 0xFFFFFFF0u) return parse_error("obj", at, "too many vertices");
      soup.positions.push_back({c[0], c[1], c[2]});
    } else if (keyword == "vt") {
      ++st.texcoords;
    } else if (keyword == "vn") {
      ++st.normals;
    } else if (keyword == "f" || keyword == "l" || keyword == "p") {
      std::vector<std::uint32_t> idx;
      const auto count = static_cast<std::int64_t>(soup.positions.size());
      for (const auto& [a, pos] : args) {
        // v, v/vt, v//vn, v/vt/vn
        std::string_view parts[3];
        std::size_t n = 0, start = 0;
        for (std::size_t i = 0; i <= a.size(); ++i) {
          if (i == a.size() || a[i] == '/') {
            if (n == 3) return parse_error("obj", pos, "bad vertex reference " + quote(a));
            parts[n++] = a.substr(start, i - start);
            start = i + 1;
          }
        }
        const std::int64_t limits[3] = {count, st.texcoords, st.normals};
        const char* names[3] = {"vertex", "texture coordinate", "normal"};
        std::int64_t resolved[3] = {0, 0, 0};
        for (std::size_t k = 0; k < n; ++k) {
          if (k > 0 && parts[k].empty()) continue;  // v//vn, or a trailing slash
          std::int64_t i;
          if (!parse_int64(parts[k], i))
            return parse_error("obj", pos, "bad vertex reference " + quote(a));
          if (!resolve(i, limits[k], resolved[k])) {
            return parse_error("obj", pos,
                               std::string(names[k]) + " index " + std::to_string(i) +
                                   " out of range (" + std::to_string(limits[k]) + " defined)");
          }
        }
        idx.push_back(static_cast<std::uint32_t>(resolved[0]));
      }
      if (keyword == "f") {
        if (idx.size() < 3)
          return parse_error("obj", at,
                             "face has " + std::to_string(idx.size()) + " vertices (at least 3)");
        soup.polygons.push_back(std::move(idx));
      } else if (keyword == "l") {
        if (idx.size() < 2) return parse_error("obj", at, "line needs at least 2 vertices");
        for (std::size_t k = 0; k + 1 < idx.size(); ++k) soup.wires.push_back({idx[k], idx[k + 1]});
      } else {
        soup.points.insert(soup.points.end(), idx.begin(), idx.end());
      }
    } else if ((keyword == "o" || keyword == "g") && soup.name.empty() && !args.empty()) {
      soup.name = std::string(args[0].first);
    }
  }
  return std::move(st.soup);
}

Result<std::string> write_obj(const Model& m, const WriteOptions& options) {
  const TriangleMesh mesh = triangle_mesh(m, true);
  std::string out = "# written by cellforge\n";
  for (GroupId g : m.groups()) {
    if (!m.name(g).empty()) out += "o " + m.name(g) + "\n";
    break;
  }
  char buf[96];
  for (const Vec3& p : mesh.positions) {
    std::snprintf(buf, sizeof buf, "v %.17g %.17g %.17g\n", p.x, p.y, p.z);
    out += buf;
  }
  for (const auto& poly : export_polygons(m, mesh, options.triangulate)) {
    out += 'f';
    for (std::uint32_t i : poly) out += ' ' + std::to_string(i + 1);
    out += '\n';
  }
  for (EdgeId e : m.edges()) {
    if (!m.is_wire(e)) continue;
    out += "l " + std::to_string(mesh.index[m.start_of(e).value] + 1) + ' ' +
           std::to_string(mesh.index[m.end_of(e).value] + 1) + '\n';
  }
  for (VertexId v : m.vertices()) {
    if (m.first_end(v).edge.is_valid() || m.point_loop(v).is_valid()) continue;
    out += "p " + std::to_string(mesh.index[v.value] + 1) + '\n';
  }
  return out;
}

}  // namespace cellforge::io
