#include "cellforge/csg/tree_json.h"

#include <charconv>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <unordered_map>

#include "cellforge/shape/faceting.h"

namespace cellforge::csg {
namespace {

std::string num(double x) { return shape::format_number(x); }

std::string quote(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

// x appended as num(x) writes it (std::to_chars: the shortest text that reads back as x).
template <class T>
void append_number(std::string& out, T x) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, r.ptr);
}

std::string vec3(Vec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

void write(const Node& n, std::string& out, bool positions, bool children = true) {
  out += "{\"type\": \"" + std::string(node_name(n.kind)) + "\"";
  auto field = [&](const char* k, const std::string& v) {
    out += std::string(", \"") + k + "\": " + v;
  };
  auto flag = [&](const char* k, bool b) { field(k, b ? "true" : "false"); };
  auto facets = [&](const shape::Faceting& f) {
    field("fn", num(f.fn));
    field("fa", num(f.fa));
    field("fs", num(f.fs));
  };
  switch (n.kind) {
    case NodeKind::kCube:
      field("size", vec3(n.size));
      flag("center", n.center);
      break;
    case NodeKind::kSphere:
    case NodeKind::kCircle:
      field("r", num(n.r));
      facets(n.faceting);
      break;
    case NodeKind::kCylinder:
      field("h", num(n.h));
      field("r1", num(n.r1));
      field("r2", num(n.r2));
      flag("center", n.center);
      facets(n.faceting);
      break;
    case NodeKind::kSquare:
      field("size", "[" + num(n.size.x) + ", " + num(n.size.y) + "]");
      flag("center", n.center);
      break;
    case NodeKind::kPolyhedron:
    case NodeKind::kPolygon: {
      // Appended in place, number by number (a surface() of a 50 x 50 image is 2,500
      // points, and content_key writes a subtree at each level it is asked for).
      const int dims = n.kind == NodeKind::kPolygon ? 2 : 3;
      std::string pts = "[";
      pts.reserve(n.points.size() * 16 * static_cast<std::size_t>(dims));
      for (std::size_t i = 0; i < n.points.size(); ++i) {
        pts += i ? ", [" : "[";
        for (int d = 0; d < dims; ++d) {
          if (d) pts += ", ";
          append_number(pts, n.points[i][d]);
        }
        pts += ']';
      }
      field("points", pts + "]");
      std::string fs = "[";
      for (std::size_t i = 0; i < n.faces.size(); ++i) {
        fs += i ? ", [" : "[";
        for (std::size_t j = 0; j < n.faces[i].size(); ++j) {
          if (j) fs += ", ";
          append_number(fs, n.faces[i][j]);
        }
        fs += ']';
      }
      field(n.kind == NodeKind::kPolygon ? "paths" : "faces", fs + "]");
      break;
    }
    case NodeKind::kImport:
      field("file", quote(n.path));
      if (!n.layer.empty()) field("layer", quote(n.layer));
      if (n.origin.x != 0 || n.origin.y != 0)
        field("origin", "[" + num(n.origin.x) + ", " + num(n.origin.y) + "]");
      if (n.import_scale != 1) field("scale", num(n.import_scale));
      facets(n.faceting);
      break;
    case NodeKind::kMultmatrix: {
      std::string m = "[";
      for (int i = 0; i < 3; ++i) {
        m += "[";
        for (int j = 0; j < 4; ++j)
          m += (j ? ", " : "") +
               num(n.matrix.m[static_cast<std::size_t>(i)][static_cast<std::size_t>(j)]);
        m += "], ";
      }
      field("matrix", m + "[0, 0, 0, 1]]");
      break;
    }
    case NodeKind::kResize:
      field("size", vec3(n.size));
      field("auto", std::string("[") + (n.auto_size[0] ? "true" : "false") + ", " +
                        (n.auto_size[1] ? "true" : "false") + ", " +
                        (n.auto_size[2] ? "true" : "false") + "]");
      break;
    case NodeKind::kColor:
      field("color", "[" + num(n.color[0]) + ", " + num(n.color[1]) + ", " + num(n.color[2]) +
                         ", " + num(n.color[3]) + "]");
      break;
    case NodeKind::kLinearExtrude:
      field("height", num(n.linear.height));
      flag("center", n.linear.center);
      field("twist", num(n.linear.twist));
      field("slices", std::to_string(n.linear.slices));
      field("scale", "[" + num(n.linear.scale_x) + ", " + num(n.linear.scale_y) + "]");
      facets(n.linear.faceting);
      break;
    case NodeKind::kRotateExtrude:
      field("angle", num(n.rotate.angle));
      facets(n.rotate.faceting);
      break;
    case NodeKind::kOffset:
      field(n.round ? "r" : "delta", num(n.delta));
      flag("chamfer", n.chamfer);
      facets(n.faceting);
      break;
    case NodeKind::kProjection:
      flag("cut", n.cut);
      break;
    default:
      break;
  }
  if (n.background) flag("background", true);
  if (n.highlight) flag("highlight", true);
  if (positions && n.pos.line != 0) {
    field("line", std::to_string(n.pos.line));
    field("column", std::to_string(n.pos.column));
  }
  if (children && !n.children.empty()) {
    out += ", \"children\": [";
    for (std::size_t i = 0; i < n.children.size(); ++i) {
      if (i) out += ", ";
      write(*n.children[i], out, positions);
    }
    out += "]";
  }
  out += "}";
}

// ---- a small JSON reader
struct Json {
  enum class Type { kNull, kBool, kNumber, kString, kArray, kObject } type = Type::kNull;
  bool b = false;
  double n = 0;
  std::string s;
  std::vector<Json> items;        // an array's elements; an object's values
  std::vector<std::string> keys;  // an object's keys, beside items
  std::size_t offset = 0;

  const Json* get(const std::string& key) const {
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (keys[i] == key) return &items[i];
    }
    return nullptr;
  }
};

struct JsonError {
  std::size_t offset;
  std::string message;
};

class Reader {
 public:
  explicit Reader(std::string_view t) : t_(t) {}
  Json document() {
    Json v = value(0);
    space();
    if (i_ != t_.size()) fail("text after the end of the document");
    return v;
  }

