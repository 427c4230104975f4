// import() of DXF: the ENTITIES section's outlines (import2d.h says which and how).
#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <optional>
#include <set>

#include "import2d.h"

namespace cellforge::csg {

namespace {

// OpenSCAD's point grid: 1/1024. A point whose cell is empty joins an occupied
// neighbouring cell (the nearest by cell steps), as OpenSCAD's Grid2d does.
class Grid {
 public:
  std::uint32_t add(Vec2 p) {
    std::int64_t ix = std::llround(p.x * kPerUnit), iy = std::llround(p.y * kPerUnit);
    if (!cells_.count({ix, iy})) {
      int best = 10;
      std::int64_t bx = ix, by = iy;
      for (std::int64_t jx = ix - 1; jx <= ix + 1; ++jx) {
        for (std::int64_t jy = iy - 1; jy <= iy + 1; ++jy) {
          if (!cells_.count({jx, jy})) continue;
          const int d = static_cast<int>(std::llabs(ix - jx) + std::llabs(iy - jy));
          if (d < best) {
            best = d;
            bx = jx;
            by = jy;
          }
        }
      }
      ix = bx;
      iy = by;
    }
    auto [it, fresh] = cells_.emplace(std::pair{ix, iy}, static_cast<std::uint32_t>(points.size()));
    if (fresh) points.push_back(Vec2{ix / kPerUnit, iy / kPerUnit});
    return it->second;
  }
  std::vector<Vec2> points;

