#include "support/properties.h"

#include <gtest/gtest.h>

#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cellforge/topo/property.h"
#include "cellforge/topo/snapshot.h"

namespace cellforge::testing {

namespace {

template <class P, class Ids>
void fill(Model& m, const std::string& name, typename P::value_type def, const Ids& ids,
          const std::vector<typename P::value_type>& hard, std::mt19937& rng,
          typename P::value_type (*random)(std::mt19937&)) {
  auto p = add_property<P>(m, name, def);
  ASSERT_TRUE(p.ok()) << p.error().message;
  std::size_t k = 0;
  for (auto id : ids) {
    if (k < hard.size()) {
      p->set(id, hard[k++]);
    } else if (rng() % 2) {
      p->set(id, random(rng));
    }
  }
}

bool same_bits(const PropertyValue& a, const PropertyValue& b) {
  if (a.index() != b.index()) return false;
  if (const auto* d = std::get_if<double>(&a))
    return std::memcmp(d, std::get_if<double>(&b), sizeof *d) == 0;
  if (const auto* c = std::get_if<Colour>(&a))
    return std::memcmp(c, std::get_if<Colour>(&b), sizeof *c) == 0;
  if (const auto* v = std::get_if<Vec3>(&a))
    return std::memcmp(v, std::get_if<Vec3>(&b), sizeof *v) == 0;
  return a == b;
}

}  // namespace

void add_every_property_type(Model& m, std::uint32_t seed) {
  std::mt19937 rng(seed);
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  constexpr float kInfF = std::numeric_limits<float>::infinity();
  constexpr float kNaNF = std::numeric_limits<float>::quiet_NaN();
  using I64 = std::numeric_limits<std::int64_t>;
  using U64 = std::numeric_limits<std::uint64_t>;

  fill<VertexProperty<double>>(m, "weight", -1.0, m.vertices(),
                               {-0.0, kNaN, kInf, -kInf, 4.9e-324, 1.7976931348623157e308, 0.1},
                               rng,
                               [](std::mt19937& r) { return std::ldexp(double(r()), -20) - 2000; });
  fill<VertexProperty<std::int8_t>>(m, "i8", 0, m.vertices(), {-128, 127}, rng,
                                    [](std::mt19937& r) { return std::int8_t(r() % 256 - 128); });
  fill<VertexProperty<Vec3>>(m, "normal", Vec3{0, 0, -0.0}, m.vertices(), {{-0.0, kInf, 1e-310}},
                             rng, [](std::mt19937& r) {
                               return Vec3{r() * 1e-3, -double(r()), 0.5};
                             });
  fill<EdgeProperty<std::int64_t>>(
      m, "i64", I64::min(), m.edges(), {I64::max(), 0, -1}, rng,
      [](std::mt19937& r) { return std::int64_t(r()) * 1000003 - (std::int64_t{1} << 40); });
  fill<EdgeProperty<std::uint64_t>>(m, "u64", U64::max(), m.edges(),
                                    {0, U64::max() - 1, std::uint64_t{1} << 63}, rng,
                                    [](std::mt19937& r) { return std::uint64_t(r()) << 31; });
  fill<EdgeProperty<std::int16_t>>(
      m, "i16", 7, m.edges(), {-32768, 32767}, rng,
      [](std::mt19937& r) { return std::int16_t(r() % 60000 - 30000); });
  fill<EdgeProperty<std::uint16_t>>(m, "u16", 7, m.edges(), {65535}, rng,
                                    [](std::mt19937& r) { return std::uint16_t(r()); });
  fill<FaceProperty<std::uint32_t>>(m, "source", kInvalidIndex, m.faces(), {0, 0xFFFFFFFEu}, rng,
                                    [](std::mt19937& r) { return std::uint32_t(r()); });
  fill<FaceProperty<std::int32_t>>(m, "i32", 0, m.faces(), {-2147483647 - 1, 2147483647}, rng,
                                   [](std::mt19937& r) { return std::int32_t(r()); });
  fill<FaceProperty<std::uint8_t>>(m, "u8", 1, m.faces(), {255, 0}, rng,
                                   [](std::mt19937& r) { return std::uint8_t(r()); });
  fill<FaceProperty<float>>(m, "f32", 0.5f, m.faces(),
                            {-0.0f, 0.1f, 3.4028235e38f, 1e-45f, kInfF, kNaNF}, rng,
                            [](std::mt19937& r) { return float(r()) * 1e-7f; });
  fill<FaceProperty<Colour>>(m, "colour", Colour{}, m.faces(),
                             {{1, 0, 0, 1}, {0.1f, -0.0f, kNaNF, 0.333333343f}}, rng,
                             [](std::mt19937& r) {
                               return Colour{float(r() % 256) / 255, 0.5f, 0.25f, 1};
                             });
  fill<FaceProperty<std::string>>(
      m, "label", "none", m.faces(),
      {"", "na\xc3\xafve \xe5\x90\x8d\xe5\x89\x8d", "quote\" back\\ nl\n tab\t \x01"}, rng,
      [](std::mt19937& r) { return "face " + std::to_string(r() % 1000); });
  fill<VolumeProperty<std::string>>(
      m, "material", "steel", m.volumes(), {"brass"}, rng,
      [](std::mt19937& r) { return std::string(r() % 2 ? "oak" : "ash"); });
  fill<VolumeProperty<double>>(m, "density", 7.85, m.volumes(), {-0.0}, rng,
                               [](std::mt19937& r) { return double(r()) / 3; });
  auto scratch = add_property<FaceProperty<std::vector<int>>>(m, "scratch");
  ASSERT_TRUE(scratch.ok());
  scratch->set(*m.faces().begin(), {1, 2, 3});
}

void expect_same_properties(const Model& a, const Model& b) {
  const auto pa = snapshot(a).properties, pb = snapshot(b).properties;
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) {
    SCOPED_TRACE("property '" + pa[i].name + "'");
    EXPECT_EQ(pa[i].owner, pb[i].owner);
    EXPECT_EQ(pa[i].name, pb[i].name);
    EXPECT_EQ(pa[i].type, pb[i].type);
    EXPECT_TRUE(same_bits(pa[i].fallback, pb[i].fallback));
    ASSERT_EQ(pa[i].values.size(), pb[i].values.size());
    for (std::size_t k = 0; k < pa[i].values.size(); ++k) {
      EXPECT_EQ(pa[i].values[k].first, pb[i].values[k].first) << "value " << k;
      EXPECT_TRUE(same_bits(pa[i].values[k].second, pb[i].values[k].second)) << "value " << k;
    }
  }
}

}  // namespace cellforge::testing