 private:
  [[noreturn]] void fail(const std::string& m) const { throw JsonError{i_, m}; }
  void space() {
    while (i_ < t_.size() && (t_[i_] == ' ' || t_[i_] == '\n' || t_[i_] == '\r' || t_[i_] == '\t'))
      ++i_;
  }
  bool literal(std::string_view w) {
    if (t_.substr(i_, w.size()) != w) return false;
    i_ += w.size();
    return true;
  }
  Json value(int depth) {
    if (depth > 1000) fail("nested more than 1000 deep");
    space();
    Json v;
    v.offset = i_;
    if (i_ >= t_.size()) fail("expected a value, found the end");
    const char c = t_[i_];
    if (c == '{') {
      v.type = Json::Type::kObject;
      ++i_;
      space();
      if (i_ < t_.size() && t_[i_] == '}') {
        ++i_;
        return v;
      }
      for (;;) {
        space();
        if (i_ >= t_.size() || t_[i_] != '"') fail("expected a key in quotes");
        std::string k = string();
        space();
        if (i_ >= t_.size() || t_[i_] != ':') fail("expected ':'");
        ++i_;
        v.keys.push_back(std::move(k));
        v.items.push_back(value(depth + 1));
        space();
        if (i_ < t_.size() && t_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < t_.size() && t_[i_] == '}') {
          ++i_;
          return v;
        }
        fail("expected ',' or '}'");
      }
    }
    if (c == '[') {
      v.type = Json::Type::kArray;
      ++i_;
      space();
      if (i_ < t_.size() && t_[i_] == ']') {
        ++i_;
        return v;
      }
      for (;;) {
        v.items.push_back(value(depth + 1));
        space();
        if (i_ < t_.size() && t_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < t_.size() && t_[i_] == ']') {
          ++i_;
          return v;
        }
        fail("expected ',' or ']'");
      }
    }
    if (c == '"') {
      v.type = Json::Type::kString;
      v.s = string();
      return v;
    }
    if (literal("true")) {
      v.type = Json::Type::kBool;
      v.b = true;
      return v;
    }
    if (literal("false")) {
      v.type = Json::Type::kBool;
      return v;
    }
    if (literal("null")) return v;
    if (c == '-' || (c >= '0' && c <= '9')) {
      std::size_t j = i_;
      while (j < t_.size() &&
             (std::string_view("+-.eE0123456789").find(t_[j]) != std::string_view::npos))
        ++j;
      const std::string s(t_.substr(i_, j - i_));
      char* end = nullptr;
      v.type = Json::Type::kNumber;
      v.n = std::strtod(s.c_str(), &end);
      if (end != s.c_str() + s.size()) fail("a malformed number '" + s + "'");
      i_ = j;
      return v;
    }
    fail(std::string("unexpected character '") + c + "'");
  }
  std::string string() {
    ++i_;  // opening quote
    std::string out;
    for (;;) {
      if (i_ >= t_.size()) fail("the string is not closed");
      const char c = t_[i_++];
      if (c == '"') return out;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= t_.size()) fail("the string ends in a backslash");
      const char e = t_[i_++];
      switch (e) {
        case 'n':
          out += '\n';
          break;
        case 't':
          out += '\t';
          break;
        case 'r':
          out += '\r';
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case '/':
          out += '/';
          break;
        case '\\':
          out += '\\';
          break;
        case '"':
          out += '"';
          break;
        case 'u': {
          if (i_ + 4 > t_.size()) fail("a short \\u escape");
          const unsigned cp = static_cast<unsigned>(
              std::strtoul(std::string(t_.substr(i_, 4)).c_str(), nullptr, 16));
          i_ += 4;
          if (cp < 0x80) {
            out += static_cast<char>(cp);
          } else if (cp < 0x800) {
            out += static_cast<char>(0xC0 | (cp >> 6));
            out += static_cast<char>(0x80 | (cp & 0x3F));
          } else {
            out += static_cast<char>(0xE0 | (cp >> 12));
            out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
            out += static_cast<char>(0x80 | (cp & 0x3F));
          }
          break;
        }
        default:
          fail(std::string("an unknown escape \\") + e);
      }
    }
  }
  std::string_view t_;
  std::size_t i_ = 0;
};