 private:
  static constexpr double kPerUnit = 1024;
  std::map<std::pair<std::int64_t, std::int64_t>, std::uint32_t> cells_;
};

struct Group {
  int code;
  std::string value;
  std::size_t line;  // of the code
};

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}


// An entity: its type, its groups up to the next entity, the line of its type name.
struct Entity {
  std::string type;
  std::vector<Group> body;
  std::size_t line;
};

// The ENTITIES section and the BLOCKS (for INSERT).
struct Drawing {
  std::vector<Entity> entities;
  std::map<std::string, std::vector<Entity>> blocks;
};

std::string at_line(const std::string& path, std::size_t line) {
  return path + ":" + std::to_string(line) + ": ";
}

// The group codes whose values are numbers (coordinates, sizes, angles, flags).
bool numeric_code(int code) {
  return (code >= 10 && code <= 59) || (code >= 70 && code <= 79) || (code >= 210 && code <= 239);
}

// A group's value as a number; an error naming the line when it is not one.
Result<double> group_number(const std::string& path, const Group& g) {
  char* end = nullptr;
  const double v = std::strtod(g.value.c_str(), &end);
  if (g.value.empty() || *end != '\0' || !std::isfinite(v)) {
    return Error{ErrorCode::kInvalidInput, at_line(path, g.line + 1) + "group " + std::to_string(g.code) +
                                               " must be a number, not \"" + g.value + "\""};
  }
  if (g.code >= 70 && g.code <= 79 && (v != std::floor(v) || std::abs(v) > 2147483647.0)) {
    return Error{ErrorCode::kInvalidInput, at_line(path, g.line + 1) + "group " + std::to_string(g.code) +
                                               " must be an integer, not \"" + g.value + "\""};
  }
  return v;
}

Result<Drawing> read_drawing(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return Error{ErrorCode::kIo, "cannot open " + path};
  auto at = [&](std::size_t line) { return at_line(path, line); };
  std::vector<Group> groups;
  {
    std::string code, value;
    std::size_t line = 0;
    while (std::getline(in, code)) {
      ++line;
      if (trim(code).empty() && in.peek() == EOF) break;
      if (!std::getline(in, value))
        return Error{ErrorCode::kInvalidInput, at(line) + "a group code without its value"};
      char* end = nullptr;
      const std::string c = trim(code);
      const long v = std::strtol(c.c_str(), &end, 10);
      if (c.empty() || *end != '\0')
        return Error{ErrorCode::kInvalidInput, at(line) + "not a DXF group code: " + c};
      groups.push_back(Group{static_cast<int>(v), trim(value), line});
      ++line;
    }
  }

  Drawing d;
  std::vector<Entity>& entities = d.entities;
  std::map<std::string, std::vector<Entity>>& blocks = d.blocks;
  {
    std::string section;
    std::vector<Entity>* block = nullptr;
    for (std::size_t i = 0; i < groups.size();) {
      const Group& head = groups[i];
      std::size_t j = i + 1;
      while (j < groups.size() && groups[j].code != 0) ++j;
      Entity e{head.value,
               std::vector<Group>(groups.begin() + static_cast<long>(i) + 1,
                                  groups.begin() + static_cast<long>(j)),
               head.line + 1};
      i = j;
      if (head.code != 0) continue;
      if (e.type == "SECTION") {
        section = !e.body.empty() && e.body[0].code == 2 ? e.body[0].value : "";
        continue;
      }
      if (e.type == "ENDSEC") {
        section.clear();
        block = nullptr;
        continue;
      }
      if (section == "ENTITIES") {
        entities.push_back(std::move(e));
      } else if (section == "BLOCKS") {
        if (e.type == "BLOCK") {
          std::string name;
          for (const Group& g : e.body) {
            if (g.code == 2) name = g.value;
          }
          block = &blocks[name];
        } else if (e.type == "ENDBLK") {
          block = nullptr;
        } else if (block) {
          block->push_back(std::move(e));
        }
      }
    }
  }

  return d;
}

// The outlines' segments between points on OpenSCAD's grid.
struct Segments {
  Grid grid;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> segments;
};

Result<Segments> read_segments(const std::string& path, const Import2DOptions& o) {
  auto drawing = read_drawing(path);
  if (!drawing) return drawing.error();
  const std::map<std::string, std::vector<Entity>>& blocks = drawing->blocks;
  auto at = [&](std::size_t line) { return at_line(path, line); };
  Segments out;
  Grid& grid = out.grid;
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& segments = out.segments;
  // A point of an entity: through the INSERTs it sits in (placement), then origin and
  // scale.
  struct Placement {
    double sx = 1, sy = 1, angle = 0, tx = 0, ty = 0;  // p -> rotate(scale(p)) + t
    Vec2 apply(Vec2 p) const {
      const double a = angle * M_PI / 180, x = p.x * sx, y = p.y * sy;
      return Vec2{std::cos(a) * x - std::sin(a) * y + tx, std::sin(a) * x + std::cos(a) * y + ty};
    }
  };
  std::vector<Placement> placements;  // innermost last
  auto point = [&](double x, double y) {
    Vec2 p{x, y};
    for (auto it = placements.rbegin(); it != placements.rend(); ++it) p = it->apply(p);
    return grid.add(Vec2{(p.x - o.origin.x) * o.scale, (p.y - o.origin.y) * o.scale});
  };
  auto line_to = [&](double x1, double y1, double x2, double y2) {
    const std::uint32_t a = point(x1, y1), b = point(x2, y2);
    if (a != b) segments.emplace_back(a, b);
  };
  auto fragments = [&](double r) { return shape::fragments(r * o.scale, o.faceting); };

  std::function<std::optional<Error>(const std::vector<Entity>&, int)> emit;
  emit = [&](const std::vector<Entity>& list, int depth) -> std::optional<Error> {
    struct Polyline {
      bool active = false, closed = false;
      std::vector<Vec2> points;
    } polyline;
    bool skipped_polyline = false;  // the VERTEXes of a POLYLINE of another layer
    auto end_polyline = [&]() {
      for (std::size_t i = 0; i + 1 < polyline.points.size(); ++i)
        line_to(polyline.points[i].x, polyline.points[i].y, polyline.points[i + 1].x,
                polyline.points[i + 1].y);
      if (polyline.closed && polyline.points.size() > 2)
        line_to(polyline.points.back().x, polyline.points.back().y, polyline.points[0].x,
                polyline.points[0].y);
      polyline = Polyline{};
    };
    for (const Entity& ent : list) {
      const std::string& type = ent.type;
      std::string layer = "0", block_name;
      std::map<int, double> num;
      std::vector<Vec2> vertices;  // LWPOLYLINE: each 10 starts a vertex
      for (const Group& g : ent.body) {
        if (g.code == 8) layer = g.value;
        if (g.code == 2) block_name = g.value;
        if (!numeric_code(g.code)) continue;
        const auto number = group_number(path, g);
        if (!number) return number.error();
        const double v = *number;
        num[g.code] = v;
        if (type == "LWPOLYLINE") {
          if (g.code == 10) vertices.push_back(Vec2{v, 0});
          if (g.code == 20 && !vertices.empty()) vertices.back().y = v;
          if (g.code == 42 && v != 0) {
            return Error{
                ErrorCode::kUnsupported,
                at(g.line + 1) + "LWPOLYLINE with a bulge (an arc segment) is not supported yet"};
          }
        }
      }
      const bool wanted = o.layer.empty() || o.layer == layer;
      auto get = [&](int code, double fallback = 0) {
        return num.count(code) ? num[code] : fallback;
      };
      if (type == "VERTEX" && (polyline.active || skipped_polyline)) {
        if (polyline.active) polyline.points.push_back(Vec2{get(10), get(20)});
        continue;
      }
      if (type == "SEQEND") {
        if (polyline.active) end_polyline();
        skipped_polyline = false;
        continue;
      }
      if (polyline.active) end_polyline();
      skipped_polyline = false;
      if (type == "DIMENSION" || type == "TEXT" || type == "MTEXT" || type == "POINT") continue;
      if (type == "LINE") {
        if (wanted) line_to(get(10), get(20), get(11), get(21));
      } else if (type == "LWPOLYLINE") {
        if (!wanted) continue;
        for (std::size_t k = 0; k + 1 < vertices.size(); ++k)
          line_to(vertices[k].x, vertices[k].y, vertices[k + 1].x, vertices[k + 1].y);
        if ((static_cast<long>(get(70)) & 1) && vertices.size() > 2)
          line_to(vertices.back().x, vertices.back().y, vertices[0].x, vertices[0].y);
      } else if (type == "POLYLINE") {
        skipped_polyline = !wanted;
        if (!wanted) continue;
        polyline.active = true;
        polyline.closed = static_cast<long>(get(70)) & 1;
      } else if (type == "CIRCLE") {
        if (!wanted) continue;
        const double cx = get(10), cy = get(20), r = get(40);
        const int n = fragments(r);
        for (int k = 0; k < n; ++k) {
          const double a1 = (2 * M_PI / n) * k, a2 = (2 * M_PI / n) * (k + 1);
          line_to(std::cos(a1) * r + cx, std::sin(a1) * r + cy, std::cos(a2) * r + cx,
                  std::sin(a2) * r + cy);
        }
      } else if (type == "ARC") {
        if (!wanted) continue;
        const double cx = get(10), cy = get(20), r = get(40);
        double start = get(50), stop = get(51);
        while (start > stop) stop += 360;
        const double angle = stop - start;
        const int n = static_cast<int>(std::ceil(fragments(r) * angle / 360));
        for (int k = 0; k < n; ++k) {
          const double a1 = (start + angle * k / n) * M_PI / 180;
          const double a2 = (start + angle * (k + 1) / n) * M_PI / 180;
          line_to(std::cos(a1) * r + cx, std::sin(a1) * r + cy, std::cos(a2) * r + cx,
                  std::sin(a2) * r + cy);
        }
      } else if (type == "INSERT") {
        // The block's entities scaled (41, 42), turned (50) and moved to the insertion
        // point (10, 20); an INSERT's layer does not filter the block's entities.
        const auto it = blocks.find(block_name);
        if (it == blocks.end())
          return Error{ErrorCode::kInvalidInput, at(ent.line) + "INSERT of block \"" + block_name +
                                                     "\", which the file does not define"};
        if (depth >= 16)
          return Error{ErrorCode::kInvalidInput, at(ent.line) + "blocks nested more than 16 deep"};
        if (get(70, 1) > 1 || get(71, 1) > 1)
          return Error{ErrorCode::kUnsupported,
                       at(ent.line) + "INSERT of an array of blocks (70, 71) is not supported yet"};
        placements.push_back(Placement{get(41, 1), get(42, 1), get(50), get(10), get(20)});
        auto err = emit(it->second, depth + 1);
        placements.pop_back();
        if (err) return err;
      } else {
        return Error{ErrorCode::kUnsupported,
                     at(ent.line) + "DXF entity " + type + " is not supported yet"};
      }
    }
    if (polyline.active) end_polyline();
    return std::nullopt;
  };
  if (auto err = emit(drawing->entities, 0)) return *err;
  return out;
}

}  // namespace

