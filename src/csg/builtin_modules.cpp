// The geometry modules: OpenSCAD's parameters (names, positions, defaults, r/d
// alternatives) read into tree nodes. Arguments OpenSCAD would ignore with a warning
// and replace by a default are errors here when they would change the geometry: a
// cube whose size is a string is not built as a unit cube.
#include <cmath>
#include <map>
#include <span>

#include "cellforge/geom/union_find.h"
#include "cellforge/geom/volume.h"
#include "interp.h"

namespace cellforge::csg {

const Arg* Params::find(const std::string& name) const {
  for (const Arg& a : args_) {
    if (a.name == name) return &a;
  }
  std::size_t index = 0;
  for (; index < names_.size() && names_[index] != name; ++index) {
  }
  if (index == names_.size()) return nullptr;
  std::size_t positional = 0;
  for (const Arg& a : args_) {
    if (!a.name.empty()) continue;
    if (positional++ == index) return &a;
  }
  return nullptr;
}

const Value& Params::get(const std::string& name) const {
  static const Value kUndef;
  const Arg* a = find(name);
  return a ? a->value : kUndef;
}

SourcePos Params::pos(const std::string& name) const {
  const Arg* a = find(name);
  return a ? a->pos : call_;
}

shape::Faceting Interp::faceting(const Params& p, const EnvPtr& env) {
  shape::Faceting f;
  auto get = [&](const char* name, double& out) {
    Value v = p.get(name);
    if (v.is_undef()) v = dollar(name, env);
    if (v.is_number()) out = v.as_number();
  };
  get("$fn", f.fn);
  get("$fa", f.fa);
  get("$fs", f.fs);
  return f;
}

namespace {

// The faces of the shells (faces joined by edges) that point inward: listed clockwise
// seen from outside, as OpenSCAD wants them, a closed shell (each edge used once each
// way) enclosing a negative volume. OpenSCAD (CGAL) builds such a shell as the volume
// it encloses.
std::vector<std::size_t> inward_faces(const std::vector<Vec3>& points,
                                      const std::vector<std::vector<std::uint32_t>>& faces) {
  UnionFind shells(faces.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> face_at;  // an edge's first face
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (std::size_t i = 0; i < faces[f].size(); ++i) {
      const std::uint32_t a = faces[f][i], b = faces[f][(i + 1) % faces[f].size()];
      const auto [it, fresh] = face_at.try_emplace({std::min(a, b), std::max(a, b)}, f);
      if (!fresh) shells.unite_to_smaller(static_cast<std::uint32_t>(it->second), static_cast<std::uint32_t>(f));
    }
  std::map<std::uint32_t, std::vector<std::vector<std::uint32_t>>> loops;  // by shell
  std::map<std::uint32_t, std::vector<std::size_t>> members;
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const std::uint32_t root = shells.find(static_cast<std::uint32_t>(f));
    loops[root].push_back(faces[f]);
    members[root].push_back(f);
  }
  std::vector<std::size_t> out;
  for (const auto& [root, shell] : loops) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> balance;
    for (const auto& f : shell)
      for (std::size_t i = 0; i < f.size(); ++i) {
        const std::uint32_t a = f[i], b = f[(i + 1) % f.size()];
        balance[{std::min(a, b), std::max(a, b)}] += a < b ? 1 : -1;
      }
    bool closed = true;
    for (const auto& [edge, n] : balance) closed &= n == 0;
    if (closed && volume_sign(std::span<const Vec3>(points), shell) > 0)
      out.insert(out.end(), members[root].begin(), members[root].end());
  }
  return out;
}

struct Named {
  const char* name;
  unsigned rgb;
};

// The SVG (CSS 3) color names OpenSCAD's color() knows.
constexpr Named kColors[] = {
    {"black", 0x000000},        {"white", 0xFFFFFF},       {"red", 0xFF0000},
    {"green", 0x008000},        {"lime", 0x00FF00},        {"blue", 0x0000FF},
    {"yellow", 0xFFFF00},       {"cyan", 0x00FFFF},        {"aqua", 0x00FFFF},
    {"magenta", 0xFF00FF},      {"fuchsia", 0xFF00FF},     {"gray", 0x808080},
    {"grey", 0x808080},         {"silver", 0xC0C0C0},      {"maroon", 0x800000},
    {"olive", 0x808000},        {"navy", 0x000080},        {"purple", 0x800080},
    {"teal", 0x008080},         {"orange", 0xFFA500},      {"pink", 0xFFC0CB},
    {"brown", 0xA52A2A},        {"gold", 0xFFD700},        {"lightgray", 0xD3D3D3},
    {"lightgrey", 0xD3D3D3},    {"darkgray", 0xA9A9A9},    {"darkgrey", 0xA9A9A9},
    {"lightblue", 0xADD8E6},    {"darkblue", 0x00008B},    {"lightgreen", 0x90EE90},
    {"darkgreen", 0x006400},    {"darkred", 0x8B0000},     {"steelblue", 0x4682B4},
    {"skyblue", 0x87CEEB},      {"tan", 0xD2B48C},         {"beige", 0xF5F5DC},
    {"ivory", 0xFFFFF0},        {"khaki", 0xF0E68C},       {"violet", 0xEE82EE},
    {"indigo", 0x4B0082},       {"coral", 0xFF7F50},       {"salmon", 0xFA8072},
    {"tomato", 0xFF6347},       {"crimson", 0xDC143C},     {"chocolate", 0xD2691E},
    {"sienna", 0xA0522D},       {"peru", 0xCD853F},        {"wheat", 0xF5DEB3},
    {"turquoise", 0x40E0D0},    {"slategray", 0x708090},   {"slategrey", 0x708090},
    {"dimgray", 0x696969},      {"dimgrey", 0x696969},     {"orchid", 0xDA70D6},
    {"plum", 0xDDA0DD},         {"lavender", 0xE6E6FA},    {"firebrick", 0xB22222},
    {"forestgreen", 0x228B22},  {"seagreen", 0x2E8B57},    {"royalblue", 0x4169E1},
    {"midnightblue", 0x191970}, {"darkorange", 0xFF8C00},  {"goldenrod", 0xDAA520},
    {"whitesmoke", 0xF5F5F5},   {"gainsboro", 0xDCDCDC},   {"linen", 0xFAF0E6},
    {"snow", 0xFFFAFA},         {"honeydew", 0xF0FFF0},    {"mintcream", 0xF5FFFA},
    {"azure", 0xF0FFFF},        {"aliceblue", 0xF0F8FF},   {"ghostwhite", 0xF8F8FF},
    {"seashell", 0xFFF5EE},     {"oldlace", 0xFDF5E6},     {"cornsilk", 0xFFF8DC},
    {"chartreuse", 0x7FFF00},   {"lawngreen", 0x7CFC00},   {"springgreen", 0x00FF7F},
    {"dodgerblue", 0x1E90FF},   {"deepskyblue", 0x00BFFF}, {"cadetblue", 0x5F9EA0},
    {"hotpink", 0xFF69B4},      {"deeppink", 0xFF1493},    {"mediumpurple", 0x9370DB},
    {"darkviolet", 0x9400D3},   {"olivedrab", 0x6B8E23},   {"yellowgreen", 0x9ACD32},
    {"burlywood", 0xDEB887},    {"sandybrown", 0xF4A460},  {"rosybrown", 0xBC8F8F},
    {"antiquewhite", 0xFAEBD7}, {"aquamarine", 0x7FFFD4},  {"bisque", 0xFFE4C4},
    {"blanchedalmond", 0xFFEBCD}, {"blueviolet", 0x8A2BE2}, {"cornflowerblue", 0x6495ED},
    {"darkcyan", 0x008B8B},     {"darkgoldenrod", 0xB8860B}, {"darkkhaki", 0xBDB76B},
    {"darkmagenta", 0x8B008B},  {"darkolivegreen", 0x556B2F}, {"darkorchid", 0x9932CC},
    {"darksalmon", 0xE9967A},   {"darkseagreen", 0x8FBC8F}, {"darkslateblue", 0x483D8B},
    {"darkslategray", 0x2F4F4F}, {"darkslategrey", 0x2F4F4F}, {"darkturquoise", 0x00CED1},
    {"floralwhite", 0xFFFAF0},  {"greenyellow", 0xADFF2F}, {"indianred", 0xCD5C5C},
    {"lavenderblush", 0xFFF0F5}, {"lemonchiffon", 0xFFFACD}, {"lightcoral", 0xF08080},
    {"lightcyan", 0xE0FFFF},    {"lightgoldenrodyellow", 0xFAFAD2}, {"lightpink", 0xFFB6C1},
    {"lightsalmon", 0xFFA07A},  {"lightseagreen", 0x20B2AA}, {"lightskyblue", 0x87CEFA},
    {"lightslategray", 0x778899}, {"lightslategrey", 0x778899}, {"lightsteelblue", 0xB0C4DE},
    {"lightyellow", 0xFFFFE0},  {"limegreen", 0x32CD32},   {"mediumaquamarine", 0x66CDAA},
    {"mediumblue", 0x0000CD},   {"mediumorchid", 0xBA55D3}, {"mediumseagreen", 0x3CB371},
    {"mediumslateblue", 0x7B68EE}, {"mediumspringgreen", 0x00FA9A},
    {"mediumturquoise", 0x48D1CC}, {"mediumvioletred", 0xC71585}, {"mistyrose", 0xFFE4E1},
    {"moccasin", 0xFFE4B5},     {"navajowhite", 0xFFDEAD}, {"orangered", 0xFF4500},
    {"palegoldenrod", 0xEEE8AA}, {"palegreen", 0x98FB98},  {"paleturquoise", 0xAFEEEE},
    {"palevioletred", 0xDB7093}, {"papayawhip", 0xFFEFD5}, {"peachpuff", 0xFFDAB9},
    {"powderblue", 0xB0E0E6},   {"saddlebrown", 0x8B4513}, {"slateblue", 0x6A5ACD},
    {"thistle", 0xD8BFD8},
};

int hex_digit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

bool parse_color(const std::string& s, std::array<double, 4>& rgba) {
  if (!s.empty() && s[0] == '#') {
    const std::string h = s.substr(1);
    std::vector<int> d;
    for (char c : h) {
      if (hex_digit(c) < 0) return false;
      d.push_back(hex_digit(c));
    }
    if (d.size() == 3 || d.size() == 4) {
      for (std::size_t i = 0; i < d.size(); ++i) rgba[i] = d[i] * 17 / 255.0;
      if (d.size() == 3) rgba[3] = 1;
      return true;
    }
    if (d.size() == 6 || d.size() == 8) {
      for (std::size_t i = 0; i < d.size() / 2; ++i)
        rgba[i] = (d[2 * i] * 16 + d[2 * i + 1]) / 255.0;
      if (d.size() == 6) rgba[3] = 1;
      return true;
    }
    return false;
  }
  std::string lower;
  for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  for (const Named& n : kColors) {
    if (lower == n.name) {
      rgba = {((n.rgb >> 16) & 0xFF) / 255.0, ((n.rgb >> 8) & 0xFF) / 255.0, (n.rgb & 0xFF) / 255.0,
              1};
      return true;
    }
  }
  if (lower == "transparent") {
    rgba = {0, 0, 0, 0};
    return true;
  }
  return false;
}

}  // namespace

