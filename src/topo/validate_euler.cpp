// Check "euler": the Euler-Poincare relations.
//
// Manifold formula (seed 003), per closed shell: a shell is a set of faces joined
// through edges; it is closed when each of its edges has exactly two uses, and a
// surface when, besides, its faces form one fan around each of its vertices. Then
// v - e + f - r = 2 - 2h must give an integer genus h >= 0.
//
// Extended formula (seed 001), per connected component K of the model:
//   v - e + (f - r) - (V - Vh + Vc) = C - Ch + Cc,   C = 1 for each component.
// The left side counts cells. The right side is computed another way:
//   Vh, Vc  a volume's through-holes (genus of its bounding shells) and cavities
//           (its bounding shells less one);
//   Cc      the regions of space the component encloses: face sides are joined
//           across each wedge between radially consecutive faces; the classes
//           without a volume, less the one outside, are the cavities;
//   Ch      the independent 1-cycles, summed over the component's pieces: a closed
//           shell of genus g adds g for each side without a volume (2g for a bare
//           surface, g for a solid's boundary), an open shell adds 1 - (v-e+f-r),
//           a graph of wire edges adds e - v + 1.
// Summing over pieces is exact when the pieces meet in a tree of single vertices,
// no edge has more than two uses, and every shell is closed or open without
// non-manifold vertices inside it; components beyond that are counted but their
// right side is not compared (they are listed in EulerFigures::unchecked).
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "cellforge/geom/union_find.h"
#include "topo/operators_common.h"
#include "topo/validate_checks.h"

