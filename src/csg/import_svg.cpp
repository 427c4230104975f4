// import() of SVG (import2d.h): the shapes' outlines in OpenSCAD 2021.01's units.
#include <expat.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>

#include "import2d.h"

namespace cellforge::csg {

namespace {

// An affine map of the plane: (a c e; b d f), as SVG writes matrix(a b c d e f).
struct Affine {
  double a = 1, b = 0, c = 0, d = 1, e = 0, f = 0;
  Affine then(const Affine& inner) const {  // this * inner
    return Affine{a * inner.a + c * inner.b,     b * inner.a + d * inner.b,
                  a * inner.c + c * inner.d,     b * inner.c + d * inner.d,
                  a * inner.e + c * inner.f + e, b * inner.e + d * inner.f + f};
  }
  Vec2 apply(Vec2 p) const { return Vec2{a * p.x + c * p.y + e, b * p.x + d * p.y + f}; }
};

// Millimetres per unit of a length attribute, as OpenSCAD 2021.01 reads them: a
// number without a unit is a point (25.4 / 72 mm), px is 1/96 in.
bool length_mm(const char* text, double& out) {
  char* end = nullptr;
  const double v = std::strtod(text, &end);
  if (end == text || !std::isfinite(v)) return false;
  const std::string unit(end);
  double k = 0;
  if (unit.empty() || unit == "pt")
    k = 25.4 / 72;
  else if (unit == "mm")
    k = 1;
  else if (unit == "cm")
    k = 10;
  else if (unit == "in")
    k = 25.4;
  else if (unit == "px")
    k = 25.4 / 96;
  else if (unit == "pc")
    k = 25.4 / 6;
  else
    return false;
  out = v * k;
  return true;
}

// The numbers in an attribute (separated by spaces and commas).
std::vector<double> numbers_in(const std::string& s, bool& ok) {
  std::vector<double> out;
  ok = true;
  const char* p = s.c_str();
  while (*p) {
    while (*p == ' ' || *p == ',' || *p == '\t' || *p == '\n' || *p == '\r') ++p;
    if (!*p) break;
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v)) {
      ok = false;
      return out;
    }
    out.push_back(v);
    p = end;
  }
  return out;
}

struct State {
  std::string path;
  XML_Parser parser = nullptr;
  std::string error;
  bool seen_root = false;
  double height_mm = 0;
  Affine page;                // user units of the root to OpenSCAD's millimetres
  std::vector<Affine> stack;  // per open element: its transform, composed
  int skip_depth = 0;         // inside defs, clipPath... (not drawn)
  std::vector<std::vector<std::vector<Vec2>>> shapes;

  std::string here() const {
    return path + ":" + std::to_string(XML_GetCurrentLineNumber(parser)) + ": ";
  }
  void fail(const std::string& message) {
    if (error.empty()) error = here() + message;
    XML_StopParser(parser, XML_FALSE);
  }
};

const char* attr(const char** atts, const char* name) {
  for (int i = 0; atts[i]; i += 2) {
    if (std::strcmp(atts[i], name) == 0) return atts[i + 1];
  }
  return nullptr;
}

bool parse_transform(const std::string& s, Affine& out) {
  out = Affine{};
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && (std::isspace(static_cast<unsigned char>(s[i])) || s[i] == ',')) ++i;
    if (i >= s.size()) break;
    const std::size_t open = s.find('(', i), close = s.find(')', i);
    if (open == std::string::npos || close == std::string::npos || close < open) return false;
    std::string name = s.substr(i, open - i);
    while (!name.empty() && std::isspace(static_cast<unsigned char>(name.back()))) name.pop_back();
    bool ok = true;
    const std::vector<double> v = numbers_in(s.substr(open + 1, close - open - 1), ok);
    if (!ok) return false;
    Affine t;
    if (name == "matrix" && v.size() == 6) {
      t = Affine{v[0], v[1], v[2], v[3], v[4], v[5]};
    } else if (name == "translate" && (v.size() == 1 || v.size() == 2)) {
      t.e = v[0];
      t.f = v.size() == 2 ? v[1] : 0;
    } else if (name == "scale" && (v.size() == 1 || v.size() == 2)) {
      t.a = v[0];
      t.d = v.size() == 2 ? v[1] : v[0];
    } else if (name == "rotate" && (v.size() == 1 || v.size() == 3)) {
      const double r = v[0] * M_PI / 180;
      const Affine rot{std::cos(r), std::sin(r), -std::sin(r), std::cos(r), 0, 0};
      if (v.size() == 3) {
        t = Affine{1, 0, 0, 1, v[1], v[2]}.then(rot).then(Affine{1, 0, 0, 1, -v[1], -v[2]});
      } else {
        t = rot;
      }
    } else if (name == "skewX" && v.size() == 1) {
      t.c = std::tan(v[0] * M_PI / 180);
    } else if (name == "skewY" && v.size() == 1) {
      t.b = std::tan(v[0] * M_PI / 180);
    } else {
      return false;
    }
    out = out.then(t);
    i = close + 1;
  }
  return true;
}