struct TreeError {
  std::size_t offset;
  std::string message;
};

double number(const Json& n, const char* key, double fallback) {
  const Json* v = n.get(key);
  if (!v) return fallback;
  if (v->type != Json::Type::kNumber || !std::isfinite(v->n))
    throw TreeError{v->offset, std::string(key) + " must be a number"};
  return v->n;
}

bool boolean(const Json& n, const char* key) {
  const Json* v = n.get(key);
  if (!v) return false;
  if (v->type != Json::Type::kBool)
    throw TreeError{v->offset, std::string(key) + " must be true or false"};
  return v->b;
}

std::vector<double> numbers(const Json& v, const char* what) {
  if (v.type != Json::Type::kArray)
    throw TreeError{v.offset, std::string(what) + " must be an array of numbers"};
  std::vector<double> out;
  for (const Json& x : v.items) {
    if (x.type != Json::Type::kNumber || !std::isfinite(x.n))
      throw TreeError{x.offset, std::string(what) + " must hold numbers"};
    out.push_back(x.n);
  }
  return out;
}

shape::Faceting facets(const Json& n) {
  return shape::Faceting{number(n, "fn", 0), number(n, "fa", 12), number(n, "fs", 2)};
}

NodePtr read_node(const Json& j) {
  if (j.type != Json::Type::kObject) throw TreeError{j.offset, "a node must be an object"};
  const Json* type = j.get("type");
  if (!type || type->type != Json::Type::kString)
    throw TreeError{j.offset, "a node needs \"type\""};
  const auto kind = node_kind(type->s);
  if (!kind) throw TreeError{type->offset, "unknown node type \"" + type->s + "\""};
  auto n = std::make_shared<Node>();
  n->kind = *kind;
  n->background = boolean(j, "background");
  n->highlight = boolean(j, "highlight");
  auto vec = [&](const char* key, Vec3 fallback, std::size_t min, std::size_t max) {
    const Json* v = j.get(key);
    if (!v) return fallback;
    const auto xs = numbers(*v, key);
    if (xs.size() < min || xs.size() > max)
      throw TreeError{v->offset, std::string(key) + " has the wrong length"};
    return Vec3{xs[0], xs.size() > 1 ? xs[1] : 0, xs.size() > 2 ? xs[2] : 0};
  };
  switch (n->kind) {
    case NodeKind::kCube:
      n->size = vec("size", {1, 1, 1}, 3, 3);
      n->center = boolean(j, "center");
      break;
    case NodeKind::kSquare:
      n->size = vec("size", {1, 1, 0}, 2, 2);
      n->center = boolean(j, "center");
      break;
    case NodeKind::kSphere:
    case NodeKind::kCircle:
      n->r = number(j, "r", 1);
      n->faceting = facets(j);
      break;
    case NodeKind::kCylinder:
      n->h = number(j, "h", 1);
      n->r1 = number(j, "r1", 1);
      n->r2 = number(j, "r2", 1);
      n->center = boolean(j, "center");
      n->faceting = facets(j);
      break;
    case NodeKind::kPolyhedron:
    case NodeKind::kPolygon: {
      const bool poly3 = n->kind == NodeKind::kPolyhedron;
      if (const Json* pts = j.get("points")) {
        if (pts->type != Json::Type::kArray)
          throw TreeError{pts->offset, "points must be an array"};
        for (const Json& p : pts->items) {
          const auto xs = numbers(p, "a point");
          if (xs.size() != (poly3 ? 3u : 2u))
            throw TreeError{p.offset, "a point has the wrong length"};
          n->points.push_back(Vec3{xs[0], xs[1], poly3 ? xs[2] : 0});
        }
      }
      if (const Json* fs = j.get(poly3 ? "faces" : "paths")) {
        if (fs->type != Json::Type::kArray) throw TreeError{fs->offset, "faces must be an array"};
        for (const Json& f : fs->items) {
          std::vector<std::uint32_t> idx;
          for (double x : numbers(f, "a face")) {
            if (!(x >= 0) || x >= static_cast<double>(n->points.size()) || x != std::floor(x))
              throw TreeError{f.offset, "an index names no point"};
            idx.push_back(static_cast<std::uint32_t>(x));
          }
          n->faces.push_back(std::move(idx));
        }
      }
      break;
    }
    case NodeKind::kImport: {
      const Json* f = j.get("file");
      if (!f || f->type != Json::Type::kString) throw TreeError{j.offset, "import needs \"file\""};
      n->path = f->s;
      if (const Json* l = j.get("layer")) {
        if (l->type != Json::Type::kString) throw TreeError{l->offset, "layer must be a string"};
        n->layer = l->s;
      }
      if (const Json* o = j.get("origin")) {
        const std::vector<double> v = numbers(*o, "origin");
        if (v.size() != 2) throw TreeError{o->offset, "origin must be [x, y]"};
        n->origin = Vec3{v[0], v[1], 0};
      }
      n->import_scale = number(j, "scale", 1);
      n->faceting = facets(j);
      break;
    }
    case NodeKind::kMultmatrix: {
      std::array<std::array<double, 4>, 4> rows{
          {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}, {0, 0, 0, 1}}};
      if (const Json* m = j.get("matrix")) {
        if (m->type != Json::Type::kArray || m->items.size() != 4)
          throw TreeError{m->offset, "matrix must be 4 rows"};
        for (std::size_t i = 0; i < 4; ++i) {
          const auto xs = numbers(m->items[i], "a matrix row");
          if (xs.size() != 4)
            throw TreeError{m->items[i].offset, "a matrix row must have 4 numbers"};
          for (std::size_t k = 0; k < 4; ++k) rows[i][k] = xs[k];
        }
      }
      auto t = shape::Transform::from_matrix(rows);
      if (!t) throw TreeError{j.offset, t.error().message};
      n->matrix = *t;
      break;
    }
    case NodeKind::kResize: {
      n->size = vec("size", {0, 0, 0}, 3, 3);
      if (const Json* a = j.get("auto")) {
        if (a->type != Json::Type::kArray || a->items.size() != 3)
          throw TreeError{a->offset, "auto must be 3 booleans"};
        for (std::size_t i = 0; i < 3; ++i)
          n->auto_size[i] = a->items[i].type == Json::Type::kBool && a->items[i].b;
      }
      break;
    }
    case NodeKind::kColor:
      if (const Json* c = j.get("color")) {
        const auto xs = numbers(*c, "color");
        if (xs.size() < 3 || xs.size() > 4)
          throw TreeError{c->offset, "color must be [r, g, b] or [r, g, b, a]"};
        n->color = {xs[0], xs[1], xs[2], xs.size() > 3 ? xs[3] : 1};
      }
      break;
    case NodeKind::kLinearExtrude: {
      n->linear.height = number(j, "height", 100);
      n->linear.center = boolean(j, "center");
      n->linear.twist = number(j, "twist", 0);
      n->linear.slices = static_cast<int>(std::clamp(number(j, "slices", 0), 0.0, 1e6));
      const Vec3 s = vec("scale", {1, 1, 0}, 2, 2);
      n->linear.scale_x = s.x;
      n->linear.scale_y = s.y;
      n->linear.faceting = facets(j);
      break;
    }
    case NodeKind::kRotateExtrude:
      n->rotate.angle = number(j, "angle", 360);
      n->rotate.faceting = facets(j);
      break;
    case NodeKind::kOffset:
      n->round = j.get("r") != nullptr;
      n->delta = n->round ? number(j, "r", 0) : number(j, "delta", 1);
      n->chamfer = boolean(j, "chamfer");
      n->faceting = facets(j);
      break;
    case NodeKind::kProjection:
      n->cut = boolean(j, "cut");
      break;
    default:
      break;
  }
  if (const Json* c = j.get("children")) {
    if (c->type != Json::Type::kArray) throw TreeError{c->offset, "children must be an array"};
    for (const Json& x : c->items) n->children.push_back(read_node(x));
  }
  return n;
}

}  // namespace

