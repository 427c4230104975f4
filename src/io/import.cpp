// import_soup: from a polygon soup to a group of the model.
//
// 1. weld positions (weld.h) and rewrite the polygons; drop repeated consecutive
//    corners, and polygons left with fewer than 3 distinct corners (reported);
// 2. repair orientation (optional): flip faces across two-face edges so that
//    neighbours agree, then orient each closed patch by its nesting: outward when
//    an even number of closed patches contain it (a solid, or an island in a
//    cavity), inward when an odd number do (a cavity);
// 3. merge coplanar triangles (optional) into polygons, with holes, when the
//    boundary of the merged patch is a set of simple loops;
// 4. build_mesh, with the positions no face, wire or point uses left out;
// 5. make the cells of the regions the faces bound (VolumeMode::kAuto, volumes.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "cellforge/geom/polygon.h"
#include "cellforge/geom/predicates.h"
#include "cellforge/geom/volume.h"
#include "cellforge/topo/builder.h"
#include "cellforge/geom/winding.h"
#include "io/formats.h"
#include "cellforge/io/volumes.h"
#include "io/weld.h"

namespace cellforge::io {

namespace {

using Polygon = std::vector<std::uint32_t>;

// Undirected edges of a polygon list, with the corners (polygon, position) using
// each; corner c of polygon p runs from p[c] to p[c + 1].
class EdgeTable {
 public:
  explicit EdgeTable(const std::vector<Polygon>& polys) {
    first_corner_.resize(polys.size() + 1, 0);
    for (std::size_t p = 0; p < polys.size(); ++p)
      first_corner_[p + 1] = first_corner_[p] + static_cast<std::uint32_t>(polys[p].size());
    const std::uint32_t corners = first_corner_.back();
    std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(corners);
    corner_poly_.resize(corners);
    forward_.resize(corners);
    for (std::size_t p = 0; p < polys.size(); ++p) {
      for (std::size_t k = 0; k < polys[p].size(); ++k) {
        const std::uint32_t a = polys[p][k], b = polys[p][(k + 1) % polys[p].size()];
        const std::uint32_t c = first_corner_[p] + static_cast<std::uint32_t>(k);
        keys[c] = {a < b ? (std::uint64_t{a} << 32 | b) : (std::uint64_t{b} << 32 | a), c};
        corner_poly_[c] = static_cast<std::uint32_t>(p);
        forward_[c] = a < b;
      }
    }
    std::sort(keys.begin(), keys.end());
    edge_of_.resize(corners);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (i == 0 || keys[i].first != keys[i - 1].first)
        use_begin_.push_back(static_cast<std::uint32_t>(i));
      edge_of_[keys[i].second] = static_cast<std::uint32_t>(use_begin_.size() - 1);
      uses_.push_back(keys[i].second);
    }
    use_begin_.push_back(static_cast<std::uint32_t>(keys.size()));
  }

  std::size_t num_edges() const { return use_begin_.size() - 1; }
  std::uint32_t corner(std::size_t poly, std::size_t k) const {
    return first_corner_[poly] + static_cast<std::uint32_t>(k);
  }
  std::uint32_t edge_of(std::uint32_t corner) const { return edge_of_[corner]; }
  std::uint32_t poly_of(std::uint32_t corner) const { return corner_poly_[corner]; }
  bool forward(std::uint32_t corner) const { return forward_[corner]; }
  std::span<const std::uint32_t> uses(std::uint32_t edge) const {
    return {uses_.data() + use_begin_[edge], use_begin_[edge + 1] - use_begin_[edge]};
  }
  // The other corner of a two-use edge (or ~0).
  std::uint32_t mate(std::uint32_t corner) const {
    const auto u = uses(edge_of_[corner]);
    if (u.size() != 2) return kNoRep;
    return u[0] == corner ? u[1] : u[0];
  }

