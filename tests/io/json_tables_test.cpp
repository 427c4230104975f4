// The native JSON beyond the topology: property tables of every stored value type
// and attachments (topo/attachment.h) come back bit for bit and byte for byte; a
// damaged table or attachment is an error that says what and where.
#include <gtest/gtest.h>

#include "cellforge/topo/dump.h"
#include "cellforge/topo/examples.h"
#include "cellforge/topo/operators.h"
#include "cellforge/topo/property.h"
#include "cellforge/topo/snapshot.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"
#include "support/properties.h"

namespace cellforge {
namespace {

using io::Format;

// Two groups, freed slots (the Euler example's), two cells: dense keys differ
// from ids.
Model tagged_model(std::uint32_t seed) {
  Model m;
  EXPECT_TRUE(euler_box_with_hole(m, {0, 0, 0}, {3, 3, 1}, 1, 2, "block").ok());
  const auto more =
      io::write_model(testing::build(testing::two_cubes_sharing_face()), Format::kJson);
  EXPECT_TRUE(more.ok());
  EXPECT_TRUE(io::read_model(m, testing::bytes_of(*more), Format::kJson).ok());
  // A face and an edge made and killed: free slots.
  const FaceId top = testing::face_at(m, {0.5, 0.5, 2});
  auto split =
      mef(m, m.outer_loop(top), testing::vertex_at(m, {0, 0, 2}), testing::vertex_at(m, {1, 1, 2}));
  EXPECT_TRUE(split.ok());
  EXPECT_TRUE(kef(m, split->edge, split->face).ok());
  testing::add_every_property_type(m, seed);
  return m;
}

std::string json_of(const Model& m, const io::WriteOptions& options = {}) {
  auto bytes = io::write_model(m, Format::kJson, options);
  EXPECT_TRUE(bytes.ok()) << bytes.error().message;
  return bytes.ok() ? *bytes : std::string();
}

std::string read_error(const std::string& text) {
  Model m;
  auto r = io::read_model(m, testing::bytes_of(text), Format::kJson);
  EXPECT_FALSE(r.ok()) << text;
  EXPECT_EQ(m.num_groups(), 0u);  // an error leaves the model as it was
  return r.ok() ? std::string() : r.error().message;
}

TEST(JsonTables, PropertiesOfEveryTypeComeBackBitForBit) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Model m = tagged_model(seed);
    ASSERT_NE(m.face_slots(), m.num_faces());  // keys are not ids
    const std::string text = json_of(m);
    EXPECT_NE(text.find("\"version\":2"), std::string::npos);
    Model back;
    ASSERT_OK(io::read_model(back, testing::bytes_of(text), Format::kJson));
    EXPECT_EQ(canonical_dump(m), canonical_dump(back));
    testing::expect_same_properties(m, back);
    // Values read through the API, by element: the first face's label.
    const auto label = find_property<FaceProperty<std::string>>(back, "label");
    ASSERT_TRUE(label.is_valid());
    EXPECT_EQ(label[*back.faces().begin()], "");
    // The in-memory-only table is left out, and said to be.
    EXPECT_FALSE(find_property<FaceProperty<std::vector<int>>>(back, "scratch").is_valid());
    const auto losses = io::format_losses(m, Format::kJson);
    ASSERT_EQ(losses.size(), 1u);
    EXPECT_NE(losses[0].find("face property 'scratch'"), std::string::npos) << losses[0];
    EXPECT_EQ(json_of(back), text);  // written again, the same bytes
  }
}

TEST(JsonTables, PlainModelsStayVersion1) {
  const std::string text = json_of(testing::build(testing::unit_cube()));
  EXPECT_NE(text.find("\"version\":1"), std::string::npos);
  EXPECT_EQ(text.find("properties"), std::string::npos);
}

TEST(JsonTables, ReadingIntoAModelJoinsItsTables) {
  Model file = testing::build(testing::unit_cube());
  auto tag = add_property<FaceProperty<std::int32_t>>(file, "tag", 5);
  ASSERT_OK(tag);
  tag->set(*file.faces().begin(), 9);
  const std::string text = json_of(file);

  Model m = testing::build(testing::book());
  auto mine = add_property<FaceProperty<std::int32_t>>(m, "tag", 0);
  ASSERT_OK(mine);
  mine->set(*m.faces().begin(), 1);
  const std::size_t before = m.num_faces();
  ASSERT_OK(io::read_model(m, testing::bytes_of(text), Format::kJson));
  const auto joined = find_property<FaceProperty<std::int32_t>>(m, "tag");
  ASSERT_TRUE(joined.is_valid());
  EXPECT_EQ(joined.default_value(), 0);  // the model's table, with the file's values in it
  std::vector<std::int32_t> values;
  for (FaceId f : m.faces()) values.push_back(joined[f]);
  std::vector<std::int32_t> want(before, 0);
  want[0] = 1;
  want.push_back(9);
  want.resize(m.num_faces(), 5);  // the file's default, written out
  EXPECT_EQ(values, want);

  // The same name with another type is refused, and the model is unchanged.
  Model other = testing::build(testing::book());
  ASSERT_OK(add_property<FaceProperty<double>>(other, "tag"));
  const std::string dump = canonical_dump(other);
  auto r = io::read_model(other, testing::bytes_of(text), Format::kJson);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("face property 'tag' is int32 in the file and double"),
            std::string::npos)
      << r.error().message;
  EXPECT_EQ(canonical_dump(other), dump);

  // A table of a type files do not keep stays with the model's own elements.
  Model held = testing::build(testing::book());
  auto scratch = add_property<FaceProperty<std::vector<int>>>(held, "scratch");
  ASSERT_OK(scratch);
  const FaceId last = [&] {
    FaceId f;
    for (FaceId g : held.faces()) f = g;
    return f;
  }();
  scratch->set(last, {4, 2});
  const std::size_t faces_before = held.num_faces();
  ASSERT_OK(io::read_model(held, testing::bytes_of(text), Format::kJson));
  const auto kept = find_property<FaceProperty<std::vector<int>>>(held, "scratch");
  ASSERT_TRUE(kept.is_valid());
  std::size_t k = 0;
  for (FaceId f : held.faces()) {
    EXPECT_EQ(kept[f], k + 1 == faces_before ? std::vector<int>({4, 2}) : std::vector<int>())
        << f.str();
    ++k;
  }
}

