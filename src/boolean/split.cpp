// Stage 2 of the Boolean by segments (arrangement.h): a cluster's faces cut along
// its segments alone, not along their whole lines.
//
// The segments are the cluster's triangle edges (not the diagonals inside one face,
// Arrangement::open_edges) and the traces of the triangles that cross it, each
// clipped to the triangle it was found on. They are cut where they cross or touch
// one another, making a plane graph whose every vertex is an input vertex, a point
// of a segment on a plane (lpi) or the crossing of two of the cluster's lines, as in
// the convex split. Three kinds of edges are added so that every face is a simple
// polygon: a segment that ends inside a face is extended along its line to the next
// edge; a point where another solid touches the face inside gets a chord through it
// along the axis line u = its u, to the next edge each way; and each part of the
// graph not joined to the rest (a hole's loop, a ring of traces inside a face) is
// joined by two chords, one from its lexicographically least vertex along one of its
// edges' lines away from it, which meets only what is smaller, and one from its
// greatest. Each joint's removal leaves the graph joined by the others, so no face
// passes along an edge twice. The faces are then traced: at each vertex the edges in
// counterclockwise order (orient2 around the first), each face to the left of its
// edges; the one face outside is the one to the right of the least vertex's most
// clockwise edge.
//
// Against the convex split (a segment cuts every piece it crosses along the whole
// chord), this makes about two vertices a segment rather than a crossing of every
// pair of lines that meet in a piece. A face that would still pass a point twice (two
// holes touching at a corner) makes the cluster fall back to the convex split.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <span>
#include <utility>
#include <unordered_map>
#include <vector>

#include "boolean/arrangement.h"
#include "cellforge/geom/predicates.h"

