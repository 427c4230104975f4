// Every kind of bad input ends in a clear error naming where (byte offset or
// line:col) and leaves the model untouched.
#include <gtest/gtest.h>

#include "io_test_util.h"

namespace cellforge {
namespace {

using testing::read_error;

struct BadCase {
  const char* file;
  const char* message;  // a substring the error must contain
};

class BadInput : public ::testing::TestWithParam<BadCase> {};

TEST_P(BadInput, FailsWithPosition) {
  const std::string error = read_error(GetParam().file);
  EXPECT_NE(error.find(GetParam().message), std::string::npos) << error;
}

INSTANTIATE_TEST_SUITE_P(
    Files, BadInput,
    ::testing::Values(
        BadCase{"bad_empty.stl", "stl: byte 0: empty file"},
        BadCase{"bad_truncated.stl",
                "byte 80: binary STL header declares 12 triangles (684 bytes) but the file has "
                "654 bytes (truncated)"},
        BadCase{"bad_oversized.stl", "but the file has 691 bytes (trailing data)"},
        BadCase{"bad_huge_count.stl", "declares 4294967295 triangles"},
        BadCase{"bad_nan_ascii.stl", "stl: line 4:14: non-finite coordinate 'nan'"},
        BadCase{"bad_nan_binary.stl", "stl: byte 96: triangle 0 vertex 0 has a non-finite"},
        BadCase{"bad_keyword.stl", "stl: line 3:11: expected 'loop', found 'lop'"},
        BadCase{"bad_index.obj", "obj: line 4:7: vertex index 9 out of range (3 defined)"},
        BadCase{"bad_zero_index.obj", "obj: line 4:3: vertex index 0 out of range"},
        BadCase{"bad_inf.obj", "obj: line 2:7: non-finite coordinate 'inf'"},
        BadCase{"bad_utf8.obj", "obj: line 3:7: invalid UTF-8 (byte 25 is 0xFF)"},
        BadCase{"bad_empty.obj", "obj: byte 0: empty file"},
        BadCase{"bad_count.off", "off: line 8:1: file ends after 1 of 2 faces"},
        BadCase{"bad_huge_count.off",
                "off: line 2:1: counts 999999999 vertices, 1 faces cannot fit in a file of 24"},
        BadCase{"bad_index.off", "off: line 6:7: index 3 out of range (3 vertices)"},
        BadCase{"bad_not_zip.3mf", "3mf: byte 0: not a ZIP archive"},
        BadCase{"bad_truncated.json", "json: line 1:62: expected '}', found end of file"},
        BadCase{"bad_format.json", "not a cellforge model"}));

Result<io::ReadResult> read_text(Model& m, const std::string& text, io::Format f) {
  return io::read_model(m, testing::bytes_of(text), f);
}

TEST(BadInput, MessagesFromText) {
  const struct {
    io::Format format;
    const char* text;
    const char* message;
  } cases[] = {
      {io::Format::kStl, "solid\nfacet normal 0 0 1\nouter loop\nvertex 1 2\n",
       "line 5:1: expected a number, found end of file"},
      {io::Format::kStl,
       "solid x\n facet normal 0 0 1\n outer loop\n vertex 0 0 0\n vertex 1 0 0\n endloop\n "
       "endfacet\nendsolid\n",
       "facet has 2 vertices"},
      {io::Format::kStl, "hello", "neither ASCII STL"},
      {io::Format::kObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/9\n",
       "texture coordinate index 9 out of range (0 defined)"},
      {io::Format::kObj, "v 0 0 0\nv 1 0 0\nf 1 2\n", "line 3:1: face has 2 vertices"},
      {io::Format::kObj, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -4 1 2\n", "vertex index -4 out of range"},
      {io::Format::kObj, "v 1 2 x\n", "line 1:7: expected a number, found 'x'"},
      {io::Format::kObj, "v 0 0 1e999\n", "non-finite coordinate '1e999'"},
      // Three faces at an edge whose order the exact predicates would get wrong (a
      // coordinate whose products underflow; found by fuzz_stl).
      {io::Format::kObj, "v 0 0 0\nv 1 0 0\nv 0 1 1e-30\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 2 5\n",
       "on an edge of three faces or more: coordinate 1.0000000000000001e-30 is outside the range"},
      {io::Format::kOff, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4 0 1 2\n",
       "face declares 4 vertices but the line has 3"},
      {io::Format::kOff, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
       "line 7:1: data after the 1 declared faces"},
      {io::Format::kOff, "PLY\n", "expected 'OFF', found 'PLY'"},
      {io::Format::kOff, "OFF\n-1 0 0\n", "bad vertex count '-1'"},
      {io::Format::kJson,
       "{\"format\":\"cellforge-model\",\"version\":1,\"edges\":[[0,1]],\"vertices\":[]}",
       "json: "},
      {io::Format::kJson,
       "{\"format\":\"cellforge-model\",\"version\":1,\"vertices\":[[0,0,NaN,0]]}",
       "line 1:58: expected a number, found 'N'"},
      {io::Format::kJson, "{\"format\":\"cellforge-model\",\"version\":1,\"faces\":[]}",
       "'faces' must come after 'edges'"},
      {io::Format::kJson,
       "[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]", "expected '{'"},
      {io::Format::kJson,
       "{\"x\":[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[]]]]]]]]]]]]]]]]]"
       "]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]]}",
       "nesting deeper than 64"},
      {io::Format::kJson,
       "{\"format\":\"cellforge-model\",\"version\":1,\"groups\":[{\"name\":\"\\ud800\"}]}",
       "unpaired surrogate"},
      {io::Format::k3mf, "PK\x03\x04garbage", "3mf: byte 0: too short for a ZIP archive"},
  };
  for (const auto& c : cases) {
    if (c.format == io::Format::k3mf && !io::has_3mf()) continue;
    Model m;
    auto r = read_text(m, c.text, c.format);
    ASSERT_FALSE(r.ok()) << c.text;
    EXPECT_NE(r.error().message.find(c.message), std::string::npos)
        << "got: " << r.error().message << "\nwanted: " << c.message;
    EXPECT_TRUE(m.empty());
  }
}

TEST(BadInput, JsonThatRestoreRefusesLeavesTheModelAsItWas) {
  // An edge that names a vertex that does not exist.
  const std::string text =
      "{\"format\":\"cellforge-model\",\"version\":1,\"groups\":[{\"name\":\"g\"}],"
      "\"vertices\":[[0,0,0,0]],\"edges\":[[0,5]]}";
  Model m;
  auto r = read_text(m, text, io::Format::kJson);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("json: "), std::string::npos) << r.error().message;
  EXPECT_TRUE(m.empty());
}

TEST(BadInput, WeldToleranceOption) {
  io::ImportOptions o;
  EXPECT_FALSE(io::set_option(o, "weld_tolerance", "-1").ok());
  EXPECT_FALSE(io::set_option(o, "weld_tolerance", "nan").ok());
  EXPECT_FALSE(io::set_option(o, "welding", "1").ok());
  EXPECT_FALSE(io::set_option(o, "merge_coplanar", "maybe").ok());
  EXPECT_TRUE(io::set_option(o, "weld_tolerance", "1e-3").ok());
  EXPECT_EQ(o.weld_tolerance, 1e-3);
}

}  // namespace
}  // namespace cellforge
