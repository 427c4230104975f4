// validate(model): every structural invariant of the cycle structure and the
// Euler-Poincare relations. Returns the violations found, each naming the check
// and the ids involved; an empty list means the model is valid.
//
// Checks (one per file in src/topo/validate_*.cpp):
//   records     every reference names a live entity of the right kind
//   vertex      each vertex cycle closes and lists exactly the edge ends at it
//   radial      each radial cycle closes, lists exactly the uses of its edge, and
//               is in angular order about the edge (exact predicates)
//   loop        each loop closes, consecutive uses join head to tail, every use
//               names the loop's face, and each face's loop list ends at it
//   orientation a manifold edge's two uses run in opposite directions when their
//               faces bound a common volume
//   volume      the face sides of each volume form closed shells
//   euler       per closed manifold shell v - e + f = 2(1 - h) + r with integer
//               h >= 0 (seed 003); over the model seed 001's extended formula
//               v - e + (f - r) - (V - Vh + Vc) = C - Ch + Cc
// check_geometry: the faces' own geometry, reported apart (see below).
#pragma once

#include <string>
#include <vector>

#include "cellforge/topo/model.h"

namespace cellforge::inline topo {

struct Violation {
  std::string check;    // "vertex", "radial", "loop", ...
  std::string message;  // names the entities (v3, e7, ...)
};

std::vector<Violation> validate(const Model& m);
std::string to_string(const std::vector<Violation>& violations);

// The Euler-Poincare figures of a model, as validate computes them.
struct EulerFigures {
  long v = 0, e = 0, f = 0, r = 0;                          // vertices, edges, faces, inner loops
  long volumes = 0, volume_holes = 0, volume_cavities = 0;  // V, Vh, Vc
  long components = 0, holes = 0, cavities = 0;             // C, Ch, Cc
  long shells = 0;                                          // face-connected shells
  long unchecked = 0;  // components whose right side was not compared (see validate_euler.cpp)
  long lhs() const { return v - e + (f - r) - (volumes - volume_holes + volume_cavities); }
  long rhs() const { return components - holes + cavities; }
};
EulerFigures euler_figures(const Model& m);

// What validate leaves to geometry (validate_geometry.cpp), in two lists because
// they weigh differently. crossings: loops of planar faces that cross or touch
// themselves in their plane (check "crossing"), an error in any model. non_planar:
// faces whose vertices do not lie exactly on one plane (check "planarity"), each
// naming a vertex off the plane of three others; the quads of a faceted curved
// primitive are planar in real numbers but seldom in doubles, so this is a finding
// (the Booleans split such faces), not a fault. Exact predicates decide both.
// crossing_faces and non_planar_faces name the face of each finding, in the same
// order (a face with two crossing loops is named twice).
struct GeometryFindings {
  std::vector<Violation> crossings;
  std::vector<Violation> non_planar;
  std::vector<FaceId> crossing_faces;
  std::vector<FaceId> non_planar_faces;
};
GeometryFindings check_geometry(const Model& m);

}  // namespace cellforge::inline topo