Result<std::vector<std::vector<Vec2>>> read_dxf(const std::string& path, const Import2DOptions& o) {
  auto read = read_segments(path, o);
  if (!read) return read.error();
  const Grid& grid = read->grid;
  const auto& segments = read->segments;
  // Join the segments into closed paths at their shared points.
  std::set<std::pair<std::uint32_t, std::uint32_t>> seen;
  std::vector<std::vector<std::size_t>> at_point(grid.points.size());
  std::vector<std::pair<std::uint32_t, std::uint32_t>> unique;
  for (auto [a, b] : segments) {
    if (!seen.insert({std::min(a, b), std::max(a, b)}).second) continue;  // drawn twice
    at_point[a].push_back(unique.size());
    at_point[b].push_back(unique.size());
    unique.emplace_back(a, b);
  }
  auto where = [&](std::uint32_t p) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "(%.6g, %.6g)", grid.points[p].x, grid.points[p].y);
    return std::string(buf);
  };
  for (std::size_t p = 0; p < at_point.size(); ++p) {
    if (at_point[p].size() <= 2) continue;
    return Error{ErrorCode::kUnsupported,
                 path + ": outlines branch at " + where(static_cast<std::uint32_t>(p)) + " (" +
                     std::to_string(at_point[p].size()) +
                     " segments meet there; only paths that do not branch are supported)"};
  }
  // Open chains first, from one end (OpenSCAD closes an open path by its last
  // segment back to the start), then the closed ones.
  std::vector<bool> used(unique.size(), false);
  std::vector<std::vector<Vec2>> paths;
  auto walk = [&](std::uint32_t p, std::size_t e) {
    std::vector<Vec2> loop;
    while (!used[e]) {
      used[e] = true;
      loop.push_back(grid.points[p]);
      p = unique[e].first == p ? unique[e].second : unique[e].first;
      const auto& next = at_point[p];
      if (next.size() < 2) {
        loop.push_back(grid.points[p]);  // the far end of an open chain
        break;
      }
      e = next[0] == e ? next[1] : next[0];
    }
    paths.push_back(std::move(loop));
  };
  for (std::size_t p = 0; p < at_point.size(); ++p) {
    if (at_point[p].size() == 1 && !used[at_point[p][0]])
      walk(static_cast<std::uint32_t>(p), at_point[p][0]);
  }
  for (std::size_t s = 0; s < unique.size(); ++s) {
    if (!used[s]) walk(unique[s].first, s);
  }
  return paths;
}

