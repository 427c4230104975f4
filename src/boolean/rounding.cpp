// Rounding with a check (stages.h): the result's implicit points rounded to doubles,
// then, where two faces' triangles have come to cross, the rounded vertices of the
// crossing triangles moved to a neighbouring double (one unit in the last place in
// any coordinate, else two; four, then eight, when a round could not do better) where
// that removes crossings.
//
// Rounding to nearest moves a point by half a unit; near-degenerate arrangements (a
// face corner a hair off the line of its neighbours, two faces meeting at a very
// small angle) turn over by less. Every candidate is a double within 8.5 units of the
// exact point (2.5 unless a round found no better place within two), so the result
// still rounds the exact one; only the choice among the doubles around it changes.
// Faces are triangulated as io::triangulate_face does it (the exporters' triangles),
// the test is exact (geom::triangles_meet), and the rounding check after building
// (boolean.cpp) counts what remains.
#include <algorithm>
#include <bit>
#include <cmath>
#include <numeric>
#include <unordered_map>

#include "boolean/parallel.h"
#include "boolean/stages.h"
#include "cellforge/geom/bvh.h"
#include "cellforge/geom/intersect.h"
#include "cellforge/geom/polygon.h"
#include "cellforge/io/triangulate.h"

namespace cellforge::boolean {

namespace {

using Tri3 = std::array<std::uint32_t, 3>;  // indices into MeshInput::positions

}  // namespace

std::vector<Tri3> tile_face(const MeshInput& in, const MeshFace& f) {
  std::vector<std::vector<Vec3>> loops;
  std::vector<std::uint32_t> ids;
  for (const auto& loop : f.loops) {
    std::vector<Vec3> pts;
    for (std::uint32_t i : loop) {
      pts.push_back(in.positions[i]);
      ids.push_back(i);
    }
    loops.push_back(std::move(pts));
  }
  std::vector<Tri3> out;
  for (const auto& t : io::triangulate_polygon(loops, newell_normal(loops[0])))
    out.push_back({ids[t[0]], ids[t[1]], ids[t[2]]});
  return out;
}

namespace {

Box box_of(const MeshInput& in, const Tri3& t) {
  Box b;
  for (std::uint32_t i : t) b.add(in.positions[i]);
  return b;
}

bool share_vertex(const Tri3& a, const Tri3& b) {
  for (std::uint32_t u : a)
    for (std::uint32_t v : b)
      if (u == v) return true;
  return false;
}

bool meet(const MeshInput& in, const Tri3& x, const Tri3& y) {
  const Vec3 a[3] = {in.positions[x[0]], in.positions[x[1]], in.positions[x[2]]};
  const Vec3 b[3] = {in.positions[y[0]], in.positions[y[1]], in.positions[y[2]]};
  return triangles_meet(a, b);
}

// Boxes grown by 64 units in the last place, so that the tree built before a vertex
// moves still finds what the moved triangles meet: a move reaches 16 units, which
// across a power of two are up to 32 of the finer spacing.
Box grown(Box b) {
  // 64 units in the last place of the larger magnitude: 2^(exponent - 52 + 6), made
  // from the exponent's bits (no libm call; a million boxes a check).
  const auto margin = [](double lo, double hi) {
    const double x = std::max({std::abs(lo), std::abs(hi), 1e-300});
    const std::uint64_t e = (std::bit_cast<std::uint64_t>(x) >> 52) & 0x7ff;  // biased
    return e > 46 ? std::bit_cast<double>((e - 46) << 52) : 64 * std::ldexp(1.0, static_cast<int>(e) - 1023 - 52);
  };
  const Vec3 m{margin(b.lo.x, b.hi.x), margin(b.lo.y, b.hi.y), margin(b.lo.z, b.hi.z)};
  b.lo = b.lo - m;
  b.hi = b.hi + m;
  return b;
}

}  // namespace

TriangleBoxes::TriangleBoxes(const std::vector<std::array<Vec3, 3>>& tris, int threads) {
  const auto extent = [](const Box& b) { return std::max({b.hi.x - b.lo.x, b.hi.y - b.lo.y, b.hi.z - b.lo.z}); };
  const auto box_of3 = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    Box x;
    x.add(a);
    x.add(b);
    x.add(c);
    return x;
  };
  // Typical: 4 times the median extent.
  std::vector<double> ext(tris.size());
  for (std::size_t i = 0; i < tris.size(); ++i) ext[i] = extent(box_of3(tris[i][0], tris[i][1], tris[i][2]));
  double limit = 0;
  if (!ext.empty()) {
    std::vector<double> sorted = ext;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    limit = 4 * sorted[sorted.size() / 2];
  }
  constexpr int kMaxPieces = 256;
  begin_.reserve(tris.size() + 1);
  std::vector<std::array<Vec3, 3>> stack;
  for (std::uint32_t i = 0; i < tris.size(); ++i) {
    begin_.push_back(static_cast<std::uint32_t>(boxes_.size()));
    if (!(ext[i] > limit)) {
      boxes_.push_back(grown(box_of3(tris[i][0], tris[i][1], tris[i][2])));
      owner_.push_back(i);
      continue;
    }
    stack.assign(1, tris[i]);
    int pieces = 1;
    while (!stack.empty()) {
      std::array<Vec3, 3> t = stack.back();
      stack.pop_back();
      const Box b = box_of3(t[0], t[1], t[2]);
      if (extent(b) <= limit || pieces >= kMaxPieces) {
        boxes_.push_back(grown(b));
        owner_.push_back(i);
        continue;
      }
      // Halve the longest edge.
      int e = 0;
      double longest = -1;
      for (int k = 0; k < 3; ++k) {
        const Vec3 d = t[(k + 1) % 3] - t[k];
        const double l = dot(d, d);
        if (l > longest) longest = l, e = k;
      }
      const Vec3 p = t[e], q = t[(e + 1) % 3], r = t[(e + 2) % 3], m = (p + q) * 0.5;
      stack.push_back({p, m, r});
      stack.push_back({m, q, r});
      ++pieces;
    }
  }
  begin_.push_back(static_cast<std::uint32_t>(boxes_.size()));
  bvh_ = Bvh(boxes_, owner_, threads);  // a triangle's pieces: one group
}

