// diagnose(): what a model is as a mesh (diagnose.h). Every count walks the local
// cycles of the structure once; degeneracy and duplicates use exact tests on the
// vertices; mass properties are shape/'s (divergence theorem over the faces).
#include "cellforge/io/diagnose.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "cellforge/shape/mass.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/union_find.h"
#include "cellforge/io/triangulate.h"
#include "cellforge/topo/queries.h"
#include "cellforge/topo/validate.h"
#include "io/intersect.h"

namespace cellforge::io {

namespace {

// All vertices of f on one line (exact, in each coordinate plane).
bool degenerate(const Model& m, FaceId f) {
  const std::vector<Vec3> p = m.loop_points(m.outer_loop(f));
  if (p.size() < 3) return true;
  for (std::size_t k = 2; k < p.size(); ++k)
    if (!collinear3d(p[0], p[1], p[k])) return false;
  return true;
}

// Faces around v that form separate fans (joined across the edges at v).
std::size_t fans_at(const Model& m, VertexId v, std::vector<FaceId>& faces,
                    UnionFind& fans_of) {
  faces.clear();
  std::vector<EdgeId> edges;
  edges_of(m, v, edges);
  std::vector<FaceId> around;
  for (EdgeId e : edges) {
    faces_of(m, e, around);
    faces.insert(faces.end(), around.begin(), around.end());
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  fans_of.reset(faces.size());
  const auto index = [&](FaceId f) {
    return static_cast<std::uint32_t>(std::lower_bound(faces.begin(), faces.end(), f) -
                                      faces.begin());
  };
  std::size_t fans = faces.size();
  for (EdgeId e : edges) {
    faces_of(m, e, around);
    for (std::size_t k = 1; k < around.size(); ++k) {
      if (fans_of.unite(index(around[k]), index(around[0]))) --fans;
    }
  }
  return fans;
}

template <class T>
void put_ids(std::string& out, const char* key, const std::vector<T>& ids) {
  out += std::string(",\n  \"") + key + "\": [";
  for (std::size_t i = 0; i < ids.size() && i < 100; ++i) {
    if (i) out += ", ";
    if constexpr (std::is_same_v<T, std::pair<FaceId, FaceId>>)
      out += "[\"" + ids[i].first.str() + "\", \"" + ids[i].second.str() + "\"]";
    else
      out += "\"" + ids[i].str() + "\"";
  }
  out += "],\n  \"" + std::string(key) + "_count\": " + std::to_string(ids.size());
}

template <class T>
std::string list_text(const std::vector<T>& ids) {
  std::string s = std::to_string(ids.size());
  for (std::size_t i = 0; i < ids.size() && i < 20; ++i) {
    s += i ? ", " : " (";
    if constexpr (std::is_same_v<T, std::pair<FaceId, FaceId>>)
      s += ids[i].first.str() + "/" + ids[i].second.str();
    else
      s += ids[i].str();
  }
  if (!ids.empty()) s += ids.size() > 20 ? ", ...)" : ")";
  return s;
}

std::string num(double d) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", d);
  return buf;
}

// The signed volume of the faces as oriented: each face's fan of cones from the
// origin (counterclockwise seen from the front counts positive), as admesh and
// trimesh sum it for a mesh that is not closed.
double surface_volume(const Model& m) {
  double volume6 = 0;
  for (FaceId f : m.faces()) {
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) continue;
      const std::vector<Vec3> p = m.loop_points(l);
      for (std::size_t i = 1; i + 1 < p.size(); ++i) volume6 += dot(p[0], cross(p[i], p[i + 1]));
    }
  }
  return volume6 / 6;
}

// A warning for each closed shell (faces joined through edges, every edge of them
// used at least twice) none of whose faces bounds a cell.
void shells_without_cells(const Model& m, std::vector<std::string>& warnings) {
  UnionFind shell(m.face_slots());
  for (EdgeId e : m.edges()) {
    FaceId first;
    for (EdgeUseId u : m.radial(e)) {
      if (first.is_valid())
        shell.unite(first.value, m.face_of(u).value);
      else
        first = m.face_of(u);
    }
  }
  std::vector<char> open(m.face_slots(), 0), solid(m.face_slots(), 0);
  for (EdgeId e : m.edges())
    if (m.use_count(e) == 1) open[shell.find(m.face_of(m.first_use(e)).value)] = 1;
  for (FaceId f : m.faces())
    if (m.front_volume(f).is_valid() || m.back_volume(f).is_valid()) solid[shell.find(f.value)] = 1;
  std::size_t count = 0;
  for (FaceId f : m.faces()) {
    const std::uint32_t r = shell.find(f.value);
    if (r != f.value || open[r] || solid[r]) continue;
    if (++count <= 10)
      warnings.push_back("the closed shell of " + f.str() +
                         " bounds no cell (inside out, or a cavity with no solid around it)");
  }
  if (count > 10) warnings.push_back(std::to_string(count - 10) + " more closed shells bound no cell");
}

