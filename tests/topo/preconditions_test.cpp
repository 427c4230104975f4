// Every operator precondition, violated once: the error names it and the model is
// unchanged (compared as a raw dump, ids included).
#include <gtest/gtest.h>

#include <functional>

#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

struct Case {
  const char* expect;              // a piece of the error message
  std::function<bool(Model&)> op;  // returns whether the operator succeeded
};

template <class R>
bool ok(const R& r) {
  return r.ok();
}

void expect_all_refused(Model& m, const std::vector<Case>& cases) {
  for (const Case& c : cases) {
    const std::string before = raw_dump(m);
    const bool succeeded = c.op(m);
    EXPECT_FALSE(succeeded) << "expected refusal: " << c.expect;
    EXPECT_EQ(raw_dump(m), before) << "a refused operation changed the model: " << c.expect;
  }
}

#define REFUSE(text, call)                                               \
  Case {                                                                 \
    text, [&](Model& m_) {                                               \
      (void)m_;                                                          \
      const auto r = (call);                                             \
      if (r.ok()) return true;                                           \
      EXPECT_NE(r.error().message.find(text), std::string::npos)         \
          << "message: " << r.error().message << "\nexpected: " << text; \
      return false;                                                      \
    }                                                                    \
  }

TEST(Preconditions, VolumesGroupsAndFaces) {
  Model m = build(two_cubes_sharing_face());
  const GroupId g = *m.groups().begin();
  const FaceId shared = face_at(m, {0.5, 0.5, 1});
  const FaceId bottom = face_at(m, {0.5, 0.5, 0});
  const GroupId other = make_group(m, "other");
  auto lone = make_vertex(m, other, {9, 9, 9});
  const VertexId a = vertex_at(m, {0, 0, 0}), b = vertex_at(m, {1, 0, 0});
  expect_all_refused(
      m,
      {
          REFUSE("kill_group: group", kill_group(m, g)),
          REFUSE("make_volume: no face sides given", make_volume(m, g, {})),
          REFUSE("is not in group", make_volume(m, other, {{bottom, true}})),
          REFUSE("given twice", make_volume(m, g, {{bottom, true}, {bottom, true}})),
          REFUSE("already bounds", make_volume(m, g, {{bottom, false}})),
          REFUSE("kill_volume: volume c9", kill_volume(m, VolumeId(9))),
          REFUSE("make_face: no loops", make_face(m, {})),
          REFUSE("fewer than 3 vertices", make_face(m, {{{a, b}}})),
          REFUSE("is not in group", make_face(m, {{{a, b, *lone}}})),
          REFUSE("repeats vertex", make_face(m, {{{a, b, b}}})),
          REFUSE("kill_face: face", kill_face(m, shared)),
          REFUSE("kill_vertex: vertex", kill_vertex(m, a)),
          REFUSE("in different groups", make_wire_edge(m, a, *lone)),
          REFUSE("must have a volume on its back and none in front", glue_faces(m, shared, bottom)),
          REFUSE("kvsf: face", kvsf(m, a, bottom)),
      });
}

TEST(Preconditions, EulerOperatorsOnShapes) {
  Model m;
  const GroupId g = *euler_box_with_hole(m, {0, 0, 0}, {3, 3, 3}, 1, 2);
  FaceId top;
  for (FaceId f : m.faces()) {
    if (m.inner_loop_count(f) == 1 && m.face_normal(f).z > 0) top = f;
  }
  ASSERT_TRUE(top.is_valid());
  const LoopId outer = m.outer_loop(top), ring = m.next_loop(outer);
  const FaceId wall = m.face_of(m.first_use(edge_at(m, {1, 1, 0}, {1, 1, 3})));
  const VertexId rim = vertex_at(m, {1, 1, 3}), corner = vertex_at(m, {0, 0, 3});
  const EdgeId vertical = edge_at(m, {0, 0, 0}, {0, 0, 3});
  auto other = make_group(m, "other");
  (void)g;
  expect_all_refused(
      m,
      {
          REFUSE("is an outer loop (must be inner)", mekr(m, ring, rim, outer, corner)),
          REFUSE("is not on loop", mekr(m, outer, rim, ring, corner)),
          REFUSE("has inner loops", kfmrh(m, wall, top)),
          REFUSE("is not on the outer loop of face", kef(m, edge_at(m, {1, 1, 3}, {2, 1, 3}), top)),
          REFUSE("has 3 edges (must have 2)", jekv(m, vertical, vertex_at(m, {0, 0, 0}))),
          REFUSE("in different loops", kemr(m, m.first_use(vertical))),
      });
  (void)other;
}

TEST(Preconditions, StrutsAndParallelEdges) {
  Model m;
  const GroupId g = make_group(m);
  ASSERT_OK(euler_box_into(m, g, {0, 0, 0}, {1, 1, 1}, false));
  FaceId top;
  for (FaceId f : m.faces()) {
    if (m.face_normal(f).z > 0) top = f;
  }
  auto strut = mev(m, m.outer_loop(top), vertex_at(m, {0, 0, 1}), {0.5, 0.5, 1});
  ASSERT_OK(strut);
  auto tip = make_vertex(m, g, {0.5, 0.5, 2});
  ASSERT_OK(make_wire_edge(m, strut->vertex, *tip));
  EdgeUseId in = m.first_use(strut->edge);
  if (m.use_end(in) != strut->vertex) in = m.radial_next(in);
  auto p = make_vertex(m, g, {5, 0, 0});
  auto q = make_vertex(m, g, {6, 0, 0});
  auto twin = make_vertex(m, g, {6, 0, 0});
  auto e1 = make_wire_edge(m, *p, *q);
  ASSERT_OK(make_wire_edge(m, *p, *q));
  ASSERT_OK(make_wire_edge(m, *q, *twin));
  expect_all_refused(m, {
                            REFUSE("would carry a point loop", kemr(m, in)),
                            REFUSE("join the same vertices", jekv(m, *e1, *p)),
                            REFUSE("joins", merge_vertices(m, *q, *twin)),
                        });
}

TEST(Preconditions, SplitsAndMerges) {
  Model m = build(two_cubes_sharing_edge());
  const EdgeId e = edge_at(m, {1, 1, 0}, {1, 1, 1});
  const EdgeId plain = edge_at(m, {0, 0, 0}, {1, 0, 0});
  const VertexId v = vertex_at(m, {1, 1, 0});
  const EdgeUseId u = m.first_use(e), w = m.radial_next(u);
  std::vector<EdgeUseId> all;
  for (EdgeUseId x = u;;) {
    all.push_back(x);
    x = m.radial_next(x);
    if (x == u) break;
  }
  expect_all_refused(
      m, {
             REFUSE("no uses to move", split_edge(m, e, {})),
             REFUSE("is not a use of", split_edge(m, plain, {u})),
             REFUSE("given twice", split_edge(m, e, {u, u})),
             REFUSE("all uses of", split_edge(m, e, all)),
             REFUSE("would face different volumes", split_edge(m, e, {u})),
             REFUSE("no edge ends to move", split_vertex(m, v, {})),
             REFUSE("is not at", split_vertex(m, v, {{plain, 0}})),
             REFUSE("given twice", split_vertex(m, v, {m.first_end(v), m.first_end(v)})),
             REFUSE("both edges are", merge_edges(m, e, e)),
             REFUSE("both vertices are", merge_vertices(m, v, v)),
         });
  (void)w;
}

}  // namespace
}  // namespace cellforge
