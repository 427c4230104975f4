// 3MF (3MF Core Specification 1.x): the ZIP package (zip.h) with its model part,
// 3D/3dmodel.model or the one _rels/.rels names, in XML read by expat.
//
// Reading takes every build item: a mesh object, or an object of components (other
// objects with transforms, flattened), each with the item's transform; each item
// becomes one soup (and, through read_model, one group). Coordinates are read as
// doubles (ST_Number is xs:double); a number that no double holds (1e400) or that
// is not finite is an error naming the line and column.
//
// Writing makes one mesh object and build item per group, coordinates as the
// shortest text that reads back as the same double (std::to_chars), so a model
// survives the round trip bit for bit. A model without faces is a package with no
// objects, which reads back as an empty model.
#include <expat.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <optional>

#include "io/formats.h"
#include "io/text.h"
#include "io/zip.h"

namespace cellforge::io {

bool has_3mf() { return true; }

namespace {

constexpr const char* kCore = "http://schemas.microsoft.com/3dmanufacturing/core/2015/02";
constexpr const char* kModelRel = "http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel";
// What one part may unpack to: far above any real model's XML (about 100 bytes per
// vertex and per triangle: 10 M triangles), below what a machine has to spare.
constexpr std::uint64_t kMaxPart = std::uint64_t{1} << 30;
constexpr int kMaxComponentDepth = 32;

// [x y z 1] times the 4 x 3 matrix m00 m01 m02 m10 ... m32 (3MF's row-vector form).
// The identity is kept apart: applied as arithmetic it would turn -0 into +0.
struct Transform {
  std::array<double, 12> m{1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  bool identity = true;
  Vec3 apply(Vec3 p) const {
    if (identity) return p;
    return {p.x * m[0] + p.y * m[3] + p.z * m[6] + m[9],
            p.x * m[1] + p.y * m[4] + p.z * m[7] + m[10],
            p.x * m[2] + p.y * m[5] + p.z * m[8] + m[11]};
  }
  // This transform after `inner`.
  Transform after(const Transform& inner) const {
    if (identity) return inner;
    if (inner.identity) return *this;
    Transform t;
    t.identity = false;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 3; ++c) {
        double s = r == 3 ? m[9 + c] : 0;
        for (int k = 0; k < 3; ++k) s += inner.m[3 * r + k] * m[3 * k + c];
        t.m[3 * r + c] = s;
      }
    return t;
  }
};

struct Object {
  std::string name;
  std::vector<Vec3> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::pair<std::uint32_t, Transform>> components;
};

struct Parsed {
  std::map<std::uint32_t, Object> objects;
  std::vector<std::pair<std::uint32_t, Transform>> items;
  std::vector<std::string> relationship_targets;  // of _rels/.rels, for the model part
};

// Expat with namespaces: element names arrive as "uri local".
class XmlReader {
 public:
  XmlReader(std::string part, Parsed& out) : part_(std::move(part)), out_(out) {}

  Status parse(const std::string& text) {
    XML_Parser p = XML_ParserCreateNS("UTF-8", ' ');
    parser_ = p;
    XML_SetUserData(p, this);
    XML_SetElementHandler(p, &XmlReader::start, &XmlReader::end);
    const bool ok = XML_Parse(p, text.data(), static_cast<int>(text.size()), 1) != XML_STATUS_ERROR;
    if (!ok && !error_) error_ = at() + ": " + XML_ErrorString(XML_GetErrorCode(p));
    XML_ParserFree(p);
    if (error_) return Error{ErrorCode::kParse, "3mf: " + *error_};
    return Status::Ok();
  }

