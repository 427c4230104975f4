// A bounding-volume hierarchy over axis-aligned boxes: the boxes in the order of their
// centres along a Morton (Z-order) curve, each node the halves of its run, leaves of
// up to eight boxes (half the nodes that leaves of four take, at the same speed: a
// leaf's float boxes are tested in a row). The pairs and the ray candidates it
// reports are a superset of the ones that can meet; the exact tests come after.
// Building takes a radix sort and one pass over the nodes (a median split on the
// longest axis at every node took three times as long, 0.36 s for two spheres of 10^6
// triangles against 0.12–0.14, for nodes a little tighter); the tree is balanced
// whatever the boxes (equal boxes included), so a query descends O(log n) levels.
// Used by boolean/ (the arrangement's candidate pairs) and io/ (self-intersections,
// nesting of shells).
//
// Boxes may be put in groups whose members need not be paired with each other (the
// triangles of a surface known to be embedded): pairs() skips a pair of boxes of one
// group, and whole subtrees, or pairs of subtrees, that hold one group alone.
//
// Boxes are kept as floats rounded outward (24 bytes, not 48; nodes of 40 bytes, not
// 72): a box may meet one that doubles would have kept apart, never the reverse, so
// what is reported is a superset still, by at most a float's unit in the last place
// of the coordinates (2^-24 of them; a model whose features are smaller than that
// beside its distance from the origin gets more candidates, never fewer).
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "cellforge/geom/memory.h"
#include "cellforge/geom/vec.h"
#include "cellforge/geom/workers.h"

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

// A box in floats, rounded outward from a Box (Bvh's storage).
struct FloatBox {
  std::array<float, 3> lo, hi;  // unset until made (around): arrays of them are filled in place
  // The float next below (above) f, f finite or infinite: one step of its bits.
  static float below(float f) {
    if (f == 0) return -std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? bits - 1 : bits + 1);
  }
  static float above(float f) {
    if (f == 0) return std::numeric_limits<float>::denorm_min();
    const auto bits = std::bit_cast<std::uint32_t>(f);
    return std::bit_cast<float>(f > 0 ? bits + 1 : bits - 1);
  }
  static FloatBox around(const Box& b) {
    FloatBox f;
    const double l[3] = {b.lo.x, b.lo.y, b.lo.z}, h[3] = {b.hi.x, b.hi.y, b.hi.z};
    for (int k = 0; k < 3; ++k) {
      f.lo[k] = static_cast<float>(l[k]);
      if (static_cast<double>(f.lo[k]) > l[k]) f.lo[k] = below(f.lo[k]);
      f.hi[k] = static_cast<float>(h[k]);
      if (static_cast<double>(f.hi[k]) < h[k]) f.hi[k] = above(f.hi[k]);
    }
    return f;
  }
  Box box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  bool overlaps(const Box& b) const {
    return lo[0] <= b.hi.x && b.lo.x <= hi[0] && lo[1] <= b.hi.y && b.lo.y <= hi[1] && lo[2] <= b.hi.z &&
           b.lo.z <= hi[2];
  }
  bool overlaps(const FloatBox& o) const {
    return lo[0] <= o.hi[0] && o.lo[0] <= hi[0] && lo[1] <= o.hi[1] && o.lo[1] <= hi[1] && lo[2] <= o.hi[2] &&
           o.lo[2] <= hi[2];
  }
  void add(const FloatBox& o) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], o.lo[k]);
      hi[k] = std::max(hi[k], o.hi[k]);
    }
  }
};

class Bvh {
 public:
  Bvh() = default;
  // A box in no group: paired with every box it meets.
  static constexpr std::uint32_t kNoGroup = 0xffffffffu;

  explicit Bvh(std::vector<Box> boxes) : Bvh(std::move(boxes), {}) {}
  // groups[i] is box i's group or kNoGroup; empty: no groups.
  Bvh(const std::vector<Box>& boxes, const std::vector<std::uint32_t>& groups, int threads = 1)
      : Bvh(rounded(boxes), RawVector<std::uint32_t>(groups.begin(), groups.end()), threads) {}
  // The boxes rounded already (FloatBox::around), built on up to `threads` threads
  // (the tree the same at any count: its two halves are built apart below the top).
  // RawVectors, so that a caller fills them on its threads without zeroing them first.
  Bvh(RawVector<FloatBox> boxes, RawVector<std::uint32_t> groups, int threads = 1)
      : boxes_(std::move(boxes)), groups_(std::move(groups)) {
    morton_order(threads);
    nodes_.resize(node_count(static_cast<std::uint32_t>(boxes_.size())));
    if (!boxes_.empty()) build(0, 0, static_cast<std::uint32_t>(boxes_.size()), threads);
  }