namespace cellforge::inline topo {

namespace {

template <class Fn>
void for_each_use(const Model& m, FaceId f, Fn fn) {
  for (LoopId l : m.loops_of(f)) {
    for (EdgeUseId u : ops::loop_uses(m, l)) fn(u);
  }
}

struct Analysis {
  EulerFigures total;
  std::vector<std::string> problems;  // manifold-formula and extended-formula failures
};

Analysis analyse(const Model& m) {
  Analysis a;
  const std::uint32_t nf = m.face_slots(), nv = m.vertex_slots();

  // Shells: faces joined through edges.
  UnionFind faces(nf);
  std::vector<EdgeUseId> uses;
  for (EdgeId e : m.edges()) {
    ops::radial_uses(m, e, uses);
    for (std::size_t i = 1; i < uses.size(); ++i) {
      faces.unite(m.face_of(uses[0]).value, m.face_of(uses[i]).value);
    }
  }
  // Pieces: shells (by root face), wire graphs (by root vertex, offset), isolated
  // vertices. Index pieces densely.
  // Each piece is named by its lowest element, for messages.
  std::vector<std::uint32_t> shell_piece(nf, kInvalidIndex);
  std::vector<std::string> piece_name;
  std::uint32_t pieces = 0;
  for (FaceId f : m.faces()) {
    const std::uint32_t r = faces.find(f.value);
    if (shell_piece[r] == kInvalidIndex) {
      shell_piece[r] = pieces++;
      piece_name.push_back("the shell of " + f.str());
    }
    shell_piece[f.value] = shell_piece[r];
  }
  const std::uint32_t shells = pieces;
  UnionFind wires(nv);
  for (EdgeId e : m.edges()) {
    if (m.is_wire(e)) wires.unite(m.start_of(e).value, m.end_of(e).value);
  }
  std::vector<std::uint32_t> wire_piece(nv, kInvalidIndex);
  for (EdgeId e : m.edges()) {
    if (!m.is_wire(e)) continue;
    const std::uint32_t r = wires.find(m.start_of(e).value);
    if (wire_piece[r] == kInvalidIndex) {
      wire_piece[r] = pieces++;
      piece_name.push_back("the wire graph of " + e.str());
    }
  }

  // Per piece counts.
  struct Piece {
    long v = 0, e = 0, f = 0, r = 0;
    bool closed = true, manifold = true;
    bool volume_front = false, volume_back = false;
    bool same_way = false;      // an edge whose two uses run the same way
    bool orientable = true;     // decided only for closed manifold shells with same_way
  };
  std::vector<Piece> piece(pieces);
  std::vector<std::vector<std::uint32_t>> pieces_at(nv);
  auto touch = [&](VertexId v, std::uint32_t p) {
    auto& list = pieces_at[v.value];
    if (std::find(list.begin(), list.end(), p) == list.end()) list.push_back(p);
  };
  for (FaceId f : m.faces()) {
    Piece& p = piece[shell_piece[f.value]];
    ++p.f;
    p.r += static_cast<long>(m.inner_loop_count(f));
    p.volume_front |= m.front_volume(f).is_valid();
    p.volume_back |= m.back_volume(f).is_valid();
    for (LoopId l : m.loops_of(f)) {
      if (m.is_point_loop(l)) touch(m.point_loop_vertex(l), shell_piece[f.value]);
    }
  }
  for (EdgeId e : m.edges()) {
    const std::size_t n = m.use_count(e);
    const std::uint32_t p = n == 0 ? wire_piece[wires.find(m.start_of(e).value)]
                                   : shell_piece[m.face_of(m.first_use(e)).value];
    ++piece[p].e;
    if (n > 2) piece[p].manifold = false;
    if (n != 2 && n != 0) piece[p].closed = false;
    if (n == 2) {
      const EdgeUseId u = m.first_use(e);
      if (m.is_reversed(u) == m.is_reversed(m.radial_next(u))) piece[p].same_way = true;
    }
    touch(m.start_of(e), p);
    touch(m.end_of(e), p);
  }
  for (VertexId v : m.vertices()) {
    if (pieces_at[v.value].empty()) {
      pieces_at[v.value].push_back(pieces++);
      piece.emplace_back();
      piece_name.push_back("the isolated vertex " + v.str());
    }
    for (std::uint32_t p : pieces_at[v.value]) ++piece[p].v;
  }
  // A shell pinched at a vertex (its faces there form more than one fan) is not a
  // surface: the manifold formula does not hold for it. Fans: the edge ends at a
  // vertex joined by each loop that passes through it from one edge to the next.
  UnionFind fans(2 * static_cast<std::size_t>(m.edge_slots()));
  for (EdgeUseId u : m.edge_uses()) {
    const EdgeUseId n = m.loop_next(u);
    fans.unite(2 * m.edge_of(u).value + (m.is_reversed(u) ? 0 : 1),
               2 * m.edge_of(n).value + (m.is_reversed(n) ? 1 : 0));
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> seen;  // (shell, fan) at a vertex
  for (VertexId v : m.vertices()) {
    seen.clear();
    for (EdgeEnd end : m.ends_around(v)) {
      const EdgeUseId u = m.first_use(end.edge);
      if (!u.is_valid()) continue;
      const std::uint32_t shell = shell_piece[m.face_of(u).value];
      const std::uint32_t fan = fans.find(2 * end.edge.value + static_cast<std::uint32_t>(end.end));
      for (const auto& [s2, f2] : seen) {
        if (s2 == shell && f2 != fan) piece[shell].manifold = false;
      }
      seen.emplace_back(shell, fan);
    }
  }

  // A closed surface whose faces cannot all be turned to agree along every edge is not
  // orientable (a projective plane, a Klein bottle: read from a mesh file, say): its
  // v - e + f is 2 - k for k >= 1 cross-caps, and it bounds nothing.
  {
    std::vector<std::int8_t> flip(m.face_slots(), -1);
    std::vector<FaceId> stack;
    std::vector<EdgeUseId> radial;
    for (FaceId f : m.faces()) {
      Piece& q = piece[shell_piece[f.value]];
      if (!q.closed || !q.manifold || !q.same_way || flip[f.value] >= 0) continue;
      flip[f.value] = 0;
      stack.assign(1, f);
      while (!stack.empty()) {
        const FaceId g = stack.back();
        stack.pop_back();
        for (LoopId l : m.loops_of(g))
          for (EdgeUseId u : m.uses_of(l)) {
            ops::radial_uses(m, m.edge_of(u), radial);
            for (EdgeUseId w : radial) {
              if (w == u) continue;
              const FaceId h = m.face_of(w);
              const std::int8_t need =
                  static_cast<std::int8_t>(flip[g.value] ^ (m.is_reversed(u) == m.is_reversed(w) ? 1 : 0));
              if (flip[h.value] < 0) {
                flip[h.value] = need;
                stack.push_back(h);
              } else if (flip[h.value] != need) {
                q.orientable = false;
              }
            }
          }
      }
    }
  }

  // Components: pieces joined at shared vertices and through volumes. A vertex
  // join that closes a cycle of pieces makes the component unsummable.
  UnionFind comp(pieces);
  std::vector<std::uint32_t> cyclic;
  for (VertexId v : m.vertices()) {
    const auto& list = pieces_at[v.value];
    for (std::size_t i = 1; i < list.size(); ++i) {
      if (!comp.unite(list[0], list[i])) cyclic.push_back(list[0]);
    }
  }
  // Shells that touch, at a common vertex or through a wire graph that reaches both,
  // see one void region where they meet: each join of two shells not yet joined so
  // merges two of the void classes counted below.
  std::vector<std::uint32_t> shell_contacts;  // a shell of each join
  {
    UnionFind joined(pieces);
    for (VertexId v : m.vertices()) {
      std::uint32_t first_shell = kInvalidIndex;
      for (std::uint32_t p : pieces_at[v.value]) {
        if (p >= shells) continue;
        if (first_shell == kInvalidIndex) first_shell = p;
        else if (joined.unite(first_shell, p)) shell_contacts.push_back(p);
      }
    }
    std::vector<std::uint32_t> wire_shell(pieces, kInvalidIndex);  // a shell the wire graph reaches
    for (VertexId v : m.vertices()) {
      const auto& list = pieces_at[v.value];
      for (std::uint32_t w : list) {
        if (w < shells) continue;  // a wire graph (an isolated vertex is alone)
        for (std::uint32_t p : list) {
          if (p >= shells) continue;
          if (wire_shell[w] == kInvalidIndex) wire_shell[w] = p;
          else if (joined.unite(wire_shell[w], p)) shell_contacts.push_back(p);
        }
      }
    }
  }
  std::vector<VolumeId> vols;
  for (VolumeId c : m.volumes()) vols.push_back(c);
  std::vector<std::vector<std::uint32_t>> vol_shells(vols.size());
  {
    std::vector<std::uint32_t> index(vols.empty() ? 0 : vols.back().value + 1, kInvalidIndex);
    for (std::size_t i = 0; i < vols.size(); ++i)
      index[vols[i].value] = static_cast<std::uint32_t>(i);
    for (FaceId f : m.faces()) {
      for (VolumeId c : {m.front_volume(f), m.back_volume(f)}) {
        if (!c.is_valid()) continue;
        auto& list = vol_shells[index[c.value]];
        const std::uint32_t s = shell_piece[f.value];
        if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
      }
    }
  }
  for (const auto& list : vol_shells) {
    for (std::size_t i = 1; i < list.size(); ++i) comp.unite(list[0], list[i]);
  }

  // Void regions: face sides joined across wedges.
  UnionFind sides(2 * static_cast<std::size_t>(nf));
  auto side = [&](EdgeUseId u, bool after) {
    // after: the side looking towards increasing angle; front = index 0.
    const bool front = after != m.is_reversed(u);
    return 2 * m.face_of(u).value + (front ? 0u : 1u);
  };
  for (EdgeId e : m.edges()) {
    ops::radial_uses(m, e, uses);
    for (std::size_t i = 0; i < uses.size(); ++i) {
      sides.unite(side(uses[i], true), side(uses[(i + 1) % uses.size()], false));
    }
  }

  // Per component tallies, keyed by the component root piece.
  struct Tally {
    long v = 0, e = 0, f = 0, r = 0, V = 0, Vh = 0, Vc = 0, Ch = 0, voids = 0, contacts = 0;
    bool summable = true;
  };
  std::vector<Tally> tally(pieces);
  for (std::uint32_t p = 0; p < pieces; ++p) {
    Tally& t = tally[comp.find(p)];
    const Piece& q = piece[p];
    t.v += q.v;  // shared vertices are subtracted below
    t.e += q.e;
    t.f += q.f;
    t.r += q.r;
    if (p < shells) {
      const long chi = q.v - q.e + q.f - q.r;
      if (!q.manifold) {
        t.summable = false;
      } else if (q.closed && !q.orientable) {
        if (q.volume_front || q.volume_back)
          a.problems.push_back(piece_name[p] + ", a closed surface that is not orientable, bounds a volume");
        else if (chi > 1)
          a.problems.push_back(piece_name[p] + ", a closed surface that is not orientable, has v - e + f - r = " +
                               std::to_string(chi) + ", above 1");
        t.summable = false;
      } else if (q.closed) {
        if (chi > 2 || (chi % 2) != 0) {
          a.problems.push_back(piece_name[p] + ", a closed shell, has v - e + f - r = " +
                               std::to_string(chi) + " (v=" + std::to_string(q.v) +
                               " e=" + std::to_string(q.e) + " f=" + std::to_string(q.f) +
                               " r=" + std::to_string(q.r) + "), which gives no integer genus h >= 0");
          t.summable = false;
        } else {
          const long g = (2 - chi) / 2;
          t.Ch += g * (2 - (q.volume_front ? 1 : 0) - (q.volume_back ? 1 : 0));
        }
      } else {
        t.Ch += 1 - chi;
      }
    } else {
      t.Ch += q.e - q.v + 1;
    }
  }
  for (VertexId v : m.vertices()) {
    const auto& list = pieces_at[v.value];
    if (list.size() > 1) tally[comp.find(list[0])].v -= static_cast<long>(list.size() - 1);
  }
  for (std::uint32_t p : shell_contacts) ++tally[comp.find(p)].contacts;
  for (std::uint32_t p : cyclic) tally[comp.find(p)].summable = false;
  for (std::size_t i = 0; i < vols.size(); ++i) {
    Tally& t = tally[comp.find(vol_shells[i].empty() ? 0 : vol_shells[i][0])];
    ++t.V;
    if (vol_shells[i].empty()) continue;
    t.Vc += static_cast<long>(vol_shells[i].size()) - 1;
    for (std::uint32_t s : vol_shells[i]) {
      const Piece& q = piece[s];
      t.Vh += (2 - (q.v - q.e + q.f - q.r)) / 2;
      if (!q.closed || !q.manifold) t.summable = false;
    }
  }
  std::vector<char> void_seen(2 * static_cast<std::size_t>(nf), 0);
  for (FaceId f : m.faces()) {
    for (int s = 0; s < 2; ++s) {
      const VolumeId c = s == 0 ? m.front_volume(f) : m.back_volume(f);
      const std::uint32_t root = sides.find(2 * f.value + s);
      if (c.is_valid() || void_seen[root]) continue;
      void_seen[root] = 1;
      ++tally[comp.find(shell_piece[f.value])].voids;
    }
  }

  EulerFigures& fig = a.total;
  fig.shells = shells;
  for (std::uint32_t p = 0; p < pieces; ++p) {
    if (comp.find(p) != p) continue;
    const Tally& t = tally[p];
    const long cavities = t.voids > 0 ? t.voids - 1 - t.contacts : 0;
    fig.v += t.v;
    fig.e += t.e;
    fig.f += t.f;
    fig.r += t.r;
    fig.volumes += t.V;
    fig.volume_holes += t.Vh;
    fig.volume_cavities += t.Vc;
    fig.components += 1;
    fig.holes += t.Ch;
    fig.cavities += cavities;
    if (!t.summable) {
      ++fig.unchecked;
      continue;
    }
    const long lhs = t.v - t.e + (t.f - t.r) - (t.V - t.Vh + t.Vc);
    const long rhs = 1 - t.Ch + cavities;
    if (lhs != rhs) {
      a.problems.push_back(
          "extended Euler formula fails on the component holding " + piece_name[p] +
          ": v - e + (f - r) - (V - Vh + Vc) = " +
          std::to_string(lhs) + " but C - Ch + Cc = " + std::to_string(rhs) +
          " (v=" + std::to_string(t.v) + " e=" + std::to_string(t.e) + " f=" + std::to_string(t.f) +
          " r=" + std::to_string(t.r) + " V=" + std::to_string(t.V) +
          " Vh=" + std::to_string(t.Vh) + " Vc=" + std::to_string(t.Vc) +
          " Ch=" + std::to_string(t.Ch) + " Cc=" + std::to_string(cavities) + ")");
    }
  }
  return a;
}

}  // namespace

EulerFigures euler_figures(const Model& m) { return analyse(m).total; }

namespace checks {

void euler(const Model& m, Violations& out) {
  for (std::string& p : analyse(m).problems) out.push_back({"euler", std::move(p)});
}

}  // namespace checks

}  // namespace cellforge::inline topo
