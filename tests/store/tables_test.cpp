// The database beyond the topology: property tables of every stored value type
// and a version's attachments come back bit for bit and byte for byte on both
// backends, a partial load keeps the values of what it loads, and damaged rows
// are errors that name the property and the element.
#include <gtest/gtest.h>

#include "cellforge/topo/dump.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/property.h"
#include "store/connection.h"
#include "store/store_fixture.h"
#include "support/checks.h"
#include "support/fixtures.h"
#include "support/properties.h"

namespace cellforge::testing {
namespace {

using StoreTables = StoreTest;

// Two cells, free slots (keys are not ids), every property type.
Model tagged_model(std::uint32_t seed) {
  Model cubes = build(two_cubes_sharing_face());
  const FaceId lid = face_at(cubes, {0.5, 0.5, 2});
  auto split =
      mef(cubes, cubes.outer_loop(lid), vertex_at(cubes, {0, 0, 2}), vertex_at(cubes, {1, 1, 2}));
  EXPECT_TRUE(split.ok());
  EXPECT_TRUE(kef(cubes, split->edge, split->face).ok());
  add_every_property_type(cubes, seed);
  EXPECT_NE(cubes.face_slots(), cubes.num_faces());
  return cubes;
}

std::unique_ptr<store::Connection> connect(const std::string& backend, const std::string& db) {
  auto c = backend == "sqlite" ? store::open_sqlite(db) : store::open_postgresql(db);
  EXPECT_TRUE(c.ok()) << c.error().message;
  return c ? std::move(c.value()) : nullptr;
}

TEST_P(StoreTables, PropertiesOfEveryTypeComeBackBitForBit) {
  for (std::uint32_t seed : {1u, 2u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Model m = tagged_model(seed);
    ASSERT_OK(store_->put("tagged", m));
    auto got = store_->get("tagged");
    ASSERT_OK(got);
    EXPECT_VALID(got.value());
    expect_same_model(m, got.value());
    expect_same_properties(m, got.value());
    EXPECT_FALSE(find_property<FaceProperty<std::vector<int>>>(got.value(), "scratch").is_valid());
  }
  // User SQL sees the tables: the label of the stored first face.
  auto label = store_->query(
      "SELECT v.text_value FROM properties p JOIN property_values v ON v.volume_id = p.volume_id "
      "AND v.property_key = p.property_key JOIN volumes w ON w.id = p.volume_id WHERE w.version = "
      "2 "
      "AND p.name = 'label' AND v.element_key = 0");
  ASSERT_OK(label);
  ASSERT_EQ(label->rows.size(), 1u);
  EXPECT_EQ(*label->rows[0][0], "");
  // A removal takes the tables with it.
  ASSERT_OK(store_->remove("tagged"));
  for (const char* t : {"properties", "property_values", "attachments"}) {
    auto left = store_->query(std::string("SELECT COUNT(*) FROM ") + t);
    ASSERT_OK(left);
    EXPECT_EQ(*left->rows[0][0], "0") << t;
  }
}

TEST_P(StoreTables, AttachmentsComeBackByteForByte) {
  const Model m = build(unit_cube());
  std::string data =
      "cellforge exact form 1\nexpr (union 0 1)\n \"quoted\" \\ \t \x01 na\xc3\xafve";
  for (int c = 0x20; c < 0x7f; ++c) data += static_cast<char>(c);
  const std::vector<Attachment> two = {{"cellforge.exact", 1, data}, {"note", 3, ""}};
  ASSERT_OK(store_->put("cube", m, {.attachments = two}));
  ASSERT_OK(store_->put("cube", m));
  EXPECT_EQ(store_->get_attachments("cube", 1).value(), two);
  EXPECT_TRUE(store_->get_attachments("cube").value().empty());  // version 2 has none
  EXPECT_FALSE(store_->get_attachments("nothing").ok());
  // Text the databases cannot keep, and a name twice, are refused before anything is written.
  for (const auto& bad : {std::vector<Attachment>{{"x", 1, std::string("a\0b", 3)}},
                          std::vector<Attachment>{{"x", 1, "\xff"}},
                          std::vector<Attachment>{{"x", 1, "a"}, {"x", 2, "b"}}}) {
    auto r = store_->put("cube", m, {.attachments = bad});
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.error().message.find("attachment"), std::string::npos) << r.error().message;
  }
  EXPECT_EQ(store_->versions("cube")->size(), 2u);
}

// A partial load keeps the values of the faces, edges and vertices it loads,
// renumbered as they are.
TEST_P(StoreTables, PartialLoadKeepsTheValuesOfWhatItLoads) {
  Model m = build(two_cubes_sharing_face());
  auto id = add_property<FaceProperty<std::uint32_t>>(m, "id", kInvalidIndex);
  auto height = add_property<VertexProperty<double>>(m, "height", -1.0);
  auto cell = add_property<VolumeProperty<std::string>>(m, "material", "steel");
  ASSERT_OK(id);
  ASSERT_OK(height);
  ASSERT_OK(cell);
  std::uint32_t k = 0;
  for (FaceId f : m.faces()) id->set(f, 100 + k++);
  for (VertexId v : m.vertices()) height->set(v, m.position(v).z);
  cell->set(*m.volumes().begin(), "brass");
  ASSERT_OK(store_->put("pair", m));
  // The faces with z >= 1 everywhere: the upper cube's top, four sides and the shared face.
  auto part = store_->get_faces_where("pair", "f.min_z >= 1");
  ASSERT_OK(part);
  const Model& p = part.value();
  ASSERT_EQ(p.num_faces(), 6u);
  const auto pid = find_property<FaceProperty<std::uint32_t>>(p, "id");
  const auto ph = find_property<VertexProperty<double>>(p, "height");
  ASSERT_TRUE(pid.is_valid());
  ASSERT_TRUE(ph.is_valid());
  for (FaceId f : p.faces()) {
    // The stored face with the same centroid has the same id value.
    const Vec3 c = centroid_of(p, f);
    EXPECT_EQ(pid[f], (*id)[face_at(m, c)]) << "face at " << c.x << " " << c.y << " " << c.z;
  }
  for (VertexId v : p.vertices()) EXPECT_EQ(ph[v], p.position(v).z);
  const auto pc = find_property<VolumeProperty<std::string>>(p, "material");
  ASSERT_TRUE(pc.is_valid());  // the table, with its default alone: no cells
  EXPECT_EQ(pc.default_value(), "steel");
}

// Damaged rows: each an error naming the property (and the element), never a crash.
TEST_P(StoreTables, DamagedRowsAreErrorsThatSayWhere) {
  Model m = build(unit_cube());
  auto u8 = add_property<FaceProperty<std::uint8_t>>(m, "level", 1);
  auto label = add_property<FaceProperty<std::string>>(m, "label", "none");
  ASSERT_OK(u8);
  ASSERT_OK(label);
  u8->set(*m.faces().begin(), 200);
  label->set(*m.faces().begin(), "first");
  const std::pair<std::string, std::string> cases[] = {
      {"UPDATE properties SET type = 'quaternion' WHERE name = 'level'",
       "property 0 ('level') has an unknown owner or type ('face', 'quaternion')"},
      {"UPDATE properties SET owner = 'volume' WHERE name = 'level'",
       "unknown owner or type ('volume'"},
      {"UPDATE property_values SET int_value = 300 WHERE property_key = 0 AND element_key = 0",
       "face property 'level': value of face 0: 300 is out of the range of uint8"},
      {"UPDATE property_values SET int_value = NULL WHERE property_key = 0 AND element_key = 0",
       "property 'level', face 0: int_value is NULL for a uint8"},
      {"UPDATE property_values SET text_value = NULL WHERE property_key = 1 AND element_key = -1",
       "property 'label', its default: text_value is NULL for a string"},
      {"DELETE FROM property_values WHERE property_key = 1 AND element_key = -1",
       "property 'label' has no default"},
      {"UPDATE property_values SET element_key = 6 WHERE property_key = 1 AND element_key = 0",
       "face property 'label': value 0 names face 6 (of 6"},
      {"UPDATE property_values SET property_key = 7 WHERE property_key = 1 AND element_key = 0",
       "a property value names property 7, element 0"},
      {"UPDATE properties SET name = 'level' WHERE property_key = 1",
       "face property 'level' is there twice"},
  };
  int n = 0;
  for (const auto& [damage, want] : cases) {
    SCOPED_TRACE(damage);
    const std::string name = "cube" + std::to_string(n++);
    auto put = store_->put(name, m);
    ASSERT_OK(put);
    {
      auto c = connect(GetParam(), db_);
      ASSERT_TRUE(c);
      ASSERT_OK(c->exec(damage + " AND volume_id = " + std::to_string(put->id)));
    }
    auto got = store_->get(name);
    ASSERT_FALSE(got.ok());
    EXPECT_EQ(got.error().code, ErrorCode::kDatabase);
    EXPECT_NE(got.error().message.find(want), std::string::npos) << got.error().message;
  }
  // Text a database cannot keep is refused at the save.
  label->set(*m.faces().begin(), "\xff");
  auto r = store_->put("bad", m);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("property 'label': the value of face 0"), std::string::npos)
      << r.error().message;
}

CELLFORGE_BACKENDS(StoreTables);

}  // namespace
}  // namespace cellforge::testing
