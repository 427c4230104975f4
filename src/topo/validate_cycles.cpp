// Checks "vertex", "radial" and "loop": each cycle closes within the number of
// elements that could be on it, contains only elements that belong there, and
// together the cycles account for every edge end, use and loop exactly once.
#include "topo/model_editor.h"
#include "topo/validate_checks.h"

namespace cellforge::inline topo::checks {

void vertex_cycles(const Model& m, Violations& out) {
  auto fail = [&](std::string msg) { out.push_back({"vertex", std::move(msg)}); };
  const std::size_t limit = 2 * m.num_edges();
  std::size_t total = 0;
  for (VertexId v : m.vertices()) {
    std::size_t n = 0;
    for (EdgeEnd end : m.ends_around(v)) {  // stopped after `limit` ends if it does not close
      if (m.vertex_of(end.edge, end.end) != v) {
        fail("the edge cycle of " + v.str() + " reaches " + end.edge.str() + ", which ends at " +
             m.vertex_of(end.edge, end.end).str());
        break;
      }
      if (++n > limit) break;
    }
    if (n > limit) fail("the edge cycle of " + v.str() + " does not close");
    total += n;
  }
  if (total != 2 * m.num_edges()) {
    fail("the vertex cycles hold " + std::to_string(total) + " edge ends; there are " +
         std::to_string(2 * m.num_edges()));
  }
}

void radial_cycles(const Model& m, Violations& out) {
  auto fail = [&](std::string msg) { out.push_back({"radial", std::move(msg)}); };
  const std::size_t limit = m.num_edge_uses();
  std::size_t total = 0;
  std::vector<EdgeUseId> cycle;
  FaceNormals normals;  // the model does not change while it is checked
  for (EdgeId e : m.edges()) {
    if (m.is_wire(e)) continue;
    cycle.clear();
    bool ok = true;
    for (EdgeUseId u : m.radial(e)) {  // stopped after `limit` uses if it does not close
      if (m.edge_of(u) != e) {
        fail("the radial cycle of " + e.str() + " reaches " + u.str() + ", a use of " +
             m.edge_of(u).str());
        ok = false;
        break;
      }
      cycle.push_back(u);
      if (cycle.size() > limit) break;
    }
    if (cycle.size() > limit) {
      fail("the radial cycle of " + e.str() + " does not close");
      ok = false;
    }
    total += cycle.size();
    if (ok && !radially_ordered(m, e, cycle, &normals)) {
      fail("the radial cycle of " + e.str() + " is not in angular order");
    }
  }
  if (total != m.num_edge_uses()) {
    fail("the radial cycles hold " + std::to_string(total) + " uses; there are " +
         std::to_string(m.num_edge_uses()));
  }
}

void loops(const Model& m, Violations& out) {
  auto fail = [&](std::string msg) { out.push_back({"loop", std::move(msg)}); };
  std::size_t uses = 0, loops_seen = 0;
  for (FaceId f : m.faces()) {
    std::size_t n = 0;
    for (LoopId l : m.loops_of(f)) {
      if (++n > m.num_loops()) {
        fail("the loop list of " + f.str() + " does not end");
        return;
      }
      if (m.face_of(l) != f) fail(l.str() + " is listed by " + f.str() + " but names another face");
      if (m.is_point_loop(l)) continue;
      std::size_t k = 0;
      for (EdgeUseId u : m.uses_of(l)) {  // stopped after every use if it does not close
        if (m.face_of(u) != f)
          fail(u.str() + " in " + l.str() + " names face " + m.face_of(u).str());
        const EdgeUseId next = m.loop_next(u);
        if (m.use_end(u) != m.use_start(next)) {
          fail(l.str() + ": " + u.str() + " ends at " + m.use_end(u).str() + " but " + next.str() +
               " starts at " + m.use_start(next).str());
        }
        if (++k > m.num_edge_uses()) break;
      }
      if (k > m.num_edge_uses()) fail(l.str() + " does not close");
      uses += k;
    }
    loops_seen += n;
  }
  if (loops_seen != m.num_loops()) {
    fail("faces list " + std::to_string(loops_seen) + " loops; there are " +
         std::to_string(m.num_loops()));
  }
  if (uses != m.num_edge_uses()) {
    fail("loops hold " + std::to_string(uses) + " uses; there are " +
         std::to_string(m.num_edge_uses()));
  }
}

}  // namespace cellforge::inline topo::checks
