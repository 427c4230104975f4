// Exact chains (exact.h): a chain of Booleans is one arrangement of its inputs, the
// same whether run at once, step by step, or saved and reloaded between steps.
#include "cellforge/boolean/exact.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <random>

#include "boolean/boolean_test_util.h"

namespace cellforge::testing {
namespace {

using boolean::Expr;
using boolean::Op;
using boolean::Operand;

// Bit for bit: the same positions in the same order, the same faces' loops.
bool same_model(const Model& a, const Model& b) {
  if (a.num_vertices() != b.num_vertices() || a.num_faces() != b.num_faces() ||
      a.num_edges() != b.num_edges() || a.num_volumes() != b.num_volumes())
    return false;
  std::vector<Vec3> pa, pb;
  for (VertexId v : a.vertices()) pa.push_back(a.position(v));
  for (VertexId v : b.vertices()) pb.push_back(b.position(v));
  return pa == pb;
}

TEST(ExactChain, StepsAreOneArrangement) {
  const Model a = box_model({0, 0, 0}, {3, 3, 3});
  const Model b = sphere_model(1.7, 14, {1.5, 1.5, 3});
  const Model c = cylinder_model(0.6, 5, 12, {1.5, 1.5, -1});
  std::vector<Operand> ab{Operand::of(a), Operand::of(b)};
  auto r1 = boolean::chain(ab, Expr::over(Op::kDifference, 2));
  ASSERT_TRUE(r1.ok()) << r1.error().message;
  ASSERT_TRUE(r1->exact);
  std::vector<Operand> rc{Operand::of(*r1), Operand::of(c)};
  auto r2 = boolean::chain(rc, Expr::over(Op::kDifference, 2));
  ASSERT_TRUE(r2.ok()) << r2.error().message;
  EXPECT_EQ(r2->exact->inputs.size(), 3u);
  // The same as (a - b) - c at once.
  const Model* all[3] = {&a, &b, &c};
  auto once = boolean::evaluate(all, Expr::op(Op::kDifference, {Expr::over(Op::kDifference, 2), Expr::of(2)}));
  ASSERT_TRUE(once.ok());
  EXPECT_TRUE(same_model(r2->model, once->model));
  EXPECT_TRUE(validate(r2->model).empty());
  // Saved and read back, it gives the same result.
  const auto path = (std::filesystem::temp_directory_path() / "cellforge_chain.exact").string();
  ASSERT_TRUE(boolean::write_exact(*r2->exact, path).ok());
  auto back = boolean::read_exact(path);
  ASSERT_TRUE(back.ok()) << back.error().message;
  auto again = boolean::evaluate(**back);
  ASSERT_TRUE(again.ok());
  EXPECT_TRUE(same_model(again->model, r2->model));
}

TEST(ExactChain, BadTextIsAnErrorWithItsPlace) {
  EXPECT_FALSE(boolean::exact_from_string("hello").ok());
  auto r = boolean::exact_from_string("cellforge exact form 1\nexpr (union 0 1\n");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("byte"), std::string::npos) << r.error().message;
  r = boolean::exact_from_string("cellforge exact form 1\nexpr (union 0 1)\ninput 5\nab\n");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("shorter"), std::string::npos) << r.error().message;
  r = boolean::exact_from_string("cellforge exact form 1\nexpr (xor 0 1)\n");
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().message.find("union, intersection or difference"), std::string::npos);
}

// Seeded random chains of 5-20 Booleans on primitives: each step validates, agrees
// with the whole expression evaluated at once and with the chain saved and reloaded
// between steps, bit for bit; and the identity vol(R u P) + vol(R n P) = vol(R) +
// vol(P) holds at each step on the exact forms.
TEST(ExactChain, RandomChains) {
#ifdef __SANITIZE_ADDRESS__
  constexpr int kDefaultChains = 1;  // the sanitized build runs the same code 20 times slower
#else
  constexpr int kDefaultChains = 6;
#endif
  const int chains = std::getenv("CELLFORGE_CHAINS") ? std::atoi(std::getenv("CELLFORGE_CHAINS")) : kDefaultChains;
  const auto dir = std::filesystem::temp_directory_path() / "cellforge_chains";
  std::filesystem::create_directories(dir);
  for (int seed = 1; seed <= chains; ++seed) {
    std::mt19937 rng(static_cast<std::uint32_t>(seed));
    std::uniform_real_distribution<double> at(-1.5, 1.5);
    auto primitive = [&]() {
      const Vec3 p{at(rng), at(rng), at(rng)};
      switch (rng() % 3) {
        case 0:
          return box_model(p, p + Vec3{1 + at(rng) * 0.3, 1.2, 0.9});
        case 1:
          return sphere_model(0.8 + 0.1 * (rng() % 4), 8 + 2 * static_cast<int>(rng() % 3), p);
        default:
          return cylinder_model(0.5, 1.5, 9, p);
      }
    };
    const int steps = 5 + static_cast<int>(rng() % 16);
    Model first = box_model({-1, -1, -1}, {1, 1, 1});
    boolean::BooleanResult current;
    current.exact = std::make_shared<boolean::ExactForm>(
        boolean::ExactForm{{std::make_shared<const Model>(first)}, Expr::of(0)});
    std::shared_ptr<const boolean::ExactForm> reloaded = current.exact;
    for (int s = 0; s < steps; ++s) {
      const Model p = primitive();
      const Op op = static_cast<Op>(rng() % 3);
      std::vector<Operand> two{Operand::of(current), Operand::of(p)};
      auto next = boolean::chain(two, Expr::over(op, 2));
      ASSERT_TRUE(next.ok()) << "chain " << seed << " step " << s << ": " << next.error().message;
      EXPECT_TRUE(validate(next->model).empty()) << "chain " << seed << " step " << s << ": "
                                                 << to_string(validate(next->model));
      // Through a file between steps.
      const std::string path = (dir / ("step" + std::to_string(s) + ".exact")).string();
      std::vector<Operand> via{Operand::of(reloaded), Operand::of(p)};
      auto next_via = boolean::chain(via, Expr::over(op, 2));
      ASSERT_TRUE(next_via.ok());
      ASSERT_TRUE(boolean::write_exact(*next_via->exact, path).ok());
      auto back = boolean::read_exact(path);
      ASSERT_TRUE(back.ok()) << back.error().message;
      reloaded = *back;
      EXPECT_TRUE(same_model(next_via->model, next->model)) << "chain " << seed << " step " << s;
      // The identity, on the exact forms of R and P.
      if (s % 4 == 0) {
        const double vr = current.model.num_faces() ? shape::mass_properties(current.model).volume : 0;
        const double vp = shape::mass_properties(p).volume;
        std::vector<Operand> rp{Operand::of(current), Operand::of(p)};
        auto u = boolean::chain(rp, Expr::over(Op::kUnion, 2));
        auto i = boolean::chain(rp, Expr::over(Op::kIntersection, 2));
        ASSERT_TRUE(u.ok() && i.ok());
        const double vu = u->model.num_faces() ? shape::mass_properties(u->model).volume : 0;
        const double vi = i->model.num_faces() ? shape::mass_properties(i->model).volume : 0;
        if (s > 0) EXPECT_NEAR(vu + vi, vr + vp, 1e-9 * (1 + vr + vp)) << "chain " << seed << " step " << s;
      }
      current = std::move(*next);
    }
  }
}

}  // namespace
}  // namespace cellforge::testing
