// The CSG tree (seed 000's CSG expression above the B-rep): what a script evaluates
// to, and what build() turns into a Model, bottom up.
//
// Nodes are primitives (3D: cube, sphere, cylinder, polyhedron, import; 2D: square,
// circle, polygon), an affine transform (multmatrix: translate, rotate, scale, mirror,
// multmatrix all become one), resize, color, the set operations (group — an implicit
// union, as a module's children or a for loop — union, difference, intersection),
// the sweeps (linear_extrude, rotate_extrude), and hull, minkowski, offset and
// projection. A node keeps the place in the script that made it.
//
// build() flattens each run of set operations, with the transforms and colors between
// them pushed down to the leaves, into one n-ary Boolean (boolean::evaluate): a tree
// of 100 unions and differences is one arrangement, not 100. Colors are kept per
// face: every result face knows its operand, and so the color of the leaf it came
// from. The modifiers: '*' removes a subtree (the evaluator drops it), '!' makes it
// the root (the evaluator too), '%' (background) leaves it out of the result, '#'
// (highlight) keeps it.
//
// Anything not supported yet is an error naming the node and its place, never
// different geometry.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "cellforge/csg/source.h"
#include "cellforge/result.h"
#include "cellforge/shape/faceting.h"
#include "cellforge/shape/sweep.h"
#include "cellforge/shape/transform.h"
#include "cellforge/topo/model.h"

namespace cellforge::csg {

enum class NodeKind {
  kGroup,
  kUnion,
  kDifference,
  kIntersection,
  kCube,
  kSphere,
  kCylinder,
  kPolyhedron,
  kImport,
  kSquare,
  kCircle,
  kPolygon,
  kMultmatrix,
  kResize,
  kColor,
  kLinearExtrude,
  kRotateExtrude,
  kHull,
  kMinkowski,
  kOffset,
  kProjection,
};

// The name a node kind has in OpenSCAD and in the JSON form ("cube", "multmatrix"...).
const char* node_name(NodeKind k);
std::optional<NodeKind> node_kind(const std::string& name);

struct Node;
using NodePtr = std::shared_ptr<const Node>;

struct Node {
  NodeKind kind = NodeKind::kGroup;
  SourcePos pos;            // where the script made it (line 0 when it came from JSON)
  bool background = false;  // '%': built for display only, left out of the result
  bool highlight = false;   // '#'

  // cube: size, center. sphere: r. cylinder: h, r1, r2, center. square: size (x, y),
  // center. circle: r. The curved ones: faceting ($fn, $fa, $fs).
  Vec3 size{1, 1, 1};
  bool center = false;
  double r = 1, r1 = 1, r2 = 1, h = 1;
  shape::Faceting faceting;

  // polyhedron: points and faces (OpenSCAD's clockwise order seen from outside).
  // polygon: points (z = 0) and paths (empty: one path through all the points).
  std::vector<Vec3> points;
  std::vector<std::vector<std::uint32_t>> faces;

  shape::Transform matrix;          // multmatrix
  std::array<bool, 3> auto_size{};  // resize: size is the new size; 0 keeps the axis
                                    // (or scales it with the others where auto is set)
  std::array<double, 4> color{0.976, 0.843, 0.173, 1};  // color: r, g, b, alpha in [0, 1]

  shape::LinearExtrudeOptions linear;  // linear_extrude (faceting: the $fn... in scope)
  shape::RotateExtrudeOptions rotate;  // rotate_extrude

  // offset: r (round) or delta (with chamfer); projection: cut.
  double delta = 0;
  bool round = false;  // offset(r = ...) rather than offset(delta = ...)
  bool chamfer = false;
  bool cut = false;

  // import: the file (resolved against the script's folder); for DXF also the layer
  // ("" : every layer), origin and scale (points read as (p - origin) * scale), and
  // the faceting of its circles and arcs.
  std::string path;
  std::string layer;
  Vec3 origin{0, 0, 0};
  double import_scale = 1;

  std::vector<NodePtr> children;
};

struct BuildOptions {
  // For messages with the source line and caret (the script's files); may be null.
  const Sources* sources = nullptr;
  // The folder of the on-disk cache of subtree results; empty: no cache.
  std::string cache_dir;
  // Called as the top-level parts are built: (parts done, parts in all).
  std::function<void(std::size_t, std::size_t)> progress;
  // Threads for each Boolean's stages (boolean::Options::threads; 0: every hardware
  // thread). The result is the same at any count, bit for bit.
  int threads = 1;
};

// One 3D Boolean of a build: its size, what its stages met, and their seconds
// (boolean::Report).
struct BooleanStats {
  std::size_t operands = 0, triangles = 0, candidate_pairs = 0, cutting_pairs = 0;
  std::size_t pieces = 0, rays = 0, points = 0;
  double soup = 0, intersect = 0, split = 0, classify = 0, output = 0, check = 0, total = 0;
};

struct BuildStats {
  std::size_t leaves = 0;    // primitives and other leaf nodes built
  std::size_t booleans = 0;  // n-ary Boolean evaluations
  std::size_t boolean_operands = 0;
  // Booleans evaluated in the frame of a subtree turned off the axes that holds most of
  // their faces, the others moved there and the result moved back (docs/csg.md).
  std::size_t booleans_in_frame = 0;
  // Unions (of the top-level parts, or in the tree) whose parts fall into clusters
  // that do not meet, put side by side with a Boolean for each cluster only
  // (docs/csg.md).
  std::size_t parts_apart = 0;
  std::size_t cache_hits = 0, cache_misses = 0;
  // Leaves and whole subtrees met again within the build, taken from the first time.
  std::size_t memo_hits = 0;
  double leaf_seconds = 0, boolean_seconds = 0;
  // Each 3D Boolean, the most triangles first (parts built at once finish in any
  // order; this one does not depend on it).
  std::vector<BooleanStats> boolean_list;
};

struct BuildOutput {
  Model model;
  int dimension = 3;  // 2: the result is 2D (sheet faces in z = 0); 0: empty
  // By result FaceId value: the color of the leaf the face came from, when set.
  std::vector<std::optional<std::array<double, 4>>> face_colors;
  BuildStats stats;
};

Result<BuildOutput> build(const Node& root, const BuildOptions& options = {});

// A stable digest of a subtree's content (kinds, parameters, children; not the
// source positions) and of the bytes of every file its import() nodes read: the
// cache key, so that editing an imported file rebuilds the parts that import it.
// Each node's digest is that of its own fields' JSON followed by its children's
// digests (and an import's file digest), so equal subtrees have equal keys.
std::string content_key(const Node& node);

// content_key for the subtrees of one tree, which must outlive it: the digests of
// all the tree's nodes are made at once, each node's own fields written once (a build
// asks for a part, its core and its leaves: the points of a surface() were written
// five times, 7 % of example010.scad's build), and kept by address. A node outside
// the tree (one a builder makes for a question) is digested when asked, its
// descendants in the tree found. Safe to call from several threads (nothing changes
// after the constructor).
class ContentKeys {
 public:
  ContentKeys() = default;
  explicit ContentKeys(const Node& root);
  std::string operator()(const Node& node) const;

 private:
  struct Digest {
    std::uint64_t hash = 0;
    std::size_t length = 0;
  };
  // Found in memo_, or made (and put in *keep when given).
  Digest digest(const Node& node, std::unordered_map<const Node*, Digest>* keep) const;

  std::unordered_map<const Node*, Digest> memo_;
};

}  // namespace cellforge::csg
