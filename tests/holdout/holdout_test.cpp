// The holdout check: every model of tests/data/ (its folders included; the bad_*
// files are errors by design and left to bad_input_test) is read, diagnosed,
// written in every format and read back, and saved in and loaded from a database.
// Where the model is closed, or bounds no cell, its volume agrees with a signed
// volume computed here from the file's own polygons, apart from io/ and shape/.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "cellforge/io/diagnose.h"
#include "cellforge/io/mesh_io.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/dump.h"
#include "cellforge/topo/validate.h"

namespace cellforge {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> models() {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(CELLFORGE_TEST_DATA)) {
    if (!e.is_regular_file()) continue;
    const std::string name = e.path().filename().string();
    if (name.rfind("bad_", 0) == 0 || !io::format_from_path(name).ok()) continue;
    out.push_back(fs::relative(e.path(), CELLFORGE_TEST_DATA).string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::span<const std::uint8_t> bytes_of(const std::string& s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

// Six times the signed volume of polygons about the origin, in long double.
double signed_volume(const io::PolygonSoup& soup) {
  long double v6 = 0;
  for (const auto& p : soup.polygons)
    for (std::size_t i = 1; i + 1 < p.size(); ++i) {
      const Vec3 a = soup.positions[p[0]], b = soup.positions[p[i]], c = soup.positions[p[i + 1]];
      v6 += static_cast<long double>(a.x) *
                (static_cast<long double>(b.y) * c.z - static_cast<long double>(b.z) * c.y) +
            static_cast<long double>(a.y) *
                (static_cast<long double>(b.z) * c.x - static_cast<long double>(b.x) * c.z) +
            static_cast<long double>(a.z) *
                (static_cast<long double>(b.x) * c.y - static_cast<long double>(b.y) * c.x);
    }
  return static_cast<double>(v6 / 6);
}

// The model's polygons as a soup, through an ASCII STL (coordinates exact).
io::PolygonSoup soup_of(const Model& m) {
  auto stl = io::write_model(m, io::Format::kStl, {.stl_binary = false});
  EXPECT_TRUE(stl.ok());
  auto soup = io::parse_mesh(bytes_of(*stl), io::Format::kStl);
  return soup.ok() ? *soup : io::PolygonSoup{};
}

bool float_exact(const Model& m) {
  for (VertexId v : m.vertices()) {
    const Vec3 p = m.position(v);
    for (double c : {p.x, p.y, p.z})
      if (static_cast<double>(static_cast<float>(c)) != c) return false;
  }
  return true;
}

// Faces with cells on both sides: a nested solid, whose file's signed volume counts
// the inner solid once per shell around it.
bool has_shared_faces(const Model& m) {
  for (FaceId f : m.faces())
    if (m.front_volume(f).is_valid() && m.back_volume(f).is_valid()) return true;
  return false;
}

double tolerance(double scale, bool exact) { return (exact ? 1e-9 : 1e-5) * std::max(1.0, scale); }

TEST(Holdout, EveryModelOfTestData) {
  const auto names = models();
  ASSERT_GE(names.size(), 20u);
  const std::string db = ::testing::TempDir() + "/cellforge_holdout.db";
  fs::remove(db);
  auto opened = open_store(db);
  ASSERT_TRUE(opened.ok()) << opened.error().message;
  Store& database = **opened;
  for (const std::string& name : names) {
    SCOPED_TRACE(name);
    const std::string path = std::string(CELLFORGE_TEST_DATA) + "/" + name;
    Model m;
    auto read = io::read_file(m, path);
    ASSERT_TRUE(read.ok()) << read.error().message;
    const io::Diagnosis d = io::diagnose(m);
    EXPECT_TRUE(d.valid) << (d.violations.empty() ? "" : d.violations[0]);
    const double scale = std::fabs(d.volume);

    // The independent volume: the file's own polygons (JSON: the model's).
    const auto format = *io::format_from_path(name);
    io::PolygonSoup soup;
    if (format == io::Format::kJson) {
      soup = soup_of(m);
    } else {
      auto bytes = io::read_bytes(path);
      ASSERT_TRUE(bytes.ok());
      auto parsed = io::parse_mesh(*bytes, format);
      ASSERT_TRUE(parsed.ok()) << parsed.error().message;
      soup = *parsed;
    }
    if ((d.closed || d.volumes == 0) && !has_shared_faces(m) && d.faces > 0) {
      EXPECT_NEAR(d.volume, signed_volume(soup), tolerance(scale, true));
    }

    // Every format and back.
    struct Target {
      io::Format format;
      io::WriteOptions options;
      bool exact;
      const char* what;
    };
    const bool single = float_exact(m);
    for (const Target& t :
         {Target{io::Format::kStl, {.stl_binary = true}, single, "binary stl"},
          Target{io::Format::kStl, {.stl_binary = false}, true, "ascii stl"},
          Target{io::Format::kObj, {}, true, "obj"}, Target{io::Format::kOff, {}, true, "off"},
          Target{io::Format::k3mf, {}, true, "3mf"}, Target{io::Format::kJson, {}, true, "json"}}) {
      SCOPED_TRACE(t.what);
      if (d.faces == 0 && t.format != io::Format::kJson && t.format != io::Format::kObj &&
          t.format != io::Format::k3mf)
        continue;  // STL and OFF hold faces only: no file for a model without them
      auto bytes = io::write_model(m, t.format, t.options);
      ASSERT_TRUE(bytes.ok()) << bytes.error().message;
      Model back;
      auto again = io::read_model(back, bytes_of(*bytes), t.format);
      ASSERT_TRUE(again.ok()) << again.error().message;
      EXPECT_TRUE(validate(back).empty()) << to_string(validate(back));
      if (t.format == io::Format::kJson) {
        EXPECT_EQ(canonical_dump(back), canonical_dump(m));
        continue;
      }
      if (!t.exact) continue;  // float32 coordinates: read back, not compared
      const io::Diagnosis b = io::diagnose(back);
      EXPECT_EQ(b.volumes, d.volumes);
      EXPECT_EQ(b.closed, d.closed);
      EXPECT_NEAR(b.volume, d.volume, tolerance(scale, true));
    }

    // Saved and loaded.
    auto put = database.put(name, m);
    ASSERT_TRUE(put.ok()) << put.error().message;
    auto got = database.get(name);
    ASSERT_TRUE(got.ok()) << got.error().message;
    EXPECT_EQ(canonical_dump(*got), canonical_dump(m));
  }
  fs::remove(db);
}

}  // namespace
}  // namespace cellforge