// SVG path data: M L H V Z and the curves C S Q T (each flattened into 20 equal
// parameter steps, as OpenSCAD does), absolute and relative. Arcs are refused.
bool parse_path(const std::string& d, std::vector<std::vector<Vec2>>& out, std::string& error) {
  std::size_t i = 0;
  char cmd = 0;
  Vec2 cur{0, 0}, start{0, 0}, last_control{0, 0};
  char last_cmd = 0;
  auto skip = [&]() {
    while (i < d.size() && (std::isspace(static_cast<unsigned char>(d[i])) || d[i] == ',')) ++i;
  };
  auto number = [&](double& v) {
    skip();
    if (i >= d.size()) return false;
    char* end = nullptr;
    v = std::strtod(d.c_str() + i, &end);
    if (end == d.c_str() + i || !std::isfinite(v)) return false;
    i = static_cast<std::size_t>(end - d.c_str());
    return true;
  };
  auto add = [&](Vec2 p) {
    if (out.empty()) out.emplace_back(1, cur);
    out.back().push_back(p);
    cur = p;
  };
  constexpr int kSteps = 20;
  for (;;) {
    skip();
    if (i >= d.size()) break;
    if (std::isalpha(static_cast<unsigned char>(d[i]))) {
      cmd = d[i++];
    } else if (cmd == 0) {
      error = "path data must start with a command";
      return false;
    }
    const bool rel = std::islower(static_cast<unsigned char>(cmd));
    const char up = static_cast<char>(std::toupper(static_cast<unsigned char>(cmd)));
    auto point = [&](Vec2& p) {
      double x, y;
      if (!number(x) || !number(y)) return false;
      p = rel ? Vec2{cur.x + x, cur.y + y} : Vec2{x, y};
      return true;
    };
    Vec2 p, c1, c2;
    double v;
    switch (up) {
      case 'M':
        if (!point(p)) goto bad;
        out.emplace_back(1, p);
        cur = start = p;
        cmd = rel ? 'l' : 'L';  // further pairs are line segments
        break;
      case 'L':
        if (!point(p)) goto bad;
        add(p);
        break;
      case 'H':
        if (!number(v)) goto bad;
        add(Vec2{rel ? cur.x + v : v, cur.y});
        break;
      case 'V':
        if (!number(v)) goto bad;
        add(Vec2{cur.x, rel ? cur.y + v : v});
        break;
      case 'Z':
        cur = start;
        out.emplace_back(1, cur);  // a later segment starts a new subpath here
        break;
      case 'C':
      case 'S': {
        const Vec2 p0 = cur;
        if (up == 'C') {
          if (!point(c1)) goto bad;
        } else {
          c1 = (last_cmd == 'C' || last_cmd == 'S')
                   ? Vec2{2 * cur.x - last_control.x, 2 * cur.y - last_control.y}
                   : cur;
        }
        if (!point(c2) || !point(p)) goto bad;
        for (int k = 1; k <= kSteps; ++k) {
          const double t = static_cast<double>(k) / kSteps, s = 1 - t;
          add(Vec2{
              s * s * s * p0.x + 3 * s * s * t * c1.x + 3 * s * t * t * c2.x + t * t * t * p.x,
              s * s * s * p0.y + 3 * s * s * t * c1.y + 3 * s * t * t * c2.y + t * t * t * p.y});
        }
        last_control = c2;
        break;
      }
      case 'Q':
      case 'T': {
        const Vec2 p0 = cur;
        if (up == 'Q') {
          if (!point(c1)) goto bad;
        } else {
          c1 = (last_cmd == 'Q' || last_cmd == 'T')
                   ? Vec2{2 * cur.x - last_control.x, 2 * cur.y - last_control.y}
                   : cur;
        }
        if (!point(p)) goto bad;
        for (int k = 1; k <= kSteps; ++k) {
          const double t = static_cast<double>(k) / kSteps, s = 1 - t;
          add(Vec2{s * s * p0.x + 2 * s * t * c1.x + t * t * p.x,
                   s * s * p0.y + 2 * s * t * c1.y + t * t * p.y});
        }
        last_control = c1;
        break;
      }
      case 'A':
        error = "path arcs (A) are not supported yet";
        return false;
      default:
        error = std::string("unknown path command ") + cmd;
        return false;
    }
    last_cmd = up;
  }
  return true;
bad:
  error = std::string("path command ") + cmd + " is missing numbers";
  return false;
}

