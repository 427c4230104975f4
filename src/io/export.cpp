// The triangle mesh the mesh writers share: live vertices renumbered densely in id
// order, every face triangulated (triangulate.h).
#include "cellforge/io/triangulate.h"
#include "io/formats.h"

namespace cellforge::io {

TriangleMesh triangle_mesh(const Model& m, bool all_vertices) {
  TriangleMesh mesh;
  mesh.index.assign(m.vertex_slots(), kInvalidIndex);
  std::vector<bool> used(m.vertex_slots(), all_vertices);
  if (!all_vertices) {
    for (EdgeUseId u : m.edge_uses()) used[m.use_start(u).value] = true;
  }
  for (VertexId v : m.vertices()) {
    if (!used[v.value]) continue;
    mesh.index[v.value] = static_cast<std::uint32_t>(mesh.positions.size());
    mesh.positions.push_back(m.position(v));
    mesh.vertex.push_back(v);
  }
  mesh.triangles.reserve(m.num_faces());
  for (FaceId f : m.faces()) {
    for (const auto& t : triangulate_face(m, f)) {
      mesh.triangles.push_back(
          {mesh.index[t[0].value], mesh.index[t[1].value], mesh.index[t[2].value]});
      mesh.face_of.push_back(f);
    }
  }
  return mesh;
}

Vec3 triangle_normal(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
  return normalized(cross(b - a, c - a));
}

std::vector<std::vector<std::uint32_t>> export_polygons(const Model& m, const TriangleMesh& mesh,
                                                        bool triangulate) {
  std::vector<std::vector<std::uint32_t>> out;
  out.reserve(m.num_faces());
  std::size_t t = 0;  // triangles of mesh are in face order
  for (FaceId f : m.faces()) {
    std::size_t end = t;
    while (end < mesh.triangles.size() && mesh.face_of[end] == f) ++end;
    const LoopId outer = m.outer_loop(f);
    if (!triangulate && m.inner_loop_count(f) == 0 && !m.is_point_loop(outer)) {
      std::vector<std::uint32_t> poly;
      for (VertexId v : m.loop_vertices(outer)) poly.push_back(mesh.index[v.value]);
      out.push_back(std::move(poly));
    } else {
      for (std::size_t k = t; k < end; ++k)
        out.push_back({mesh.triangles[k][0], mesh.triangles[k][1], mesh.triangles[k][2]});
    }
    t = end;
  }
  return out;
}

}  // namespace cellforge::io
