// Groups as parts: the group index (Model::faces(g) and friends) against a scan of
// the whole model, through the builder, the operators and deletions; the property
// tables through edits; extract and append with their id maps.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "cellforge/topo/builder.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/parts.h"
#include "cellforge/topo/property.h"
#include "cellforge/topo/snapshot.h"
#include "support/checks.h"
#include "support/fixtures.h"

namespace cellforge {
namespace {

using namespace testing;

template <class Range>
auto collect(const Range& r) {
  std::vector<std::decay_t<decltype(*r.begin())>> out;
  for (auto id : r) out.push_back(id);
  return out;
}

// What the group index must list for g, found by scanning every element.
template <class IdT, class Range>
std::vector<IdT> scan(const Model& m, const Range& all, GroupId g) {
  std::vector<IdT> out;
  for (IdT id : all)
    if (m.group_of(id) == g) out.push_back(id);
  return out;
}

void expect_index_matches_scan(const Model& m) {
  for (GroupId g : m.groups()) {
    EXPECT_EQ(collect(m.vertices(g)), scan<VertexId>(m, m.vertices(), g)) << g.str();
    EXPECT_EQ(collect(m.edges(g)), scan<EdgeId>(m, m.edges(), g)) << g.str();
    EXPECT_EQ(collect(m.faces(g)), scan<FaceId>(m, m.faces(), g)) << g.str();
    EXPECT_EQ(collect(m.volumes(g)), scan<VolumeId>(m, m.volumes(), g)) << g.str();
    EXPECT_EQ(m.num_vertices(g), scan<VertexId>(m, m.vertices(), g).size());
    EXPECT_EQ(m.num_edges(g), scan<EdgeId>(m, m.edges(), g).size());
    EXPECT_EQ(m.num_faces(g), scan<FaceId>(m, m.faces(), g).size());
    EXPECT_EQ(m.num_volumes(g), scan<VolumeId>(m, m.volumes(), g).size());
  }
}

Model three_groups() {
  Model m;
  for (const MeshInput& in : {unit_cube(), two_cubes_sharing_edge(), book()}) {
    auto r = build_mesh(m, in);
    EXPECT_TRUE(r.ok());
  }
  return m;
}

TEST(GroupIndex, BuiltGroupsListWhatTheBuilderMade) {
  Model m;
  std::vector<BuildResult> built;
  for (const MeshInput& in : {unit_cube(), cube_with_wire_and_point(), two_cubes_sharing_edge()}) {
    auto r = build_mesh(m, in);
    ASSERT_OK(r);
    built.push_back(*r);
  }
  for (const BuildResult& b : built) {
    EXPECT_EQ(collect(m.faces(b.group)), b.faces);
    EXPECT_EQ(collect(m.vertices(b.group)), b.vertices);
    EXPECT_EQ(collect(m.volumes(b.group)), b.volumes);
  }
  EXPECT_EQ(m.num_edges(built[0].group), 12u);
  EXPECT_EQ(m.num_edges(built[1].group), 13u);  // the cube's 12 and the wire
  EXPECT_EQ(m.num_vertices(built[1].group), 10u);
  EXPECT_EQ(m.num_volumes(built[2].group), 2u);
  expect_index_matches_scan(m);
  EXPECT_VALID(m);
}

// Random edits over three groups: vertices, wires and triangles made and killed in
// any group, so that freed slots are taken by other groups and the runs split.
TEST(GroupIndex, FollowsOperatorsAndDeletions) {
  for (unsigned seed = 1; seed <= 6; ++seed) {
    std::mt19937 rng(seed);
    Model m = three_groups();
    const std::vector<GroupId> groups = collect(m.groups());
    const auto pick = [&](auto range) {
      auto v = collect(range);
      using T = typename decltype(v)::value_type;
      return v.empty() ? T() : v[rng() % v.size()];
    };
    for (int step = 0; step < 150; ++step) {
      const GroupId g = groups[rng() % groups.size()];
      switch (rng() % 5) {
        case 0:
          ASSERT_OK(make_vertex(m, g, {double(rng() % 100), double(rng() % 100), 7.0 + step}));
          break;
        case 1: {  // a triangle on three vertices of g
          std::vector<VertexId> vs = collect(m.vertices(g));
          std::shuffle(vs.begin(), vs.end(), rng);
          if (vs.size() < 3) break;
          const FaceSpec spec{{{vs[0], vs[1], vs[2]}}};
          if (can_make_face(m, spec)) ASSERT_OK(make_face(m, spec));
          break;
        }
        case 2: {
          const VertexId a = pick(m.vertices(g));
          const VertexId b = pick(m.vertices(g));
          if (a.is_valid() && can_make_wire_edge(m, a, b)) ASSERT_OK(make_wire_edge(m, a, b));
          break;
        }
        case 3: {
          const FaceId f = pick(m.faces(g));
          if (f.is_valid() && can_kill_face(m, f))
            ASSERT_OK(kill_face(m, f, {.kill_bare_edges = true, .kill_bare_vertices = true}));
          break;
        }
        default: {
          const EdgeId e = pick(m.edges(g));
          if (e.is_valid() && can_kill_wire_edge(m, e)) ASSERT_OK(kill_wire_edge(m, e));
          const VertexId v = pick(m.vertices(g));
          if (v.is_valid() && can_kill_vertex(m, v)) ASSERT_OK(kill_vertex(m, v));
        }
      }
      expect_index_matches_scan(m);
      if (HasFailure()) FAIL() << "seed " << seed << " step " << step;
    }
    // (Sheet triangles made across the solids leave wedges that name no volume: the
    // structure's own checks are what matters here.)
    for (const Violation& v : validate(m))
      EXPECT_TRUE(v.check == "wedge" || v.check == "euler") << v.check << ": " << v.message;
    EXPECT_GT(m.group_runs(), 4u * groups.size());  // slots did change hands
  }
}

TEST(GroupIndex, EulerOperatorsAndKillGroup) {
  Model m;
  auto a = euler_box(m, {0, 0, 0}, {1, 1, 1}, true, "a");
  auto b = euler_box_with_hole(m, {0, 0, 4}, {3, 3, 7}, 1, 2, "b");
  ASSERT_OK(a);
  ASSERT_OK(b);
  EXPECT_EQ(m.num_faces(*a), 6u);
  EXPECT_EQ(m.num_faces(*b), 10u);  // 6 sides and 4 walls of the hole
  EXPECT_EQ(m.num_vertices(*b), 16u);
  EXPECT_EQ(m.num_edges(*b), 24u);
  expect_index_matches_scan(m);
  EXPECT_VALID(m);
  // An empty group can be killed; its slot, reused, lists nothing of the old one.
  const GroupId e = make_group(m, "empty");
  EXPECT_TRUE(m.group_empty(e));
  EXPECT_FALSE(kill_group(m, *a).ok());
  ASSERT_OK(kill_group(m, e));
  const GroupId again = make_group(m, "again");
  EXPECT_TRUE(collect(m.faces(again)).empty());
  ASSERT_OK(make_vertex(m, again, {9, 9, 9}));
  EXPECT_EQ(m.num_vertices(again), 1u);
  expect_index_matches_scan(m);
  EXPECT_VALID(m);
}

TEST(Properties, FollowTheOperators) {
  Model m;
  auto g = euler_box(m, {0, 0, 0}, {1, 1, 1}, true);
  ASSERT_OK(g);
  auto source = add_property<FaceProperty<std::uint32_t>>(m, "source", kInvalidIndex);
  auto colour = add_property<FaceProperty<Colour>>(m, "colour");
  auto weight = add_property<VertexProperty<double>>(m, "weight", -1.0);
  ASSERT_OK(source);
  ASSERT_OK(colour);
  ASSERT_OK(weight);
  for (FaceId f : m.faces()) source->set(f, 100 + f.value);
  const FaceId top = face_at(m, {0.5, 0.5, 1});
  colour->set(top, {1, 0, 0, 1});
  for (VertexId v : m.vertices()) weight->set(v, v.value * 0.5);

  // mef splits the top: the old face keeps its values, the new one has the defaults.
  const VertexId a = vertex_at(m, {0, 0, 1});
  const VertexId c = vertex_at(m, {1, 1, 1});
  auto split = mef(m, m.outer_loop(top), a, c);
  ASSERT_OK(split);
  EXPECT_EQ((*source)[top], 100 + top.value);
  EXPECT_EQ((*source)[split->face], kInvalidIndex);
  EXPECT_EQ((*colour)[top], (Colour{1, 0, 0, 1}));
  EXPECT_EQ((*colour)[split->face], Colour{});
  for (FaceId f : m.faces()) {
    if (f != split->face) {
      EXPECT_EQ((*source)[f], 100 + f.value) << f.str();
    }
  }
  // semv: a new vertex with the default weight, the others keep theirs.
  auto mid = semv(m, split->edge, {0.5, 0.5, 1});
  ASSERT_OK(mid);
  EXPECT_EQ((*weight)[mid->vertex], -1.0);
  EXPECT_EQ((*weight)[a], a.value * 0.5);

  // Undo: the split face dies and its slot goes back to the default; a face made
  // later in that slot starts from the default too.
  source->set(split->face, 7);
  ASSERT_OK(jekv(m, mid->edge, mid->vertex));
  ASSERT_OK(kef(m, split->edge, split->face));
  EXPECT_FALSE(m.is_live(split->face));
  EXPECT_EQ((*source)[split->face], kInvalidIndex);
  auto again = mef(m, m.outer_loop(top), a, c);
  ASSERT_OK(again);
  EXPECT_EQ(again->face, split->face);  // the slot is reused
  EXPECT_EQ((*source)[again->face], kInvalidIndex);
  EXPECT_EQ((*colour)[top], (Colour{1, 0, 0, 1}));
  EXPECT_VALID(m);

  // A copy of the model has its own tables.
  Model copy = m;
  auto copied = find_property<FaceProperty<std::uint32_t>>(copy, "source");
  ASSERT_TRUE(copied.is_valid());
  copied.set(top, 1);
  EXPECT_EQ((*source)[top], 100 + top.value);
  EXPECT_EQ(copied[top], 1u);
}

TEST(Properties, NamesAndTypes) {
  Model m = build(unit_cube());
  ASSERT_OK(add_property<FaceProperty<int>>(m, "tag", 3));
  auto same = add_property<FaceProperty<int>>(m, "tag", 99);  // the existing one
  ASSERT_OK(same);
  EXPECT_EQ(same->default_value(), 3);
  const auto clash = add_property<FaceProperty<double>>(m, "tag");
  ASSERT_FALSE(clash.ok());
  EXPECT_NE(clash.error().message.find("another value type"), std::string::npos);
  ASSERT_OK(add_property<EdgeProperty<double>>(m, "tag"));  // another kind, another table
  EXPECT_FALSE(find_property<FaceProperty<double>>(m, "tag").is_valid());
  const Model& cm = m;
  EXPECT_EQ(find_property<FaceProperty<int>>(cm, "tag")[*m.faces().begin()], 3);
  EXPECT_EQ(property_names<FaceId>(m), std::vector<std::string>{"tag"});
  EXPECT_TRUE(remove_property<FaceId>(m, "tag"));
  EXPECT_FALSE(find_property<FaceProperty<int>>(m, "tag").is_valid());
}

TEST(Parts, ExtractEachGroup) {
  Model m = three_groups();
  auto id = add_property<FaceProperty<std::uint32_t>>(m, "id", kInvalidIndex);
  ASSERT_OK(id);
  for (FaceId f : m.faces()) id->set(f, f.value);
  for (GroupId g : m.groups()) {
    auto part = extract(m, g);
    ASSERT_OK(part);
    const Model& p = part->model;
    EXPECT_VALID(p);
    EXPECT_EQ(p.num_groups(), 1u);
    EXPECT_EQ(p.num_vertices(), m.num_vertices(g));
    EXPECT_EQ(p.num_edges(), m.num_edges(g));
    EXPECT_EQ(p.num_faces(), m.num_faces(g));
    EXPECT_EQ(p.num_volumes(), m.num_volumes(g));
    EXPECT_EQ(p.num_edge_uses(), [&] {
      std::size_t n = 0;
      for (EdgeId e : m.edges(g)) n += m.use_count(e);
      return n;
    }());
    EXPECT_EQ(p.name(part->ids[g]), m.name(g));
    for (VertexId v : m.vertices(g)) EXPECT_EQ(p.position(part->ids[v]), m.position(v));
    for (EdgeId e : m.edges(g)) {
      EXPECT_EQ(p.start_of(part->ids[e]), part->ids[m.start_of(e)]);
      EXPECT_EQ(p.use_count(part->ids[e]), m.use_count(e));
    }
    auto pid = find_property<FaceProperty<std::uint32_t>>(p, "id");
    ASSERT_TRUE(pid.is_valid());
    for (FaceId f : m.faces(g)) {
      EXPECT_EQ(pid[part->ids[f]], f.value);
      EXPECT_EQ(p.back_volume(part->ids[f]), part->ids[m.back_volume(f)]);
    }
    // Nothing of the other groups is mapped.
    for (GroupId h : m.groups()) {
      if (h == g) continue;
      for (FaceId f : m.faces(h)) EXPECT_FALSE(part->ids[f].is_valid());
    }
  }
  EXPECT_FALSE(extract(m, GroupId(17)).ok());
}

TEST(Parts, AppendAndRoundTrip) {
  Model m = three_groups();
  Model other;
  ASSERT_OK(euler_box_with_hole(other, {0, 0, 0}, {3, 3, 3}, 1, 2, "ring"));
  ASSERT_OK(euler_nonmanifold_example(other, "nm"));
  const Model before = m;
  auto ids = append(m, other);
  ASSERT_OK(ids);
  EXPECT_VALID(m);
  EXPECT_EQ(m.num_groups(), before.num_groups() + other.num_groups());
  EXPECT_EQ(m.num_vertices(), before.num_vertices() + other.num_vertices());
  EXPECT_EQ(m.num_edges(), before.num_edges() + other.num_edges());
  EXPECT_EQ(m.num_faces(), before.num_faces() + other.num_faces());
  EXPECT_EQ(m.num_loops(), before.num_loops() + other.num_loops());
  EXPECT_EQ(m.num_volumes(), before.num_volumes() + other.num_volumes());
  for (VertexId v : other.vertices()) EXPECT_EQ(m.position((*ids)[v]), other.position(v));
  for (GroupId g : other.groups()) {
    EXPECT_EQ(m.name((*ids)[g]), other.name(g));
    EXPECT_EQ(m.num_faces((*ids)[g]), other.num_faces(g));
    // extract after append gives back the same part as extract from the source.
    auto a = extract(other, g), b = extract(m, (*ids)[g]);
    ASSERT_OK(a);
    ASSERT_OK(b);
    EXPECT_EQ(snapshot(a->model), snapshot(b->model)) << g.str();
  }
  // The groups that were there are untouched.
  for (GroupId g : before.groups()) {
    auto a = extract(before, g), b = extract(m, g);
    EXPECT_EQ(snapshot(a->model), snapshot(b->model)) << g.str();
  }
  // append of every extracted part rebuilds the model.
  Model rebuilt;
  for (GroupId g : other.groups()) ASSERT_OK(append(rebuilt, extract(other, g)->model));
  EXPECT_EQ(snapshot(rebuilt), snapshot(other));
  EXPECT_FALSE(append(m, m).ok());
}

TEST(Parts, AppendMovedKeepsTheTopologyAndMovesThePoints) {
  Model other;
  ASSERT_OK(euler_box_with_hole(other, {0, 0, 0}, {3, 3, 3}, 1, 2, "ring"));
  ASSERT_OK(euler_nonmanifold_example(other, "nm"));
  const Vec3 shift{10, -4, 0.5};  // moves and moves back exactly
  Model moved = three_groups();
  const Model before = moved;
  auto ids = append(moved, other, [&](Vec3 p) { return p + shift; });
  ASSERT_OK(ids);
  EXPECT_VALID(moved);
  for (VertexId v : other.vertices()) EXPECT_EQ(moved.position((*ids)[v]), other.position(v) + shift);
  for (GroupId g : before.groups()) {
    auto a = extract(before, g), b = extract(moved, g);
    EXPECT_EQ(snapshot(a->model), snapshot(b->model)) << g.str();
  }
  // Moved back, each part is its source again, record for record.
  for (GroupId g : other.groups()) {
    Model back;
    ASSERT_OK(append(back, extract(moved, (*ids)[g])->model, [&](Vec3 p) { return p - shift; }));
    EXPECT_EQ(snapshot(back), snapshot(extract(other, g)->model)) << g.str();
  }
  // A face's analytic surface does not follow the map, so it is not copied.
  Model curved;
  ASSERT_OK(build_mesh(curved, unit_cube()));
  const FaceId first = *curved.faces().begin();
  curved.set_surface(first, curved.add_surface(Surface{.kind = "sphere", .radius = 1}));
  Model copy;
  auto copied = append(copy, curved, [&](Vec3 p) { return p + shift; });
  ASSERT_OK(copied);
  EXPECT_EQ(copy.surface_of((*copied)[first]), kInvalidIndex);
  Model plain;
  auto kept = append(plain, curved);
  ASSERT_OK(kept);
  EXPECT_NE(plain.surface_of((*kept)[first]), kInvalidIndex);
  EXPECT_FALSE(append(copy, copy, [](Vec3 p) { return p; }).ok());
}

}  // namespace
}  // namespace cellforge
