// Check "groups": the group index (detail/model_records.h) against the records.
// Every live element is listed by exactly one live group, the one its records name
// (a vertex's run, an edge's start vertex, a face's side row, a volume's record),
// and each group's counts are the number of elements it lists.
#include "topo/validate_checks.h"

namespace cellforge::inline topo::checks {

namespace {

template <class Range>
void check_kind(const Model& m, GroupId g, const char* kind, Range listed, std::size_t count,
                std::size_t& total, Violations& out) {
  std::size_t n = 0;
  for (auto id : listed) {
    ++n;
    if (m.group_of(id) != g) {
      out.push_back({"groups", g.str() + " lists " + id.str() + ", which is in " + m.group_of(id).str()});
    }
  }
  if (n != count) {
    out.push_back({"groups", g.str() + " lists " + std::to_string(n) + " " + kind + " but counts " +
                                 std::to_string(count)});
  }
  total += n;
}

}  // namespace

void groups(const Model& m, Violations& out) {
  std::size_t v = 0, e = 0, f = 0, c = 0;
  for (GroupId g : m.groups()) {
    check_kind(m, g, "vertices", m.vertices(g), m.num_vertices(g), v, out);
    check_kind(m, g, "edges", m.edges(g), m.num_edges(g), e, out);
    check_kind(m, g, "faces", m.faces(g), m.num_faces(g), f, out);
    check_kind(m, g, "volumes", m.volumes(g), m.num_volumes(g), c, out);
  }
  const auto total = [&](const char* kind, std::size_t listed, std::size_t live) {
    if (listed != live) {
      out.push_back({"groups", "the groups list " + std::to_string(listed) + " " + kind + " of " +
                                   std::to_string(live)});
    }
  };
  total("vertices", v, m.num_vertices());
  total("edges", e, m.num_edges());
  total("faces", f, m.num_faces());
  total("volumes", c, m.num_volumes());
}

}  // namespace cellforge::inline topo::checks