 private:
  std::vector<std::uint32_t> first_corner_, corner_poly_, edge_of_, uses_, use_begin_;
  std::vector<bool> forward_;
};

// The exact sign of the volume each closed patch encloses (0 for the others): one
// filtered pass over the loops, then an exact pass over the loops of each patch the
// filter left undecided.
std::vector<int> patch_volume_signs(const std::vector<Vec3>& pos, const std::vector<Polygon>& loops,
                                    const std::vector<std::uint32_t>& patch,
                                    const std::vector<bool>& closed) {
  const std::size_t count = closed.size();
  std::vector<std::uint32_t> first(count + 1, 0);  // loops of patch p: order[first[p] ..]
  for (std::size_t l = 0; l < loops.size(); ++l) ++first[patch[l] + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  std::vector<std::uint32_t> order(loops.size()), at(first.begin(), first.end() - 1);
  for (std::size_t l = 0; l < loops.size(); ++l) order[at[patch[l]]++] = static_cast<std::uint32_t>(l);
  std::vector<int> sign(count, 0);
  for (std::size_t p = 0; p < count; ++p) {
    if (!closed[p] || first[p] == first[p + 1]) continue;
    const auto patch_loops = std::span(order).subspan(first[p], first[p + 1] - first[p]);
    const Vec3 origin = pos[loops[patch_loops[0]][0]];
    const auto sum = [&](auto& volume) {
      for (std::uint32_t l : patch_loops)
        for_each_fan_triangle<std::uint32_t>(
            pos, loops[l], [&](Vec3 a, Vec3 b, Vec3 c) { volume.add_triangle(a, b, c); });
      return volume.sign();
    };
    VolumeFilter filter(origin);
    sign[p] = sum(filter);
    if (sign[p] == 0) {
      ExactVolume exact(origin);
      sign[p] = sum(exact);
    }
  }
  return sign;
}

// Face-connected patches: polygons joined across two-use edges that `join` accepts.
// join(c, o) is asked once for each polygon not yet in a patch, across corner c of a
// polygon in the patch growing and its mate o, depth first from the lowest seed.
template <class Join>
std::vector<std::uint32_t> patches(const std::vector<Polygon>& polys, const EdgeTable& edges,
                                   Join join, std::uint32_t& count) {
  std::vector<std::uint32_t> patch(polys.size(), kNoRep);
  count = 0;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t seed = 0; seed < polys.size(); ++seed) {
    if (patch[seed] != kNoRep) continue;
    patch[seed] = count;
    stack.push_back(seed);
    while (!stack.empty()) {
      const std::uint32_t p = stack.back();
      stack.pop_back();
      for (std::size_t k = 0; k < polys[p].size(); ++k) {
        const std::uint32_t c = edges.corner(p, k), o = edges.mate(c);
        if (o == kNoRep) continue;
        const std::uint32_t q = edges.poly_of(o);
        if (patch[q] != kNoRep || !join(c, o)) continue;
        patch[q] = count;
        stack.push_back(q);
      }
    }
    ++count;
  }
  return patch;
}

// Whether every edge used by a patch is used by it equally often in both
// directions (a closed, consistently oriented shell).
std::vector<bool> closed_patches(const EdgeTable& edges, const std::vector<std::uint32_t>& patch,
                                 std::uint32_t count) {
  std::vector<bool> closed(count, true);
  std::vector<std::pair<std::uint32_t, int>> balance;  // (patch, +1 forward / -1 backward)
  for (std::uint32_t e = 0; e < edges.num_edges(); ++e) {
    const auto uses = edges.uses(e);
    if (uses.size() == 2 && patch[edges.poly_of(uses[0])] == patch[edges.poly_of(uses[1])] &&
        edges.forward(uses[0]) != edges.forward(uses[1]))
      continue;  // the common case, balanced
    balance.clear();
    for (std::uint32_t c : uses) balance.push_back({patch[edges.poly_of(c)], edges.forward(c) ? 1 : -1});
    std::sort(balance.begin(), balance.end());
    for (std::size_t i = 0; i < balance.size();) {
      int sum = 0;
      std::size_t j = i;
      for (; j < balance.size() && balance[j].first == balance[i].first; ++j) sum += balance[j].second;
      if (sum != 0) closed[balance[i].first] = false;
      i = j;
    }
  }
  return closed;
}

// The depth of each closed patch: how many other closed patches contain it (exact,
// geom/winding.h).
std::vector<std::uint32_t> patch_depths(const std::vector<Vec3>& pos,
                                        const std::vector<Polygon>& polys,
                                        const std::vector<std::uint32_t>& patch,
                                        const std::vector<bool>& closed) {
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<std::uint32_t> surface_of;
  for (std::size_t p = 0; p < polys.size(); ++p) {
    if (!closed[patch[p]]) continue;
    for (std::size_t i = 1; i + 1 < polys[p].size(); ++i) {
      triangles.push_back({polys[p][0], polys[p][i], polys[p][i + 1]});
      surface_of.push_back(patch[p]);
    }
  }
  return nest_surfaces(pos, triangles, surface_of, static_cast<std::uint32_t>(closed.size()))
      .depth;
}

std::size_t repair_orientation(const std::vector<Vec3>& pos, std::vector<Polygon>& polys) {
  const EdgeTable edges(polys);
  std::vector<std::int8_t> flip(polys.size(), 0);  // 1: reverse, relative to the patch's seed
  std::uint32_t count = 0;
  const auto patch = patches(
      polys, edges,
      [&](std::uint32_t c, std::uint32_t o) {
        // Agreeing neighbours run the shared edge in opposite directions.
        const bool same_way = edges.forward(c) == edges.forward(o);
        flip[edges.poly_of(o)] =
            static_cast<std::int8_t>(flip[edges.poly_of(c)] ^ (same_way ? 1 : 0));
        return true;
      },
      count);
  for (std::size_t p = 0; p < polys.size(); ++p)
    if (flip[p] == 1) std::reverse(polys[p].begin(), polys[p].end());
  // A closed patch points outward at even depth and inward (a cavity) at odd depth.
  const EdgeTable fixed(polys);
  const auto closed = closed_patches(fixed, patch, count);
  const std::vector<int> volume = patch_volume_signs(pos, polys, patch, closed);
  std::vector<std::uint32_t> depth;
  if (std::count(closed.begin(), closed.end(), true) > 1)
    depth = patch_depths(pos, polys, patch, closed);
  std::size_t flipped = 0;
  for (std::size_t p = 0; p < polys.size(); ++p) {
    const int want = depth.empty() || depth[patch[p]] % 2 == 0 ? 1 : -1;
    const bool turn = closed[patch[p]] && volume[patch[p]] == -want;
    if (turn) std::reverse(polys[p].begin(), polys[p].end());
    flipped += (turn != (flip[p] == 1)) ? 1 : 0;
  }
  return flipped;
}

// ---- merging coplanar triangles

bool degenerate_triangle(const std::vector<Vec3>& pos, const Polygon& t) {
  const Vec3 a = pos[t[0]], b = pos[t[1]], c = pos[t[2]];
  return collinear3d(a, b, c);
}

// Two triangles across corner c (of t1) and its mate o (of t2) lie in one plane and
// on opposite sides of the shared edge, running it in opposite directions.
bool flat_across(const std::vector<Vec3>& pos, const std::vector<Polygon>& polys,
                 const EdgeTable& edges, std::uint32_t c, std::uint32_t o) {
  if (edges.forward(c) == edges.forward(o)) return false;
  const Polygon& t1 = polys[edges.poly_of(c)];
  const Polygon& t2 = polys[edges.poly_of(o)];
  if (t1.size() != 3 || t2.size() != 3) return false;
  std::uint32_t d = kNoRep;
  for (std::uint32_t v : t2)
    if (v != t1[0] && v != t1[1] && v != t1[2]) d = v;
  if (d == kNoRep) return false;  // the same three vertices: a folded pair
  if (orient3d(pos[t1[0]], pos[t1[1]], pos[t1[2]], pos[d]) != 0) return false;
  // In the plane: t1's third vertex and d on opposite sides of the shared edge.
  const Vec3 n = cross(pos[t1[1]] - pos[t1[0]], pos[t1[2]] - pos[t1[0]]);
  const Projection proj(n);
  const std::size_t k = c - edges.corner(edges.poly_of(c), 0);
  const std::uint32_t a = t1[k], b = t1[(k + 1) % 3], third = t1[(k + 2) % 3];
  return orient2d(proj(pos[a]), proj(pos[b]), proj(pos[third])) *
             orient2d(proj(pos[a]), proj(pos[b]), proj(pos[d])) <
         0;
}

// The boundary of a patch of triangles as loops (outer first), or nothing when it
// is not a set of simple loops with exactly one counterclockwise outer loop.
std::vector<Polygon> patch_boundary(const std::vector<Vec3>& pos, const std::vector<Polygon>& polys,
                                    const EdgeTable& edges, const std::vector<std::uint32_t>& tris,
                                    const std::vector<std::uint32_t>& patch) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> out;  // directed boundary edges
  for (std::uint32_t t : tris) {
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t c = edges.corner(t, k), o = edges.mate(c);
      if (o != kNoRep && patch[edges.poly_of(o)] == patch[t]) continue;
      out.push_back({polys[t][k], polys[t][(k + 1) % 3]});
    }
  }
  std::sort(out.begin(), out.end());
  for (std::size_t i = 1; i < out.size(); ++i)
    if (out[i].first == out[i - 1].first) return {};  // a vertex where the boundary touches itself
  const auto next_of = [&](std::uint32_t v) {
    const auto it = std::lower_bound(out.begin(), out.end(), std::make_pair(v, 0u));
    return (it != out.end() && it->first == v) ? static_cast<std::size_t>(it - out.begin())
                                               : out.size();
  };
  std::vector<bool> used(out.size(), false);
  std::vector<Polygon> loops;
  const Vec3 n = cross(pos[polys[tris[0]][1]] - pos[polys[tris[0]][0]],
                       pos[polys[tris[0]][2]] - pos[polys[tris[0]][0]]);
  const Projection proj(n);
  int outer = -1;
  for (std::size_t s = 0; s < out.size(); ++s) {
    if (used[s]) continue;
    Polygon loop;
    for (std::size_t i = s; i < out.size() && !used[i]; i = next_of(out[i].second)) {
      used[i] = true;
      loop.push_back(out[i].first);
    }
    if (loop.size() < 3 || next_of(out[s].first) != s) return {};
    std::vector<Vec2> projected;
    projected.reserve(loop.size());
    for (std::uint32_t v : loop) projected.push_back(proj(pos[v]));
    if (area_sign(projected) > 0) {
      if (outer >= 0) return {};
      outer = static_cast<int>(loops.size());
    }
    loops.push_back(std::move(loop));
  }
  if (outer < 0) return {};
  std::swap(loops[0], loops[static_cast<std::size_t>(outer)]);
  return loops;
}

