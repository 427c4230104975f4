// A bounding-volume hierarchy over axis-aligned boxes: median splits on the longest
// axis, leaves of up to four boxes. Boxes of triangles with double vertices are
// exact, so the pairs and the ray candidates it reports are a superset of the ones
// that can meet; the exact tests come after. Building takes O(n log n); the tree is
// balanced whatever the boxes (equal boxes included), so a query descends O(log n)
// levels. Used by boolean/ (the arrangement's candidate pairs) and io/ (self-
// intersections, nesting of shells).
//
// Boxes may be put in groups whose members need not be paired with each other (the
// triangles of a surface known to be embedded): pairs() skips a pair of boxes of one
// group, and whole subtrees, or pairs of subtrees, that hold one group alone.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "cellforge/geom/vec.h"

namespace cellforge::inline geom {

struct Box {
  Vec3 lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
  void add(Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  void add(const Box& b) {
    add(b.lo);
    add(b.hi);
  }
  bool overlaps(const Box& b) const {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y &&
           lo.z <= b.hi.z && b.lo.z <= hi.z;
  }
};

class Bvh {
 public:
  Bvh() = default;
  // A box in no group: paired with every box it meets.
  static constexpr std::uint32_t kNoGroup = 0xffffffffu;

  explicit Bvh(std::vector<Box> boxes) : Bvh(std::move(boxes), {}) {}
  // groups[i] is box i's group or kNoGroup; empty: no groups.
  Bvh(std::vector<Box> boxes, std::vector<std::uint32_t> groups)
      : boxes_(std::move(boxes)), groups_(std::move(groups)) {
    // The split keys (twice the centres: lo + hi) travel with the box ids, so that the
    // partitions read them in order rather than through the ids.
    std::vector<Item> items(boxes_.size());
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      items[i] = {boxes_[i].lo + boxes_[i].hi, static_cast<std::uint32_t>(i)};
    nodes_.reserve(boxes_.size() + 1);  // leaves of 2 to 4 boxes: fewer nodes than boxes
    if (!items.empty()) build(0, static_cast<std::uint32_t>(items.size()), items);
    order_.resize(items.size());
    for (std::size_t k = 0; k < items.size(); ++k) order_[k] = items[k].id;
  }

  const Box& box(std::uint32_t i) const { return boxes_[i]; }