std::string tree_to_json(const Node& root) {
  std::string out = "{\"cellforge_csg\": 1, \"root\": ";
  write(root, out, true);
  return out + "}";
}

std::string node_json(const Node& node) {
  std::string out;
  write(node, out, false);
  return out;
}

Result<NodePtr> tree_from_json(std::string_view text) {
  try {
    const Json doc = Reader(text).document();
    if (doc.type != Json::Type::kObject) throw TreeError{0, "the document must be an object"};
    const Json* version = doc.get("cellforge_csg");
    if (!version || version->type != Json::Type::kNumber || version->n != 1) {
      throw TreeError{doc.offset, "not a cellforge CSG tree (\"cellforge_csg\": 1 missing)"};
    }
    const Json* root = doc.get("root");
    if (!root) throw TreeError{doc.offset, "\"root\" is missing"};
    return read_node(*root);
  } catch (const JsonError& e) {
    return Error{ErrorCode::kParse, "byte " + std::to_string(e.offset) + ": " + e.message};
  } catch (const TreeError& e) {
    return Error{ErrorCode::kParse, "byte " + std::to_string(e.offset) + ": " + e.message};
  }
}

}  // namespace cellforge::csg

namespace cellforge::csg {

namespace {

void fnv1a(std::uint64_t& h, const char* data, std::size_t size) {
  for (std::size_t i = 0; i < size; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
}

// A file's bytes digested (FNV-1a) with their count; nullopt when it cannot be read.
// Memoized by path, size and modification time: every subtree above an import asks
// for its key (projection.scad hashed its 730 kB STL some fifty times).
struct FileDigest {
  std::uint64_t hash = 0;
  std::size_t length = 0;
};
std::optional<FileDigest> file_digest(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  const auto time = ec ? std::filesystem::file_time_type{} : std::filesystem::last_write_time(path, ec);
  if (ec) return std::nullopt;
  struct Entry {
    std::uintmax_t size;
    std::filesystem::file_time_type time;
    FileDigest digest;
  };
  static std::mutex lock;
  static std::unordered_map<std::string, Entry> memo;
  {
    std::lock_guard hold(lock);
    if (auto it = memo.find(path); it != memo.end() && it->second.size == size && it->second.time == time)
      return it->second.digest;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  FileDigest d;
  d.hash = 1469598103934665603ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    fnv1a(d.hash, buf, static_cast<std::size_t>(in.gcount()));
    d.length += static_cast<std::size_t>(in.gcount());
  }
  std::lock_guard hold(lock);
  memo[path] = {size, time, d};
  return d;
}

// An imported file's path and digest.
void hash_import(const Node& n, std::uint64_t& h, std::size_t& length) {
  const std::optional<FileDigest> d = file_digest(n.path);
  const std::string tag = d ? "\nfile " + n.path + "\n" : "\nunreadable " + n.path + "\n";
  fnv1a(h, tag.data(), tag.size());
  length += tag.size();
  if (d) {
    fnv1a(h, reinterpret_cast<const char*>(&d->hash), sizeof d->hash);
    length += d->length;
  }
}

}  // namespace

// FNV-1a (64 bits) of the node's own fields as JSON (positions and children left
// out), then of each child's digest and length, then of an imported file's path and
// bytes; the length counts the text, the children's lengths and the file's bytes.
ContentKeys::Digest ContentKeys::digest(const Node& node, std::unordered_map<const Node*, Digest>* keep) const {
  if (auto it = memo_.find(&node); it != memo_.end()) return it->second;
  std::string own;
  write(node, own, false, false);
  Digest d{1469598103934665603ull, own.size()};
  fnv1a(d.hash, own.data(), own.size());
  for (const NodePtr& c : node.children) {
    const Digest x = digest(*c, keep);
    fnv1a(d.hash, reinterpret_cast<const char*>(&x.hash), sizeof x.hash);
    fnv1a(d.hash, reinterpret_cast<const char*>(&x.length), sizeof x.length);
    d.length += x.length;
  }
  if (node.kind == NodeKind::kImport) hash_import(node, d.hash, d.length);
  if (keep) keep->emplace(&node, d);
  return d;
}

ContentKeys::ContentKeys(const Node& root) { digest(root, &memo_); }

std::string ContentKeys::operator()(const Node& node) const {
  const Digest d = digest(node, nullptr);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%016llx-%zx", static_cast<unsigned long long>(d.hash), d.length);
  return buf;
}

std::string content_key(const Node& node) { return ContentKeys()(node); }

}  // namespace cellforge::csg