// Each merged patch becomes one face (its loops); other polygons stay as they are.
// first[i] is the index in polys of the first polygon of face i.
std::vector<std::vector<Polygon>> merge_coplanar(const std::vector<Vec3>& pos,
                                                 const std::vector<Polygon>& polys,
                                                 std::vector<std::uint32_t>& first) {
  const EdgeTable edges(polys);
  std::vector<bool> flat(polys.size());
  for (std::size_t p = 0; p < polys.size(); ++p)
    flat[p] = polys[p].size() == 3 && !degenerate_triangle(pos, polys[p]);
  std::uint32_t count = 0;
  const auto patch = patches(
      polys, edges,
      [&](std::uint32_t c, std::uint32_t o) {
        return flat[edges.poly_of(c)] && flat[edges.poly_of(o)] &&
               flat_across(pos, polys, edges, c, o);
      },
      count);
  std::vector<std::vector<std::uint32_t>> members(count);
  for (std::uint32_t p = 0; p < polys.size(); ++p) members[patch[p]].push_back(p);
  std::vector<std::vector<Polygon>> faces;
  faces.reserve(count);
  for (const auto& tris : members) {
    std::vector<Polygon> loops;
    if (tris.size() > 1) loops = patch_boundary(pos, polys, edges, tris, patch);
    if (!loops.empty()) {
      faces.push_back(std::move(loops));
      first.push_back(tris.front());
    } else {
      for (std::uint32_t t : tris) {
        faces.push_back({polys[t]});
        first.push_back(t);
      }
    }
  }
  return faces;
}

}  // namespace