std::string vec_json(Vec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

}  // namespace

Diagnosis diagnose(const Model& m, const DiagnoseOptions& options) {
  const auto stage = [&](std::string_view name) {
    if (options.progress) options.progress(name);
  };
  Diagnosis d;
  d.vertices = m.num_vertices();
  d.edges = m.num_edges();
  d.faces = m.num_faces();
  d.loops = m.num_loops();
  d.volumes = m.num_volumes();
  d.groups = m.num_groups();
  {
    const EulerFigures fig = euler_figures(m);
    d.euler_characteristic_surface = fig.v - fig.e + (fig.f - fig.r);
    d.euler_characteristic_solid = fig.lhs();
  }
  stage("validating");
  const auto violations = validate(m);
  d.valid = violations.empty();
  for (std::size_t i = 0; i < violations.size() && i < 10; ++i)
    d.violations.push_back(violations[i].check + ": " + violations[i].message);

  std::vector<bool> on_nm_edge(m.vertex_slots(), false);
  for (EdgeId e : m.edges()) {
    const std::size_t uses = m.use_count(e);
    if (uses == 0) {
      ++d.wire_edges;
    } else if (uses == 1) {
      d.boundary_edges.push_back(e);
    } else if (uses == 2) {
      const EdgeUseId u = m.first_use(e);
      if (m.is_reversed(u) == m.is_reversed(m.radial_next(u))) d.inconsistent_edges.push_back(e);
    } else {
      d.non_manifold_edges.push_back(e);
      on_nm_edge[m.start_of(e).value] = on_nm_edge[m.end_of(e).value] = true;
    }
  }
  std::vector<FaceId> faces;
  UnionFind parent;
  for (VertexId v : m.vertices()) {
    if (!m.first_end(v).edge.is_valid()) {
      if (!m.point_loop(v).is_valid()) ++d.isolated_vertices;
      continue;
    }
    if (on_nm_edge[v.value]) continue;
    if (fans_at(m, v, faces, parent) > 1) d.non_manifold_vertices.push_back(v);
  }
  std::vector<std::pair<std::vector<std::uint32_t>, FaceId>> keys;
  keys.reserve(m.num_faces());
  for (FaceId f : m.faces()) {
    if (degenerate(m, f)) d.degenerate_faces.push_back(f);
    std::vector<std::uint32_t> key;
    for (LoopId l : m.loops_of(f))
      for (VertexId v : m.loop_vertices(l)) key.push_back(v.value);
    std::sort(key.begin(), key.end());
    keys.push_back({std::move(key), f});
  }
  std::sort(keys.begin(), keys.end());
  for (std::size_t i = 1; i < keys.size(); ++i)
    if (keys[i].first == keys[i - 1].first)
      d.duplicate_faces.push_back({keys[i - 1].second, keys[i].second});
  if (options.geometry) {
    stage("geometry");
    GeometryFindings g = check_geometry(m);
    d.self_crossing_faces = std::move(g.crossing_faces);
    d.non_planar_faces = std::move(g.non_planar_faces);
    for (const auto* list : {&g.crossings, &g.non_planar})
      for (std::size_t i = 0; i < list->size() && i < 10; ++i)
        d.geometry_findings.push_back((*list)[i].check + ": " + (*list)[i].message);
    d.geometry_checked = true;
  }
  if (options.self_intersections) {
    stage("self-intersections");
    d.self_intersections = self_intersections(m);
    d.self_intersections_checked = true;
  }
  d.closed = d.faces > 0 && d.boundary_edges.empty();
  d.manifold = d.non_manifold_edges.empty() && d.non_manifold_vertices.empty() &&
               d.wire_edges == 0 && d.isolated_vertices == 0;
  stage("mass properties");
  d.mass = shape::mass_properties(m);
  d.volume = d.mass.volume;
  if (!d.mass.solid && d.faces > 0) {
    d.volume = surface_volume(m);
    d.warnings.push_back(std::string("no face bounds a cell (") +
                         (d.closed ? "the surface is closed but bounds no solid"
                                   : "the surface is open: " +
                                         std::to_string(d.boundary_edges.size()) +
                                         " boundary edges") +
                         "): volume is the signed volume of the faces as they are oriented");
  }
  shells_without_cells(m, d.warnings);
  return d;
}

