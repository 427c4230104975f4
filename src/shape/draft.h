// Draft: a primitive or sweep on its way into the model — the MeshInput for
// build_mesh plus what build_mesh does not carry (analytic surfaces per face, the
// group's attributes). commit() builds it; on error the model is unchanged.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cellforge/shape/faceting.h"
#include "cellforge/shape/region.h"
#include "cellforge/result.h"
#include "cellforge/topo/builder.h"

namespace cellforge::shape {

using Loop = std::vector<std::uint32_t>;

struct Draft {
  MeshInput mesh;
  std::vector<Surface> surfaces;
  std::vector<int> face_surface;  // per face: index into surfaces, or -1
  std::vector<Attribute> attributes;

  // A draft of one closed cell (faces get back volume 0) or of a sheet.
  static Draft solid(std::string kind);
  static Draft sheet(std::string kind);

  std::uint32_t vertex(Vec3 p);
  int surface(Surface s);
  // A face with loops[0] outer (counterclockwise seen from outside), the rest inner.
  void face(std::vector<Loop> loops, int surface = -1);
  void face(Loop outer, int surface = -1) { face(std::vector<Loop>{std::move(outer)}, surface); }
  void wire(std::uint32_t a, std::uint32_t b) { mesh.wires.push_back({a, b}); }
  void attribute(std::string key, std::string value);
  void attribute(std::string key, double value);
  void attribute(std::string key, bool value);
  void attribute(std::string key, int value);
  // fn, fa, fs as given and the segment count they produced.
  void faceting(const Faceting& f, int segments);
};

Result<GroupId> commit(Model& m, const Draft& d);

// An invalid-input error.
inline Error invalid(std::string message) {
  return Error{ErrorCode::kInvalidInput, std::move(message)};
}

// The region checked by polygon() and oriented (outer counterclockwise, holes clockwise).
Result<Region> checked(const Region& region);

}  // namespace cellforge::shape
