// Property tables in snapshots (snapshot.h): restore(snapshot(m)) keeps every table
// of a stored value type bit for bit, on a model whose ids are not its keys, and a
// table that does not fit its model is refused with the property and the element.
#include <gtest/gtest.h>

#include "cellforge/topo/operators.h"
#include "cellforge/topo/property.h"
#include "cellforge/topo/snapshot.h"
#include "support/checks.h"
#include "support/fixtures.h"
#include "support/properties.h"

namespace cellforge::testing {
namespace {

Model model_with_free_slots() {
  Model m = build(two_cubes_sharing_face());
  const FaceId lid = face_at(m, {0.5, 0.5, 2});
  auto split = mef(m, m.outer_loop(lid), vertex_at(m, {0, 0, 2}), vertex_at(m, {1, 1, 2}));
  EXPECT_TRUE(split.ok());
  EXPECT_TRUE(kef(m, split->edge, split->face).ok());
  return m;
}

TEST(SnapshotProperties, RestoreKeepsEveryStoredTable) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    Model m = model_with_free_slots();
    add_every_property_type(m, seed);
    const Snapshot s = snapshot(m);
    EXPECT_EQ(s.properties.size(), 15u);  // every table but the in-memory "scratch"
    auto back = restore(s);
    ASSERT_OK(back);
    EXPECT_VALID(back.value());
    expect_same_properties(m, back.value());
    EXPECT_EQ(unstored_properties(m), std::vector<std::string>{"face property 'scratch'"});
    EXPECT_TRUE(unstored_properties(back.value()).empty());
  }
}

TEST(SnapshotProperties, TablesThatDoNotFitAreRefused) {
  Model m = build(unit_cube());
  auto tag = add_property<FaceProperty<std::uint8_t>>(m, "tag", 1);
  ASSERT_OK(tag);
  const Snapshot good = snapshot(m);
  const auto refused = [&](auto damage, const std::string& want) {
    Snapshot s = good;
    damage(s.properties.front());
    auto r = restore(s);
    ASSERT_FALSE(r.ok()) << want;
    EXPECT_NE(r.error().message.find(want), std::string::npos) << r.error().message;
  };
  using P = Snapshot::Property;
  refused([](P& p) { p.fallback = std::uint64_t{256}; },
          "face property 'tag': default: 256 is out of the range of uint8");
  refused([](P& p) { p.fallback = std::int64_t{1}; },
          "default: expected a non-negative integer (uint8)");
  refused(
      [](P& p) {
        p.values = {{6, std::uint64_t{2}}};
      },
      "face property 'tag': value 0 names face 6 (of 6");
  refused(
      [](P& p) {
        p.values = {{2, std::uint64_t{2}}, {2, std::uint64_t{3}}};
      },
      "value 1 names face 2");
  refused(
      [](P& p) {
        p.values = {{0, std::string("x")}};
      },
      "value of face 0: expected a non-negative integer");
  refused([](P& p) { p.type = PropertyType::kFloat, p.fallback = 0.1; },
          "default: the number is not a float");
  Snapshot twice = good;
  twice.properties.push_back(twice.properties.front());
  auto r = restore(twice);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("face property 'tag' is there twice"), std::string::npos)
      << r.error().message;
}

}  // namespace
}  // namespace cellforge::testing
