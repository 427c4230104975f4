// What a mesh is: the report `cellforge info` prints. Counts, closedness, the
// non-manifold places named by id, orientation, degenerate and duplicate faces,
// self-intersections, and the mass properties (divergence theorem over the
// triangulated faces).
#pragma once

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "cellforge/shape/mass.h"
#include "cellforge/topo/model.h"

namespace cellforge::io {

// Volume, area, centroid and bounding box of the whole model (shape/mass.h).
using MassProperties = shape::MassProperties;

struct DiagnoseOptions {
  // Exact triangle-triangle tests between faces that share no vertex, found
  // through a bounding-volume hierarchy over their bounding boxes.
  bool self_intersections = true;
  // The faces' own geometry (topo/validate.h, check_geometry): loops that cross
  // themselves and faces whose vertices are not exactly on one plane.
  bool geometry = true;
  // Called as each stage begins ("validating", "geometry", "self-intersections",
  // "mass properties"), for a caller that shows progress; may be empty.
  std::function<void(std::string_view stage)> progress;
};

struct Diagnosis {
  std::size_t vertices = 0, edges = 0, faces = 0, loops = 0, volumes = 0, groups = 0;
  // The Euler characteristic of the surface, v - e + (f - r) (2 for a sphere, the value
  // mesh tools report), and of the cell complex with its 3-cells,
  // v - e + (f - r) - (V - Vh + Vc) (validate.h; 1 for a ball).
  long euler_characteristic_surface = 0;
  long euler_characteristic_solid = 0;
  bool valid = false;                   // validate() found nothing
  std::vector<std::string> violations;  // the first few, when not valid
  std::size_t wire_edges = 0, isolated_vertices = 0;
  std::vector<EdgeId> boundary_edges;      // edges with exactly one face use
  std::vector<EdgeId> non_manifold_edges;  // edges with three or more face uses
  // Vertices whose incident faces form two or more fans that meet only there
  // (vertices of non-manifold edges are not repeated here).
  std::vector<VertexId> non_manifold_vertices;
  std::vector<EdgeId> inconsistent_edges;                  // two uses running the same way
  std::vector<FaceId> degenerate_faces;                    // zero area (all vertices on one line)
  std::vector<std::pair<FaceId, FaceId>> duplicate_faces;  // same vertex set
  std::vector<std::pair<FaceId, FaceId>> self_intersections;
  bool self_intersections_checked = false;
  // check_geometry's findings, apart from validity (which is the structure's): the
  // faces with a loop that crosses or touches itself in its plane, and the faces
  // whose vertices do not lie exactly on one plane (a finding, not a fault: the
  // quads of faceted curved surfaces are planar only in exact arithmetic). The
  // first few findings in words, naming the vertices.
  std::vector<FaceId> self_crossing_faces;
  std::vector<FaceId> non_planar_faces;
  std::vector<std::string> geometry_findings;
  bool geometry_checked = false;
  bool closed = false;    // faces present, no boundary edge
  bool manifold = false;  // no non-manifold edge or vertex, no wire edge or isolated vertex
  // mass.volume is the volume of the cells. Without cells (an open mesh, an inside-out
  // shell), `volume` is the signed volume of the surface as its faces are oriented
  // (each face's cone from the origin, as admesh and trimesh report it), and
  // a warning says so; with cells it is mass.volume.
  MassProperties mass;
  double volume = 0;
  // Closed shells that bound no cell, the volume of a surface that is not a solid.
  std::vector<std::string> warnings;
};

Diagnosis diagnose(const Model& m, const DiagnoseOptions& options = {});

// The report as text (one "key: value" per line) and as a JSON object whose keys
// include vertices, edges, faces, loops, volumes, groups, euler_characteristic_surface,
// euler_characteristic_solid, valid, closed, manifold, volume, area, centroid, bbox,
// warnings, self_crossing_faces, non_planar_faces and geometry_findings.
std::string to_text(const Diagnosis& d);
std::string to_json(const Diagnosis& d);

}  // namespace cellforge::io