namespace cellforge::boolean {

namespace {

std::uint64_t unordered_pair(std::uint32_t a, std::uint32_t b) {
  return (static_cast<std::uint64_t>(std::min(a, b)) << 32) | std::max(a, b);
}

// Whether the segment from (x0, y0) to (x1, y1) meets box b grown by pad on each side.
bool segment_meets_box(double x0, double y0, double x1, double y1, const Box& b, double pad) {
  double t0 = 0, t1 = 1;
  const double d[2] = {x1 - x0, y1 - y0}, o[2] = {x0, y0};
  const double lo[2] = {b.lo.x - pad, b.lo.y - pad}, hi[2] = {b.hi.x + pad, b.hi.y + pad};
  for (int a = 0; a < 2; ++a) {
    if (d[a] == 0) {
      if (o[a] < lo[a] || o[a] > hi[a]) return false;
      continue;
    }
    double ta = (lo[a] - o[a]) / d[a], tb = (hi[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace

// What one cluster's split builds, kept from cluster to cluster (most clusters are a
// triangle or two and a few segments: their tables would otherwise be allocated anew
// each time).
// Sorts pairs by first, then second, where every first is below n: counted into
// place by first (a linear pass), then each first's few pairs sorted (`out` is scratch).
template <class Pair>
void sort_by_first(std::vector<Pair>& v, std::size_t n, std::vector<Pair>& out, std::vector<std::uint32_t>& start) {
  start.assign(n + 1, 0);
  for (const Pair& x : v) ++start[std::get<0>(x) + 1];
  for (std::size_t i = 0; i < n; ++i) start[i + 1] += start[i];
  out.resize(v.size());
  for (const Pair& x : v) out[start[std::get<0>(x)]++] = x;
  // start[i] now ends bucket i; bucket i begins where bucket i - 1 ends.
  std::uint32_t begin = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (start[i] - begin > 1) std::sort(out.begin() + begin, out.begin() + start[i]);
    begin = start[i];
  }
  v.swap(out);
}

struct SplitScratch {
  struct Segment {
    std::uint32_t line, p, q;
    auto operator<=>(const Segment&) const = default;
  };
  struct TriSides {  // a triangle's edges, or a convex quad's when both its tiles are here
    std::uint32_t line[4];
    std::uint32_t end[4][2];
    int inner[4];  // the side of the triangle's (or quad's) other corners
    int n;
  };
  struct Edge {
    std::uint32_t a, b, line;  // local vertices (roots)
  };
  struct Keyed {  // a point on a segment: its place along the line, within +-e
    double t, e;
    std::uint32_t p;
  };
  struct Approx {  // a point's (u, v), each within +-e (Arrangement::approx2)
    double u, v, e;
  };
  FlatMap<std::uint32_t, std::uint32_t> through, traces, local;
  FlatMap<std::uint64_t, std::uint32_t> crossings, edge_at;
  FlatMap<std::uint32_t, TriSides> tri_sides;
  FlatMap<std::uint32_t, Approx> approx;
  std::vector<Segment> segments;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> touching, on, on_sorted;
  std::vector<std::array<std::uint32_t, 2>> pairs, pairs_sorted;
  std::vector<std::uint32_t> count;
  std::vector<Box> seg_box, edge_box;
  std::vector<std::uint32_t> chain, chain_begin, pts, vid, parent;
  std::vector<Edge> edges;
  std::vector<Keyed> keyed;
  // The faces: vertices' half-edges, and the traced boundaries (flat, by face).
  std::vector<std::uint32_t> start, around, fill, slot, used, seen, part, first_edge;
  std::vector<std::pair<int, std::uint32_t>> sectors;
  std::vector<char> done;
  std::vector<std::uint32_t> face_pts, face_lines, face_begin;

  void clear() {
    for (auto* m : {&through, &traces, &local}) m->clear();
    crossings.clear();
    edge_at.clear();
    tri_sides.clear();
    approx.clear();
    segments.clear();
    touching.clear();
    seg_box.clear();
    edge_box.clear();
    vid.clear();
    parent.clear();
    edges.clear();
  }
};

void Arrangement::split() {
  open_edges.assign(tris.size(), 0);
  SplitScratch scratch;
  for (std::uint32_t ci = 0; ci < clusters.size(); ++ci)
    if (clusters[ci].touched && (!segment_split || !split_cluster_graph(ci, scratch))) {
      ++convex_splits;
      split_cluster(ci);
    }
}

bool Arrangement::split_cluster_graph(std::uint32_t ci, SplitScratch& scratch) {
  scratch.clear();
  Cluster& c = clusters[ci];
  const int k = c.k, iu = (k + 1) % 3;
  if (c.tris().size() > 1) mark_open_edges(c);

  // ---- lines and the crossing points of pairs of them
  auto& through = scratch.through;  // edge key -> line
  auto through_line = [&](std::uint32_t p, std::uint32_t q) { return edge_line(c, through, p, q); };
  auto& crossings = scratch.crossings;  // line pair -> point
  auto cross_of = [&](std::uint32_t l1, std::uint32_t l2) {
    auto [it, fresh] = crossings.try_emplace(unordered_pair(l1, l2), 0);
    if (fresh) it->second = crossing_point(ci, std::min(l1, l2), std::max(l1, l2));
    return it->second;
  };
  auto side_of = [&](std::uint32_t li, std::uint32_t p) { return side(c, c.lines()[li], p); };
  auto along_of = [&](std::uint32_t li, std::uint32_t p, std::uint32_t q) { return along(c, c.lines()[li], p, q); };
  // A point's place along line li (increasing along its direction), within +-e: the
  // doubles, computed once a point; places whose intervals part order their points
  // as along_of does.
  auto place = [&](std::uint32_t li, std::uint32_t p) {
    auto [it, fresh] = scratch.approx.try_emplace(p);
    SplitScratch::Approx& a = it->second;
    if (fresh) approx2(c, p, a.u, a.v, a.e);
    const Line& l = c.lines()[li];
    return l.sign_b != 0 ? std::pair{l.sign_b * a.u, a.e} : std::pair{-l.sign_a * a.v, a.e};
  };
  // along_of, the doubles first.
  auto along_fast = [&](std::uint32_t li, std::uint32_t p, std::uint32_t q) {
    if (p == q) return 0;
    const auto [tp, ep] = place(li, p);
    const auto [tq, eq] = place(li, q);
    if (tp + ep < tq - eq) return -1;
    if (tq + eq < tp - ep) return 1;
    return along_of(li, p, q);
  };
  // Sign of A_m B_l - B_m A_l: how line m's side function changes along l's direction.
  auto turn_of = [&](std::uint32_t l, std::uint32_t m) { return turn(c, c.lines()[l], c.lines()[m]); };

  // ---- the segments
  using Segment = SplitScratch::Segment;
  auto& segments = scratch.segments;
  for (std::uint32_t t : c.tris())
    for (int e = 0; e < 3; ++e) {
      if (open_edges[t] & (1u << e)) continue;
      const std::uint32_t a = tris[t].v[e], b = tris[t].v[(e + 1) % 3];
      segments.push_back({through_line(a, b), a, b});
    }
  // A constraint's segment clipped to its triangle t: the part inside each of t's
  // edges' lines (the side of the opposite corner). A segment that meets t at one
  // point only (an end on t's side, the rest outside) leaves that point, where the
  // surfaces touch, to be made a vertex as the touching points are.
  auto& touching = scratch.touching;  // point, a line through it
  for (std::uint32_t v : c.touch_points()) touching.push_back({v, kInvalidIndex});
  using TriSides = SplitScratch::TriSides;
  auto& tri_sides = scratch.tri_sides;  // by triangle, made once
  auto clip = [&](std::uint32_t line, std::uint32_t p, std::uint32_t q, std::uint32_t t) {
    const Tri& tri = tris[t];
    auto [at, fresh] = tri_sides.try_emplace(t);
    TriSides& ts = at->second;
    if (fresh) {
      // A tile of a strictly convex quad whose diagonal is open (the other tile is in
      // this cluster, and nothing else uses the diagonal): the quad's four edges, so
      // that a cut across the quad is one segment, with no point on the diagonal.
      const SoupFace& f = faces[tri.input_face];
      int open = -1;
      for (int e = 0; e < 3; ++e)
        if (open_edges[t] & (1u << e)) open = e;
      const std::span<const std::uint32_t> corners =
          f.quad && f.convex && open >= 0 ? loops_of(f)[0] : std::span<const std::uint32_t>(tri.v);
      ts.n = static_cast<int>(corners.size());
      for (int e = 0; e < ts.n; ++e) {
        ts.end[e][0] = corners[e];
        ts.end[e][1] = corners[(e + 1) % ts.n];
        ts.line[e] = through_line(ts.end[e][0], ts.end[e][1]);
        ts.inner[e] = side_of(ts.line[e], corners[(e + 2) % ts.n]);
      }
    }
    const std::uint32_t* el = ts.line;
    const int n = ts.n;
    int sp[4], sq[4];
    bool inside = true;
    for (int e = 0; e < n; ++e) {
      sp[e] = side_of(el[e], p) * ts.inner[e];
      sq[e] = side_of(el[e], q) * ts.inner[e];
      if (sp[e] < 0 && sq[e] < 0) return;
      inside &= sp[e] >= 0 && sq[e] >= 0;
    }
    if (inside) {
      segments.push_back({line, p, q});
      return;
    }
    for (int e = 0; e < n; ++e) {
      if (sp[e] > 0 || sq[e] > 0) continue;  // both on the line, or one outside, one on it
      if (sp[e] == 0 && sq[e] == 0) continue;
      const std::uint32_t x = sp[e] == 0 ? p : q;
      const int* sx = sp[e] == 0 ? sp : sq;
      if (std::all_of(sx, sx + n, [](int v) { return v >= 0; })) touching.push_back({x, line});
      return;
    }
    const int dir = along_of(line, p, q);  // -1: p first along the line
    if (dir == 0) return;
    std::uint32_t in_p = p, in_q = q;  // the ends, moved in
    for (int e = 0; e < n; ++e) {
      if (sp[e] >= 0 && sq[e] >= 0) continue;
      const std::uint32_t a = ts.end[e][0], b = ts.end[e][1];
      // Where the line crosses el: at a or b when it passes through that corner (no
      // second name for the input vertex), else their crossing point.
      const std::uint32_t x = side_of(line, a) == 0 ? a : (side_of(line, b) == 0 ? b : cross_of(line, el[e]));
      if (sp[e] < 0) {  // enters here: the later of the entries
        if (in_p == p || along_of(line, in_p, x) == dir) in_p = x;
      } else if (in_q == q || along_of(line, x, in_q) == dir) {  // leaves: the earlier
        in_q = x;
      }
    }
    const int d = along_of(line, in_p, in_q);
    if (d == 0) touching.push_back({in_p, line});
    if (d != dir) return;
    segments.push_back({line, in_p, in_q});
  };
  auto& traces = scratch.traces;  // other plane -> line
  for (const Constraint& k2 : c.constraints()) {
    if (k2.p == k2.q) continue;
    // An edge of the other triangle lying in this plane: the line through its ends.
    if (k2.p < pos.size() && k2.q < pos.size()) {
      clip(through_line(k2.p, k2.q), k2.p, k2.q, k2.tri);
      continue;
    }
    if (equal3(k2.p, k2.q)) continue;
    auto [it, fresh] = traces.try_emplace(plane_of[k2.other_cluster], 0);
    if (fresh) {
      Line l = Line::make(LineKind::kTrace, k2.other_tri);
      l.key = pair_key(plane_of[ci], plane_of[k2.other_cluster]);
      it->second = add_line(c, std::move(l));
    }
    clip(it->second, k2.p, k2.q, k2.tri);
  }
  for (Segment& s : segments)
    if (s.p > s.q) std::swap(s.p, s.q);
  std::sort(segments.begin(), segments.end());
  segments.erase(std::unique(segments.begin(), segments.end()), segments.end());

  // ---- the cluster's extent, and bounds in (u, v) that hold each segment exactly
  auto bounds_of = [&](std::uint32_t p, Box& b) {
    double u, v, e;
    approx2(c, p, u, v, e);
    b.add(Vec3{u - e, v - e, 0});
    b.add(Vec3{u + e, v + e, 0});
  };
  Box extent;
  auto& seg_box = scratch.seg_box;
  seg_box.resize(segments.size());
  for (std::size_t s = 0; s < segments.size(); ++s) {
    bounds_of(segments[s].p, seg_box[s]);
    bounds_of(segments[s].q, seg_box[s]);
    extent.add(seg_box[s]);
  }
  const double size = std::max(extent.hi.x - extent.lo.x, extent.hi.y - extent.lo.y);

  // ---- the points on each segment: its ends, the crossings, the ends of others on it
  // (segment, point) pairs: each segment's ends, then what meet finds.
  std::vector<std::pair<std::uint32_t, std::uint32_t>>& on = scratch.on;
  on.clear();
  struct OnList {  // on.push_back for one segment
    std::vector<std::pair<std::uint32_t, std::uint32_t>>& on;
    std::uint32_t s;
    void push_back(std::uint32_t x) { on.push_back({s, x}); }
  };
  auto on_of = [&](std::uint32_t si) { return OnList{on, si}; };
  for (std::uint32_t s = 0; s < segments.size(); ++s) {
    on.push_back({s, segments[s].p});
    on.push_back({s, segments[s].q});
  }
  auto meet = [&](std::uint32_t si, std::uint32_t ti) {
    const Segment &s = segments[si], &t = segments[ti];
    // The ends of one lying on the other's line and within it (closed).
    auto ends_within = [&](const Segment& x, std::uint32_t xi, const Segment& y) {
      for (std::uint32_t e : {y.p, y.q})
        if (along_fast(x.line, x.p, e) * along_fast(x.line, e, x.q) >= 0) on_of(xi).push_back(e);
    };
    if (s.line == t.line) {
      ends_within(s, si, t);
      ends_within(t, ti, s);
      return;
    }
    const int a = side_of(s.line, t.p), b = side_of(s.line, t.q);
    if (a == 0 && b == 0) {  // one line under two names
      line_union(c.lines()[s.line].key, c.lines()[t.line].key);
      ends_within(s, si, t);
      ends_within(t, ti, s);
      return;
    }
    if (a * b > 0) return;
    const int cp = side_of(t.line, s.p), cq = side_of(t.line, s.q);
    if (cp * cq > 0) return;
    if (a * b < 0 && cp * cq < 0) {
      const std::uint32_t x = cross_of(s.line, t.line);
      on_of(si).push_back(x);
      on_of(ti).push_back(x);
      return;
    }
    // They touch where an end of one lies on the other (the lines meet only there).
    if (a == 0) on_of(si).push_back(t.p);
    if (b == 0) on_of(si).push_back(t.q);
    if (cp == 0) on_of(ti).push_back(s.p);
    if (cq == 0) on_of(ti).push_back(s.q);
  };
  auto boxes_meet = [](const Box& x, const Box& y) {
    return x.lo.x <= y.hi.x && y.lo.x <= x.hi.x && x.lo.y <= y.hi.y && y.lo.y <= x.hi.y;
  };
  if (segments.size() <= 48) {
    for (std::uint32_t s = 0; s < segments.size(); ++s)
      for (std::uint32_t t = s + 1; t < segments.size(); ++t)
        if (boxes_meet(seg_box[s], seg_box[t])) meet(s, t);
  } else {
    auto& pairs = scratch.pairs;
    pairs.clear();
    Bvh(seg_box).pairs([&](std::uint32_t s, std::uint32_t t) { pairs.push_back({std::min(s, t), std::max(s, t)}); });
    sort_by_first(pairs, segments.size(), scratch.pairs_sorted, scratch.count);
    for (auto [s, t] : pairs) meet(s, t);
  }

  // ---- the graph's vertices: points at one place are one vertex (the smallest id)
  auto& vid = scratch.vid;        // local vertex -> point id
  auto& local = scratch.local;    // point id -> local vertex
  auto& parent = scratch.parent;  // local union, to the smaller id
  auto vertex = [&](std::uint32_t p) {
    auto [it, fresh] = local.try_emplace(p, static_cast<std::uint32_t>(vid.size()));
    if (fresh) {
      vid.push_back(p);
      parent.push_back(it->second);
    }
    return it->second;
  };
  auto root = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  auto join = [&](std::uint32_t x, std::uint32_t y) {
    x = root(x);
    y = root(y);
    if (x == y) return;
    if (vid[y] < vid[x]) std::swap(x, y);
    parent[y] = x;
  };
  // Each segment's points in order along it (a segment with its two ends alone needs
  // no comparison), as local vertices: chain[chain_begin[s]] ...
  sort_by_first(on, segments.size(), scratch.on_sorted, scratch.count);
  on.erase(std::unique(on.begin(), on.end()), on.end());
  std::vector<std::uint32_t>& chain = scratch.chain;
  std::vector<std::uint32_t>& chain_begin = scratch.chain_begin;
  chain.clear();
  chain_begin.assign(1, 0);
  std::vector<std::uint32_t>& pts = scratch.pts;
  for (std::size_t i = 0; i < on.size();) {
    const std::uint32_t si = on[i].first, li = segments[si].line;
    pts.clear();
    for (; i < on.size() && on[i].first == si; ++i) pts.push_back(on[i].second);
    // By the doubles where their error intervals part, exactly where they do not: the
    // order along_of gives, with an exact comparison only between points close together.
    auto& keyed = scratch.keyed;
    keyed.clear();
    if (pts.size() > 2) {
      for (std::uint32_t x : pts) {
        const auto [t, e] = place(li, x);
        keyed.push_back({t, e, x});
      }
      std::sort(keyed.begin(), keyed.end(), [&](const SplitScratch::Keyed& x, const SplitScratch::Keyed& y) {
        if (x.t + x.e < y.t - y.e) return true;
        if (y.t + y.e < x.t - x.e) return false;
        return along_of(li, x.p, y.p) < 0;
      });
      for (std::size_t m = 0; m < pts.size(); ++m) pts[m] = keyed[m].p;
    }
    const std::size_t first = chain.size();
    for (std::size_t m = 0; m < pts.size(); ++m) {
      chain.push_back(vertex(pts[m]));
      if (m == 0 || pts.size() <= 2) continue;
      const SplitScratch::Keyed &x = keyed[m - 1], &y = keyed[m];
      if (x.t + x.e >= y.t - y.e && along_of(li, x.p, y.p) == 0) join(chain[first + m - 1], chain[first + m]);
    }
    chain_begin.push_back(static_cast<std::uint32_t>(chain.size()));
  }

  // ---- the edges
  using Edge = SplitScratch::Edge;
  auto& edges = scratch.edges;
  auto& edge_at = scratch.edge_at;
  auto add_edge = [&](std::uint32_t a, std::uint32_t b, std::uint32_t line) {
    if (a == b) return;
    if (edge_at.try_emplace(unordered_pair(a, b), static_cast<std::uint32_t>(edges.size())).second)
      edges.push_back({a, b, line});
  };
  for (std::size_t s = 0; s + 1 < chain_begin.size(); ++s) {
    std::uint32_t prev = kInvalidIndex;
    for (std::uint32_t m = chain_begin[s]; m < chain_begin[s + 1]; ++m) {
      const std::uint32_t r = root(chain[m]);
      if (prev != kInvalidIndex) add_edge(prev, r, segments[s].line);
      prev = r;
    }
  }

  // ---- rays: from vertex o along line l (dir +1: the line's direction (B, -A)) to the
  // first edge or vertex they meet, which they join (splitting the edge there).
  auto& edge_box = scratch.edge_box;
  edge_box.resize(edges.size());
  for (std::size_t e = 0; e < edges.size(); ++e) {
    bounds_of(vid[edges[e].a], edge_box[e]);
    bounds_of(vid[edges[e].b], edge_box[e]);
  }
  const std::size_t indexed = edges.size();
  std::optional<Bvh> edge_tree;
  if (indexed > 32) edge_tree.emplace(edge_box);
  // The edges the rays add (a face with a thousand holes: two chords a hole) have a
  // tree of their own, made again each time they double; the few since, one by one.
  std::optional<Bvh> added_tree;
  std::size_t added_end = indexed;  // added_tree holds edges [indexed, added_end)
  auto reindex = [&] {
    if (edges.size() - added_end <= std::max<std::size_t>(32, added_end - indexed)) return;
    added_tree.emplace(std::vector<Box>(edge_box.begin() + static_cast<std::ptrdiff_t>(indexed), edge_box.end()));
    added_end = edges.size();
  };
  const double pad = 1e-9 * size + 1e-300;
  // Edge ei cut at vertex x, a point inside it: it keeps the first part (its box, a
  // superset, stays) and the second is a new edge.
  auto split_edge = [&](std::uint32_t ei, std::uint32_t x) {
    const Edge e = edges[ei];
    edge_at.erase(unordered_pair(e.a, e.b));
    edges[ei].b = x;
    edge_at[unordered_pair(e.a, x)] = ei;
    edge_at[unordered_pair(x, e.b)] = static_cast<std::uint32_t>(edges.size());
    edges.push_back({x, e.b, e.line});
    edge_box.push_back(edge_box[ei]);
  };
  auto ray = [&](std::uint32_t o, std::uint32_t l, int dir) {
    reindex();
    const Line& L = c.lines()[l];
    double ou, ov, oe;
    approx2(c, vid[o], ou, ov, oe);
    double du = dir * L.B.v, dv = -dir * L.A.v;
    const double norm = std::hypot(du, dv);
    if (!(norm > 0)) return false;
    du /= norm;
    dv /= norm;
    const double reach = 4 * size + 4 * oe + pad;
    const double fu = ou + du * reach, fv = ov + dv * reach;
    // The tube the ray may be in: its origin's error, and its direction's from the
    // line's filtered coefficients over its length.
    const double grow = pad + oe + reach * (L.A.e + L.B.e) / norm;
    struct Hit {
      double t;
      std::uint32_t edge;   // crossing that edge; kInvalidIndex: at vertex x
      std::uint32_t x;
    };
    std::vector<Hit> hits;
    auto ahead = [&](std::uint32_t x) { return along_of(l, vid[o], vid[x]) == -dir; };
    auto param = [&](std::uint32_t x) {
      double u, v, e;
      approx2(c, vid[x], u, v, e);
      return (u - ou) * du + (v - ov) * dv;
    };
    auto test = [&](std::uint32_t ei) {
      const Edge& E = edges[ei];
      if (E.a == o || E.b == o) return;
      const int sa = side_of(l, vid[E.a]), sb = side_of(l, vid[E.b]);
      if (sa * sb > 0) return;
      if (sa == 0 && ahead(E.a)) hits.push_back({param(E.a), kInvalidIndex, E.a});
      if (sb == 0 && ahead(E.b)) hits.push_back({param(E.b), kInvalidIndex, E.b});
      if (sa * sb < 0) {
        const int so = side_of(E.line, vid[o]);
        if (so == 0 || so != -dir * turn_of(l, E.line)) return;
        double au, av, ae, bu, bv, be;
        approx2(c, vid[E.a], au, av, ae);
        approx2(c, vid[E.b], bu, bv, be);
        const double eu = bu - au, ev = bv - av;
        const double den = du * ev - dv * eu;
        const double t = den != 0 ? ((au - ou) * ev - (av - ov) * eu) / den : 0;
        hits.push_back({t, ei, kInvalidIndex});
      }
    };
    if (edge_tree)
      edge_tree->query([&](const Box& b) { return segment_meets_box(ou, ov, fu, fv, b, grow); },
                       [&](std::uint32_t ei) { test(ei); });
    else
      for (std::uint32_t ei = 0; ei < indexed; ++ei)
        if (segment_meets_box(ou, ov, fu, fv, edge_box[ei], grow)) test(ei);
    if (added_tree)
      added_tree->query([&](const Box& b) { return segment_meets_box(ou, ov, fu, fv, b, grow); },
                        [&](std::uint32_t k) { test(static_cast<std::uint32_t>(indexed + k)); });
    for (std::uint32_t ei = static_cast<std::uint32_t>(added_end); ei < edges.size(); ++ei)
      if (segment_meets_box(ou, ov, fu, fv, edge_box[ei], grow)) test(ei);
    if (hits.empty()) return false;
    // The nearest by the doubles, then made sure of exactly: a hit before it is taken.
    std::size_t best = 0;
    for (std::size_t h = 1; h < hits.size(); ++h)
      if (hits[h].t < hits[best].t) best = h;
    auto point_of = [&](const Hit& h) {
      return h.edge == kInvalidIndex ? vid[h.x] : cross_of(l, edges[h.edge].line);
    };
    std::uint32_t at = point_of(hits[best]);
    for (bool moved = true; moved;) {
      moved = false;
      for (std::size_t h = 0; h < hits.size(); ++h) {
        if (h == best) continue;
        bool before;
        if (hits[h].edge == kInvalidIndex) {
          before = along_of(l, vid[hits[h].x], at) == -dir;
        } else {
          const std::uint32_t m = edges[hits[h].edge].line;
          const int s_at = side_of(m, at);
          before = s_at != 0 && s_at == -side_of(m, vid[o]);
        }
        if (before) {
          best = h;
          at = point_of(hits[h]);
          moved = true;
        }
      }
    }
    const Hit hit = hits[best];
    std::uint32_t x;
    if (hit.edge == kInvalidIndex) {
      x = hit.x;
    } else {
      x = vertex(at);
      if (root(x) != x) x = root(x);
      split_edge(hit.edge, x);
    }
    const std::size_t before = edges.size();
    add_edge(o, x, l);
    if (edges.size() > before) {
      edge_box.emplace_back();
      bounds_of(vid[o], edge_box.back());
      bounds_of(vid[x], edge_box.back());
    }
    return true;
  };
  auto degree = [&] {
    std::vector<std::uint32_t> d(vid.size(), 0);
    for (const Edge& e : edges) {
      ++d[e.a];
      ++d[e.b];
    }
    return d;
  };

  // Touching points: on an edge, a vertex of it; inside a face, a chord along u = its u.
  std::sort(touching.begin(), touching.end());
  touching.erase(std::unique(touching.begin(), touching.end()), touching.end());
  for (auto [v, through_v] : touching) {
    if (local.count(v)) continue;
    Box b;
    bounds_of(v, b);
    std::vector<std::uint32_t> near;
    if (edge_tree)
      edge_tree->query([&](const Box& x) { return boxes_meet(x, b); }, [&](std::uint32_t ei) { near.push_back(ei); });
    else
      for (std::uint32_t ei = 0; ei < indexed; ++ei) near.push_back(ei);
    for (std::uint32_t ei = static_cast<std::uint32_t>(indexed); ei < edges.size(); ++ei) near.push_back(ei);
    std::sort(near.begin(), near.end());
    bool placed = false;
    for (std::uint32_t ei : near) {
      if (placed) break;
      if (!boxes_meet(edge_box[ei], b)) continue;
      const Edge E = edges[ei];
      if (side_of(E.line, v) != 0) continue;
      const int s1 = along_of(E.line, vid[E.a], v), s2 = along_of(E.line, v, vid[E.b]);
      if (s1 == 0 || s2 == 0) {
        placed = true;  // at a vertex already
      } else if (s1 == s2) {
        split_edge(ei, vertex(v));
        placed = true;
      }
    }
    if (placed) continue;
    std::uint32_t l = through_v;
    if (l == kInvalidIndex) {  // an input vertex: the axis line u = its u
      l = add_line(c, Line::make(LineKind::kAxisU, 0, 0, pos[v][iu]));
      c.lines()[l].key = fresh_key();
    }
    const std::uint32_t x = vertex(v);
    if (!ray(x, l, 1) || !ray(x, l, -1)) return false;
  }
  // Segments that end inside a face: on along their line.
  {
    const std::vector<std::uint32_t> d = degree();
    std::vector<std::uint32_t> dangling, from, line;
    for (const Edge& e : edges)
      for (auto [x, y] : {std::pair{e.a, e.b}, std::pair{e.b, e.a}})
        if (d[x] == 1) {
          dangling.push_back(x);
          from.push_back(y);
          line.push_back(e.line);
        }
    // A cut of the edge by an earlier ray leaves `from` on the same side.
    for (std::size_t m = 0; m < dangling.size(); ++m)
      if (!ray(dangling[m], line[m], along_of(line[m], vid[dangling[m]], vid[from[m]]))) return false;
  }
  // The least vertex of xs in (u, v) lexicographically (the greatest with
  // greatest): the doubles pick the few that may be it, exact comparisons decide.
  auto lex_less = [&](std::uint32_t x, std::uint32_t y) {
    const int s = compare3(vid[x], vid[y], iu);
    return s != 0 ? s < 0 : compare3(vid[x], vid[y], (k + 2) % 3) < 0;
  };
  auto extreme = [&](const std::vector<std::uint32_t>& xs, bool greatest) {
    const double sign = greatest ? -1 : 1;
    std::vector<double> u(xs.size()), e(xs.size());
    double bound = 1e308;
    for (std::size_t m = 0; m < xs.size(); ++m) {
      double v;
      approx2(c, vid[xs[m]], u[m], v, e[m]);
      u[m] *= sign;
      bound = std::min(bound, u[m] + e[m]);
    }
    std::uint32_t best = kInvalidIndex;
    for (std::size_t m = 0; m < xs.size(); ++m)
      if (u[m] - e[m] <= bound &&
          (best == kInvalidIndex || (greatest ? lex_less(best, xs[m]) : lex_less(xs[m], best))))
        best = xs[m];
    return best;
  };
  // Parts not joined to the rest: two chords each.
  {
    auto& part = scratch.part;
    part.resize(vid.size());
    for (std::uint32_t x = 0; x < vid.size(); ++x) part[x] = x;
    auto find = [&](std::uint32_t x) {
      while (part[x] != x) x = part[x] = part[part[x]];
      return x;
    };
    auto& first_edge = scratch.first_edge;
    first_edge.assign(vid.size(), kInvalidIndex);
    for (std::uint32_t ei = 0; ei < edges.size(); ++ei) {
      part[find(edges[ei].a)] = find(edges[ei].b);
      for (std::uint32_t x : {edges[ei].a, edges[ei].b})
        if (first_edge[x] == kInvalidIndex) first_edge[x] = ei;
    }
    std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> members;
    std::vector<std::uint32_t> order;  // parts in the order of their first vertex
    for (std::uint32_t x = 0; x < vid.size(); ++x) {
      if (first_edge[x] == kInvalidIndex) continue;
      auto& m = members[find(x)];
      if (m.empty()) order.push_back(find(x));
      m.push_back(x);
    }
    if (order.empty()) return false;
    if (order.size() > 1) {
      std::vector<std::uint32_t> all;
      for (std::uint32_t x = 0; x < vid.size(); ++x)
        if (first_edge[x] != kInvalidIndex) all.push_back(x);
      const std::uint32_t main_part = find(extreme(all, false));
      std::vector<std::array<std::uint32_t, 2>> ends;
      for (std::uint32_t p : order)
        if (p != main_part) ends.push_back({extreme(members[p], false), extreme(members[p], true)});
      for (const auto& pair : ends)
        for (std::uint32_t x : pair) {
          const Edge& e = edges[first_edge[x]];
          const std::uint32_t away = e.a == x ? e.b : e.a, l = e.line;
          if (!ray(x, l, along_of(l, vid[x], vid[away]))) return false;
        }
    }
  }

  // ---- the faces
  const std::uint32_t n = static_cast<std::uint32_t>(vid.size());
  // Half-edge h = 2 e (a -> b) or 2 e + 1 (b -> a); around each vertex, its outgoing
  // half-edges counterclockwise.
  auto& start = scratch.start;
  start.assign(n + 1, 0);
  for (const Edge& e : edges) {
    ++start[e.a + 1];
    ++start[e.b + 1];
  }
  for (std::uint32_t x = 0; x < n; ++x) start[x + 1] += start[x];
  auto& around = scratch.around;
  around.resize(start[n]);
  {
    auto& fill = scratch.fill;
    fill.assign(start.begin(), start.end() - 1);
    for (std::uint32_t ei = 0; ei < edges.size(); ++ei) {
      around[fill[edges[ei].a]++] = 2 * ei;
      around[fill[edges[ei].b]++] = 2 * ei + 1;
    }
  }
  auto head = [&](std::uint32_t h) { return h & 1 ? edges[h >> 1].a : edges[h >> 1].b; };
  auto tail = [&](std::uint32_t h) { return h & 1 ? edges[h >> 1].b : edges[h >> 1].a; };
  auto& slot = scratch.slot;  // half-edge -> index in its tail's list
  slot.resize(2 * edges.size());
  for (std::uint32_t x = 0; x < n; ++x) {
    const std::uint32_t b = start[x], d = start[x + 1] - b;
    if (d > 2) {
      const std::uint32_t o = vid[x], r = vid[head(around[b])], r_line = edges[around[b] >> 1].line;
      // Counterclockwise from the first: (0, pi) before pi before (pi, 2 pi). Another
      // edge on the first's line goes the other way.
      auto sector = [&](std::uint32_t h) {
        const std::uint32_t y = vid[head(h)];
        if (y == r) return 0;
        if (edges[h >> 1].line == r_line) return 2;
        const int s = orient2(c, o, r, y);
        return s > 0 ? 1 : (s == 0 ? 2 : 3);
      };
      auto& keyed = scratch.sectors;
      keyed.clear();
      for (std::uint32_t m = b; m < b + d; ++m) keyed.push_back({sector(around[m]), around[m]});
      std::sort(keyed.begin(), keyed.end(), [&](const auto& p, const auto& q) {
        if (p.first != q.first) return p.first < q.first;
        if (p.second == q.second) return false;
        return orient2(c, o, vid[head(p.second)], vid[head(q.second)]) > 0;
      });
      for (std::uint32_t m = 0; m < d; ++m) around[b + m] = keyed[m].second;
    }
    for (std::uint32_t m = b; m < b + d; ++m) slot[around[m]] = m - b;
  }
  // The face to the left of h -> next: at h's head, the edge just clockwise of h's twin.
  auto next = [&](std::uint32_t h) {
    const std::uint32_t y = head(h), b = start[y], d = start[y + 1] - b;
    return around[b + (slot[h ^ 1] + d - 1) % d];
  };
  // The outer face: right of the least vertex's most clockwise edge.
  auto& used = scratch.used;
  used.clear();
  for (std::uint32_t x = 0; x < n; ++x)
    if (start[x + 1] > start[x]) used.push_back(x);
  const std::uint32_t least = extreme(used, false);
  std::uint32_t outer = around[start[least]];
  for (std::uint32_t m = start[least] + 1; m < start[least + 1]; ++m)
    if (orient2(c, vid[least], vid[head(around[m])], vid[head(outer)]) > 0) outer = around[m];
  outer ^= 1;  // its twin, pointing at the least vertex

  auto& done = scratch.done;
  done.assign(2 * edges.size(), 0);
  auto& seen = scratch.seen;
  seen.assign(n, kInvalidIndex);
  // The faces' boundaries, flat: face f is face_pts[face_begin[f] .. face_begin[f + 1]).
  auto& face_pts = scratch.face_pts;
  auto& face_lines = scratch.face_lines;
  auto& face_begin = scratch.face_begin;
  face_pts.clear();
  face_lines.clear();
  face_begin.assign(1, 0);
  for (std::uint32_t h0 = 0; h0 < done.size(); ++h0) {
    if (done[h0]) continue;
    bool is_outer = false;
    std::uint32_t h = h0;
    do {
      if (done[h]) return false;
      done[h] = 1;
      is_outer |= h == outer;
      const std::uint32_t x = tail(h);
      if (seen[x] == h0) return false;  // a point twice
      seen[x] = h0;
      face_pts.push_back(vid[x]);
      face_lines.push_back(edges[h >> 1].line);
      h = next(h);
    } while (h != h0);
    if (is_outer || face_pts.size() - face_begin.back() < 3) {
      if (!is_outer) return false;
      face_pts.resize(face_begin.back());
      face_lines.resize(face_begin.back());
      continue;
    }
    face_begin.push_back(static_cast<std::uint32_t>(face_pts.size()));
  }
  const std::size_t faces_made = face_begin.size() - 1;
  // One connected plane graph: V - E + F = 2 (F with the outer face).
  if (used.size() + faces_made + 1 != edges.size() + 2) return false;
  // Each line's points, once each, appended in one go.
  auto& on_line = scratch.on;  // (line, point)
  on_line.clear();
  for (const Edge& e : edges) {
    on_line.push_back({e.line, vid[e.a]});
    on_line.push_back({e.line, vid[e.b]});
  }
  std::sort(on_line.begin(), on_line.end());
  on_line.erase(std::unique(on_line.begin(), on_line.end()), on_line.end());
  for (std::size_t i = 0; i < on_line.size();) {
    std::size_t j = i;
    while (j < on_line.size() && on_line[j].first == on_line[i].first) ++j;
    std::vector<std::uint32_t>& points = c.lines()[on_line[i].first].points;
    points.reserve(points.size() + (j - i));
    for (; i < j; ++i) points.push_back(on_line[i].second);
  }
  for (std::size_t f = 0; f < faces_made; ++f) {
    Piece p;  // each vector allocated once, at its size
    p.pts.assign(face_pts.begin() + face_begin[f], face_pts.begin() + face_begin[f + 1]);
    p.lines.assign(face_lines.begin() + face_begin[f], face_lines.begin() + face_begin[f + 1]);
    piece_box(c, p);
    c.pieces().push_back(std::move(p));
  }
  return true;
}

}  // namespace cellforge::boolean