Result<ReadResult> import_soup(Model& m, const PolygonSoup& soup, const ImportOptions& options) {
  const std::size_t n = soup.positions.size();
  const auto bad_index = [&](std::size_t i, const char* what, std::size_t k) {
    return i >= n ? std::optional<Error>(Error{ErrorCode::kInvalidInput,
                                               std::string(what) + " " + std::to_string(k) +
                                                   " names vertex " + std::to_string(i) + " of " +
                                                   std::to_string(n)})
                  : std::nullopt;
  };
  for (std::size_t p = 0; p < soup.polygons.size(); ++p)
    for (std::uint32_t i : soup.polygons[p])
      if (auto e = bad_index(i, "polygon", p)) return *e;
  for (std::size_t w = 0; w < soup.wires.size(); ++w)
    for (std::uint32_t i : soup.wires[w])
      if (auto e = bad_index(i, "wire", w)) return *e;
  for (std::size_t k = 0; k < soup.points.size(); ++k)
    if (auto e = bad_index(soup.points[k], "point", k)) return *e;

  ReadResult result;
  ImportReport& report = result.report;
  report.input_positions = n;
  report.input_polygons = soup.polygons.size();
  std::vector<Vec3> welded;
  auto map = weld(soup.positions, options.weld_tolerance, welded);
  if (!map) return map.error();
  report.welded_vertices = welded.size();

  std::vector<Polygon> polys;
  std::vector<std::uint32_t> source;  // per entry of polys, its index in the soup
  polys.reserve(soup.polygons.size());
  source.reserve(soup.polygons.size());
  for (std::size_t p = 0; p < soup.polygons.size(); ++p) {
    Polygon poly;
    for (std::uint32_t i : soup.polygons[p]) {
      const std::uint32_t w = (*map)[i];
      if (poly.empty() || poly.back() != w) poly.push_back(w);
    }
    while (poly.size() > 1 && poly.front() == poly.back()) poly.pop_back();
    Polygon sorted = poly;
    std::sort(sorted.begin(), sorted.end());
    if (poly.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      ++report.degenerate_dropped;
      if (report.degenerate_polygons.size() < 100) report.degenerate_polygons.push_back(p);
      continue;
    }
    polys.push_back(std::move(poly));
    source.push_back(static_cast<std::uint32_t>(p));
  }
  if (options.repair_orientation) report.flipped_faces = repair_orientation(welded, polys);

  std::vector<std::vector<Polygon>> faces;
  std::vector<std::uint32_t> face_source;  // per face, its polygon's index in the soup
  if (options.merge_coplanar) {
    std::vector<std::uint32_t> first;
    faces = merge_coplanar(welded, polys, first);
    for (std::uint32_t i : first) face_source.push_back(source[i]);
  } else {
    faces.reserve(polys.size());
    for (Polygon& p : polys) faces.push_back({std::move(p)});
    face_source = source;
  }
  report.merged_faces = faces.size();

  // Keep the positions something uses, in input order.
  std::vector<bool> used(welded.size(), false);
  for (const auto& f : faces)
    for (const Polygon& l : f)
      for (std::uint32_t i : l) used[i] = true;
  std::vector<std::array<std::uint32_t, 2>> wires;
  for (const auto& w : soup.wires) {
    const std::uint32_t a = (*map)[w[0]], b = (*map)[w[1]];
    if (a == b) continue;  // collapsed by welding
    wires.push_back({a, b});
    used[a] = used[b] = true;
  }
  for (std::uint32_t p : soup.points) used[(*map)[p]] = true;
  std::vector<std::uint32_t> compact(welded.size(), kNoRep);
  MeshInput in;
  for (std::size_t i = 0; i < welded.size(); ++i) {
    if (!used[i]) continue;
    compact[i] = static_cast<std::uint32_t>(in.positions.size());
    in.positions.push_back(welded[i]);
  }
  report.unused_vertices = welded.size() - in.positions.size();

  in.faces.reserve(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    MeshFace face;
    for (Polygon& l : faces[f]) {
      for (std::uint32_t& i : l) i = compact[i];
      face.loops.push_back(std::move(l));
    }
    in.faces.push_back(std::move(face));
  }
  // Wires duplicating a face edge or another wire are left out.
  if (!wires.empty()) {
    const auto key = [](std::uint32_t a, std::uint32_t b) {
      return a < b ? (std::uint64_t{a} << 32 | b) : (std::uint64_t{b} << 32 | a);
    };
    std::unordered_set<std::uint64_t> known;
    for (const MeshFace& f : in.faces)
      for (const Polygon& l : f.loops)
        for (std::size_t k = 0; k < l.size(); ++k) known.insert(key(l[k], l[(k + 1) % l.size()]));
    for (auto& w : wires) {
      const std::uint32_t a = compact[w[0]], b = compact[w[1]];
      if (known.insert(key(a, b)).second) in.wires.push_back({a, b});
    }
  }
  // The exact predicates order the faces around an edge of three or more exactly
  // while their coordinates are 0 or of magnitude 2^-80 to 2^120 (geom/predicates.h);
  // beyond, their products underflow or overflow, and a model built on a wrong order
  // would be invalid. The faces at such edges are held to that range.
  {
    std::unordered_map<std::uint64_t, std::uint32_t> uses;
    const auto key = [](std::uint32_t a, std::uint32_t b) {
      return a < b ? (std::uint64_t{a} << 32 | b) : (std::uint64_t{b} << 32 | a);
    };
    for (const MeshFace& f : in.faces)
      for (const Polygon& l : f.loops)
        for (std::size_t k = 0; k < l.size(); ++k) ++uses[key(l[k], l[(k + 1) % l.size()])];
    for (const MeshFace& f : in.faces) {
      bool radial = false;
      for (const Polygon& l : f.loops)
        for (std::size_t k = 0; k < l.size() && !radial; ++k) radial = uses[key(l[k], l[(k + 1) % l.size()])] > 2;
      if (!radial) continue;
      for (const Polygon& l : f.loops)
        for (std::uint32_t v : l)
          for (int k = 0; k < 3; ++k) {
            const Vec3 p = in.positions[v];
            const double x = std::abs(p[k]);
            if (x == 0 || (x >= 0x1p-80 && x <= 0x1p120)) continue;
            char text[320];
            std::snprintf(text, sizeof text,
                          "vertex %u (%.17g, %.17g, %.17g), on an edge of three faces or more: coordinate "
                          "%.17g is outside the range their order is decided in exactly (0, or 2^-80 to "
                          "2^120 in magnitude)",
                          v, p.x, p.y, p.z, p[k]);
            return Error{ErrorCode::kInvalidInput, text};
          }
    }
  }
  in.group_name = !options.group_name.empty() ? options.group_name : soup.name;
  auto built = build_mesh(m, in);
  if (!built) return built.error();
  result.group = built->group;
  // Provenance and colour, per face (mesh_io.h); the model may have the tables already.
  auto from = add_property<FaceProperty<std::uint32_t>>(m, kSourcePolygonProperty, kInvalidIndex);
  if (from) {
    for (std::size_t f = 0; f < built->faces.size(); ++f) from->set(built->faces[f], face_source[f]);
  }
  if (!soup.colours.empty()) {
    if (auto colour = add_property<FaceProperty<Colour>>(m, kColourProperty)) {
      for (std::size_t f = 0; f < built->faces.size(); ++f)
        colour->set(built->faces[f], soup.colours[face_source[f]]);
    }
  }
  if (options.volumes == VolumeMode::kAuto) {
    auto cells = make_region_volumes(m, built->group);
    if (!cells) return cells.error();
    report.closed_shells = *cells;
  }
  return result;
}

}  // namespace cellforge::io