 private:
  std::string at() const {
    return part_ + " line " + std::to_string(XML_GetCurrentLineNumber(parser_)) + ":" +
           std::to_string(XML_GetCurrentColumnNumber(parser_) + 1);
  }
  void fail(const std::string& message) {
    if (!error_) error_ = at() + ": " + message;
    XML_StopParser(parser_, XML_FALSE);
  }
  static const char* attribute(const XML_Char** attrs, const char* name) {
    for (int i = 0; attrs[i]; i += 2)
      if (std::strcmp(attrs[i], name) == 0) return attrs[i + 1];
    return nullptr;
  }
  bool number(const XML_Char** attrs, const char* name, double& out) {
    const char* s = attribute(attrs, name);
    if (!s) return fail(std::string("missing attribute ") + name), false;
    const char* e = s + std::strlen(s);
    const auto r = std::from_chars(s, e, out);
    if (r.ec == std::errc::result_out_of_range)
      return fail(std::string(name) + "=\"" + s + "\" is beyond the range of a double"), false;
    if (r.ec != std::errc() || r.ptr != e || !std::isfinite(out))
      return fail(std::string(name) + "=\"" + s + "\" is not a finite number"), false;
    return true;
  }
  bool index(const XML_Char** attrs, const char* name, std::uint32_t& out) {
    const char* s = attribute(attrs, name);
    if (!s) return fail(std::string("missing attribute ") + name), false;
    const char* e = s + std::strlen(s);
    const auto r = std::from_chars(s, e, out);
    if (r.ec != std::errc() || r.ptr != e)
      return fail(std::string(name) + "=\"" + s + "\" is not an index"), false;
    return true;
  }
  bool transform(const XML_Char** attrs, Transform& t) {
    const char* s = attribute(attrs, "transform");
    if (!s) return true;
    t.identity = false;
    const char* e = s + std::strlen(s);
    for (double& v : t.m) {
      while (s < e && (*s == ' ' || *s == '\t' || *s == '\n' || *s == '\r')) ++s;
      const auto r = std::from_chars(s, e, v);
      if (r.ec != std::errc() || !std::isfinite(v))
        return fail("transform needs 12 finite numbers"), false;
      s = r.ptr;
    }
    return true;
  }

  static void start(void* self, const XML_Char* name, const XML_Char** attrs) {
    static_cast<XmlReader*>(self)->on_start(name, attrs);
  }
  static void end(void* self, const XML_Char* name) { static_cast<XmlReader*>(self)->on_end(name); }

  void on_start(const char* qname, const XML_Char** attrs) {
    const char* space = std::strchr(qname, ' ');
    const std::string ns = space ? std::string(qname, space) : "";
    const std::string local = space ? space + 1 : qname;
    if (local == "Relationship") {
      const char* type = attribute(attrs, "Type");
      const char* target = attribute(attrs, "Target");
      if (type && target && std::strcmp(type, kModelRel) == 0)
        out_.relationship_targets.push_back(target[0] == '/' ? target + 1 : target);
      return;
    }
    if (ns != kCore) return;  // extensions: not read
    if (local == "object") {
      std::uint32_t id = 0;
      if (!index(attrs, "id", id)) return;
      if (out_.objects.count(id)) return fail("object id " + std::to_string(id) + " repeats");
      object_ = &out_.objects[id];
      if (const char* n = attribute(attrs, "name")) object_->name = n;
    } else if (local == "vertex" && object_) {
      Vec3 v;
      if (number(attrs, "x", v.x) && number(attrs, "y", v.y) && number(attrs, "z", v.z))
        object_->vertices.push_back(v);
    } else if (local == "triangle" && object_) {
      std::array<std::uint32_t, 3> t;
      if (!index(attrs, "v1", t[0]) || !index(attrs, "v2", t[1]) || !index(attrs, "v3", t[2]))
        return;
      for (std::uint32_t i : t)
        if (i >= object_->vertices.size())
          return fail("triangle " + std::to_string(object_->triangles.size()) + " names vertex " +
                      std::to_string(i) + " of " + std::to_string(object_->vertices.size()));
      object_->triangles.push_back(t);
    } else if (local == "component" && object_) {
      std::pair<std::uint32_t, Transform> c;
      if (index(attrs, "objectid", c.first) && transform(attrs, c.second))
        object_->components.push_back(c);
    } else if (local == "item") {
      std::pair<std::uint32_t, Transform> item;
      if (index(attrs, "objectid", item.first) && transform(attrs, item.second))
        out_.items.push_back(item);
    }
  }
  void on_end(const char* qname) {
    const char* space = std::strchr(qname, ' ');
    if (space && std::strcmp(space + 1, "object") == 0) object_ = nullptr;
  }