Result<std::vector<DxfDimension>> read_dxf_dimensions(const std::string& path,
                                                      const Import2DOptions& o) {
  auto drawing = read_drawing(path);
  if (!drawing) return drawing.error();
  std::vector<DxfDimension> out;
  for (const Entity& ent : drawing->entities) {
    if (ent.type != "DIMENSION") continue;
    DxfDimension d;
    d.line = ent.line;
    std::string layer = "0";
    for (const Group& g : ent.body) {
      if (g.code == 8) layer = g.value;
      if (g.code == 1) d.name = g.value;
      if (!numeric_code(g.code)) continue;
      const auto v = group_number(path, g);
      if (!v) return v.error();
      // Points 0, 3, 4 and 5 are places (origin moved), 1, 2 and 6 offsets (scaled only),
      // as OpenSCAD reads them.
      const auto offset = [](int k) { return k == 1 || k == 2 || k == 6; };
      if (const int k = g.code - 10; k >= 0 && k <= 6)
        d.points[k].x = offset(k) ? *v * o.scale : (*v - o.origin.x) * o.scale;
      if (const int k = g.code - 20; k >= 0 && k <= 6)
        d.points[k].y = offset(k) ? *v * o.scale : (*v - o.origin.y) * o.scale;
      if (g.code == 50) d.angle = *v;
      if (g.code == 70) d.type = static_cast<int>(*v);
    }
    if (o.layer.empty() || o.layer == layer) out.push_back(std::move(d));
  }
  return out;
}

