// OpenSCAD's built-in functions: the math (trigonometry in degrees, exact at multiples
// of 30 and 45 as OpenSCAD's), the type tests, strings (str, chr, ord, len), lists
// (concat, lookup, search, max, min, norm, cross), rands (std::mt19937 with
// std::uniform_real_distribution, so that a seed gives OpenSCAD's numbers), version()
// and parent_module(). A wrong argument gives undef with a warning, as OpenSCAD does.
#include <cmath>
#include <limits>
#include <random>

#include "cellforge/shape/faceting.h"
#include "import2d.h"
#include "interp.h"

namespace cellforge::csg {

bool to_number(const Value& v, double& out) {
  if (!v.is_number()) return false;
  out = v.as_number();
  return true;
}

bool to_vec3(const Value& v, Vec3& out, bool allow_2d) {
  if (!v.is_vector()) return false;
  const Vector& x = v.as_vector();
  if (x.size() != 3 && !(allow_2d && x.size() == 2)) return false;
  double c[3] = {0, 0, 0};
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!to_number(x[i], c[i])) return false;
  }
  out = Vec3{c[0], c[1], c[2]};
  return true;
}

namespace {

constexpr double kDeg = 180.0 / M_PI;

std::size_t utf8_length(const std::string& s) {
  std::size_t n = 0;
  for (char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

// One Unicode code point from a one-character string, or -1.
long decode_one(const std::string& s) {
  if (s.empty()) return -1;
  const unsigned char c = static_cast<unsigned char>(s[0]);
  std::size_t n = c < 0x80 ? 1 : (c >> 5) == 6 ? 2 : (c >> 4) == 14 ? 3 : (c >> 3) == 30 ? 4 : 0;
  if (n == 0 || s.size() != n) return -1;
  long cp = n == 1 ? c : n == 2 ? (c & 0x1F) : n == 3 ? (c & 0x0F) : (c & 0x07);
  for (std::size_t k = 1; k < n; ++k) {
    const unsigned char d = static_cast<unsigned char>(s[k]);
    if ((d & 0xC0) != 0x80) return -1;
    cp = (cp << 6) | (d & 0x3F);
  }
  return cp;
}

std::mt19937& deterministic_rng() {
  static thread_local std::mt19937 rng(std::random_device{}());
  return rng;
}

// search(): does the entry (or its index_col element) equal the needle?
bool search_match(const Value& entry, const Value& needle, std::size_t col, bool by_char) {
  if (by_char && !entry.is_vector()) return false;  // OpenSCAD skips such entries
  if (entry.is_vector()) {
    const Vector& v = entry.as_vector();
    return col < v.size() && v[col] == needle;
  }
  return col == 0 && entry == needle;
}

}  // namespace

bool Interp::call_builtin_function(const std::string& name, const Args& args, SourcePos pos,
                                   const EnvPtr& env, Value& out) {
  auto arg = [&](std::size_t i) -> const Value& {
    static const Value kUndef;
    return i < args.size() ? args[i].value : kUndef;
  };
  auto bad = [&]() {
    warn(pos, name + "() cannot take these arguments (undef)");
    out = Value();
    return true;
  };
  auto num1 = [&](double (*f)(double)) {
    double x;
    if (args.size() != 1 || !to_number(arg(0), x)) return bad();
    out = Value::number(f(x));
    return true;
  };
  auto num_result = [&](double x) {
    out = Value::number(x);
    return true;
  };

  if (name == "abs") return num1([](double x) { return std::fabs(x); });
  if (name == "sign") return num1([](double x) { return x < 0 ? -1.0 : x > 0 ? 1.0 : 0.0; });
  if (name == "sin") return num1([](double x) { return shape::sin_degrees(x); });
  if (name == "cos") return num1([](double x) { return shape::cos_degrees(x); });
  if (name == "tan") {
    return num1([](double x) {
      // OpenSCAD's tan_degrees: exact at multiples of 45, infinite at odd multiples of 90.
      if (std::isfinite(x) && std::fmod(x, 45) == 0) {
        double m = std::fmod(x, 180);
        if (m < 0) m += 180;
        if (m == 0) return 0.0;
        if (m == 45) return 1.0;
        if (m == 90) return std::numeric_limits<double>::infinity();
        if (m == 135) return -1.0;
      }
      return std::tan(x / kDeg);
    });
  }
  if (name == "asin") return num1([](double x) { return std::asin(x) * kDeg; });
  if (name == "acos") return num1([](double x) { return std::acos(x) * kDeg; });
  if (name == "atan") return num1([](double x) { return std::atan(x) * kDeg; });
  if (name == "atan2") {
    double y, x;
    if (args.size() != 2 || !to_number(arg(0), y) || !to_number(arg(1), x)) return bad();
    return num_result(std::atan2(y, x) * kDeg);
  }
  if (name == "floor") return num1([](double x) { return std::floor(x); });
  if (name == "ceil") return num1([](double x) { return std::ceil(x); });
  if (name == "round") return num1([](double x) { return std::round(x); });
  if (name == "sqrt") return num1([](double x) { return std::sqrt(x); });
  if (name == "exp") return num1([](double x) { return std::exp(x); });
  if (name == "ln") return num1([](double x) { return std::log(x); });
  if (name == "log") {
    double b, x;
    if (args.size() == 1 && to_number(arg(0), x)) return num_result(std::log10(x));
    if (args.size() == 2 && to_number(arg(0), b) && to_number(arg(1), x))
      return num_result(std::log(x) / std::log(b));
    return bad();
  }
  if (name == "pow") {
    double b, x;
    if (args.size() != 2 || !to_number(arg(0), b) || !to_number(arg(1), x)) return bad();
    return num_result(std::pow(b, x));
  }
  if (name == "min" || name == "max") {
    const bool is_max = name == "max";
    const Vector* list = nullptr;
    Vector given;
    if (args.size() == 1 && arg(0).is_vector()) {
      list = &arg(0).as_vector();
    } else {
      for (const Arg& a : args) given.push_back(a.value);
      list = &given;
    }
    if (list->empty()) return bad();
    double best = 0;
    for (std::size_t i = 0; i < list->size(); ++i) {
      double x;
      if (!to_number((*list)[i], x)) return bad();
      if (i == 0 || (is_max ? x > best : x < best)) best = x;
    }
    return num_result(best);
  }
  if (name == "norm") {
    if (args.size() != 1 || !arg(0).is_vector()) return bad();
    double s = 0;
    for (const Value& v : arg(0).as_vector()) {
      double x;
      if (!to_number(v, x)) return bad();
      s += x * x;
    }
    return num_result(std::sqrt(s));
  }
  if (name == "cross") {
    Vec3 a, b;
    if (args.size() != 2 || !arg(0).is_vector() || !arg(1).is_vector()) return bad();
    const std::size_t n = arg(0).as_vector().size();
    if (n != arg(1).as_vector().size() || !to_vec3(arg(0), a) || !to_vec3(arg(1), b)) return bad();
    if (n == 2) return num_result(a.x * b.y - a.y * b.x);
    out = Value::vector({Value::number(a.y * b.z - a.z * b.y), Value::number(a.z * b.x - a.x * b.z),
                         Value::number(a.x * b.y - a.y * b.x)});
    return true;
  }
  if (name == "len") {
    const Value& v = arg(0);
    if (args.size() == 1 && v.is_vector())
      return num_result(static_cast<double>(v.as_vector().size()));
    if (args.size() == 1 && v.is_string())
      return num_result(static_cast<double>(utf8_length(v.as_string())));
    return bad();
  }
  if (name == "concat") {
    Vector all;
    for (const Arg& a : args) {
      if (a.value.is_vector()) {
        all.insert(all.end(), a.value.as_vector().begin(), a.value.as_vector().end());
      } else {
        all.push_back(a.value);
      }
      if (all.size() > options_.max_list_size) make_vector(std::move(all), pos);
    }
    out = make_vector(std::move(all), pos);
    return true;
  }
  if (name == "str") {
    std::string s;
    for (const Arg& a : args) {
      s += a.value.to_text();
      if (s.size() > options_.max_list_size)
        fail(pos, "str() makes a string longer than the limit");
    }
    out = Value::string(std::move(s));
    return true;
  }
  if (name == "chr") {
    std::string s;
    std::function<bool(const Value&)> add = [&](const Value& v) {
      if (v.is_number()) {
        const double d = v.as_number();
        if (d >= 1 && d <= 0x10FFFF && d == std::floor(d))
          append_utf8(s, static_cast<std::uint32_t>(d));
        return true;
      }
      if (v.is_vector() || v.is_range()) {
        bool ok = true;
        iterate(v, pos, [&](const Value& x) { ok = ok && x.is_number() && add(x); });
        return ok;
      }
      return false;
    };
    for (const Arg& a : args) {
      if (!add(a.value)) return bad();
    }
    out = Value::string(std::move(s));
    return true;
  }
  if (name == "ord") {
    if (args.size() != 1 || !arg(0).is_string()) return bad();
    const long cp = decode_one(arg(0).as_string());
    if (cp < 0) {
      out = Value();
      return true;
    }
    return num_result(static_cast<double>(cp));
  }
  if (name == "lookup") {
    double key;
    if (args.size() != 2 || !to_number(arg(0), key) || !arg(1).is_vector()) return bad();
    double low_p = 0, low_v = 0, high_p = 0, high_v = 0;
    bool first = true;
    for (const Value& entry : arg(1).as_vector()) {
      double p, v;
      if (!entry.is_vector() || entry.as_vector().size() < 2 ||
          !to_number(entry.as_vector()[0], p) || !to_number(entry.as_vector()[1], v)) {
        continue;
      }
      if (first) {
        low_p = high_p = p;
        low_v = high_v = v;
        first = false;
        continue;
      }
      if (p <= key && (p > low_p || low_p > key)) {
        low_p = p;
        low_v = v;
      }
      if (p >= key && (p < high_p || high_p < key)) {
        high_p = p;
        high_v = v;
      }
    }
    if (first) return bad();
    if (key <= low_p) return num_result(high_v);
    if (key >= high_p) return num_result(low_v);
    const double f = (key - low_p) / (high_p - low_p);
    return num_result(high_v * f + low_v * (1 - f));
  }
  if (name == "search") {
    if (args.size() < 2) return bad();
    const Value& needle = arg(0);
    const Value& hay = arg(1);
    double returns = 1, col = 0;
    if (args.size() > 2 && !to_number(arg(2), returns)) return bad();
    if (args.size() > 3 && !to_number(arg(3), col)) return bad();
    if (!(returns >= 0) || !(col >= 0)) return bad();
    returns = std::min(returns, 1e15);  // beyond any list: "all of them"
    col = std::min(col, 1e15);
    const std::size_t want = static_cast<std::size_t>(returns);
    const std::size_t c = static_cast<std::size_t>(col);
    Vector entries;
    if (hay.is_string()) {
      iterate(hay, pos, [&](const Value& x) { entries.push_back(x); });
    } else if (hay.is_vector()) {
      entries = hay.as_vector();
    } else {
      return bad();
    }
    const bool by_char = needle.is_string() && hay.is_vector();
    auto find_all = [&](const Value& n) {
      Vector hits;
      for (std::size_t i = 0; i < entries.size(); ++i) {
        if (search_match(entries[i], n, c, by_char)) {
          hits.push_back(Value::number(static_cast<double>(i)));
          if (want != 0 && hits.size() >= want) break;
        }
      }
      return hits;
    };
    Vector result;
    if (needle.is_number() || needle.is_bool()) {
      out = make_vector(find_all(needle), pos);
      return true;
    }
    if (needle.is_string() || needle.is_vector()) {
      Vector items;
      iterate(needle, pos, [&](const Value& x) { items.push_back(x); });
      for (const Value& n : items) {
        Vector hits = find_all(n);
        if (want == 1) {
          if (!hits.empty()) {
            result.push_back(hits[0]);
          } else if (needle.is_vector()) {
            result.push_back(Value::vector({}));
          }
        } else {
          result.push_back(make_vector(std::move(hits), pos));
        }
      }
      out = make_vector(std::move(result), pos);
      return true;
    }
    return bad();
  }
  if (name == "rands") {
    double lo, hi, count, seed = 0;
    if (args.size() < 3 || !to_number(arg(0), lo) || !to_number(arg(1), hi) ||
        !to_number(arg(2), count))
      return bad();
    if (args.size() > 3) {
      if (!to_number(arg(3), seed)) return bad();
      // OpenSCAD converts the seed to an unsigned int; out-of-range seeds wrap.
      const double wrapped = std::isfinite(seed) ? std::fmod(std::trunc(seed), 4294967296.0) : 0;
      deterministic_rng().seed(static_cast<unsigned int>(static_cast<long long>(wrapped)));
    }
    if (!(count >= 0) || count > static_cast<double>(options_.max_list_size)) return bad();
    std::uniform_real_distribution<double> dist(std::min(lo, hi), std::max(lo, hi));
    Vector v;
    for (double i = 0; i < std::floor(count); ++i) {
      v.push_back(Value::number(lo == hi ? lo : dist(deterministic_rng())));
    }
    out = make_vector(std::move(v), pos);
    return true;
  }
  if (name == "version") {
    out = Value::vector({Value::number(2021), Value::number(1), Value::number(0)});
    return true;
  }
  if (name == "version_num") return num_result(20210100);
  if (name == "is_undef" || name == "is_bool" || name == "is_num" || name == "is_string" ||
      name == "is_list" || name == "is_function") {
    if (args.size() != 1) return bad();
    const Value& v = arg(0);
    bool r = false;
    if (name == "is_undef") r = v.is_undef();
    if (name == "is_bool") r = v.is_bool();
    if (name == "is_num") r = v.is_number() && !std::isnan(v.as_number());
    if (name == "is_string") r = v.is_string();
    if (name == "is_list") r = v.is_vector();
    if (name == "is_function") r = v.is_function();
    out = Value::boolean(r);
    return true;
  }
  if (name == "parent_module") {
    double n = 1;
    if (!args.empty() && !to_number(arg(0), n)) return bad();
    // The stack holds the module calls; the innermost is the one running this.
    const double depth = static_cast<double>(module_stack_.size());
    if (!(n >= 0) || n >= depth) {
      warn(pos, "parent_module(" + format_number(n) + "): not that many modules on the stack");
      out = Value();
      return true;
    }
    out = Value::string(module_stack_[module_stack_.size() - 1 - static_cast<std::size_t>(n)]);
    return true;
  }
  if (name == "dxf_dim" || name == "dxf_cross") return dxf_function(name, args, pos, out);
  (void)env;
  return false;
}

// dxf_dim(file, layer, origin, scale, name) and dxf_cross(file, layer, origin, scale):
// a dimension's measurement and the crossing of two lines, read from a DXF file
// (import2d.h). Where OpenSCAD warns and gives undef (no such file, no such dimension,
// no crossing), cellforge stops with an error naming the file: a size that is not
// there would only show up later as wrong geometry.
bool Interp::dxf_function(const std::string& name, const Args& args, SourcePos pos, Value& out) {
  const bool dim = name == "dxf_dim";
  const Params p(args, dim ? std::vector<std::string>{"file", "layer", "origin", "scale", "name"}
                           : std::vector<std::string>{"file", "layer", "origin", "scale"},
                 pos);
  for (const Arg& a : args)
    if (!a.name.empty() && a.name != "file" && a.name != "layer" && a.name != "origin" &&
        a.name != "scale" && !(dim && a.name == "name"))
      warn(a.pos, name + "(): unknown argument " + a.name + " (ignored)");
  const Value& file = p.get("file");
  if (!file.is_string()) fail(p.call(), name + "(): file must be a string");
  if (!options_.allow_files) fail(pos, name + "(): reading files is turned off");
  Import2DOptions o;
  const std::string path = script_relative(file.as_string(), pos);
  const auto text = [&](const char* param) {
    const Value& v = p.get(param);
    if (v.is_undef()) return std::string();
    if (!v.is_string()) fail(p.pos(param), name + "(): " + param + " must be a string");
    return v.as_string();
  };
  o.layer = text("layer");
  if (p.has("origin")) {
    Vec3 origin;
    if (!to_vec3(p.get("origin"), origin)) fail(p.pos("origin"), name + "(): origin must be [x, y]");
    o.origin = Vec2{origin.x, origin.y};
  }
  if (p.has("scale") && !to_number(p.get("scale"), o.scale))
    fail(p.pos("scale"), name + "(): scale must be a number");
  const std::string where = " in " + file.as_string() + (o.layer.empty() ? "" : ", layer \"" + o.layer + "\"");
  if (dim) {
    const std::string wanted = text("name");
    auto dims = read_dxf_dimensions(path, o);
    if (!dims) fail(pos, name + "(): " + dims.error().message);
    for (const DxfDimension& d : *dims) {
      if (!wanted.empty() && d.name != wanted) continue;
      const std::optional<double> v = dimension_value(d);
      if (!v) fail(pos, name + "(): dimension \"" + d.name + "\"" + where + " (line " + std::to_string(d.line) +
                            ") is of type " + std::to_string(d.type & 7) + ", which is not measured");
      out = Value::number(*v);
      return true;
    }
    fail(pos, name + "(): no dimension" + (wanted.empty() ? "" : " named \"" + wanted + "\"") + where);
  }
  auto cross = read_dxf_cross(path, o);
  if (!cross) fail(pos, name + "(): " + cross.error().message);
  if (!*cross) fail(pos, name + "(): no two crossing lone lines" + where);
  out = Value::vector({Value::number((*cross)->x), Value::number((*cross)->y)});
  return true;
}

}  // namespace cellforge::csg
