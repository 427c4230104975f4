// What a mesh is: the report `cellforge info` prints. Counts, closedness, the
// non-manifold places named by id, orientation, degenerate and duplicate faces,
// self-intersections, and the mass properties (divergence theorem over the
// triangulated faces).
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "cellforge/shape/mass.h"
#include "cellforge/topo/model.h"

namespace cellforge::io {

// Volume, area, centroid and bounding box of the whole model (shape/mass.h).
using MassProperties = shape::MassProperties;

struct DiagnoseOptions {
  // Exact triangle-triangle tests between faces that share no vertex, found
  // through a grid over their bounding boxes.
  bool self_intersections = true;
};

struct Diagnosis {
  std::size_t vertices = 0, edges = 0, faces = 0, loops = 0, volumes = 0, groups = 0;
  long euler_characteristic = 0;        // v - e + (f - r) - (V - Vh + Vc) (validate.h)
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
  bool closed = false;    // faces present, no boundary edge
  bool manifold = false;  // no non-manifold edge or vertex, no wire edge or isolated vertex
  MassProperties mass;
};

Diagnosis diagnose(const Model& m, const DiagnoseOptions& options = {});

// The report as text (one "key: value" per line) and as a JSON object whose keys
// include vertices, edges, faces, loops, volumes, groups, euler_characteristic,
// valid, closed, manifold, volume, area, centroid, bbox.
std::string to_text(const Diagnosis& d);
std::string to_json(const Diagnosis& d);

}  // namespace cellforge::io
