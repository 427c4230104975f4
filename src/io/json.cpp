// The native JSON format (docs/io.md): the model's snapshot tables (topo/snapshot.h)
// written as JSON, so that reading gives back the same topology and the same
// coordinates bit for bit (doubles written with 17 significant digits). Faces carry
// their loops as vertex cycles with the edge and radial position of each use.
//
// The reader is a pull parser over the text (no document tree, nothing allocated
// from a count in the file); the tables it fills go through restore(), which checks
// every key and validates the model.
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <functional>
#include <unordered_map>

#include "cellforge/topo/snapshot.h"
#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

namespace {

constexpr std::string_view kFormat = "cellforge-model";
constexpr int kVersion = 1;

// ---- writing

void put_number(std::string& out, double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  out += buf;
}

void put_string(std::string& out, std::string_view text) {
  // The reader takes only UTF-8: a name set through the API that is not UTF-8 is
  // written with U+FFFD for its stray bytes.
  const std::string s = valid_utf8(text);
  out += '"';
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += ch;
    }
  }
  out += '"';
}

void put_vec(std::string& out, Vec3 v) {
  out += '[';
  put_number(out, v.x);
  out += ',';
  put_number(out, v.y);
  out += ',';
  put_number(out, v.z);
  out += ']';
}

template <class T, class F>
void put_list(std::string& out, const std::vector<T>& xs, F each, const char* sep = ",") {
  out += '[';
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (i) out += sep;
    each(xs[i]);
  }
  out += ']';
}

}  // namespace

std::string write_json(const Model& m) {
  const Snapshot s = snapshot(m);
  std::string out = "{\"format\":\"" + std::string(kFormat) +
                    "\",\"version\":" + std::to_string(kVersion) + ",\n\"groups\":";
  std::vector<std::vector<const Snapshot::Parameter*>> params(s.groups.size());
  for (const auto& p : s.parameters) params[p.group].push_back(&p);
  for (std::size_t g = 0; g < s.groups.size(); ++g) {
    out += g ? ",\n " : "[";
    out += "{\"name\":";
    put_string(out, s.groups[g].name);
    out += ",\"attributes\":";
    put_list(out, params[g], [&](const Snapshot::Parameter* p) {
      out += '[';
      put_string(out, p->name);
      out += ',';
      put_string(out, p->value);
      out += ']';
    });
    out += '}';
  }
  out += s.groups.empty() ? "[]" : "]";
  out += ",\n\"cells\":";
  put_list(out, s.cells, [&](std::uint32_t g) { out += std::to_string(g); });
  out += ",\n\"vertices\":";
  put_list(
      out, s.vertices,
      [&](const Snapshot::Vertex& v) {
        out += '[';
        put_number(out, v.p.x);
        out += ',';
        put_number(out, v.p.y);
        out += ',';
        put_number(out, v.p.z);
        out += ',' + std::to_string(v.group) + ']';
      },
      ",\n ");
  out += ",\n\"edges\":";
  put_list(out, s.edges, [&](const Snapshot::Edge& e) {
    out += '[' + std::to_string(e.start) + ',' + std::to_string(e.end) + ']';
  });
  out += ",\n\"surfaces\":";
  put_list(
      out, s.surfaces,
      [&](const Surface& f) {
        out += "{\"kind\":";
        put_string(out, f.kind);
        out += ",\"center\":";
        put_vec(out, f.center);
        out += ",\"axis\":";
        put_vec(out, f.axis);
        out += ",\"radius\":";
        put_number(out, f.radius);
        out += ",\"radius2\":";
        put_number(out, f.radius2);
        out += ",\"height\":";
        put_number(out, f.height);
        out += ",\"segments\":" + std::to_string(f.segments) + '}';
      },
      ",\n ");
  // Uses by loop, loops by face (snapshot order is already face, loop, use order,
  // but bucketing keeps this independent of it).
  std::vector<std::vector<const Snapshot::Use*>> uses(s.loops.size());
  for (const auto& u : s.uses) uses[u.loop].push_back(&u);
  for (auto& l : uses)
    std::sort(l.begin(), l.end(), [](auto* a, auto* b) { return a->ord < b->ord; });
  std::vector<std::vector<std::uint32_t>> loops(s.faces.size());
  for (std::uint32_t l = 0; l < s.loops.size(); ++l) loops[s.loops[l].face].push_back(l);
  for (auto& f : loops)
    std::sort(f.begin(), f.end(), [&](auto a, auto b) { return s.loops[a].ord < s.loops[b].ord; });
  out += ",\n\"faces\":[";
  for (std::size_t f = 0; f < s.faces.size(); ++f) {
    const auto& face = s.faces[f];
    out += f ? ",\n " : "";
    out += "{\"group\":" + std::to_string(face.group) + ",\"front\":" + std::to_string(face.front) +
           ",\"back\":" + std::to_string(face.back) +
           ",\"surface\":" + std::to_string(face.surface) + ",\"loops\":";
    put_list(out, loops[f], [&](std::uint32_t l) {
      if (s.loops[l].point_vertex != Snapshot::kNone) {
        out += "{\"point\":" + std::to_string(s.loops[l].point_vertex) + '}';
        return;
      }
      const auto& us = uses[l];
      out += "{\"vertices\":";
      put_list(out, us, [&](const Snapshot::Use* u) {
        const auto& e = s.edges[u->edge];
        out += std::to_string(u->reversed ? e.end : e.start);
      });
      out += ",\"edges\":";
      put_list(out, us, [&](const Snapshot::Use* u) { out += std::to_string(u->edge); });
      out += ",\"radial\":";
      put_list(out, us, [&](const Snapshot::Use* u) { out += std::to_string(u->radial_ord); });
      out += '}';
    });
    out += '}';
  }
  out += "]}\n";
  return out;
}