// stages.h.
std::vector<std::uint64_t> TriangleBoxes::pairs_with(const std::vector<char>& marked, int threads,
                                                     const Keep& keep) const {
  const std::size_t n = begin_.size() - 1;
  const std::size_t count = static_cast<std::size_t>(std::count(marked.begin(), marked.end(), 1));
  if (4 * count >= n)  // most of them: every pair at once
    return pairs(threads, [&](std::uint32_t i, std::uint32_t j) {
      return (marked[i] || marked[j]) && (!keep || keep(i, j));
    });
  // A few: the pairs around each (a pair of two marked ones once).
  const auto found = parallel_ranges<std::vector<std::uint64_t>>(
      n, threads, [&](std::size_t lo, std::size_t hi, std::vector<std::uint64_t>& out) {
        std::vector<std::uint32_t> scratch;
        for (auto i = static_cast<std::uint32_t>(lo); i < hi; ++i) {
          if (!marked[i]) continue;
          near(i, scratch, [&](std::uint32_t j) {
            if (j == i || (marked[j] && j < i) || (keep && !keep(std::min(i, j), std::max(i, j)))) return;
            out.push_back(static_cast<std::uint64_t>(std::min(i, j)) << 32 | std::max(i, j));
          });
        }
      });
  std::vector<std::uint64_t> all;
  for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
  std::sort(all.begin(), all.end());
  return all;
}

std::vector<std::uint64_t> TriangleBoxes::pairs(int threads, const Keep& keep) const {
  const std::vector<Bvh::Piece> pieces = bvh_.pair_pieces(64);
  const std::vector<std::vector<std::uint64_t>> found =
      parallel_jobs<std::vector<std::uint64_t>>(pieces.size(), threads, [&](std::size_t k, auto& out) {
        bvh_.pairs(pieces[k], [&](std::uint32_t x, std::uint32_t y) {
          const std::uint32_t i = std::min(owner_[x], owner_[y]), j = std::max(owner_[x], owner_[y]);
          if (keep && (i == j || !keep(i, j))) return;
          out.push_back(static_cast<std::uint64_t>(i) << 32 | j);
        });
        std::sort(out.begin(), out.end());
        out.erase(std::unique(out.begin(), out.end()), out.end());
      });
  std::vector<std::uint64_t> all;
  for (const auto& f : found) all.insert(all.end(), f.begin(), f.end());
  std::sort(all.begin(), all.end());
  all.erase(std::unique(all.begin(), all.end()), all.end());
  return all;
}