  // Box i as kept: holding the box given, within a float's unit in the last place.
  Box box(std::uint32_t i) const { return boxes_[i].box(); }
  // The box around all of them (empty when there are none).
  Box bounds() const { return nodes_.empty() ? Box{} : nodes_[0].box.box(); }

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
          if (na.leaf()) {
            next.push_back(p);
            continue;
          }
          next.push_back({p.a + 1, p.a + 1, true});
          next.push_back({na.right, na.right, true});
          next.push_back({p.a + 1, na.right, false});
        } else if (!na.overlaps(nb) || one_group(na, nb)) {
          // no pair below
        } else if (na.leaf() && nb.leaf()) {
          next.push_back(p);
          continue;
        } else if (split_a(na, nb)) {
          next.push_back({p.a + 1, p.b, false});
          next.push_back({na.right, p.b, false});
        } else {
          next.push_back({p.a, p.b + 1, false});
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
  // Calls f(i) for every box that `accept` lets through (accept tests a Box, or,
  // when it takes one, the FloatBox as kept: no conversion a node).
  template <class Accept, class F>
  void query(Accept&& accept, F&& f) const {
    if constexpr (std::is_invocable_v<Accept&, const FloatBox&>) {
      query_kept(accept, f);
    } else {
      query_kept([&](const FloatBox& b) { return accept(b.box()); }, f);
    }
  }

 private:
  template <class Accept, class F>
  void query_kept(Accept&& accept, F&& f) const {
    if (nodes_.empty()) return;
    std::uint32_t stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const std::uint32_t id = stack[--top];
      const Node& n = nodes_[id];
      if (!accept(n.box)) continue;
      if (n.leaf()) {
        for (std::uint32_t k = n.begin; k < n.end; ++k)
          if (accept(boxes_[order_[k]])) f(order_[k]);
      } else {
        stack[top++] = id + 1;
        stack[top++] = n.right;
      }
    }
  }

  // A node's group: the one all its boxes are in, else kMixed (kNoGroup when all
  // are in none).
  static constexpr std::uint32_t kMixed = 0xfffffffeu;
  // Nodes in preorder: an inner node's left child is the next node.
  // Every field is set by build() (the nodes are made unset: RawVector).
  struct Node {
    FloatBox box;              // its boxes' box
    std::uint32_t begin, end;  // its boxes: order_[begin] .. order_[end - 1]
    std::uint32_t right;       // the right child; 0 for a leaf
    std::uint32_t group;
    bool leaf() const { return right == 0; }
    bool overlaps(const Node& o) const { return box.overlaps(o.box); }
  };
  // The nodes build() makes for n boxes.
  static std::size_t node_count(std::uint32_t n) {
    if (n == 0) return 0;
    if (n <= 8) return 1;
    return 1 + node_count(n / 2) + node_count(n - n / 2);
  }
  std::uint32_t group_of(std::uint32_t box) const { return groups_.empty() ? kNoGroup : groups_[box]; }
  // Whether no pair below nodes a and b (a == b: below a) is to be reported.
  static bool one_group(const Node& a, const Node& b) {
    return a.group == b.group && a.group != kNoGroup && a.group != kMixed;
  }

  static RawVector<FloatBox> rounded(const std::vector<Box>& boxes) {
    RawVector<FloatBox> out(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) out[i] = FloatBox::around(boxes[i]);
    return out;
  }
  // work(k) for k in [0, count), on the worker threads (workers.h).
  template <class Work>
  static void on_threads(int count, Work&& work) {
    run_on_workers(static_cast<std::size_t>(count), [&](std::size_t k) { work(static_cast<int>(k)); });
  }
  // order_: the boxes by the Morton code of their centres, ties in index order.
  void morton_order(int threads) {
    const std::size_t n = boxes_.size();
    order_.resize(n);
    // threads: the count, not 0 for all (the callers resolve it).
    const int slices = n >= (1u << 16) ? std::max(1, threads) : 1;
    on_threads(slices, [&](int s) {
      for (std::size_t i = n * s / slices; i < n * (s + 1) / slices; ++i) order_[i] = static_cast<std::uint32_t>(i);
    });
    if (order_.size() > 1) sort_by_morton(0, static_cast<std::uint32_t>(order_.size()), 0, threads);
  }
  // order_[begin, end) (its ids ascending) by the Morton code of the centres, ten bits
  // an axis over these boxes' own bounds, ties by id: three stable counting passes of
  // ten bits, or a sort of the keys when the run is short. Then each run of more than
  // a leaf's boxes in one cell is ordered again over its own bounds, up to four times
  // deep, so that a box far from the rest cannot crowd them all into one cell (which
  // would leave them in index order, and the tree's nodes as wide as the model).
  // Only the tree's shape depends on it, never what the tree reports. A long run is
  // sorted on `threads` threads, each taking a slice of the keys: in a counting pass
  // each slice's keys of a digit go after those of the slices before it, so the order
  // is the one thread's, whatever the count.
  void sort_by_morton(std::uint32_t begin, std::uint32_t end, int depth, int threads = 1) {
    const std::size_t n = end - begin;
    const int slices = n >= (1u << 16) ? std::max(1, threads) : 1;
    auto slice = [&](int k) { return std::pair<std::size_t, std::size_t>{n * k / slices, n * (k + 1) / slices}; };
    // The centres' bounds (twice the centres: no halving), slice by slice.
    std::vector<std::array<float, 6>> bounds(slices);
    on_threads(slices, [&](int s) {
      std::array<float, 6>& b = bounds[s];
      for (int d = 0; d < 3; ++d) {
        b[d] = std::numeric_limits<float>::infinity();
        b[3 + d] = -b[d];
      }
      const auto [lo_i, hi_i] = slice(s);
      for (std::size_t k = lo_i; k < hi_i; ++k)
        for (int d = 0; d < 3; ++d) {
          const FloatBox& x = boxes_[order_[begin + k]];
          const float c = x.lo[d] + x.hi[d];
          b[d] = std::min(b[d], c);
          b[3 + d] = std::max(b[3 + d], c);
        }
    });
    std::array<float, 3> lo = {bounds[0][0], bounds[0][1], bounds[0][2]};
    std::array<float, 3> hi = {bounds[0][3], bounds[0][4], bounds[0][5]};
    for (const auto& b : bounds)
      for (int d = 0; d < 3; ++d) {
        lo[d] = std::min(lo[d], b[d]);
        hi[d] = std::max(hi[d], b[3 + d]);
      }
    std::array<double, 3> scale{};
    bool spread_out = false;
    for (int d = 0; d < 3; ++d) {
      const double extent = static_cast<double>(hi[d]) - lo[d];
      scale[d] = extent > 0 && std::isfinite(extent) ? 1023.0 / extent : 0.0;
      spread_out |= scale[d] != 0;
    }
    if (!spread_out) return;  // every centre at one point (or none finite): as they are
    // Bits 0..9 of x spread to every third bit.
    const auto spread = [](std::uint32_t x) {
      x = (x | (x << 16)) & 0x030000ffu;
      x = (x | (x << 8)) & 0x0300f00fu;
      x = (x | (x << 4)) & 0x030c30c3u;
      x = (x | (x << 2)) & 0x09249249u;
      return x;
    };
    RawVector<std::uint64_t> keys(n);  // code << 32 | id
    on_threads(slices, [&](int s) {
      const auto [lo_i, hi_i] = slice(s);
      for (std::size_t i = lo_i; i < hi_i; ++i) {
        const std::uint32_t id = order_[begin + i];
        std::uint32_t code = 0;
        for (int d = 0; d < 3; ++d) {
          const double c = static_cast<double>(boxes_[id].lo[d] + boxes_[id].hi[d]) - lo[d];
          const double q = std::clamp(c * scale[d], 0.0, 1023.0);  // NaN: not >= 0, cell 0
          code |= spread(q >= 0 ? static_cast<std::uint32_t>(q) : 0u) << d;
        }
        keys[i] = (static_cast<std::uint64_t>(code) << 32) | id;
      }
    });
    if (n <= 4096) {
      std::sort(keys.begin(), keys.end());  // the same order: ids are distinct
    } else {
      RawVector<std::uint64_t> other(n);
      std::vector<std::array<std::uint32_t, 1024>> count(slices);  // by slice, by digit
      for (int pass = 0; pass < 3; ++pass) {
        const int shift = 32 + 10 * pass;
        on_threads(slices, [&](int s) {
          count[s].fill(0);
          const auto [lo_i, hi_i] = slice(s);
          for (std::size_t i = lo_i; i < hi_i; ++i) ++count[s][(keys[i] >> shift) & 1023];
        });
        std::uint32_t sum = 0;
        for (int digit = 0; digit < 1024; ++digit)
          for (int s = 0; s < slices; ++s) sum += std::exchange(count[s][digit], sum);
        on_threads(slices, [&](int s) {
          const auto [lo_i, hi_i] = slice(s);
          for (std::size_t i = lo_i; i < hi_i; ++i) other[count[s][(keys[i] >> shift) & 1023]++] = keys[i];
        });
        keys.swap(other);
      }
    }
    on_threads(slices, [&](int s) {
      const auto [lo_i, hi_i] = slice(s);
      for (std::size_t i = lo_i; i < hi_i; ++i) order_[begin + i] = static_cast<std::uint32_t>(keys[i]);
    });
    if (depth >= 4) return;
    for (std::size_t i = 0; i < n;) {
      std::size_t j = i + 1;
      while (j < n && keys[j] >> 32 == keys[i] >> 32) ++j;
      if (j - i > 8)
        sort_by_morton(begin + static_cast<std::uint32_t>(i), begin + static_cast<std::uint32_t>(j), depth + 1);
      i = j;
    }
  }
  // Node `id` over order_[begin, end), its subtree in preorder from id; returns the id
  // after the subtree. The right subtree on a thread of its own while `threads` allows
  // (its first id then counted ahead; the same nodes either way). A node's box is its
  // children's.
  std::uint32_t build(std::uint32_t id, std::uint32_t begin, std::uint32_t end, int threads) {
    nodes_[id].begin = begin;
    nodes_[id].end = end;
    if (end - begin <= 8) {
      nodes_[id].right = 0;
      FloatBox box = boxes_[order_[begin]];
      std::uint32_t group = group_of(order_[begin]);
      for (std::uint32_t k = begin; k < end; ++k) {
        box.add(boxes_[order_[k]]);
        if (group_of(order_[k]) != group) group = kMixed;
      }
      nodes_[id].box = box;
      nodes_[id].group = group;
      return id + 1;
    }
    const std::uint32_t mid = begin + (end - begin) / 2;
    const std::uint32_t left = id + 1;
    std::uint32_t right = 0, after = 0;
    if (threads > 1 && end - begin >= (1u << 15)) {
      right = static_cast<std::uint32_t>(left + node_count(mid - begin));
      run_on_workers(2, [&](std::size_t k) {
        if (k == 0) {
          build(left, begin, mid, threads - threads / 2);
        } else {
          after = build(right, mid, end, threads / 2);
        }
      });
    } else {
      right = build(left, begin, mid, 1);
      after = build(right, mid, end, 1);
    }
    nodes_[id].box = nodes_[left].box;
    nodes_[id].box.add(nodes_[right].box);
    nodes_[id].group = nodes_[left].group == nodes_[right].group ? nodes_[left].group : kMixed;
    nodes_[id].right = right;
    return after;
  }

  template <class F>
  void self(std::uint32_t a, F& f) const {
    const Node& n = nodes_[a];
    if (one_group(n, n)) return;
    if (n.leaf()) {
      for (std::uint32_t i = n.begin; i < n.end; ++i)
        for (std::uint32_t j = i + 1; j < n.end; ++j) emit(order_[i], order_[j], f);
      return;
    }
    self(a + 1, f);
    self(n.right, f);
    cross(a + 1, n.right, f);
  }
  template <class F>
  void cross(std::uint32_t a, std::uint32_t b, F& f) const {
    const Node& na = nodes_[a];
    const Node& nb = nodes_[b];
    if (!na.overlaps(nb) || one_group(na, nb)) return;
    if (na.leaf() && nb.leaf()) {
      for (std::uint32_t i = na.begin; i < na.end; ++i)
        for (std::uint32_t j = nb.begin; j < nb.end; ++j) emit(order_[i], order_[j], f);
    } else if (split_a(na, nb)) {
      cross(a + 1, b, f);
      cross(na.right, b, f);
    } else {
      cross(a, b + 1, f);
      cross(a, nb.right, f);
    }
  }
  // Which of two overlapping nodes, not both leaves, a traversal descends into: the
  // larger (a when equal), never a leaf.
  static bool split_a(const Node& na, const Node& nb) {
    return nb.leaf() || (!na.leaf() && na.end - na.begin >= nb.end - nb.begin);
  }
  template <class F>
  void emit(std::uint32_t i, std::uint32_t j, F& f) const {
    if (!groups_.empty() && groups_[i] == groups_[j] && groups_[i] != kNoGroup) return;
    if (boxes_[i].overlaps(boxes_[j])) f(std::min(i, j), std::max(i, j));
  }

  RawVector<FloatBox> boxes_;
  RawVector<std::uint32_t> groups_;
  RawVector<std::uint32_t> order_;
  RawVector<Node> nodes_;
};

}  // namespace cellforge::inline geom