TEST(JsonTables, AttachmentsComeBackByteForByte) {
  const Model m = testing::build(testing::unit_cube());
  std::string data = "line 1\nline \"2\"\t\\ \x01\x1f na\xc3\xafve {\"json\": [1, 2]}\n";
  for (int c = 0x20; c < 0x7f; ++c) data += static_cast<char>(c);
  const std::vector<Attachment> attachments = {{"cellforge.exact", 1, data}, {"note", 7, ""}};
  const std::string text = json_of(m, {.attachments = attachments});
  EXPECT_NE(text.find("\"version\":2"), std::string::npos);
  Model back;
  auto r = io::read_model(back, testing::bytes_of(text), Format::kJson);
  ASSERT_OK(r);
  EXPECT_EQ(r->attachments, attachments);
  EXPECT_EQ(canonical_dump(back), canonical_dump(m));
  // Mesh formats have no place for them.
  auto stl = io::write_model(m, Format::kStl, {.attachments = attachments});
  ASSERT_OK(stl);
  Model from_stl;
  auto rs = io::read_model(from_stl, testing::bytes_of(*stl), Format::kStl);
  ASSERT_OK(rs);
  EXPECT_TRUE(rs->attachments.empty());
}

// Every damaged table or attachment: an error with the line and column and what
// is wrong (the model tables' errors name the property and the element).
TEST(JsonTables, DamageIsAnErrorWithItsPlace) {
  const std::string head =
      "{\"format\":\"cellforge-model\",\"version\":2,\"groups\":[{\"name\":\"g\"}],\"cells\":[],"
      "\"vertices\":[[0,0,0,0]],\"edges\":[],\"faces\":[],\n";
  const auto property = [&](const std::string& body) {
    return head + "\"properties\":[" + body + "]}";
  };
  const std::pair<std::string, std::string> cases[] = {
      {property(R"({"owner":"vertex","name":"a","type":"quaternion","default":0})"),
       "line 2:51: unknown property type 'quaternion'"},
      {property(R"({"owner":"volume","name":"a","type":"int8","default":0})"),
       "line 2:24: unknown property owner 'volume'"},
      {property(R"({"owner":"vertex","name":"a","type":"uint8","default":300})"),
       "integer 300 out of range [0, 255]"},
      {property(R"({"owner":"vertex","name":"a","type":"int8","default":-129})"),
       "integer -129 out of range [-128, 127]"},
      {property(R"({"owner":"vertex","name":"a","type":"uint64","default":18446744073709551616})"),
       "out of range [0, 18446744073709551615]"},
      {property(R"({"owner":"vertex","name":"a","default":0,"type":"int8"})"),
       "a property's 'type' must come before its 'default'"},
      {property(R"({"owner":"vertex","name":"a","type":"int8"})"),
       "a property needs 'owner', 'name', 'type' and 'default'"},
      {property(R"({"owner":"vertex","name":"a","type":"float","default":1e39})"),
       "number out of the range of a float"},
      {property(R"({"owner":"vertex","name":"a","type":"double","default":"nan"})"),
       "expected a number, \"NaN\", \"Infinity\" or \"-Infinity\", found 'nan'"},
      {property(R"({"owner":"vertex","name":"a","type":"int32","default":"1"})"),
       "expected an integer"},
      {property(R"({"owner":"vertex","name":"a","type":"colour","default":[1,1,1]})"),
       "expected 4 numbers, found 3"},
      {property(
           R"({"owner":"vertex","name":"a","type":"string","default":"","values":[[0,"x"],[0,"y"]]})"),
       "property keys must increase (0 after 0)"},
      {property(R"({"owner":"vertex","name":"a","type":"string","default":"","values":[[1,"x"]]})"),
       "vertex property 'a': value 0 names vertex 1 (of 1"},
      {property(
           R"({"owner":"face","name":"a","type":"int8","default":0},{"owner":"face","name":"a","type":"int8","default":1})"),
       "face property 'a' is there twice"},
      {head + R"("attachments":[{"name":"x","version":1}]})",
       "an attachment needs 'name', 'version' and 'data'"},
      {head + R"("attachments":[{"name":"x","version":0,"data":""}]})",
       "integer 0 out of range [1, 2147483647]"},
      {head +
           R"("attachments":[{"name":"x","version":1,"data":""},{"name":"x","version":1,"data":""}]})",
       "attachment 'x' is there twice"},
      {head + R"("attachments":[{"name":"x","version":1,"data":"\ud800"}]})", "unpaired surrogate"},
      {head + R"("version":3})", "duplicate key 'version'"},
  };
  for (const auto& [text, want] : cases) {
    const std::string message = read_error(text);
    EXPECT_NE(message.find(want), std::string::npos) << text << "\n -> " << message;
  }
  // A version this reader does not know.
  std::string v3 = json_of(testing::build(testing::unit_cube()));
  v3.replace(v3.find("\"version\":1"), 11, "\"version\":3");
  EXPECT_NE(read_error(v3).find("unsupported version 3 (this reader reads 1 to 2)"),
            std::string::npos);
}

}  // namespace
}  // namespace cellforge