std::string to_text(const Diagnosis& d) {
  std::string s;
  const auto line = [&](const std::string& k, const std::string& v) { s += k + ": " + v + "\n"; };
  line("vertices", std::to_string(d.vertices));
  line("edges", std::to_string(d.edges));
  line("faces", std::to_string(d.faces));
  line("loops", std::to_string(d.loops));
  line("volumes", std::to_string(d.volumes));
  line("groups", std::to_string(d.groups));
  line("euler_characteristic_surface", std::to_string(d.euler_characteristic_surface));
  line("euler_characteristic_solid", std::to_string(d.euler_characteristic_solid));
  line("valid", d.valid ? "yes" : "no");
  for (const auto& v : d.violations) line("  violation", v);
  line("closed", d.closed ? "yes" : "no");
  line("manifold", d.manifold ? "yes" : "no");
  line("boundary_edges", list_text(d.boundary_edges));
  line("non_manifold_edges", list_text(d.non_manifold_edges));
  line("non_manifold_vertices", list_text(d.non_manifold_vertices));
  line("inconsistent_edges", list_text(d.inconsistent_edges));
  line("degenerate_faces", list_text(d.degenerate_faces));
  line("duplicate_faces", list_text(d.duplicate_faces));
  line("self_intersections",
       d.self_intersections_checked ? list_text(d.self_intersections) : "not checked");
  line("self_crossing_faces", d.geometry_checked ? list_text(d.self_crossing_faces) : "not checked");
  line("non_planar_faces", d.geometry_checked ? list_text(d.non_planar_faces) : "not checked");
  for (const auto& g : d.geometry_findings) line("  finding", g);
  line("wire_edges", std::to_string(d.wire_edges));
  line("isolated_vertices", std::to_string(d.isolated_vertices));
  for (const auto& w : d.warnings) line("warning", w);
  line("volume", num(d.volume));
  line("area", num(d.mass.area));
  const auto v = [](Vec3 p) { return num(p.x) + " " + num(p.y) + " " + num(p.z); };
  line("centroid", v(d.mass.centroid));
  line("bbox", v(d.mass.bbox_min) + " .. " + v(d.mass.bbox_max));
  return s;
}

std::string to_json(const Diagnosis& d) {
  std::string s = "{\n";
  const auto field = [&](const char* k, const std::string& v) {
    s += (s.size() > 2 ? ",\n  \"" : "  \"") + std::string(k) + "\": " + v;
  };
  field("vertices", std::to_string(d.vertices));
  field("edges", std::to_string(d.edges));
  field("faces", std::to_string(d.faces));
  field("loops", std::to_string(d.loops));
  field("volumes", std::to_string(d.volumes));
  field("groups", std::to_string(d.groups));
  field("euler_characteristic_surface", std::to_string(d.euler_characteristic_surface));
  field("euler_characteristic_solid", std::to_string(d.euler_characteristic_solid));
  field("valid", d.valid ? "true" : "false");
  field("closed", d.closed ? "true" : "false");
  field("manifold", d.manifold ? "true" : "false");
  field("volume", num(d.volume));
  field("area", num(d.mass.area));
  field("centroid", vec_json(d.mass.centroid));
  field("bbox",
        "{\"min\": " + vec_json(d.mass.bbox_min) + ", \"max\": " + vec_json(d.mass.bbox_max) + "}");
  field("boundary_edges", std::to_string(d.boundary_edges.size()));
  field("wire_edges", std::to_string(d.wire_edges));
  field("isolated_vertices", std::to_string(d.isolated_vertices));
  put_ids(s, "non_manifold_edges", d.non_manifold_edges);
  put_ids(s, "non_manifold_vertices", d.non_manifold_vertices);
  put_ids(s, "inconsistent_edges", d.inconsistent_edges);
  put_ids(s, "degenerate_faces", d.degenerate_faces);
  put_ids(s, "duplicate_faces", d.duplicate_faces);
  if (d.self_intersections_checked)
    put_ids(s, "self_intersections", d.self_intersections);
  else
    field("self_intersections", "null");
  if (d.geometry_checked) {
    put_ids(s, "self_crossing_faces", d.self_crossing_faces);
    put_ids(s, "non_planar_faces", d.non_planar_faces);
  } else {
    field("self_crossing_faces", "null");
    field("non_planar_faces", "null");
  }
  const auto strings = [](const std::vector<std::string>& list) {
    std::string v = "[";
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (i) v += ", ";
      v += '"';
      for (char c : list[i]) {
        if (c == '"' || c == '\\') v += '\\';
        if (static_cast<unsigned char>(c) >= 0x20) v += c;
      }
      v += '"';
    }
    return v + "]";
  };
  field("violations", strings(d.violations));
  field("warnings", strings(d.warnings));
  field("geometry_findings", strings(d.geometry_findings));
  return s + "\n}\n";
}

}  // namespace cellforge::io