  std::string part_;
  Parsed& out_;
  XML_Parser parser_ = nullptr;
  Object* object_ = nullptr;
  std::optional<std::string> error_;
};

// Appends object id (and its components) under transform t to the soup.
Status flatten(const Parsed& p, std::uint32_t id, const Transform& t, int depth, std::size_t item,
               PolygonSoup& soup) {
  const auto it = p.objects.find(id);
  if (it == p.objects.end())
    return Error{ErrorCode::kParse, "3mf: build item " + std::to_string(item) + " names object " +
                                        std::to_string(id) + ", which is not defined"};
  if (depth > kMaxComponentDepth)
    return Error{ErrorCode::kParse, "3mf: components nest deeper than " +
                                        std::to_string(kMaxComponentDepth) +
                                        " (a cycle?) at object " + std::to_string(id)};
  const Object& o = it->second;
  if (soup.name.empty()) soup.name = o.name;
  const auto base = static_cast<std::uint32_t>(soup.positions.size());
  for (std::size_t i = 0; i < o.vertices.size(); ++i) {
    const Vec3 v = t.apply(o.vertices[i]);
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z))
      return Error{ErrorCode::kParse, "3mf: build item " + std::to_string(item) + " object " +
                                          std::to_string(id) + " vertex " + std::to_string(i) +
                                          " is not finite after its transform"};
    soup.positions.push_back(v);
  }
  for (const auto& tri : o.triangles)
    soup.polygons.push_back({base + tri[0], base + tri[1], base + tri[2]});
  for (const auto& [child, local] : o.components)
    if (Status s = flatten(p, child, t.after(local), depth + 1, item, soup); !s) return s;
  return Status::Ok();
}

std::string number_text(double d) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, d);  // shortest round trip
  return std::string(buf, r.ptr);
}

// Text for an XML attribute: the markup characters escaped; a name that is not
// valid UTF-8 or holds characters XML 1.0 cannot carry is left out.
bool attribute_text(const std::string& s, std::string& out) {
  std::string r;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x20 && c != '\t' && c != '\n' && c != '\r') return false;
    switch (c) {
      case '&':
        r += "&amp;";
        break;
      case '<':
        r += "&lt;";
        break;
      case '>':
        r += "&gt;";
        break;
      case '"':
        r += "&quot;";
        break;
      default:
        r += static_cast<char>(c);
    }
  }
  if (!check_utf8("3mf", s)) return false;
  out = std::move(r);
  return true;
}

}  // namespace

Result<std::vector<PolygonSoup>> parse_3mf(std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return byte_error("3mf", 0, "empty file");
  if (bytes.size() < 4 || std::memcmp(bytes.data(), "PK\x03\x04", 4) != 0)
    return byte_error("3mf", 0, "not a ZIP archive (a 3MF file is a ZIP package; it starts 'PK')");
  auto zip = ZipReader::open(bytes);
  if (!zip) return zip.error();
  Parsed parsed;
  std::string part = "3D/3dmodel.model";
  if (zip->has("_rels/.rels")) {
    auto rels = zip->read("_rels/.rels", kMaxPart);
    if (!rels) return rels.error();
    if (Status s = XmlReader("_rels/.rels", parsed).parse(*rels); !s) return s.error();
    if (!parsed.relationship_targets.empty()) part = parsed.relationship_targets.front();
  }
  auto model = zip->read(part, kMaxPart);
  if (!model) return model.error();
  if (Status s = XmlReader(part, parsed).parse(*model); !s) return s.error();
  std::vector<PolygonSoup> soups;
  for (std::size_t i = 0; i < parsed.items.size(); ++i) {
    PolygonSoup soup;
    if (Status s = flatten(parsed, parsed.items[i].first, parsed.items[i].second, 0, i, soup); !s)
      return s.error();
    soups.push_back(std::move(soup));
  }
  return soups;
}

namespace {

// A color as 3MF's sRGB "#RRGGBBAA".
std::string display_color(const std::array<double, 4>& c) {
  char buf[16];
  int v[4];
  for (int i = 0; i < 4; ++i) v[i] = static_cast<int>(std::lround(std::clamp(c[i], 0.0, 1.0) * 255));
  std::snprintf(buf, sizeof buf, "#%02X%02X%02X%02X", v[0], v[1], v[2], v[3]);
  return buf;
}

}  // namespace