// ---- reading

namespace {

class JsonReader {
 public:
  explicit JsonReader(std::string_view text) : text_(text) {}

  Error error_at(std::size_t offset, const std::string& message) const {
    return parse_error("json", position_of(text_, offset), message);
  }
  Error error(const std::string& message) const { return error_at(i_, message); }
  std::string line_col(std::size_t offset) const {
    const TextPos p = position_of(text_, offset);
    return std::to_string(p.line) + ":" + std::to_string(p.col);
  }
  std::size_t offset() const { return i_; }

  void skip_ws() {
    while (i_ < text_.size() &&
           (text_[i_] == ' ' || text_[i_] == '\t' || text_[i_] == '\n' || text_[i_] == '\r'))
      ++i_;
  }
  std::string found() const {
    if (i_ >= text_.size()) return "end of file";
    return quote(text_.substr(i_, 1));
  }
  Status expect(char c) {
    skip_ws();
    if (i_ < text_.size() && text_[i_] == c) {
      ++i_;
      return Status::Ok();
    }
    return error(std::string("expected '") + c + "', found " + found());
  }
  bool accept(char c) {
    skip_ws();
    if (i_ < text_.size() && text_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }

  Status string(std::string& out) {
    out.clear();
    if (Status s = expect('"'); !s) return s;
    while (true) {
      if (i_ >= text_.size()) return error("unterminated string");
      const char c = text_[i_++];
      if (c == '"') return Status::Ok();
      if (static_cast<unsigned char>(c) < 0x20)
        return error_at(i_ - 1, "control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= text_.size()) return error("unterminated string");
      const char e = text_[i_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u': {
          std::uint32_t cp;
          if (Status s = hex4(cp); !s) return s;
          if (cp >= 0xD800 && cp < 0xDC00) {
            std::uint32_t lo;
            if (i_ + 2 > text_.size() || text_[i_] != '\\' || text_[i_ + 1] != 'u')
              return error("unpaired surrogate");
            i_ += 2;
            if (Status s = hex4(lo); !s) return s;
            if (lo < 0xDC00 || lo > 0xDFFF) return error("unpaired surrogate");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          } else if (cp >= 0xDC00 && cp <= 0xDFFF) {
            return error("unpaired surrogate");
          }
          append_utf8(out, cp);
          break;
        }
        default:
          return error_at(i_ - 1, "bad escape " + quote(text_.substr(i_ - 2, 2)));
      }
    }
  }

  Status number(double& out) {
    skip_ws();
    const std::size_t start = i_;
    while (i_ < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[i_])) || text_[i_] == '-' ||
            text_[i_] == '+' || text_[i_] == '.' || text_[i_] == 'e' || text_[i_] == 'E'))
      ++i_;
    const std::string_view tok = text_.substr(start, i_ - start);
    if (tok.empty() || tok[0] == '+' || !parse_double(tok, out))
      return error_at(start, "expected a number, found " + (tok.empty() ? found() : quote(tok)));
    if (!std::isfinite(out)) return error_at(start, "non-finite number " + quote(tok));
    return Status::Ok();
  }

  Status integer(std::int64_t& out, std::int64_t lo, std::int64_t hi) {
    skip_ws();
    const std::size_t start = i_;
    while (i_ < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[i_])) || text_[i_] == '-'))
      ++i_;
    const std::string_view tok = text_.substr(start, i_ - start);
    if (!parse_int64(tok, out))
      return error_at(start, "expected an integer, found " + (tok.empty() ? found() : quote(tok)));
    if (out < lo || out > hi)
      return error_at(start, "integer " + std::string(tok) + " out of range [" +
                                 std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return Status::Ok();
  }
  Status index(std::uint32_t& out) {
    std::int64_t v;
    if (Status s = integer(v, 0, 0xFFFFFFFEll); !s) return s;
    out = static_cast<std::uint32_t>(v);
    return Status::Ok();
  }
  Status optional_index(std::int64_t& out) { return integer(out, -1, 0xFFFFFFFEll); }

  // [ item, item, ... ] calling `item` for each.
  Status array(const std::function<Status()>& item) {
    if (Status s = expect('['); !s) return s;
    if (accept(']')) return Status::Ok();
    do {
      if (Status s = item(); !s) return s;
    } while (accept(','));
    return expect(']');
  }
  // { "key": value, ... } calling `member` with each key (positioned at the value).
  Status object(const std::function<Status(const std::string&)>& member) {
    if (Status s = expect('{'); !s) return s;
    if (accept('}')) return Status::Ok();
    std::string key;
    // The keys seen in this object and where: a key given twice is an error (the
    // reader would otherwise append the second value to the first).
    // The model's objects have a handful of keys: the first eight are kept in place
    // (short keys need no allocation), the rest in a hash map.
    std::array<std::pair<std::string, std::size_t>, 8> first_keys;
    std::unordered_map<std::string, std::size_t> more_keys;
    std::size_t count = 0;
    do {
      skip_ws();
      const std::size_t at = i_;
      if (Status s = string(key); !s) return s;
      std::size_t first = std::string::npos;
      for (std::size_t k = 0; k < std::min(count, first_keys.size()); ++k)
        if (first_keys[k].first == key) first = first_keys[k].second;
      if (const auto it = more_keys.find(key); it != more_keys.end()) first = it->second;
      if (first != std::string::npos)
        return error_at(at,
                        "duplicate key " + quote(key) + " (first at line " + line_col(first) + ")");
      if (count < first_keys.size())
        first_keys[count] = {key, at};
      else
        more_keys.emplace(key, at);
      ++count;
      if (Status s = expect(':'); !s) return s;
      if (Status s = member(key); !s) return s;
    } while (accept(','));
    return expect('}');
  }

  Status skip_value(int depth = 0) {
    if (depth > 64) return error("nesting deeper than 64");
    skip_ws();
    if (i_ >= text_.size()) return error("expected a value, found end of file");
    const char c = text_[i_];
    if (c == '{') return object([&](const std::string&) { return skip_value(depth + 1); });
    if (c == '[') return array([&] { return skip_value(depth + 1); });
    if (c == '"') {
      std::string s;
      return string(s);
    }
    for (std::string_view word : {"true", "false", "null"}) {
      if (text_.substr(i_, word.size()) == word) {
        i_ += word.size();
        return Status::Ok();
      }
    }
    double d;
    return number(d);
  }

  Status end() {
    skip_ws();
    if (i_ != text_.size()) return error("data after the end of the model");
    return Status::Ok();
  }

 private:
  Status hex4(std::uint32_t& cp) {
    if (i_ + 4 > text_.size()) return error("short \\u escape");
    cp = 0;
    for (int k = 0; k < 4; ++k) {
      const char h = text_[i_++];
      cp <<= 4;
      if (h >= '0' && h <= '9')
        cp |= static_cast<std::uint32_t>(h - '0');
      else if (h >= 'a' && h <= 'f')
        cp |= static_cast<std::uint32_t>(h - 'a' + 10);
      else if (h >= 'A' && h <= 'F')
        cp |= static_cast<std::uint32_t>(h - 'A' + 10);
      else
        return error_at(i_ - 1, "bad hex digit in \\u escape");
    }
    return Status::Ok();
  }
  static void append_utf8(std::string& out, std::uint32_t cp) {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }

  std::string_view text_;
  std::size_t i_ = 0;
};

