// `cellforge make KIND [key=value ...] -o OUT [--ascii]`: builds one primitive or sweep
// (shape/) and writes it in any format of io/ (STL binary by default). Keys follow
// OpenSCAD's parameter names where it has them (r, d, r1, r2, d1, d2, h, center, size,
// fn, fa, fs, twist, scale, slices, angle); `$fn=` is read as `fn=`.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>

#include "cellforge/io/mesh_io.h"
#include "cellforge/shape/mass.h"
#include "cellforge/shape/primitives.h"
#include "cellforge/shape/sweep.h"
#include "command.h"

namespace cellforge::cli {
namespace {

using namespace cellforge::shape;

constexpr const char* kUsage =
    "usage: cellforge make KIND [KEY=VALUE ...] -o OUT [--ascii]\n"
    "  KIND and its keys (defaults as OpenSCAD's; fn, fa, fs wherever a circle is faceted):\n"
    "    cube            size=S|X,Y,Z center=false\n"
    "    cylinder        h r|d r1|d1 r2|d2 center fn fa fs\n"
    "    sphere          r|d fn fa fs\n"
    "    torus           R r fn fa fs   (rotate_extrude() translate([R,0]) circle(r))\n"
    "    prism           n r h center   (regular n-sided prism, circumradius r)\n"
    "    pyramid         n r h center\n"
    "    frustum         n r1 r2 h center\n"
    "    polyhedron      points=X,Y,Z;X,Y,Z;... faces=I,J,K;...  (clockwise from outside)\n"
    "    linear_extrude  shape=square|circle|ngon size r|d n x y height|h center twist\n"
    "                    scale=S|SX,SY slices fn fa fs\n"
    "    rotate_extrude  shape=square|circle|ngon size r|d n x y angle start fn fa fs\n"
    "  (the 2D shape of a sweep is OpenSCAD's square(size) (center_shape=true centres it),\n"
    "   circle(r) or a regular n-gon of circumradius r, translated by [x, y])\n"
    "  Every kind also takes max_vertices=N: the most vertices it may make (default\n"
    "  10000000, checked before anything is built; docs/shape.md).\n"
    "  OUT: .stl .obj .off .3mf .json, or - for standard output with --format F;\n"
    "  --ascii writes ASCII STL.\n"
    "  Prints the counts, volume, area, centroid and bounding box of the result\n"
    "  (on standard error when the model goes to standard output).";

using Params = std::map<std::string, std::string>;

struct Kind {
  std::string name;
  std::vector<std::string> keys;
  std::function<Result<GroupId>(Model&, const Params&)> make;
};

Error bad(const std::string& key, const std::string& value, const std::string& what) {
  return Error{ErrorCode::kInvalidInput, key + "=" + value + ": expected " + what};
}

Result<std::vector<double>> numbers(const std::string& key, const std::string& text) {
  std::vector<double> out;
  std::string s = text;
  std::erase_if(s, [](char c) { return c == '[' || c == ']' || c == ' '; });
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) {
    double x = 0;
    const auto r = std::from_chars(item.data(), item.data() + item.size(), x);
    if (r.ec != std::errc() || r.ptr != item.data() + item.size()) {
      return bad(key, text, "a number or comma-separated numbers");
    }
    out.push_back(x);
  }
  if (out.empty()) return bad(key, text, "a number");
  return out;
}

// Typed lookups with OpenSCAD's defaults; errors name the key.
class Reader {
 public:
  explicit Reader(const Params& p) : p_(p) {}
  bool has(const std::string& key) const { return p_.count(key) != 0; }
  Result<double> number(const std::string& key, double fallback) const {
    if (!has(key)) return fallback;
    auto v = numbers(key, p_.at(key));
    if (!v) return v.error();
    if (v->size() != 1) return bad(key, p_.at(key), "one number");
    return v->front();
  }
  Result<bool> boolean(const std::string& key) const {
    if (!has(key)) return false;
    const std::string& v = p_.at(key);
    if (v == "true" || v == "1") return true;
    if (v == "false" || v == "0") return false;
    return bad(key, v, "true or false");
  }
  // r from r= or d= (d wins, as in OpenSCAD).
  Result<double> radius(const std::string& r, const std::string& d, double fallback) const {
    if (has(d)) {
      auto v = number(d, 0);
      if (!v) return v;
      return *v / 2;
    }
    return number(r, fallback);
  }
  Result<Faceting> faceting() const {
    auto fn = number("fn", 0), fa = number("fa", 12), fs = number("fs", 2);
    if (!fn) return fn.error();
    if (!fa) return fa.error();
    if (!fs) return fs.error();
    auto limit = max_vertices();
    if (!limit) return limit.error();
    return Faceting{.fn = *fn, .fa = *fa, .fs = *fs, .max_vertices = *limit};
  }
  Result<int> count(const std::string& key, int fallback) const {
    auto v = number(key, fallback);
    if (!v) return v.error();
    // Checked in double before the conversion, which is undefined out of range.
    if (!(std::fabs(*v) <= 2147483647.0) || *v != std::trunc(*v))
      return bad(key, p_.at(key), "a whole number of at most 2147483647");
    return static_cast<int>(*v);
  }
  Result<std::uint64_t> max_vertices() const {
    if (!has("max_vertices")) return kDefaultMaxVertices;
    const std::string& t = p_.at("max_vertices");
    std::uint64_t n = 0;
    const auto r = std::from_chars(t.data(), t.data() + t.size(), n);
    if (t.empty() || r.ec != std::errc() || r.ptr != t.data() + t.size())
      return bad("max_vertices", t, "a count of vertices");
    return n;
  }