  // Calls f(i, j) once for every pair i < j of overlapping boxes not in one group.
  template <class F>
  void pairs(F&& f) const {
    if (!nodes_.empty()) self(0, f);
  }
  // pairs() cut into pieces for threads: about `at_least` pieces (fewer when the tree
  // is small), each a subtree or a pair of subtrees, in the order pairs() visits them,
  // so that pairs(piece, f) over the pieces in order calls f on the same pairs in the
  // same order as pairs(f).
  struct Piece {
    std::uint32_t a = 0, b = 0;
    bool self = true;
  };
  std::vector<Piece> pair_pieces(std::size_t at_least) const {
    std::vector<Piece> out;
    if (nodes_.empty()) return out;
    out.push_back({});
    for (bool grew = true; grew && out.size() < at_least;) {
      grew = false;
      std::vector<Piece> next;
      for (const Piece& p : out) {
        const Node& na = nodes_[p.a];
        const Node& nb = nodes_[p.b];
        if (p.self) {
          if (one_group(na, na)) {  // no pair below
            grew = true;
            continue;
          }
          if (na.leaf) {
            next.push_back(p);
            continue;
          }
          next.push_back({na.left, na.left, true});
          next.push_back({na.right, na.right, true});
          next.push_back({na.left, na.right, false});
        } else if (!na.box.overlaps(nb.box) || one_group(na, nb)) {
          // no pair below
        } else if (na.leaf && nb.leaf) {
          next.push_back(p);
          continue;
        } else if (split_a(na, nb)) {
          next.push_back({na.left, p.b, false});
          next.push_back({na.right, p.b, false});
        } else {
          next.push_back({p.a, nb.left, false});
          next.push_back({p.a, nb.right, false});
        }
        grew = true;
      }
      out = std::move(next);
    }
    return out;
  }
  template <class F>
  void pairs(const Piece& piece, F&& f) const {
    if (piece.self) {
      self(piece.a, f);
    } else {
      cross(piece.a, piece.b, f);
    }
  }
  // Calls f(i) for every box that `accept` lets through (accept tests a Box).
  template <class Accept, class F>
  void query(Accept&& accept, F&& f) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!accept(n.box)) continue;
      if (n.leaf) {
        for (std::uint32_t k = n.begin; k < n.end; ++k)
          if (accept(boxes_[order_[k]])) f(order_[k]);
      } else {
        stack[top++] = n.left;
        stack[top++] = n.right;
      }
    }
  }

 private:
  // A node's group: the one all its boxes are in, else kMixed (kNoGroup when all
  // are in none).
  static constexpr std::uint32_t kMixed = 0xfffffffeu;
  struct Node {
    Box box;
    std::uint32_t begin = 0, end = 0, left = 0, right = 0;
    std::uint32_t group = kNoGroup;
    bool leaf = true;
  };
  std::uint32_t group_of(std::uint32_t box) const { return groups_.empty() ? kNoGroup : groups_[box]; }
  // Whether no pair below nodes a and b (a == b: below a) is to be reported.
  static bool one_group(const Node& a, const Node& b) {
    return a.group == b.group && a.group != kNoGroup && a.group != kMixed;
  }

  struct Item {
    Vec3 twice_centre;
    std::uint32_t id;
  };
  std::uint32_t build(std::uint32_t begin, std::uint32_t end, std::vector<Item>& items) {
    const auto id = static_cast<std::uint32_t>(nodes_.size());
    nodes_.push_back({});
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    if (end - begin <= 4) {
      Box box;
      std::uint32_t group = group_of(items[begin].id);
      for (std::uint32_t k = begin; k < end; ++k) {
        box.add(boxes_[items[k].id]);
        if (group_of(items[k].id) != group) group = kMixed;
      }
      nodes_[id].box = box;
      nodes_[id].group = group;
      return id;
    }
    // Split at the median centre along the axis the centres spread most on (twice the
    // centres: the same order, one addition less). A node's box is its children's.
    Box centres;
    for (std::uint32_t k = begin; k < end; ++k) centres.add(items[k].twice_centre);
    const Vec3 ext = centres.hi - centres.lo;
    const int axis = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    const std::uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                     [axis](const Item& a, const Item& b) { return a.twice_centre[axis] < b.twice_centre[axis]; });
    const std::uint32_t left = build(begin, mid, items);
    const std::uint32_t right = build(mid, end, items);
    Box box = nodes_[left].box;
    box.add(nodes_[right].box);
    nodes_[id].box = box;
    nodes_[id].group = nodes_[left].group == nodes_[right].group ? nodes_[left].group : kMixed;
    nodes_[id].leaf = false;
    nodes_[id].left = left;
    nodes_[id].right = right;
    return id;
  }

  template <class F>
  void self(std::uint32_t a, F& f) const {
    const Node& n = nodes_[a];
    if (one_group(n, n)) return;
    if (n.leaf) {
      for (std::uint32_t i = n.begin; i < n.end; ++i)
        for (std::uint32_t j = i + 1; j < n.end; ++j) emit(order_[i], order_[j], f);
      return;
    }
    self(n.left, f);
    self(n.right, f);
    cross(n.left, n.right, f);
  }
  template <class F>
  void cross(std::uint32_t a, std::uint32_t b, F& f) const {
    const Node& na = nodes_[a];
    const Node& nb = nodes_[b];
    if (!na.box.overlaps(nb.box) || one_group(na, nb)) return;
    if (na.leaf && nb.leaf) {
      for (std::uint32_t i = na.begin; i < na.end; ++i)
        for (std::uint32_t j = nb.begin; j < nb.end; ++j) emit(order_[i], order_[j], f);
    } else if (split_a(na, nb)) {
      cross(na.left, b, f);
      cross(na.right, b, f);
    } else {
      cross(a, nb.left, f);
      cross(a, nb.right, f);
    }
  }
  // Which of two overlapping nodes, not both leaves, a traversal descends into: the
  // larger (a when equal), never a leaf.
  static bool split_a(const Node& na, const Node& nb) {
    return nb.leaf || (!na.leaf && na.end - na.begin >= nb.end - nb.begin);
  }
  template <class F>
  void emit(std::uint32_t i, std::uint32_t j, F& f) const {
    if (!groups_.empty() && groups_[i] == groups_[j] && groups_[i] != kNoGroup) return;
    if (boxes_[i].overlaps(boxes_[j])) f(std::min(i, j), std::max(i, j));
  }

  std::vector<Box> boxes_;
  std::vector<std::uint32_t> groups_;
  std::vector<std::uint32_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace cellforge::inline geom