// A vector of exactly `n` numbers.
Status numbers(JsonReader& r, double* out, std::size_t n) {
  std::size_t k = 0;
  const std::size_t at = r.offset();
  Status s = r.array([&]() -> Status {
    if (k == n) return r.error("more than " + std::to_string(n) + " numbers");
    return r.number(out[k++]);
  });
  if (!s) return s;
  if (k != n)
    return r.error_at(at, "expected " + std::to_string(n) + " numbers, found " + std::to_string(k));
  return Status::Ok();
}

Status read_loop(JsonReader& r, Snapshot& s, std::uint32_t face, std::uint32_t ord) {
  const std::size_t at = r.offset();
  std::vector<std::uint32_t> vertices, edges, radial;
  std::int64_t point = Snapshot::kNone;
  const auto list = [&](std::vector<std::uint32_t>& out) {
    return r.array([&]() -> Status {
      std::uint32_t v = 0;
      if (Status st = r.index(v); !st) return st;
      out.push_back(v);
      return Status::Ok();
    });
  };
  Status st = r.object([&](const std::string& key) -> Status {
    if (key == "vertices") return list(vertices);
    if (key == "edges") return list(edges);
    if (key == "radial") return list(radial);
    if (key == "point") return r.optional_index(point);
    return r.skip_value();
  });
  if (!st) return st;
  const auto loop = static_cast<std::uint32_t>(s.loops.size());
  s.loops.push_back({face, ord, point});
  if (point != Snapshot::kNone) {
    if (!vertices.empty() || !edges.empty())
      return r.error_at(at, "a point loop has no vertices or edges");
    return Status::Ok();
  }
  if (vertices.empty() || vertices.size() != edges.size() || vertices.size() != radial.size()) {
    return r.error_at(at, "loop needs 'vertices', 'edges' and 'radial' of one nonzero length (" +
                              std::to_string(vertices.size()) + ", " +
                              std::to_string(edges.size()) + ", " + std::to_string(radial.size()) +
                              ")");
  }
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    const std::uint32_t e = edges[k];
    if (e >= s.edges.size())
      return r.error_at(
          at, "loop names edge " + std::to_string(e) + " of " + std::to_string(s.edges.size()));
    const std::uint32_t a = vertices[k], b = vertices[(k + 1) % vertices.size()];
    const Snapshot::Edge& edge = s.edges[e];
    const bool forward = edge.start == a && edge.end == b;
    if (!forward && !(edge.start == b && edge.end == a)) {
      return r.error_at(at, "loop use " + std::to_string(k) + " runs " + std::to_string(a) + "->" +
                                std::to_string(b) + " but edge " + std::to_string(e) + " joins " +
                                std::to_string(edge.start) + " and " + std::to_string(edge.end));
    }
    s.uses.push_back({loop, static_cast<std::uint32_t>(k), e, !forward, radial[k]});
  }
  return Status::Ok();
}