std::optional<double> dimension_value(const DxfDimension& d) {
  const auto& c = d.points;
  const auto dx = [&](int a, int b) { return c[a].x - c[b].x; };
  const auto dy = [&](int a, int b) { return c[a].y - c[b].y; };
  switch (d.type & 7) {
    case 0:  // rotated, horizontal or vertical: the distance along the angle
      return std::fabs(dx(4, 3) * shape::cos_degrees(d.angle) + dy(4, 3) * shape::sin_degrees(d.angle));
    case 1:  // aligned
      return std::hypot(dx(4, 3), dy(4, 3));
    case 2: {  // angular, in degrees (atan2 of x over y, as OpenSCAD measures it)
      const double a1 = std::atan2(dx(0, 5), dy(0, 5)) * 180 / M_PI;
      const double a2 = std::atan2(dx(4, 3), dy(4, 3)) * 180 / M_PI;
      return std::fabs(a1 - a2);
    }
    case 3:  // diameter
    case 4:  // radius
      return std::hypot(dx(5, 0), dy(5, 0));
    case 6:  // ordinate: x when flag 64 is set, else y
      return (d.type & 64) ? c[3].x : c[3].y;
    default:  // 5, angular by three points: not measured, as in OpenSCAD
      return std::nullopt;
  }
}

Result<std::optional<Vec2>> read_dxf_cross(const std::string& path, const Import2DOptions& o) {
  auto read = read_segments(path, o);
  if (!read) return read.error();
  std::vector<int> degree(read->grid.points.size(), 0);
  for (auto [a, b] : read->segments) {
    ++degree[a];
    ++degree[b];
  }
  std::vector<Vec2> ends;  // of the first two lone segments
  for (auto [a, b] : read->segments) {
    if (degree[a] != 1 || degree[b] != 1) continue;
    ends.push_back(read->grid.points[a]);
    ends.push_back(read->grid.points[b]);
    if (ends.size() == 4) break;
  }
  if (ends.size() < 4) return std::optional<Vec2>{};
  const double d1x = ends[1].x - ends[0].x, d1y = ends[1].y - ends[0].y;
  const double d2x = ends[3].x - ends[2].x, d2y = ends[3].y - ends[2].y;
  const double den = d2y * d1x - d2x * d1y;
  if (den == 0) return std::optional<Vec2>{};  // parallel
  const double t = (d2x * (ends[0].y - ends[2].y) - d2y * (ends[0].x - ends[2].x)) / den;
  return std::optional<Vec2>{Vec2{ends[0].x + d1x * t, ends[0].y + d1y * t}};
}

}  // namespace cellforge::csg