 private:
  const Params& p_;
};

// Unwraps a Result inside a builder lambda.
#define TRY(var, expr)                  \
  auto var##_r = (expr);                \
  if (!var##_r) return var##_r.error(); \
  auto var = *var##_r

Result<GroupId> cube(Model& m, const Params& p) {
  const Reader r(p);
  Vec3 size{1, 1, 1};
  if (r.has("size")) {
    TRY(v, numbers("size", p.at("size")));
    if (v.size() == 1)
      size = {v[0], v[0], v[0]};
    else if (v.size() == 3)
      size = {v[0], v[1], v[2]};
    else
      return bad("size", p.at("size"), "one number or X,Y,Z");
  }
  TRY(center, r.boolean("center"));
  return make_cube(m, {.size = size, .center = center});
}

Result<GroupId> cylinder(Model& m, const Params& p) {
  const Reader r(p);
  TRY(h, r.number("h", 1));
  TRY(base, r.radius("r", "d", 1));
  TRY(r1, r.radius("r1", "d1", base));
  TRY(r2, r.radius("r2", "d2", base));
  TRY(center, r.boolean("center"));
  TRY(f, r.faceting());
  return make_cylinder(m, {.h = h, .r1 = r1, .r2 = r2, .center = center, .faceting = f});
}

Result<GroupId> sphere(Model& m, const Params& p) {
  const Reader r(p);
  TRY(radius, r.radius("r", "d", 1));
  TRY(f, r.faceting());
  return make_sphere(m, {.r = radius, .faceting = f});
}

Result<GroupId> torus(Model& m, const Params& p) {
  const Reader r(p);
  TRY(big, r.number("R", 2));
  TRY(small, r.number("r", 1));
  TRY(f, r.faceting());
  return make_torus(m, {.major_radius = big, .minor_radius = small, .faceting = f});
}

Result<GroupId> regular(Model& m, const Params& p, const std::string& kind) {
  const Reader r(p);
  TRY(n, r.count("n", kind == "prism" ? 6 : 4));
  TRY(h, r.number("h", 1));
  TRY(center, r.boolean("center"));
  TRY(limit, r.max_vertices());
  if (kind == "frustum") {
    TRY(r1, r.number("r1", 1));
    TRY(r2, r.number("r2", 0.5));
    return make_frustum(
        m, {.sides = n, .r1 = r1, .r2 = r2, .h = h, .center = center, .max_vertices = limit});
  }
  TRY(radius, r.number("r", 1));
  if (kind == "prism")
    return make_regular_prism(
        m, {.sides = n, .r = radius, .h = h, .center = center, .max_vertices = limit});
  return make_pyramid(m,
                      {.sides = n, .r = radius, .h = h, .center = center, .max_vertices = limit});
}

Result<GroupId> polyhedron(Model& m, const Params& p) {
  PolyhedronOptions o;
  for (const std::string key : {"points", "faces"}) {
    if (!p.count(key)) return Error{ErrorCode::kInvalidInput, "polyhedron needs " + key + "="};
    std::stringstream in(p.at(key));
    std::string item;
    while (std::getline(in, item, ';')) {
      TRY(v, numbers(key, item));
      if (key == std::string("points")) {
        if (v.size() != 3) return bad(key, item, "X,Y,Z");
        o.points.push_back({v[0], v[1], v[2]});
      } else {
        o.faces.emplace_back();
        for (double x : v) {
          if (x < 0 || x != static_cast<std::uint32_t>(x)) return bad(key, item, "indices");
          o.faces.back().push_back(static_cast<std::uint32_t>(x));
        }
      }
    }
  }
  return make_polyhedron(m, o);
}

Result<Region> shape(const Params& p) {
  const Reader r(p);
  const std::string kind = p.count("shape") ? p.at("shape") : "square";
  Result<Region> region = Error{};
  if (kind == "square") {
    Vec2 size{1, 1};
    if (r.has("size")) {
      TRY(v, numbers("size", p.at("size")));
      if (v.size() == 1)
        size = {v[0], v[0]};
      else if (v.size() == 2)
        size = {v[0], v[1]};
      else
        return bad("size", p.at("size"), "one number or X,Y");
    }
    TRY(center, r.boolean("center_shape"));
    region = rectangle(size, center);
  } else if (kind == "circle" || kind == "ngon") {
    TRY(radius, r.radius("r", "d", 1));
    TRY(f, r.faceting());
    TRY(n, r.count("n", 6));
    region = kind == "circle" ? circle(radius, f) : regular_polygon(n, radius);
  } else {
    return bad("shape", kind, "square, circle or ngon");
  }
  if (!region) return region;
  TRY(x, r.number("x", 0));
  TRY(y, r.number("y", 0));
  for (auto& loop : region->loops) {
    for (Vec2& q : loop) q = {q.x + x, q.y + y};
  }
  return region;
}

Result<GroupId> extrude(Model& m, const Params& p) {
  const Reader r(p);
  TRY(region, shape(p));
  TRY(height, r.number(r.has("h") ? "h" : "height", 1));
  TRY(center, r.boolean("center"));
  TRY(twist, r.number("twist", 0));
  TRY(slices, r.count("slices", 0));
  TRY(f, r.faceting());
  double sx = 1, sy = 1;
  if (r.has("scale")) {
    TRY(v, numbers("scale", p.at("scale")));
    if (v.size() == 1)
      sx = sy = v[0];
    else if (v.size() == 2)
      sx = v[0], sy = v[1];
    else
      return bad("scale", p.at("scale"), "S or SX,SY");
  }
  return linear_extrude(m, region,
                        {.height = height,
                         .center = center,
                         .twist = twist,
                         .scale_x = sx,
                         .scale_y = sy,
                         .slices = slices,
                         .faceting = f});
}

Result<GroupId> revolve(Model& m, const Params& p) {
  const Reader r(p);
  TRY(region, shape(p));
  TRY(angle, r.number("angle", 360));
  TRY(f, r.faceting());
  RotateExtrudeOptions o{.angle = angle, .faceting = f};
  if (r.has("start")) {
    TRY(start, r.number("start", 0));
    o.start = start;
  }
  return rotate_extrude(m, region, o);
}

const std::vector<Kind>& kinds() {
  static const std::vector<Kind> k = {
      {"cube", {"size", "center"}, cube},
      {"cylinder", {"h", "r", "d", "r1", "r2", "d1", "d2", "center", "fn", "fa", "fs"}, cylinder},
      {"sphere", {"r", "d", "fn", "fa", "fs"}, sphere},
      {"torus", {"R", "r", "fn", "fa", "fs"}, torus},
      {"prism",
       {"n", "r", "h", "center"},
       [](Model& m, const Params& p) { return regular(m, p, "prism"); }},
      {"pyramid",
       {"n", "r", "h", "center"},
       [](Model& m, const Params& p) { return regular(m, p, "pyramid"); }},
      {"frustum",
       {"n", "r1", "r2", "h", "center"},
       [](Model& m, const Params& p) { return regular(m, p, "frustum"); }},
      {"polyhedron", {"points", "faces"}, polyhedron},
      {"linear_extrude",
       {"shape", "size", "r", "d", "n", "x", "y", "center_shape", "height", "h", "center", "twist",
        "scale", "slices", "fn", "fa", "fs"},
       extrude},
      {"rotate_extrude",
       {"shape", "size", "r", "d", "n", "x", "y", "center_shape", "angle", "start", "fn", "fa",
        "fs"},
       revolve},
  };
  return k;
}

std::string joined(const std::vector<std::string>& items) {
  std::string s;
  for (const auto& i : items) s += (s.empty() ? "" : ", ") + i;
  return s;
}

void print_summary(std::ostream& os, const Model& m, GroupId g, const std::string& kind) {
  std::size_t v = 0, e = 0, f = 0;
  for (VertexId x : m.vertices()) v += m.group_of(x) == g;
  for (EdgeId x : m.edges()) e += m.group_of(x) == g;
  for (FaceId x : m.faces()) f += m.group_of(x) == g;
  const MassProperties p = mass_properties(m, g);
  os << kind << ": " << v << " vertices, " << e << " edges, " << f << " faces";
  if (!m.attribute(g, "segments").empty()) os << ", " << m.attribute(g, "segments") << " segments";
  os << "\n";
  if (p.solid) os << "volume " << format_number(p.volume) << "\n";
  os << "area " << format_number(p.area) << "\ncentroid " << p.centroid << "\nbbox " << p.bbox_min
     << " .. " << p.bbox_max << "\n";
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"build a primitive or sweep (OpenSCAD parameters) and write it to a file",
               "cellforge make"};
  std::string kind_name, out, format;
  std::vector<std::string> keys;
  bool ascii = false;
  app.add_option("KIND", kind_name, "cube, cylinder, sphere, ... (below)")->required();
  app.add_option("KEY=VALUE", keys, "the kind's parameters");
  app.add_option("-o", out, "the file to write, or - for standard output")->required();
  app.add_flag("--ascii", ascii, "write ASCII STL (default binary)");
  app.add_option("--format", format, "the format of OUT (needed for -)");
  app.footer(kUsage);
  if (auto code = parse(app, args)) return *code;
  std::vector<std::string> names;
  for (const Kind& k : kinds()) names.push_back(k.name);
  const auto kind = std::find_if(kinds().begin(), kinds().end(),
                                 [&](const Kind& k) { return k.name == kind_name; });
  if (kind == kinds().end()) {
    std::cerr << "cellforge make: unknown kind '" << kind_name << "' (valid: " << joined(names)
              << ")\n";
    return 2;
  }
  Params params;
  io::WriteOptions write;
  write.stl_binary = !ascii;
  if (!format.empty()) {
    auto f = io::format_from_name(format);
    if (!f) {
      std::cerr << "cellforge make: " << f.error().message << '\n';
      return 2;
    }
    write.format = *f;
  }
  for (const std::string& a : keys) {
    std::string key, value;
    if (!split_key_value(a, key, value)) {
      std::cerr << "cellforge make: unexpected argument '" << a << "' (KEY=VALUE expected)\n";
      return 2;
    }
    if (key[0] == '$') key.erase(0, 1);
    if (key != "max_vertices" &&
        std::find(kind->keys.begin(), kind->keys.end(), key) == kind->keys.end()) {
      std::cerr << "cellforge make " << kind->name << ": unknown key '" << key
                << "' (valid: " << joined(kind->keys) << ", max_vertices)\n";
      return 2;
    }
    params[key] = value;
  }
  if (out == "-" && !write.format) {
    std::cerr << "cellforge make: writing standard output needs --format FORMAT\n";
    return 2;
  }
  Model m;
  auto g = kind->make(m, params);
  if (!g) {
    std::cerr << "cellforge make " << kind->name << ": " << g.error().message << '\n';
    return 1;
  }
  if (Status s = io::write_file(m, out, write); !s) {
    std::cerr << "cellforge make: " << s.error().message << '\n';
    return 1;
  }
  std::ostream& report = out == "-" ? std::cerr : std::cout;
  print_summary(report, m, *g, kind->name);
  report << "wrote " << out << '\n';
  return 0;
}

const CommandRegistration kMake{
    Command{"make", "build a primitive or sweep (OpenSCAD parameters) and write it to a file",
            kUsage, run, true}};

}  // namespace
}  // namespace cellforge::cli