void close_paths(std::vector<std::vector<Vec2>>& paths) {
  std::vector<std::vector<Vec2>> kept;
  for (auto& p : paths) {
    std::vector<Vec2> q;
    for (Vec2 v : p) {
      if (!q.empty() && q.back().x == v.x && q.back().y == v.y) continue;
      q.push_back(v);
    }
    while (q.size() > 1 && q.back().x == q.front().x && q.back().y == q.front().y) q.pop_back();
    if (q.size() >= 3) kept.push_back(std::move(q));
  }
  paths = std::move(kept);
}

void on_start(void* data, const char* name, const char** atts) {
  auto& st = *static_cast<State*>(data);
  std::string tag = name;
  if (const auto colon = tag.find(':'); colon != std::string::npos) tag = tag.substr(colon + 1);
  const Affine parent = st.stack.empty() ? st.page : st.stack.back();
  Affine here = parent;
  if (const char* t = attr(atts, "transform")) {
    Affine m;
    if (!parse_transform(t, m))
      return st.fail("transform \"" + std::string(t) + "\" is not supported");
    here = parent.then(m);
  }
  st.stack.push_back(here);
  if (st.skip_depth > 0) {
    ++st.skip_depth;
    return;
  }
  if (tag == "svg") {
    if (st.seen_root) return st.fail("a nested <svg> element is not supported yet");
    st.seen_root = true;
    const char* w = attr(atts, "width");
    const char* h = attr(atts, "height");
    const char* vb = attr(atts, "viewBox");
    double wmm = 0, hmm = 0;
    if (w && !length_mm(w, wmm)) return st.fail("width \"" + std::string(w) + "\" is not a length");
    if (h && !length_mm(h, hmm))
      return st.fail("height \"" + std::string(h) + "\" is not a length");
    Affine page;  // OpenSCAD 2021.01: y turned up about the height in millimetres
    if (vb) {
      bool ok = true;
      const std::vector<double> v = numbers_in(vb, ok);
      if (!ok || v.size() != 4 || v[2] <= 0 || v[3] <= 0)
        return st.fail("viewBox \"" + std::string(vb) + "\" is not 4 numbers");
      if (!w) wmm = v[2] * 25.4 / 72;
      if (!h) hmm = v[3] * 25.4 / 72;
      const double sx = wmm / v[2], sy = hmm / v[3];
      page = Affine{sx, 0, 0, -sy, -v[0] * sx, hmm - v[1] * sy};
    } else {
      page = Affine{1, 0, 0, -1, 0, hmm};
    }
    st.height_mm = hmm;
    st.page = page;
    Affine m;
    if (const char* t = attr(atts, "transform")) parse_transform(t, m);
    st.stack.back() = page.then(m);
    return;
  }
  if (!st.seen_root) return st.fail("the root element is <" + tag + ">, not <svg>");
  static const char* const kHidden[] = {
      "defs", "clipPath", "mask",  "pattern",        "symbol",         "marker", "title",
      "desc", "metadata", "style", "linearGradient", "radialGradient", "filter"};
  for (const char* h : kHidden) {
    if (tag == h) {
      st.skip_depth = 1;
      return;
    }
  }
  if (tag == "g" || tag == "a") return;
  const char* fill = attr(atts, "fill");
  const char* style = attr(atts, "style");
  if ((fill && std::string(fill) == "none") ||
      (style && std::string(style).find("fill:none") != std::string::npos)) {
    return st.fail("<" + tag + "> with fill none (a stroked outline) is not supported yet");
  }
  std::vector<std::vector<Vec2>> paths;
  auto num = [&](const char* key, double fallback, double& out) {
    const char* v = attr(atts, key);
    if (!v) {
      out = fallback;
      return true;
    }
    char* end = nullptr;
    out = std::strtod(v, &end);
    if (end == v || !std::isfinite(out) || (*end && std::string(end) != "px")) {
      st.fail("<" + tag + "> " + key + " \"" + v + "\" is not a number");
      return false;
    }
    return true;
  };
  if (tag == "path") {
    const char* d = attr(atts, "d");
    std::string err;
    if (d && !parse_path(d, paths, err)) return st.fail("<path> " + err);
  } else if (tag == "rect") {
    double x, y, w, h, rx, ry;
    if (!num("x", 0, x) || !num("y", 0, y) || !num("width", 0, w) || !num("height", 0, h) ||
        !num("rx", 0, rx) || !num("ry", 0, ry))
      return;
    if (rx != 0 || ry != 0) return st.fail("<rect> with rounded corners is not supported yet");
    if (w > 0 && h > 0) paths.push_back({{x, y}, {x + w, y}, {x + w, y + h}, {x, y + h}});
  } else if (tag == "circle" || tag == "ellipse") {
    double cx, cy, rx, ry;
    if (!num("cx", 0, cx) || !num("cy", 0, cy)) return;
    if (tag == "circle") {
      if (!num("r", 0, rx)) return;
      ry = rx;
    } else if (!num("rx", 0, rx) || !num("ry", 0, ry)) {
      return;
    }
    // OpenSCAD 2021.01 draws SVG circles and ellipses with 40 segments.
    if (rx > 0 && ry > 0) {
      paths.emplace_back();
      for (int k = 0; k < 40; ++k) {
        const double a = 2 * M_PI * k / 40;
        paths.back().push_back(Vec2{cx + rx * std::cos(a), cy + ry * std::sin(a)});
      }
    }
  } else if (tag == "polygon") {
    const char* pts = attr(atts, "points");
    bool ok = true;
    const std::vector<double> v = numbers_in(pts ? pts : "", ok);
    if (!ok || v.size() % 2 != 0) return st.fail("<polygon> points must be pairs of numbers");
    paths.emplace_back();
    for (std::size_t k = 0; k + 1 < v.size(); k += 2) paths.back().push_back(Vec2{v[k], v[k + 1]});
  } else {
    return st.fail("<" + tag +
                   "> is not supported yet (path, polygon, rect, circle and ellipse are)");
  }
  for (auto& p : paths) {
    for (Vec2& q : p) q = here.apply(q);
  }
  close_paths(paths);
  if (!paths.empty()) st.shapes.push_back(std::move(paths));
}