Status read_face(JsonReader& r, Snapshot& s) {
  const auto face = static_cast<std::uint32_t>(s.faces.size());
  s.faces.push_back({});
  std::uint32_t ord = 0;
  bool has_group = false;
  const std::size_t at = r.offset();
  Status st = r.object([&](const std::string& key) -> Status {
    Snapshot::Face& f = s.faces[face];
    if (key == "group") {
      has_group = true;
      return r.index(f.group);
    }
    if (key == "front") return r.optional_index(f.front);
    if (key == "back") return r.optional_index(f.back);
    if (key == "surface") return r.optional_index(f.surface);
    if (key == "loops") return r.array([&] { return read_loop(r, s, face, ord++); });
    return r.skip_value();
  });
  if (!st) return st;
  if (!has_group) return r.error_at(at, "face " + std::to_string(face) + " has no 'group'");
  if (ord == 0) return r.error_at(at, "face " + std::to_string(face) + " has no loops");
  return Status::Ok();
}

Status read_snapshot(JsonReader& r, Snapshot& s) {
  std::string format;
  std::int64_t version = 0;
  bool edges_read = false;
  Status st = r.object([&](const std::string& key) -> Status {
    if (key == "format") return r.string(format);
    if (key == "version") return r.integer(version, 0, 1000000);
    if (key == "groups") {
      return r.array([&] {
        const auto g = static_cast<std::uint32_t>(s.groups.size());
        s.groups.push_back({});
        return r.object([&](const std::string& k) -> Status {
          if (k == "name") return r.string(s.groups[g].name);
          if (k == "attributes") {
            return r.array([&]() -> Status {
              Snapshot::Parameter p{g, {}, {}};
              if (Status a = r.expect('['); !a) return a;
              if (Status a = r.string(p.name); !a) return a;
              if (Status a = r.expect(','); !a) return a;
              if (Status a = r.string(p.value); !a) return a;
              s.parameters.push_back(std::move(p));
              return r.expect(']');
            });
          }
          return r.skip_value();
        });
      });
    }
    if (key == "cells") {
      return r.array([&]() -> Status {
        std::uint32_t g = 0;
        if (Status a = r.index(g); !a) return a;
        s.cells.push_back(g);
        return Status::Ok();
      });
    }
    if (key == "vertices") {
      return r.array([&]() -> Status {
        double c[4];
        if (Status a = numbers(r, c, 4); !a) return a;
        if (c[3] < 0 || c[3] > 4294967294.0 || c[3] != std::floor(c[3]))
          return r.error("vertex group must be an index");
        s.vertices.push_back({{c[0], c[1], c[2]}, static_cast<std::uint32_t>(c[3])});
        return Status::Ok();
      });
    }
    if (key == "edges") {
      edges_read = true;
      return r.array([&]() -> Status {
        Snapshot::Edge e{};
        if (Status a = r.expect('['); !a) return a;
        if (Status a = r.index(e.start); !a) return a;
        if (Status a = r.expect(','); !a) return a;
        if (Status a = r.index(e.end); !a) return a;
        s.edges.push_back(e);
        return r.expect(']');
      });
    }
    if (key == "surfaces") {
      return r.array([&] {
        Surface f;
        Status a = r.object([&](const std::string& k) -> Status {
          if (k == "kind") return r.string(f.kind);
          if (k == "center" || k == "axis") {
            double c[3];
            if (Status b = numbers(r, c, 3); !b) return b;
            (k == "center" ? f.center : f.axis) = {c[0], c[1], c[2]};
            return Status::Ok();
          }
          if (k == "radius") return r.number(f.radius);
          if (k == "radius2") return r.number(f.radius2);
          if (k == "height") return r.number(f.height);
          if (k == "segments") {
            std::int64_t n;
            if (Status b = r.integer(n, 0, 1 << 30); !b) return b;
            f.segments = static_cast<int>(n);
            return Status::Ok();
          }
          return r.skip_value();
        });
        if (a) s.surfaces.push_back(std::move(f));
        return a;
      });
    }
    if (key == "faces") {
      if (!edges_read) return r.error("'faces' must come after 'edges'");
      return r.array([&] { return read_face(r, s); });
    }
    return r.skip_value();
  });
  if (!st) return st;
  if (format != kFormat)
    return r.error_at(0, "not a cellforge model ('format' is " + quote(format) + ", expected '" +
                             std::string(kFormat) + "')");
  if (version != kVersion) return r.error_at(0, "unsupported version " + std::to_string(version));
  return r.end();
}

