// The format modules behind mesh_io.h: one parser and one writer per format
// (stl.cpp, obj.cpp, off.cpp, threemf.cpp, json.cpp), and the triangle mesh that
// the mesh writers share (export.cpp).
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "cellforge/io/mesh_io.h"

namespace cellforge::io {

// A model's faces as triangles over its live vertices (export.cpp). `positions`
// are the model's vertices used by faces (or, with all_vertices, every vertex) in
// id order; `face_of` names the face each triangle came from.
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<VertexId> vertex;  // per position
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<FaceId> face_of;       // per triangle
  std::vector<std::uint32_t> index;  // per vertex slot: position index or ~0
};
TriangleMesh triangle_mesh(const Model& m, bool all_vertices = false);
// Unit normal of a triangle (zero for a degenerate one).
Vec3 triangle_normal(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t);

// stl.cpp
Result<PolygonSoup> parse_stl(std::span<const std::uint8_t> bytes);
std::string write_stl(const TriangleMesh& mesh, bool binary, const std::string& name);
// obj.cpp
Result<PolygonSoup> parse_obj(std::string_view text);
Result<std::string> write_obj(const Model& m, const WriteOptions& options);
// off.cpp
Result<PolygonSoup> parse_off(std::string_view text);
Result<std::string> write_off(const Model& m, const WriteOptions& options);
// threemf.cpp
Result<std::vector<PolygonSoup>> parse_3mf(std::span<const std::uint8_t> bytes);
Result<std::string> write_3mf(
    const Model& m, const std::vector<std::optional<std::array<double, 4>>>& face_colors = {});
// zip_size.cpp: an error when the entries of the ZIP archive in `bytes` declare more
// than max_unpacked bytes in all (0: no limit), from its central directory alone.
// An archive whose directory cannot be read passes, for the ZIP reader to refuse.
Status check_zip_size(std::string_view format, std::span<const std::uint8_t> bytes,
                      std::uint64_t max_unpacked);
// json.cpp
Result<ReadResult> read_json(Model& m, std::string_view text);
std::string write_json(const Model& m, const std::vector<Attachment>& attachments);

// Per face, the polygon to write: loops as indices into mesh.positions when the
// face has a single loop and triangulation is not forced, else its triangles.
// Shared by the OBJ and OFF writers.
std::vector<std::vector<std::uint32_t>> export_polygons(const Model& m, const TriangleMesh& mesh,
                                                        bool triangulate);

}  // namespace cellforge::io