void on_end(void* data, const char*) {
  auto& st = *static_cast<State*>(data);
  if (!st.stack.empty()) st.stack.pop_back();
  if (st.skip_depth > 0) --st.skip_depth;
}

}  // namespace

Result<std::vector<std::vector<std::vector<Vec2>>>> read_svg(const std::string& path,
                                                             const Import2DOptions&) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kIo, "cannot open " + path};
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  State st;
  st.path = path;
  XML_Parser parser = XML_ParserCreate(nullptr);
  st.parser = parser;
  XML_SetUserData(parser, &st);
  XML_SetElementHandler(parser, on_start, on_end);
  const bool ok =
      XML_Parse(parser, text.data(), static_cast<int>(text.size()), XML_TRUE) != XML_STATUS_ERROR;
  if (!ok && st.error.empty()) {
    st.error = path + ":" + std::to_string(XML_GetCurrentLineNumber(parser)) +
               ": not well-formed XML: " + XML_ErrorString(XML_GetErrorCode(parser));
  }
  XML_ParserFree(parser);
  if (!st.error.empty()) return Error{ErrorCode::kUnsupported, st.error};
  if (!st.seen_root) return Error{ErrorCode::kInvalidInput, path + ": no <svg> element"};
  return std::move(st.shapes);
}

}  // namespace cellforge::csg