// Appends the tables of b to a, shifting b's keys past a's.
void append(Snapshot& a, const Snapshot& b) {
  const auto g0 = static_cast<std::uint32_t>(a.groups.size());
  const auto c0 = static_cast<std::int64_t>(a.cells.size());
  const auto v0 = static_cast<std::uint32_t>(a.vertices.size());
  const auto e0 = static_cast<std::uint32_t>(a.edges.size());
  const auto s0 = static_cast<std::int64_t>(a.surfaces.size());
  const auto f0 = static_cast<std::uint32_t>(a.faces.size());
  const auto l0 = static_cast<std::uint32_t>(a.loops.size());
  const auto shift = [](std::int64_t k, std::int64_t by) {
    return k == Snapshot::kNone ? k : k + by;
  };
  a.groups.insert(a.groups.end(), b.groups.begin(), b.groups.end());
  for (auto p : b.parameters) a.parameters.push_back({p.group + g0, p.name, p.value});
  for (auto c : b.cells) a.cells.push_back(c + g0);
  for (auto v : b.vertices) a.vertices.push_back({v.p, v.group + g0});
  for (auto e : b.edges) a.edges.push_back({e.start + v0, e.end + v0});
  a.surfaces.insert(a.surfaces.end(), b.surfaces.begin(), b.surfaces.end());
  for (auto f : b.faces)
    a.faces.push_back({f.group + g0, shift(f.front, c0), shift(f.back, c0), shift(f.surface, s0)});
  for (auto l : b.loops) a.loops.push_back({l.face + f0, l.ord, shift(l.point_vertex, v0)});
  for (auto u : b.uses)
    a.uses.push_back({u.loop + l0, u.ord, u.edge + e0, u.reversed, u.radial_ord});
}

}  // namespace

Result<ReadResult> read_json(Model& m, std::string_view text) {
  if (Status s = check_not_blank("json", text); !s) return s.error();
  if (Status s = check_utf8("json", text); !s) return s.error();
  JsonReader reader(text);
  Snapshot file;
  if (Status s = read_snapshot(reader, file); !s) return s.error();
  Snapshot all = snapshot(m);
  const auto first_group = static_cast<std::uint32_t>(all.groups.size());
  append(all, file);
  auto restored = restore(all);
  if (!restored) return Error{ErrorCode::kInvalidInput, "json: " + restored.error().message};
  m = std::move(*restored);
  ReadResult result;
  std::uint32_t k = 0;
  for (GroupId g : m.groups())
    if (k++ == first_group) result.group = g;
  return result;
}

}  // namespace cellforge::io
