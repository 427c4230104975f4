// 3MF (threemf.cpp, zip.cpp): coordinates round-trip bit for bit, numbers no double
// holds are errors that say so, an empty model reads back, transforms and components
// apply, and lib3mf (an independent reader) reads what is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "cellforge/io/mesh_io.h"
#include "io/formats.h"
#include "io/zip.h"
#include "io_test_util.h"
#include "support/checks.h"
#include "support/fixtures.h"

#ifdef CELLFORGE_TEST_LIB3MF
#include <Model/COM/NMR_DLLInterfaces.h>
#endif

namespace cellforge {
namespace {

using testing::bytes_of;
using testing::read_fixture;

std::vector<std::array<std::uint64_t, 3>> position_bits(const Model& m) {
  std::vector<std::array<std::uint64_t, 3>> out;
  for (VertexId v : m.vertices()) {
    const Vec3 p = m.position(v);
    std::array<std::uint64_t, 3> b;
    std::memcpy(&b[0], &p.x, 8);
    std::memcpy(&b[1], &p.y, 8);
    std::memcpy(&b[2], &p.z, 8);
    out.push_back(b);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// A package whose model part is `xml`, as a producer other than io/ might write it.
std::string package(const std::string& xml) { return io::write_zip({{"3D/3dmodel.model", xml}}); }

std::string model_xml(const std::string& resources, const std::string& build) {
  return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<model unit=\"millimeter\" "
         "xmlns=\"http://schemas.microsoft.com/3dmanufacturing/core/2015/02\">\n<resources>" +
         resources + "</resources>\n<build>" + build + "</build></model>\n";
}

std::string triangle_object(int id, const std::string& a, const std::string& b,
                            const std::string& c) {
  return "<object id=\"" + std::to_string(id) + "\" type=\"model\"><mesh><vertices>" + a + b + c +
         "</vertices><triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh></object>";
}

TEST(ThreeMf, CoordinatesRoundTripBitForBit) {
  for (const char* file : {"precision/tiny_cube.obj", "precision/negative_zero.obj",
                           "nested/cube_sphere_cavity.stl"}) {
    SCOPED_TRACE(file);
    const Model m = read_fixture(file);
    const Model back = testing::round_trip(m, io::Format::k3mf);
    EXPECT_EQ(position_bits(back), position_bits(m));
    EXPECT_EQ(back.num_volumes(), m.num_volumes());
  }
  // Extremes a 6-decimal or float32 writer loses.
  MeshInput in;
  const std::uint32_t a = testing::add_point(in, {1e300, 5e-324, -0.0});
  const std::uint32_t b = testing::add_point(in, {-1e-300, 0.1, 1.0 / 3});
  const std::uint32_t c = testing::add_point(in, {2.5e-7, 1e22, -123456.789012345678});
  in.faces.push_back({{{a, b, c}}});
  const Model m = testing::build(in);
  const Model back = testing::round_trip(m, io::Format::k3mf);
  EXPECT_EQ(position_bits(back), position_bits(m));
}

TEST(ThreeMf, ANumberNoDoubleHoldsIsAnErrorThatSaysSo) {
  const std::string bad = package(model_xml(
      triangle_object(1, "<vertex x=\"0\" y=\"0\" z=\"0\"/>\n",
                      "<vertex x=\"1e400\" y=\"0\" z=\"0\"/>", "<vertex x=\"0\" y=\"1\" z=\"0\"/>"),
      "<item objectid=\"1\"/>"));
  Model m;
  auto r = io::read_model(m, bytes_of(bad), io::Format::k3mf);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("1e400"), std::string::npos) << r.error().message;
  EXPECT_NE(r.error().message.find("beyond the range of a double"), std::string::npos)
      << r.error().message;
  EXPECT_NE(r.error().message.find("line 4:"), std::string::npos) << r.error().message;
  EXPECT_TRUE(m.empty());
  const std::string nan = package(model_xml(
      triangle_object(1, "<vertex x=\"nan\" y=\"0\" z=\"0\"/>", "<vertex x=\"1\" y=\"0\" z=\"0\"/>",
                      "<vertex x=\"0\" y=\"1\" z=\"0\"/>"),
      "<item objectid=\"1\"/>"));
  auto n = io::read_model(m, bytes_of(nan), io::Format::k3mf);
  ASSERT_FALSE(n.ok());
  EXPECT_NE(n.error().message.find("not a finite number"), std::string::npos) << n.error().message;
}

TEST(ThreeMf, AnEmptyModelReadsBack) {
  auto bytes = io::write_model(Model(), io::Format::k3mf);
  ASSERT_OK(bytes);
  Model m;
  ASSERT_OK(io::read_model(m, bytes_of(*bytes), io::Format::k3mf));
  EXPECT_TRUE(m.empty());
}

TEST(ThreeMf, TransformsAndComponentsApply) {
  // Item transform: a translation by (10, 0, 0) (m30 m31 m32 are the last three);
  // the component scales by 2 first.
  const std::string xml = model_xml(
      triangle_object(1, "<vertex x=\"0\" y=\"0\" z=\"0\"/>", "<vertex x=\"1\" y=\"0\" z=\"0\"/>",
                      "<vertex x=\"0\" y=\"1\" z=\"0\"/>") +
          "<object id=\"2\" type=\"model\"><components><component objectid=\"1\" "
          "transform=\"2 0 0 0 2 0 0 0 2 0 0 0\"/></components></object>",
      "<item objectid=\"2\" transform=\"1 0 0 0 1 0 0 0 1 10 0 0\"/>");
  Model m;
  ASSERT_OK(io::read_model(m, bytes_of(package(xml)), io::Format::k3mf));
  std::vector<Vec3> got;
  for (VertexId v : m.vertices()) got.push_back(m.position(v));
  EXPECT_EQ(got, (std::vector<Vec3>{{10, 0, 0}, {12, 0, 0}, {10, 2, 0}}));
  const std::string loop = model_xml(
      "<object id=\"1\" type=\"model\"><components><component "
      "objectid=\"1\"/></components></object>",
      "<item objectid=\"1\"/>");
  auto r = io::read_model(m, bytes_of(package(loop)), io::Format::k3mf);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("nest deeper"), std::string::npos) << r.error().message;
}

TEST(ThreeMf, DamagedPackagesAreErrors) {
  auto good = io::write_model(read_fixture("cube.obj"), io::Format::k3mf);
  ASSERT_OK(good);
  std::string flipped = *good;
  flipped[flipped.size() / 3] ^= 0x5a;  // inside the deflated model part
  Model m;
  auto r = io::read_model(m, bytes_of(flipped), io::Format::k3mf);
  EXPECT_FALSE(r.ok());
  EXPECT_TRUE(m.empty());
  std::string cut = good->substr(0, good->size() - 10);
  EXPECT_FALSE(io::read_model(m, bytes_of(cut), io::Format::k3mf).ok());
  // A part that claims to unpack to 512 MB from a few hundred bytes is refused before
  // anything is allocated: the size field of the model part's central directory entry.
  std::string lie = *good;
  const auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int k = 3; k >= 0; --k) v = v << 8 | static_cast<unsigned char>(lie[at + k]);
    return v;
  };
  const std::size_t end = lie.size() - 22;
  std::size_t p = u32(end + 16);
  while (lie.compare(p + 46, 16, "3D/3dmodel.model") != 0)
    p += 46 + (u32(p + 28) & 0xffff) + (u32(p + 30) & 0xffff) + (u32(p + 32) & 0xffff);
  for (int k = 0; k < 4; ++k) lie[p + 24 + k] = static_cast<char>(k == 3 ? 0x01 : 0);  // 16 MiB: under max_3mf_bytes
  auto big = io::read_model(m, bytes_of(lie), io::Format::k3mf);
  ASSERT_FALSE(big.ok());
  EXPECT_NE(big.error().message.find("more than deflate can make"), std::string::npos)
      << big.error().message;
}