bool Interp::call_builtin_module(const Stmt& s, const Args& args, const EnvPtr& env,
                                 std::vector<NodePtr>& out) {
  const std::string& name = s.name;
  auto node = std::make_shared<Node>();
  node->pos = s.pos;
  // The children, in a scope that holds the $ arguments of this call.
  auto kids = [&]() {
    std::vector<const Stmt*> stmts;
    for (const StmtPtr& c : s.children) stmts.push_back(c.get());
    auto scope = std::make_shared<Env>();
    scope->parent = env;
    for (const Arg& a : args) {
      if (!a.name.empty() && a.name[0] == '$') scope->set(a.name, a.value);
    }
    return run_scope(stmts, scope);
  };
  auto number = [&](const Params& p, const char* key, double fallback) {
    const Value& v = p.get(key);
    if (v.is_undef()) return fallback;
    if (!v.is_number() || !std::isfinite(v.as_number())) {
      fail(p.pos(key), name + "(): " + key + " must be a finite number, not " + v.to_echo());
    }
    return v.as_number();
  };
  auto flag = [&](const Params& p, const char* key) {
    const Value& v = p.get(key);
    if (v.is_undef()) return false;
    if (!v.is_bool()) warn(p.pos(key), name + "(): " + key + " should be true or false");
    return v.truthy();
  };
  auto radius = [&](const Params& p, const char* r, const char* d, double fallback) {
    if (p.has(d)) return number(p, d, 0) / 2;
    return number(p, r, fallback);
  };
  // A vector of 2 or 3 finite numbers. A transform given anything else is left out
  // with a warning, as OpenSCAD does; a size (strict) is an error.
  auto vec = [&](const Params& p, const char* key, Vec3 fallback, double z_default,
                 bool strict = false) {
    const Value& v = p.get(key);
    if (v.is_undef()) return fallback;
    bool ok = v.is_vector() && !v.as_vector().empty() && v.as_vector().size() <= 3;
    double c[3] = {0, 0, z_default};
    for (std::size_t i = 0; ok && i < v.as_vector().size(); ++i) {
      ok = to_number(v.as_vector()[i], c[i]) && std::isfinite(c[i]);
    }
    if (!ok) {
      const std::string what =
          name + "(): " + key + " must be a vector of 2 or 3 finite numbers, not " + v.to_echo();
      if (strict) fail(p.pos(key), what);
      warn(p.pos(key), what + " (ignored, as OpenSCAD does)");
      return fallback;
    }
    return Vec3{c[0], c[1], c[2]};
  };
  auto leaf = [&](NodeKind k) {
    node->kind = k;
    out.push_back(node);
    if (!s.children.empty()) warn(s.pos, name + "() takes no children (ignored)");
    return true;
  };
  auto with_children = [&](NodeKind k) {
    node->kind = k;
    node->children = kids();
    out.push_back(node);
    return true;
  };

  if (name == "cube") {
    const Params p(args, {"size", "center"}, s.pos);
    const Value& size = p.get("size");
    if (size.is_number()) {
      const double a = number(p, "size", 1);
      node->size = Vec3{a, a, a};
    } else if (!size.is_undef()) {
      if (!size.is_vector() || size.as_vector().size() != 3) {
        fail(p.pos("size"), "cube(): size must be a number or [x, y, z], not " + size.to_echo());
      }
      node->size = vec(p, "size", {1, 1, 1}, 0, true);
    }
    node->center = flag(p, "center");
    return leaf(NodeKind::kCube);
  }
  if (name == "sphere") {
    const Params p(args, {"r"}, s.pos);
    node->r = radius(p, "r", "d", 1);
    node->faceting = faceting(p, env);
    return leaf(NodeKind::kSphere);
  }
  if (name == "cylinder") {
    const Params p(args, {"h", "r1", "r2", "center"}, s.pos);
    node->h = number(p, "h", 1);
    const double r = radius(p, "r", "d", 1);
    node->r1 = p.has("d1") ? number(p, "d1", 0) / 2 : number(p, "r1", r);
    node->r2 = p.has("d2") ? number(p, "d2", 0) / 2 : number(p, "r2", r);
    node->center = flag(p, "center");
    node->faceting = faceting(p, env);
    return leaf(NodeKind::kCylinder);
  }
  if (name == "polyhedron" || name == "polygon") {
    const bool poly3 = name == "polyhedron";
    const Params p(args,
                   poly3 ? std::vector<std::string>{"points", "faces", "convexity"}
                         : std::vector<std::string>{"points", "paths", "convexity"},
                   s.pos);
    const Value& pts = p.get("points");
    if (!pts.is_vector()) fail(p.pos("points"), name + "(): points must be a list of points");
    for (const Value& v : pts.as_vector()) {
      Vec3 q;
      if (!to_vec3(v, q, !poly3) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
          !std::isfinite(q.z)) {
        fail(p.pos("points"), name + "(): a point must be [x, y" + (poly3 ? ", z" : "") +
                                  "] of finite numbers, not " + v.to_echo());
      }
      node->points.push_back(q);
    }
    const char* key = poly3 ? (p.has("faces") ? "faces" : "triangles") : "paths";
    Value faces = p.get(key);
    if (poly3 && faces.is_undef()) {
      for (const Arg& a : args) {
        if (a.name == "triangles") faces = a.value;
      }
    }
    if (!faces.is_undef()) {
      if (!faces.is_vector())
        fail(p.pos(key), name + "(): " + key + " must be a list of index lists");
      for (const Value& f : faces.as_vector()) {
        if (!f.is_vector())
          fail(p.pos(key),
               name + "(): " + key + " must be a list of index lists, not " + f.to_echo());
        std::vector<std::uint32_t> idx;
        for (const Value& i : f.as_vector()) {
          if (!i.is_number() || !(i.as_number() >= 0) ||
              i.as_number() >= static_cast<double>(node->points.size())) {
            fail(p.pos(key), name + "(): index " + i.to_echo() + " in " + f.to_echo() +
                                 " names no point (there are " +
                                 std::to_string(node->points.size()) + ")");
          }
          idx.push_back(static_cast<std::uint32_t>(i.as_number()));
        }
        node->faces.push_back(std::move(idx));
      }
    } else if (poly3) {
      fail(s.pos, "polyhedron(): faces are missing");
    }
    if (poly3) {
      const std::vector<std::size_t> inward = inward_faces(node->points, node->faces);
      if (!inward.empty()) {
        warn(s.pos, "polyhedron(): the faces of a closed shell point inward (as listed they "
                    "enclose a negative volume); reversed, since OpenSCAD builds the volume "
                    "they enclose");
        for (std::size_t f : inward) std::reverse(node->faces[f].begin(), node->faces[f].end());
      }
    }
    return leaf(poly3 ? NodeKind::kPolyhedron : NodeKind::kPolygon);
  }
  if (name == "square") {
    const Params p(args, {"size", "center"}, s.pos);
    const Value& size = p.get("size");
    if (size.is_number()) {
      const double a = number(p, "size", 1);
      node->size = Vec3{a, a, 0};
    } else if (!size.is_undef()) {
      if (!size.is_vector() || size.as_vector().size() != 2) {
        fail(p.pos("size"), "square(): size must be a number or [x, y], not " + size.to_echo());
      }
      node->size = vec(p, "size", {1, 1, 0}, 0, true);
    } else {
      node->size = Vec3{1, 1, 0};
    }
    node->center = flag(p, "center");
    return leaf(NodeKind::kSquare);
  }
  if (name == "circle") {
    const Params p(args, {"r"}, s.pos);
    node->r = radius(p, "r", "d", 1);
    node->faceting = faceting(p, env);
    return leaf(NodeKind::kCircle);
  }
  if (name == "translate" || name == "scale" || name == "mirror") {
    const Params p(args, {"v"}, s.pos);
    if (name == "translate") {
      node->matrix = shape::Transform::translate(vec(p, "v", {0, 0, 0}, 0));
    } else if (name == "scale") {
      const Value& v = p.get("v");
      Vec3 f = v.is_number() ? Vec3{v.as_number(), v.as_number(), v.as_number()}
                             : vec(p, "v", {1, 1, 1}, 1);
      node->matrix = shape::Transform::scale(f);
    } else {
      const Vec3 n = vec(p, "v", {1, 0, 0}, 0);
      node->matrix = (n.x == 0 && n.y == 0 && n.z == 0) ? shape::Transform::identity()
                                                        : shape::Transform::mirror(n);
    }
    return with_children(NodeKind::kMultmatrix);
  }
  if (name == "rotate") {
    const Params p(args, {"a", "v"}, s.pos);
    const Value& a = p.get("a");
    if (a.is_vector()) {
      node->matrix = shape::Transform::rotate_xyz(vec(p, "a", {0, 0, 0}, 0));
    } else if (a.is_number()) {
      const Vec3 axis = p.has("v") ? vec(p, "v", {0, 0, 1}, 0) : Vec3{0, 0, 1};
      const double deg = number(p, "a", 0);
      node->matrix = (axis.x == 0 && axis.y == 0 && axis.z == 0)
                         ? shape::Transform::identity()
                         : shape::Transform::rotate(deg, axis);
    } else if (!a.is_undef()) {
      fail(p.pos("a"), "rotate(): a must be a number or a vector, not " + a.to_echo());
    }
    return with_children(NodeKind::kMultmatrix);
  }
  if (name == "multmatrix") {
    const Params p(args, {"m"}, s.pos);
    const Value& m = p.get("m");
    std::array<std::array<double, 4>, 4> rows{
        {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
    if (!m.is_undef()) {
      if (!m.is_vector() || m.as_vector().size() > 4)
        fail(p.pos("m"), "multmatrix(): m must be a 4x4 matrix");
      for (std::size_t i = 0; i < m.as_vector().size(); ++i) {
        const Value& row = m.as_vector()[i];
        if (!row.is_vector() || row.as_vector().size() > 4)
          fail(p.pos("m"), "multmatrix(): m must be a 4x4 matrix");
        for (std::size_t j = 0; j < row.as_vector().size(); ++j) {
          if (!to_number(row.as_vector()[j], rows[i][j]) || !std::isfinite(rows[i][j])) {
            fail(p.pos("m"), "multmatrix(): the matrix must hold finite numbers");
          }
        }
      }
    }
    auto t = shape::Transform::from_matrix(rows);
    if (!t) fail(p.pos("m"), "multmatrix(): " + t.error().message);
    node->matrix = *t;
    return with_children(NodeKind::kMultmatrix);
  }
  if (name == "resize") {
    const Params p(args, {"newsize", "auto"}, s.pos);
    node->size = vec(p, "newsize", {0, 0, 0}, 0);
    const Value& a = p.get("auto");
    if (a.is_vector()) {
      for (std::size_t i = 0; i < 3 && i < a.as_vector().size(); ++i)
        node->auto_size[i] = a.as_vector()[i].truthy();
    } else if (a.truthy()) {
      node->auto_size = {true, true, true};
    }
    return with_children(NodeKind::kResize);
  }
  if (name == "color") {
    const Params p(args, {"c", "alpha"}, s.pos);
    const Value& c = p.get("c");
    if (c.is_vector()) {
      const Vector& v = c.as_vector();
      for (std::size_t i = 0; i < 4 && i < v.size(); ++i) {
        if (v[i].is_number()) node->color[i] = std::clamp(v[i].as_number(), 0.0, 1.0);
      }
      if (v.size() < 4) node->color[3] = 1;
    } else if (c.is_string()) {
      if (!parse_color(c.as_string(), node->color))
        warn(p.pos("c"), "color(): unknown color " + c.to_echo());
    }
    if (p.get("alpha").is_number()) node->color[3] = p.get("alpha").as_number();
    return with_children(NodeKind::kColor);
  }
  if (name == "union" || name == "group" || name == "render") {
    return with_children(name == "union" ? NodeKind::kUnion : NodeKind::kGroup);
  }
  if (name == "difference") return with_children(NodeKind::kDifference);
  if (name == "intersection") return with_children(NodeKind::kIntersection);
  if (name == "hull") return with_children(NodeKind::kHull);
  if (name == "minkowski") return with_children(NodeKind::kMinkowski);
  if (name == "offset") {
    const Params p(args, {"r", "delta", "chamfer"}, s.pos);
    if (p.has("r")) {
      node->round = true;
      node->delta = number(p, "r", 0);
    } else {
      node->delta = number(p, "delta", 1);
    }
    node->chamfer = flag(p, "chamfer");
    node->faceting = faceting(p, env);
    return with_children(NodeKind::kOffset);
  }
  if (name == "projection") {
    const Params p(args, {"cut"}, s.pos);
    node->cut = flag(p, "cut");
    return with_children(NodeKind::kProjection);
  }
  if (name == "linear_extrude") {
    const Params p(args, {"height", "center", "convexity", "twist", "slices", "scale"}, s.pos);
    node->linear.height = number(p, "height", 100);
    node->linear.center = flag(p, "center");
    node->linear.twist = number(p, "twist", 0);
    const double slices = number(p, "slices", 0);
    node->linear.slices = slices >= 1 ? static_cast<int>(std::min(slices, 1e6)) : 0;
    const Value& sc = p.get("scale");
    if (sc.is_number()) {
      node->linear.scale_x = node->linear.scale_y = sc.as_number();
    } else if (!sc.is_undef()) {
      const Vec3 f = vec(p, "scale", {1, 1, 1}, 1);
      node->linear.scale_x = f.x;
      node->linear.scale_y = f.y;
    }
    node->linear.faceting = faceting(p, env);
    return with_children(NodeKind::kLinearExtrude);
  }
  if (name == "rotate_extrude") {
    const Params p(args, {"angle", "convexity"}, s.pos);
    node->rotate.angle = number(p, "angle", 360);
    node->rotate.faceting = faceting(p, env);
    return with_children(NodeKind::kRotateExtrude);
  }
  if (name == "import") {
    const Params p(args, {"file", "convexity", "layer"}, s.pos);
    const Value& f = p.get("file");
    if (!f.is_string()) fail(p.pos("file"), "import(): file must be a string");
    if (!options_.allow_files) fail(s.pos, "import(): reading files is turned off");
    node->path = script_relative(f.as_string(), s.pos);
    node->faceting = faceting(p, env);
    const Value& layer = p.get("layer");
    if (!layer.is_undef()) {
      if (!layer.is_string()) fail(p.pos("layer"), "import(): layer must be a string");
      node->layer = layer.as_string();
    }
    if (p.has("origin")) node->origin = vec(p, "origin", {0, 0, 0}, 0, true);
    node->import_scale = number(p, "scale", 1);
    for (const char* unsupported : {"width", "height", "center", "dpi", "id"}) {
      if (p.has(unsupported))
        fail(p.pos(unsupported), std::string("import(): ") + unsupported + " is not supported yet");
    }
    return leaf(NodeKind::kImport);
  }
  if (name == "text") return text(s, args, env, out);
  if (name == "surface") return surface(s, args, out);
  if (name == "roof") fail(s.pos, name + "() is not supported yet");
  return false;
}

}  // namespace cellforge::csg