Result<std::string> write_3mf(const Model& m,
                              const std::vector<std::optional<std::array<double, 4>>>& colors) {
  const TriangleMesh mesh = triangle_mesh(m);
  std::string xml =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" xml:lang=\"en-US\" "
      "xmlns=\"" +
      std::string(kCore) + "\">\n<resources>\n";
  std::string build = "<build>\n";
  std::uint32_t id = 0;
  // Colors: one <basematerials> group (id 1), material 0 the default color, then
  // one per distinct color in face order.
  const bool colored = !colors.empty();
  std::vector<std::string> materials;
  std::map<std::string, std::size_t> material_of;
  auto material = [&](FaceId f) -> std::size_t {
    const std::string c = f.value < colors.size() && colors[f.value]
                              ? display_color(*colors[f.value])
                              : std::string("#F9D72CFF");
    auto [it, fresh] = material_of.emplace(c, materials.size());
    if (fresh) materials.push_back(c);
    return it->second;
  };
  std::vector<std::size_t> triangle_material;
  if (colored) {
    material(FaceId{});  // the default first
    for (FaceId f : mesh.face_of) triangle_material.push_back(material(f));
    xml += "<basematerials id=\"1\">\n";
    for (std::size_t i = 0; i < materials.size(); ++i) {
      xml += "<base name=\"" + (i == 0 ? std::string("default") : "color " + std::to_string(i)) +
             "\" displaycolor=\"" + materials[i] + "\"/>\n";
    }
    xml += "</basematerials>\n";
    id = 1;
  }
  std::vector<std::uint32_t> local(mesh.positions.size(), kInvalidIndex);
  for (GroupId g : m.groups()) {
    std::string vertices, triangles;
    std::uint32_t count = 0;
    std::vector<std::uint32_t> used;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (m.group_of(mesh.face_of[t]) != g) continue;
      triangles += "<triangle";
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t i = mesh.triangles[t][k];
        if (local[i] == kInvalidIndex) {
          local[i] = count++;
          used.push_back(i);
          const Vec3 p = mesh.positions[i];
          vertices += "<vertex x=\"" + number_text(p.x) + "\" y=\"" + number_text(p.y) + "\" z=\"" +
                      number_text(p.z) + "\"/>\n";
        }
        triangles += std::string(k == 0   ? " v1=\""
                                 : k == 1 ? " v2=\""
                                          : " v3=\"") +
                     std::to_string(local[i]) + "\"";
      }
      if (colored && triangle_material[t] != 0)
        triangles += " pid=\"1\" p1=\"" + std::to_string(triangle_material[t]) + "\"";
      triangles += "/>\n";
    }
    for (std::uint32_t i : used) local[i] = kInvalidIndex;
    if (triangles.empty()) continue;
    ++id;
    std::string name;
    xml += "<object id=\"" + std::to_string(id) + "\" type=\"model\"";
    if (colored) xml += " pid=\"1\" pindex=\"0\"";
    if (!m.name(g).empty() && attribute_text(m.name(g), name)) xml += " name=\"" + name + "\"";
    xml += ">\n<mesh>\n<vertices>\n" + vertices + "</vertices>\n<triangles>\n" + triangles +
           "</triangles>\n</mesh>\n</object>\n";
    build += "<item objectid=\"" + std::to_string(id) + "\"/>\n";
  }
  xml += "</resources>\n" + build + "</build>\n</model>\n";
  const std::string types =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Types "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default "
      "Extension=\"rels\" "
      "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default "
      "Extension=\"model\" ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/>"
      "</Types>\n";
  const std::string rels =
      "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<Relationships "
      "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
      "Target=\"/3D/3dmodel.model\" Id=\"rel0\" Type=\"" +
      std::string(kModelRel) +
      "\"/>"
      "</Relationships>\n";
  return write_zip(
      {{"[Content_Types].xml", types}, {"_rels/.rels", rels}, {"3D/3dmodel.model", xml}});
}

}  // namespace cellforge::io