// A ZIP64 end record locator naming a record near 2^64 once overflowed the bounds check
// (found by the fuzzer): it must be an error that names the damaged record.
TEST(ThreeMf, AZip64LocatorPastTheArchiveIsAnError) {
  // A local header's signature (where a package starts), the locator (signature,
  // disk, record offset, disks), the end record.
  std::string zip(30 + 20 + 22, '\0');
  const auto put = [&](std::size_t at, std::uint64_t v, int bytes) {
    for (int k = 0; k < bytes; ++k) zip[at + k] = static_cast<char>(v >> (8 * k) & 0xff);
  };
  put(0, 0x04034b50, 4);
  put(30, 0x07064b50, 4);
  put(30 + 8, ~std::uint64_t{0}, 8);
  put(50, 0x06054b50, 4);
  put(50 + 10, 0xffff, 2);  // saturated entry count: look for ZIP64
  Model m;
  auto r = io::read_model(m, bytes_of(zip), io::Format::k3mf);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("ZIP64 end record is damaged"), std::string::npos)
      << r.error().message;
  EXPECT_TRUE(m.empty());
}

#ifdef CELLFORGE_TEST_LIB3MF
// lib3mf's view of a package: its mesh objects' vertex and triangle counts.
std::vector<std::pair<unsigned, unsigned>> lib3mf_counts(const std::string& bytes) {
  using namespace NMR;
  std::vector<std::pair<unsigned, unsigned>> out;
  PLib3MFModel* model = nullptr;
  PLib3MFModelReader* reader = nullptr;
  PLib3MFModelResourceIterator* it = nullptr;
  EXPECT_EQ(lib3mf_createmodel(&model), LIB3MF_OK);
  EXPECT_EQ(lib3mf_model_queryreader(model, "3mf", &reader), LIB3MF_OK);
  std::vector<BYTE> copy(bytes.begin(), bytes.end());
  EXPECT_EQ(lib3mf_reader_readfrombuffer(reader, copy.data(), copy.size()), LIB3MF_OK);
  EXPECT_EQ(lib3mf_model_getmeshobjects(model, &it), LIB3MF_OK);
  BOOL more = false;
  while (it && lib3mf_resourceiterator_movenext(it, &more) == LIB3MF_OK && more) {
    PLib3MFModelResource* mesh = nullptr;
    lib3mf_resourceiterator_getcurrent(it, &mesh);
    DWORD nv = 0, nt = 0;
    lib3mf_meshobject_getvertexcount(mesh, &nv);
    lib3mf_meshobject_gettrianglecount(mesh, &nt);
    out.push_back({nv, nt});
    lib3mf_release(mesh);
  }
  if (it) lib3mf_release(it);
  lib3mf_release(reader);
  lib3mf_release(model);
  return out;
}

