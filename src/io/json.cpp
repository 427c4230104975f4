// The native JSON format (docs/io.md): the model's snapshot tables (topo/snapshot.h)
// written as JSON, so that reading gives back the same topology and the same
// coordinates bit for bit (doubles written with 17 significant digits). Faces carry
// their loops as vertex cycles with the edge and radial position of each use;
// then come the property tables of the snapshot and the attachments beside the
// model (topo/attachment.h). A file with either is version 2, one without them
// version 1 (what earlier readers read); this reader reads both.
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
#include <cstring>
#include <functional>
#include <limits>
#include <unordered_map>

#include "cellforge/topo/snapshot.h"
#include "io/formats.h"
#include "io/text.h"

namespace cellforge::io {

namespace {

constexpr std::string_view kFormat = "cellforge-model";
constexpr int kVersion = 2;  // 1: no properties, no attachments

// Non-finite doubles of property values, which JSON numbers cannot hold.
constexpr std::string_view kNaN = "NaN", kInfinity = "Infinity", kMinusInfinity = "-Infinity";

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

// A property value's double: a number, or a string for the non-finite ones (the
// sign and payload of a NaN are not kept).
void put_real(std::string& out, double d) {
  if (std::isfinite(d)) return put_number(out, d);
  out += '"';
  out += std::isnan(d) ? kNaN : d > 0 ? kInfinity : kMinusInfinity;
  out += '"';
}

void put_value(std::string& out, const PropertyValue& v) {
  if (const auto* i = std::get_if<std::int64_t>(&v)) {
    out += std::to_string(*i);
  } else if (const auto* u = std::get_if<std::uint64_t>(&v)) {
    out += std::to_string(*u);
  } else if (const auto* d = std::get_if<double>(&v)) {
    put_real(out, *d);
  } else if (const auto* t = std::get_if<std::string>(&v)) {
    put_string(out, *t);
  } else if (const auto* c = std::get_if<Colour>(&v)) {
    out += '[';
    const float parts[] = {c->r, c->g, c->b, c->a};
    for (int k = 0; k < 4; ++k) {
      if (k) out += ',';
      put_real(out, parts[k]);
    }
    out += ']';
  } else if (const auto* p = std::get_if<Vec3>(&v)) {
    out += '[';
    put_real(out, p->x);
    out += ',';
    put_real(out, p->y);
    out += ',';
    put_real(out, p->z);
    out += ']';
  }
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

std::string write_json(const Model& m, const std::vector<Attachment>& attachments) {
  const Snapshot s = snapshot(m);
  const int version = s.properties.empty() && attachments.empty() ? 1 : kVersion;
  std::string out = "{\"format\":\"" + std::string(kFormat) +
                    "\",\"version\":" + std::to_string(version) + ",\n\"groups\":";
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
  out += ']';
  if (!s.properties.empty()) {
    out += ",\n\"properties\":";
    put_list(
        out, s.properties,
        [&](const Snapshot::Property& p) {
          out += "{\"owner\":\"" + std::string(owner_name(p.owner)) + "\",\"name\":";
          put_string(out, p.name);
          out += ",\"type\":\"" + std::string(type_name(p.type)) + "\",\"default\":";
          put_value(out, p.fallback);
          out += ",\"values\":";
          put_list(out, p.values, [&](const std::pair<std::uint32_t, PropertyValue>& kv) {
            out += '[' + std::to_string(kv.first) + ',';
            put_value(out, kv.second);
            out += ']';
          });
          out += '}';
        },
        ",\n ");
  }
  if (!attachments.empty()) {
    out += ",\n\"attachments\":";
    put_list(
        out, attachments,
        [&](const Attachment& a) {
          out += "{\"name\":";
          put_string(out, a.name);
          out += ",\"version\":" + std::to_string(a.version) + ",\"data\":";
          put_string(out, a.data);
          out += '}';
        },
        ",\n ");
  }
  out += "}\n";
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
  // Whether the next character (after white space) is c; nothing is consumed.
  bool at(char c) {
    skip_ws();
    return i_ < text_.size() && text_[i_] == c;
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
  Status unsigned_integer(std::uint64_t& out, std::uint64_t hi) {
    skip_ws();
    const std::size_t start = i_;
    while (i_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[i_]))) ++i_;
    const std::string_view tok = text_.substr(start, i_ - start);
    const auto [end, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    if (tok.empty() || ec == std::errc::invalid_argument || end != tok.data() + tok.size())
      return error_at(
          start, "expected a non-negative integer, found " + (tok.empty() ? found() : quote(tok)));
    if (ec == std::errc::result_out_of_range || out > hi)
      return error_at(
          start, "integer " + std::string(tok) + " out of range [0, " + std::to_string(hi) + "]");
    return Status::Ok();
  }
  // A number, or one of the strings "NaN", "Infinity", "-Infinity".
  Status real(double& out) {
    if (!at('"')) return number(out);
    const std::size_t start = i_;
    std::string word;
    if (Status s = string(word); !s) return s;
    if (word == kNaN) {
      out = std::numeric_limits<double>::quiet_NaN();
    } else if (word == kInfinity || word == kMinusInfinity) {
      out = word == kInfinity ? std::numeric_limits<double>::infinity()
                              : -std::numeric_limits<double>::infinity();
    } else {
      return error_at(
          start, "expected a number, \"NaN\", \"Infinity\" or \"-Infinity\", found " + quote(word));
    }
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

// ---- property values and attachments

// A double of a float value, rounded to the nearest float (what the writer writes
// is one already).
Status to_float(JsonReader& r, std::size_t at, double& d) {
  if (std::isfinite(d) && std::abs(d) > std::numeric_limits<float>::max())
    return r.error_at(at, "number out of the range of a float");
  d = static_cast<float>(d);
  return Status::Ok();
}

// A vector of exactly n property doubles (floats when `floats`).
Status reals(JsonReader& r, double* out, std::size_t n, bool floats) {
  std::size_t k = 0;
  const std::size_t at = r.offset();
  Status s = r.array([&]() -> Status {
    if (k == n) return r.error("more than " + std::to_string(n) + " numbers");
    const std::size_t here = r.offset();
    if (Status a = r.real(out[k]); !a) return a;
    if (floats)
      if (Status a = to_float(r, here, out[k]); !a) return a;
    ++k;
    return Status::Ok();
  });
  if (!s) return s;
  if (k != n)
    return r.error_at(at, "expected " + std::to_string(n) + " numbers, found " + std::to_string(k));
  return Status::Ok();
}

Status read_value(JsonReader& r, PropertyType type, PropertyValue& out) {
  using P = PropertyType;
  const auto signed_value = [&](std::int64_t lo, std::int64_t hi) -> Status {
    std::int64_t v = 0;
    if (Status s = r.integer(v, lo, hi); !s) return s;
    out = v;
    return Status::Ok();
  };
  const auto unsigned_value = [&](std::uint64_t hi) -> Status {
    std::uint64_t v = 0;
    if (Status s = r.unsigned_integer(v, hi); !s) return s;
    out = v;
    return Status::Ok();
  };
  switch (type) {
    case P::kInt8:
      return signed_value(INT8_MIN, INT8_MAX);
    case P::kInt16:
      return signed_value(INT16_MIN, INT16_MAX);
    case P::kInt32:
      return signed_value(INT32_MIN, INT32_MAX);
    case P::kInt64:
      return signed_value(INT64_MIN, INT64_MAX);
    case P::kUInt8:
      return unsigned_value(UINT8_MAX);
    case P::kUInt16:
      return unsigned_value(UINT16_MAX);
    case P::kUInt32:
      return unsigned_value(UINT32_MAX);
    case P::kUInt64:
      return unsigned_value(UINT64_MAX);
    case P::kFloat:
    case P::kDouble: {
      const std::size_t at = r.offset();
      double d = 0;
      if (Status s = r.real(d); !s) return s;
      if (type == P::kFloat)
        if (Status s = to_float(r, at, d); !s) return s;
      out = d;
      return Status::Ok();
    }
    case P::kString: {
      std::string t;
      if (Status s = r.string(t); !s) return s;
      out = std::move(t);
      return Status::Ok();
    }
    case P::kColour: {
      double c[4];
      if (Status s = reals(r, c, 4, true); !s) return s;
      out = Colour{static_cast<float>(c[0]), static_cast<float>(c[1]), static_cast<float>(c[2]),
                   static_cast<float>(c[3])};
      return Status::Ok();
    }
    case P::kVec3: {
      double c[3];
      if (Status s = reals(r, c, 3, false); !s) return s;
      out = Vec3{c[0], c[1], c[2]};
      return Status::Ok();
    }
  }
  return r.error("unknown property type");
}

// {"owner": ..., "name": ..., "type": ..., "default": value, "values": [[key, value], ...]},
// "type" before the values it types.
Status read_property(JsonReader& r, Snapshot& s) {
  const std::size_t at = r.offset();
  Snapshot::Property p{};
  bool has_owner = false, has_name = false, has_type = false, has_default = false;
  Status st = r.object([&](const std::string& key) -> Status {
    if (key == "owner" || key == "type") {
      r.skip_ws();
      const std::size_t here = r.offset();
      std::string word;
      if (Status a = r.string(word); !a) return a;
      if (key == "owner") {
        const auto owner = owner_from_name(word);
        if (!owner)
          return r.error_at(
              here, "unknown property owner " + quote(word) + " (vertex, edge, face or cell)");
        p.owner = *owner;
        has_owner = true;
      } else {
        const auto type = type_from_name(word);
        if (!type)
          return r.error_at(here, "unknown property type " + quote(word) +
                                      " (int8 to int64, uint8 to uint64, float, double, string, "
                                      "colour, vec3)");
        p.type = *type;
        has_type = true;
      }
      return Status::Ok();
    }
    if (key == "name") {
      has_name = true;
      return r.string(p.name);
    }
    if (key == "default" || key == "values") {
      if (!has_type) return r.error("a property's 'type' must come before its '" + key + "'");
      if (key == "default") {
        has_default = true;
        return read_value(r, p.type, p.fallback);
      }
      return r.array([&]() -> Status {
        r.skip_ws();
        const std::size_t here = r.offset();
        std::uint32_t k = 0;
        PropertyValue v;
        if (Status a = r.expect('['); !a) return a;
        if (Status a = r.index(k); !a) return a;
        if (!p.values.empty() && k <= p.values.back().first)
          return r.error_at(here, "property keys must increase (" + std::to_string(k) + " after " +
                                      std::to_string(p.values.back().first) + ")");
        if (Status a = r.expect(','); !a) return a;
        if (Status a = read_value(r, p.type, v); !a) return a;
        p.values.emplace_back(k, std::move(v));
        return r.expect(']');
      });
    }
    return r.skip_value();
  });
  if (!st) return st;
  if (!has_owner || !has_name || !has_type || !has_default)
    return r.error_at(at, "a property needs 'owner', 'name', 'type' and 'default'");
  for (const Snapshot::Property& q : s.properties) {
    if (q.owner == p.owner && q.name == p.name)
      return r.error_at(
          at, std::string(owner_name(p.owner)) + " property " + quote(p.name) + " is there twice");
  }
  s.properties.push_back(std::move(p));
  return Status::Ok();
}

// {"name": ..., "version": n, "data": "..."}
Status read_attachment(JsonReader& r, std::vector<Attachment>& out) {
  const std::size_t at = r.offset();
  Attachment a;
  bool has_name = false, has_version = false, has_data = false;
  Status st = r.object([&](const std::string& key) -> Status {
    if (key == "name") {
      has_name = true;
      return r.string(a.name);
    }
    if (key == "version") {
      has_version = true;
      std::int64_t v = 0;
      if (Status b = r.integer(v, 1, INT32_MAX); !b) return b;
      a.version = static_cast<int>(v);
      return Status::Ok();
    }
    if (key == "data") {
      has_data = true;
      return r.string(a.data);
    }
    return r.skip_value();
  });
  if (!st) return st;
  if (!has_name || !has_version || !has_data)
    return r.error_at(at, "an attachment needs 'name', 'version' and 'data'");
  if (find_attachment(out, a.name))
    return r.error_at(at, "attachment " + quote(a.name) + " is there twice");
  out.push_back(std::move(a));
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

Status read_snapshot(JsonReader& r, Snapshot& s, std::vector<Attachment>& attachments) {
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
    if (key == "properties") return r.array([&] { return read_property(r, s); });
    if (key == "attachments") return r.array([&] { return read_attachment(r, attachments); });
    return r.skip_value();
  });
  if (!st) return st;
  if (format != kFormat)
    return r.error_at(0, "not a cellforge model ('format' is " + quote(format) + ", expected '" +
                             std::string(kFormat) + "')");
  if (version < 1 || version > kVersion)
    return r.error_at(0, "unsupported version " + std::to_string(version) +
                             " (this reader reads 1 to " + std::to_string(kVersion) + ")");
  return r.end();
}

// Equal bit for bit (doubles and floats: -0.0 is not 0.0).
bool same_value(const PropertyValue& a, const PropertyValue& b) {
  if (a.index() != b.index()) return false;
  if (const auto* d = std::get_if<double>(&a))
    return std::memcmp(d, std::get_if<double>(&b), sizeof *d) == 0;
  if (const auto* c = std::get_if<Colour>(&a))
    return std::memcmp(c, std::get_if<Colour>(&b), sizeof *c) == 0;
  if (const auto* p = std::get_if<Vec3>(&a))
    return std::memcmp(p, std::get_if<Vec3>(&b), sizeof *p) == 0;
  return a == b;
}

// b's property tables after a's: keys shifted by base (per owner kind); a table
// of the same owner and name joins a's (the same type required), with b's default
// written out for each of b's elements when the two defaults differ.
Status append_properties(Snapshot& a, const Snapshot& b, const std::uint32_t (&base)[4]) {
  const std::size_t count[4] = {b.vertices.size(), b.edges.size(), b.faces.size(), b.cells.size()};
  for (const Snapshot::Property& p : b.properties) {
    const auto o = static_cast<std::size_t>(p.owner);
    Snapshot::Property* into = nullptr;
    for (auto& q : a.properties)
      if (q.owner == p.owner && q.name == p.name) into = &q;
    if (!into) {
      Snapshot::Property q = p;
      for (auto& kv : q.values) kv.first += base[o];
      a.properties.push_back(std::move(q));
      continue;
    }
    if (into->type != p.type) {
      return Error{ErrorCode::kInvalidInput,
                   "json: " + std::string(owner_name(p.owner)) + " property '" + p.name + "' is " +
                       std::string(type_name(p.type)) + " in the file and " +
                       std::string(type_name(into->type)) + " in the model it is read into"};
    }
    if (same_value(into->fallback, p.fallback)) {
      for (const auto& [k, v] : p.values) into->values.emplace_back(k + base[o], v);
      continue;
    }
    std::size_t next = 0;
    for (std::uint32_t k = 0; k < count[o]; ++k) {
      const bool listed = next < p.values.size() && p.values[next].first == k;
      into->values.emplace_back(k + base[o], listed ? p.values[next++].second : p.fallback);
    }
  }
  return Status::Ok();
}

// Appends the tables of b to a, shifting b's keys past a's.
Status append(Snapshot& a, const Snapshot& b) {
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
  return append_properties(a, b, {v0, e0, f0, static_cast<std::uint32_t>(c0)});
}

// The property tables of `before` that snapshots leave out (value types without a
// PropertyType), carried to `after`, which holds before's elements first, in id
// order, renumbered (restore of before's snapshot and more).
void keep_memory_only_properties(const Model& before, Model& after) {
  const auto ids = [](const Model& m, int kind) {
    std::vector<std::uint32_t> out;
    if (kind == detail::kVertexProperty)
      for (VertexId v : m.vertices()) out.push_back(v.value);
    if (kind == detail::kEdgeProperty)
      for (EdgeId e : m.edges()) out.push_back(e.value);
    if (kind == detail::kFaceProperty)
      for (FaceId f : m.faces()) out.push_back(f.value);
    if (kind == detail::kVolumeProperty)
      for (VolumeId c : m.volumes()) out.push_back(c.value);
    return out;
  };
  for (int kind = 0; kind < detail::kPropertyKinds; ++kind) {
    std::vector<std::uint32_t> from, to;
    for (const auto& column : before.property_store().columns(kind)) {
      if (property_type_of(column->type())) continue;
      if (from.empty()) from = ids(before, kind), to = ids(after, kind);
      auto copy = column->empty_like();
      for (std::size_t k = 0; k < from.size() && k < to.size(); ++k)
        column->copy_to(from[k], *copy, to[k]);
      after.property_store().add(kind, std::move(copy));
    }
  }
}

}  // namespace

Result<ReadResult> read_json(Model& m, std::string_view text) {
  if (Status s = check_not_blank("json", text); !s) return s.error();
  if (Status s = check_utf8("json", text); !s) return s.error();
  JsonReader reader(text);
  Snapshot file;
  std::vector<Attachment> attachments;
  if (Status s = read_snapshot(reader, file, attachments); !s) return s.error();
  Snapshot all = snapshot(m);
  const auto first_group = static_cast<std::uint32_t>(all.groups.size());
  if (Status s = append(all, file); !s) return s.error();
  auto restored = restore(all);
  if (!restored) return Error{ErrorCode::kInvalidInput, "json: " + restored.error().message};
  keep_memory_only_properties(m, *restored);
  m = std::move(*restored);
  ReadResult result;
  result.attachments = std::move(attachments);
  std::uint32_t k = 0;
  for (GroupId g : m.groups())
    if (k++ == first_group) result.group = g;
  return result;
}

}  // namespace cellforge::io