bool nudge_rounding(MeshInput& in, const std::vector<char>& inexact,
                    const std::function<bool(std::uint32_t, int)>& exact, int threads) {
  constexpr int kRounds = 6;
  int reach = 2;  // units in the last place a vertex may move
  // Only a triangle of a face with a rounded corner can have come to cross another
  // (the faces with all their corners exact meet as the exact arrangement does), and
  // only triangles near such a face can be what it crosses: the faces far from every
  // rounded one are neither tiled nor indexed. After the first round only the faces
  // around a vertex that moved are tiled again (a tiling depends on its face's
  // positions alone).
  const std::size_t nf = in.faces.size();
  std::vector<char> moved_face(nf, 0);
  parallel_ranges<char>(nf, threads, [&](std::size_t lo, std::size_t hi, char&) {
    for (std::size_t f = lo; f < hi; ++f)
      for (const auto& loop : in.faces[f].loops)
        for (std::uint32_t v : loop) moved_face[f] |= inexact[v];
  });
  std::vector<std::vector<Tri3>> tiles(nf);
  std::vector<char> tiled(nf, 0);
  auto tile = [&](const std::vector<std::uint32_t>& fs) {
    auto parts = parallel_ranges<std::vector<std::vector<Tri3>>>(
        fs.size(), threads, [&](std::size_t lo, std::size_t hi, auto& out) {
          for (std::size_t k = lo; k < hi; ++k) out.push_back(tile_face(in, in.faces[fs[k]]));
        });
    std::size_t k = 0;
    for (auto& p : parts)
      for (auto& t : p) {
        tiled[fs[k]] = 1;
        tiles[fs[k++]] = std::move(t);
      }
  };
  std::vector<std::uint32_t> retile;
  for (std::uint32_t f = 0; f < nf; ++f)
    if (moved_face[f]) retile.push_back(f);
  for (int round = 0; round < kRounds; ++round) {
    tile(retile);
    // The boxes of the moved faces' triangles; the other faces whose box meets one of
    // them are tiled, and their triangles meeting one are indexed with them.
    std::vector<Box> near_boxes;
    for (std::uint32_t f = 0; f < nf; ++f)
      if (moved_face[f])
        for (const Tri3& t : tiles[f]) near_boxes.push_back(grown(box_of(in, t)));
    if (near_boxes.empty()) return true;
    const Bvh near_moved(near_boxes);
    auto meets_moved = [&](const Box& b) {
      bool hit = false;
      near_moved.query([&](const auto& x) { return !hit && x.overlaps(b); }, [&](std::uint32_t) { hit = true; });
      return hit;
    };
    // Every face's box against the moved ones', on threads (the faces of a big result
    // are mostly far from all of them).
    const auto near_parts = parallel_ranges<std::vector<std::uint32_t>>(
        nf, threads, [&](std::size_t lo, std::size_t hi, std::vector<std::uint32_t>& out) {
          for (auto f = static_cast<std::uint32_t>(lo); f < hi; ++f) {
            if (moved_face[f] || tiled[f]) continue;
            Box b;
            for (const auto& loop : in.faces[f].loops)
              for (std::uint32_t v : loop) b.add(in.positions[v]);
            if (meets_moved(grown(b))) out.push_back(f);
          }
        });
    std::vector<std::uint32_t> near_faces;
    for (const auto& part : near_parts) near_faces.insert(near_faces.end(), part.begin(), part.end());
    tile(near_faces);
    // The crossing pairs among them.
    std::vector<Tri3> tris;
    std::vector<std::uint32_t> face;
    for (std::uint32_t f = 0; f < nf; ++f)
      for (const Tri3& t : tiles[f])
        if (moved_face[f] || meets_moved(grown(box_of(in, t)))) {
          tris.push_back(t);
          face.push_back(f);
        }
    std::vector<std::array<Vec3, 3>> corners(tris.size());
    std::vector<char> moved(tris.size(), 0);
    for (std::size_t i = 0; i < tris.size(); ++i) {
      for (int k = 0; k < 3; ++k) corners[i][k] = in.positions[tris[i][k]];
      for (std::uint32_t v : tris[i]) moved[i] |= inexact[v];
    }
    const TriangleBoxes index(corners, thread_count(threads));
    // The inexact vertices of crossing pairs (a pair with a moved triangle).
    const std::vector<std::uint64_t> near_pairs =
        index.pairs_with(moved, thread_count(threads), [&](std::uint32_t i, std::uint32_t j) {
          return face[i] != face[j] && !share_vertex(tris[i], tris[j]);
        });
    auto found = parallel_ranges<std::vector<std::uint32_t>>(
        near_pairs.size(), threads, [&](std::size_t lo, std::size_t hi, std::vector<std::uint32_t>& out) {
          for (std::size_t k = lo; k < hi; ++k) {
            const auto i = static_cast<std::uint32_t>(near_pairs[k] >> 32), j = static_cast<std::uint32_t>(near_pairs[k]);
            if (!meet(in, tris[i], tris[j])) continue;
            for (std::uint32_t v : tris[i]) if (inexact[v]) out.push_back(v);
            for (std::uint32_t v : tris[j]) if (inexact[v]) out.push_back(v);
          }
        });
    std::vector<std::uint32_t> suspects;
    for (auto& p : found) suspects.insert(suspects.end(), p.begin(), p.end());
    std::sort(suspects.begin(), suspects.end());
    suspects.erase(std::unique(suspects.begin(), suspects.end()), suspects.end());
    if (suspects.empty()) return true;

    // A suspect is a rounded vertex: its faces are among those with a rounded corner.
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> faces_at;  // suspect -> faces
    for (std::uint32_t f = 0; f < in.faces.size(); ++f)
      if (moved_face[f])
        for (const auto& loop : in.faces[f].loops)
          for (std::uint32_t v : loop)
            if (std::binary_search(suspects.begin(), suspects.end(), v)) {
              auto& list = faces_at[v];
              if (list.empty() || list.back() != f) list.push_back(f);
            }
    bool changed = false;
    retile.clear();
    std::vector<char> stale(nf, 0);  // a vertex of the face moved in this round
    std::vector<std::uint32_t> scratch;
    for (std::uint32_t v : suspects) {
      std::vector<std::uint32_t>& fs = faces_at[v];
      std::sort(fs.begin(), fs.end());
      fs.erase(std::unique(fs.begin(), fs.end()), fs.end());
      // Crossings of the faces at v, triangulated with v where it is: of their tiles
      // with the indexed triangles near them and with each other. A move of `reach`
      // units at most keeps every tile of a face inside the face's grown box.
      using Tiling = std::vector<std::pair<std::uint32_t, Tri3>>;  // face, triangle
      const auto tiling = [&] {
        Tiling t;
        for (std::uint32_t f : fs)
          for (const Tri3& x : tile_face(in, in.faces[f])) t.push_back({f, x});
        return t;
      };
      // The same, with v where it is: the round's tilings where none of a face's
      // vertices has moved since (a face with many holes, such as a cut through a
      // Menger sponge, is around many suspects, and tiling it is the most of a check).
      const auto tiling_here = [&] {
        Tiling t;
        for (std::uint32_t f : fs) {
          if (stale[f]) {
            tiles[f] = tile_face(in, in.faces[f]);
            stale[f] = 0;
          }
          for (const Tri3& x : tiles[f]) t.push_back({f, x});
        }
        return t;
      };
      const auto crosses = [&](const Tri3& x, const Tri3& y) {
        return box_of(in, x).overlaps(box_of(in, y)) && meet(in, x, y);
      };
      const auto at_v = [&](const Tri3& x) { return x[0] == v || x[1] == v || x[2] == v; };
      // The pairs to test (boxes grown by the farthest move meeting): with `moving`,
      // only those with a tile that has v as a corner (while the tiling stays, the
      // only tiles that move).
      const auto pairs_of = [&](const Tiling& t, bool moving) {
        std::vector<std::pair<Tri3, Tri3>> out;
        std::vector<Box> boxes(t.size());
        for (std::size_t a = 0; a < t.size(); ++a) boxes[a] = grown(box_of(in, t[a].second));
        for (std::size_t a = 0; a < t.size(); ++a) {
          const bool a_moves = at_v(t[a].second);
          if (moving && !a_moves) continue;
          index.near(boxes[a], scratch, [&](std::uint32_t j) {
            if (std::binary_search(fs.begin(), fs.end(), face[j]) || share_vertex(t[a].second, tris[j])) return;
            out.push_back({t[a].second, tris[j]});
          });
          for (std::size_t b = moving ? 0 : a + 1; b < t.size(); ++b) {
            if (moving && b < a && at_v(t[b].second)) continue;  // listed from b
            if (t[a].first != t[b].first && boxes[a].overlaps(boxes[b]) && !share_vertex(t[a].second, t[b].second))
              out.push_back({t[a].second, t[b].second});
          }
        }
        return out;
      };
      const auto count = [&](const std::vector<std::pair<Tri3, Tri3>>& pairs, std::size_t stop_at) {
        std::size_t n = 0;
        for (std::size_t k = 0; k < pairs.size() && n < stop_at; ++k) n += crosses(pairs[k].first, pairs[k].second);
        return n;
      };
      // The places around v are compared with their own tilings (a place may change
      // how a face is tiled) while the faces at v have few tiles. A face with many
      // holes has thousands, and tiling it again at every place tried made one
      // Boolean take minutes: there the places are compared on the tiling v has where
      // it is, on which only v's tiles move and only their pairs count, and the best
      // place is checked on its own tiling when that differs.
      constexpr std::size_t kRetileAtEveryPlace = 256;
      const Tiling first = tiling_here();
      const bool retiling = first.size() <= kRetileAtEveryPlace;
      const std::vector<std::pair<Tri3, Tri3>> pairs = pairs_of(first, !retiling);
      // The pairs that cross with v at its best place so far (while that place has
      // the first tiling): a place where as many of them still cross is no better,
      // whatever the others do.
      std::vector<std::size_t> crossing;
      for (std::size_t k = 0; k < pairs.size(); ++k)
        if (crosses(pairs[k].first, pairs[k].second)) crossing.push_back(k);
      bool crossing_known = true;
      const Vec3 start = in.positions[v];
      Vec3 best = start;
      std::size_t best_count = crossing.size();
      // The crossings with v where it is now when fewer than best_count, else best_count.
      auto fewer = [&] {
        if (!retiling) return count(pairs, best_count);
        if (const Tiling t = tiling(); t != first) {
          const std::size_t n = count(pairs_of(t, false), SIZE_MAX);
          if (n < best_count) crossing_known = false;
          return std::min(n, best_count);
        }
        if (crossing_known) {
          std::size_t n = 0;
          for (std::size_t k : crossing) n += crosses(pairs[k].first, pairs[k].second);
          if (n == best_count) return best_count;
        }
        std::vector<std::size_t> now;
        for (std::size_t k = 0; k < pairs.size() && now.size() < best_count; ++k)
          if (crosses(pairs[k].first, pairs[k].second)) now.push_back(k);
        if (now.size() >= best_count) return best_count;
        crossing = std::move(now);
        crossing_known = true;
        return crossing.size();
      };
      const bool keep[3] = {exact(v, 0), exact(v, 1), exact(v, 2)};
      // One unit in the last place first, then two; after a round that left crossings
      // no such move reduced, up to four, eight, then sixteen (slivers crossing a few
      // units deep; seed 63415 of the long property run needs sixteen and five rounds).
      for (int r = 1; r <= reach && best_count > 0; ++r)
      for (int dx = -r; dx <= r && best_count > 0; ++dx)
        for (int dy = -r; dy <= r && best_count > 0; ++dy)
          for (int dz = -r; dz <= r && best_count > 0; ++dz) {
            if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
            if ((keep[0] && dx != 0) || (keep[1] && dy != 0) || (keep[2] && dz != 0)) continue;
            const auto step = [](double x, int d) {
              for (; d > 0; --d) x = std::nextafter(x, INFINITY);
              for (; d < 0; ++d) x = std::nextafter(x, -INFINITY);
              return x;
            };
            in.positions[v] = {step(start.x, dx), step(start.y, dy), step(start.z, dz)};
            const std::size_t n = fewer();
            if (n < best_count) {
              best_count = n;
              best = in.positions[v];
            }
          }
      in.positions[v] = best;
      if (!retiling && !(best == start)) {
        // A new tiling at the best place: kept only when the crossings of all the
        // faces' tiles are fewer than at the start.
        if (const Tiling t = tiling(); t != first) {
          const std::size_t there = count(pairs_of(t, false), SIZE_MAX);
          in.positions[v] = start;
          const std::size_t before = count(pairs_of(first, false), SIZE_MAX);
          in.positions[v] = there < before ? best : start;
        }
      }
      if (!(in.positions[v] == start)) {
        changed = true;
        retile.insert(retile.end(), fs.begin(), fs.end());
        for (std::uint32_t f : fs) stale[f] = 1;
      }
    }
    if (!changed) {
      if (reach >= 16) return false;
      reach *= 2;  // the same suspects again, reaching further
      continue;
    }
    std::sort(retile.begin(), retile.end());
    retile.erase(std::unique(retile.begin(), retile.end()), retile.end());
  }
  return false;
}

}  // namespace cellforge::boolean