TEST(ThreeMf, Lib3mfReadsWhatIsWritten) {
  const Model m = read_fixture("nested/cube_sphere_cavity.stl");
  auto bytes = io::write_model(m, io::Format::k3mf);
  ASSERT_OK(bytes);
  const auto counts = lib3mf_counts(*bytes);
  ASSERT_EQ(counts.size(), 1u);
  EXPECT_EQ(counts[0].first, m.num_vertices());
  EXPECT_EQ(counts[0].second, 12u + 16u * 7u * 2u - 0u);  // the cube's and the sphere's triangles
}

// Colors by face go out as <basematerials>, and lib3mf reads each triangle's material
// back as the color of the face it came from; faces without a color get the default.
TEST(ThreeMf, FaceColorsReadBackByLib3mf) {
  using namespace NMR;
  const Model m = read_fixture("nested/cube_sphere_cavity.stl");
  io::WriteOptions w;
  w.face_colors.resize(m.face_slots());
  const std::array<double, 4> red{1, 0, 0, 1}, half_blue{0, 0, 1, 0.5};
  std::map<std::array<int, 4>, std::size_t> want;  // color -> triangles
  auto bytes_of_color = [](const std::array<double, 4>& c) {
    std::array<int, 4> b{};
    for (int i = 0; i < 4; ++i) b[i] = static_cast<int>(std::lround(c[i] * 255));
    return b;
  };
  std::size_t k = 0;
  for (FaceId f : m.faces()) {
    const std::size_t mod = k++ % 3;
    if (mod == 0) w.face_colors[f.value] = red;
    if (mod == 1) w.face_colors[f.value] = half_blue;
  }
  for (FaceId f : io::triangle_mesh(m).face_of) {
    const auto& c = w.face_colors[f.value];
    want[c ? bytes_of_color(*c) : std::array<int, 4>{0xF9, 0xD7, 0x2C, 0xFF}] += 1;
  }
  ASSERT_EQ(want.size(), 3u);
  auto bytes = io::write_model(m, io::Format::k3mf, w);
  ASSERT_OK(bytes);
  // io/'s own reader takes the package with its materials as before.
  Model back;
  ASSERT_OK(io::read_model(back, bytes_of(*bytes), io::Format::k3mf));
  EXPECT_EQ(back.num_faces(), m.num_faces());

  PLib3MFModel* model = nullptr;
  PLib3MFModelReader* reader = nullptr;
  PLib3MFModelResourceIterator* it = nullptr;
  ASSERT_EQ(lib3mf_createmodel(&model), LIB3MF_OK);
  ASSERT_EQ(lib3mf_model_queryreader(model, "3mf", &reader), LIB3MF_OK);
  std::vector<BYTE> copy(bytes->begin(), bytes->end());
  ASSERT_EQ(lib3mf_reader_readfrombuffer(reader, copy.data(), copy.size()), LIB3MF_OK);
  ASSERT_EQ(lib3mf_model_getmeshobjects(model, &it), LIB3MF_OK);
  std::map<std::array<int, 4>, std::size_t> got;
  BOOL more = false;
  while (lib3mf_resourceiterator_movenext(it, &more) == LIB3MF_OK && more) {
    PLib3MFModelResource* mesh = nullptr;
    lib3mf_resourceiterator_getcurrent(it, &mesh);
    DWORD nt = 0;
    lib3mf_meshobject_gettrianglecount(mesh, &nt);
    PLib3MFPropertyHandler* props = nullptr;
    ASSERT_EQ(lib3mf_meshobject_createpropertyhandler(mesh, &props), LIB3MF_OK);
    for (DWORD t = 0; t < nt; ++t) {
      DWORD group = 0, index = 0;
      ASSERT_EQ(lib3mf_propertyhandler_getbasematerial(props, t, &group, &index), LIB3MF_OK);
      PLib3MFModelBaseMaterial* mat = nullptr;
      ASSERT_EQ(lib3mf_model_getbasematerialbyid(model, group, &mat), LIB3MF_OK);
      BYTE r = 0, g = 0, b = 0, a = 0;
      ASSERT_EQ(lib3mf_basematerial_getdisplaycolor(mat, index, &r, &g, &b, &a), LIB3MF_OK);
      got[{r, g, b, a}] += 1;
      lib3mf_release(mat);
    }
    lib3mf_release(props);
    lib3mf_release(mesh);
  }
  lib3mf_release(it);
  lib3mf_release(reader);
  lib3mf_release(model);
  EXPECT_EQ(got, want);
}
#endif

}  // namespace
}  // namespace cellforge
