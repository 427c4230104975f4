// Seeded random Booleans: pairs and triples of boxes snapped to a coarse grid (so
// that faces, edges and vertices coincide often) and of faceted primitives under
// random motions. Every result must validate with no crossing made by rounding;
// volumes must satisfy vol(A u B) + vol(A n B) = vol(A) + vol(B) and
// vol(A - B) = vol(A) - vol(A n B); random points must be in the result exactly when
// the operation says so of their membership in the operands, by a winding-number
// test written apart from the Boolean (boolean_test_util.h).
//
// CELLFORGE_BOOLEAN_CASES sets the number of cases (default 2000, 300 under the
// address sanitizer); the seed of a
// failing case is printed, and CELLFORGE_BOOLEAN_SEED runs that one alone.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <random>

#include "boolean/boolean_test_util.h"
#include "cellforge/io/diagnose.h"

namespace cellforge::testing {
namespace {

using boolean::Op;

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

Model random_box(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> g(0, 8);
  Vec3 lo, hi;
  for (int i = 0; i < 3; ++i) {
    int a = g(rng), b = g(rng);
    while (a == b) b = g(rng);
    (&lo.x)[i] = 0.5 * std::min(a, b);
    (&hi.x)[i] = 0.5 * std::max(a, b);
  }
  return box_model(lo, hi);
}

Model random_primitive(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 2), fn(5, 12), grid(0, 8);
  std::uniform_real_distribution<double> angle(0, 360);
  Model m;
  switch (kind(rng)) {
    case 0:
      EXPECT_TRUE(shape::make_sphere(m, {.r = 1 + 0.25 * grid(rng), .faceting = {.fn = double(fn(rng))}}).ok());
      break;
    case 1:
      EXPECT_TRUE(shape::make_cylinder(m, {.h = 1 + 0.5 * grid(rng), .r1 = 1 + 0.25 * grid(rng),
                                           .r2 = 0.5 + 0.25 * grid(rng), .center = true,
                                           .faceting = {.fn = double(fn(rng))}})
                      .ok());
      break;
    default:
      EXPECT_TRUE(shape::make_cube(m, {.size = {1 + 0.5 * grid(rng), 1 + 0.5 * grid(rng), 1 + 0.5 * grid(rng)},
                                       .center = true})
                      .ok());
      break;
  }
  shape::Transform t = shape::Transform::translate({0.5 * grid(rng) - 2, 0.5 * grid(rng) - 2, 0.5 * grid(rng) - 2});
  if (std::uniform_int_distribution<int>(0, 1)(rng)) {
    t = t * shape::Transform::rotate(angle(rng), {angle(rng) - 180, angle(rng) - 180, angle(rng)});
  } else {
    t = t * shape::Transform::rotate(90.0 * grid(rng), {0, 0, 1});
  }
  return moved(m, t);
}

double volume_of(const Model& m) { return m.num_faces() ? shape::mass_properties(m).volume : 0; }

// A case's operands: two (three every fifth seed) grid boxes, or primitives under
// random motions every fourth seed.
std::vector<Model> random_operands(std::uint64_t seed, std::mt19937_64& rng) {
  const bool boxes = seed % 4 != 3;
  const int n = seed % 5 == 0 ? 3 : 2;
  std::vector<Model> ops;
  for (int i = 0; i < n; ++i) ops.push_back(boxes ? random_box(rng) : random_primitive(rng));
  return ops;
}

// One case; false (with the reason in `why`) on any failure, a crossing made by
// rounding included; `rounded` counts the results with such crossings.
bool run_case(std::uint64_t seed, std::string& why, int& rounded) {
  std::mt19937_64 rng(seed);
  const std::vector<Model> ops = random_operands(seed, rng);
  const int n = static_cast<int>(ops.size());
  std::vector<const Model*> p;
  for (const Model& m : ops) p.push_back(&m);
  auto eval = [&](Op op) -> Result<boolean::BooleanResult> { return boolean::apply(op, p); };
  auto u = eval(Op::kUnion), i = eval(Op::kIntersection), d = eval(Op::kDifference);
  if (!u || !i || !d) {
    why = "refused: " + (!u ? u.error().message : !i ? i.error().message : d.error().message);
    return false;
  }
  for (auto* r : {&u, &i, &d}) {
    const auto v = validate(r->value().model);
    if (!v.empty()) {
      why = "invalid: " + v[0].check + " " + v[0].message;
      return false;
    }
    if (r->value().report.rounding_self_intersections != 0) {
      ++rounded;
      why = "rounding made " + std::to_string(r->value().report.rounding_self_intersections) + " crossings";
      return false;  // the rounded result must be free of crossings too
    }
    // The count against an independent exact check of the built model (io).
    io::DiagnoseOptions only_crossings;
    only_crossings.geometry = false;
    if (r->value().model.num_faces() > 0 && !io::diagnose(r->value().model, only_crossings).self_intersections.empty()) {
      ++rounded;
      why = "faces cross in the built model although the report counts none";
      return false;
    }
  }
  const double va = volume_of(ops[0]), vb = volume_of(ops[1]);
  const double vu = volume_of(u->model), vi = volume_of(i->model), vd = volume_of(d->model);
  const double scale = std::max(1.0, va + vb);
  if (n == 2 && (std::abs(vu + vi - va - vb) > 1e-9 * scale || std::abs(vd - (va - vi)) > 1e-9 * scale)) {
    why = "volumes: A " + std::to_string(va) + " B " + std::to_string(vb) + " union " + std::to_string(vu) +
          " intersection " + std::to_string(vi) + " difference " + std::to_string(vd);
    return false;
  }
  // Membership of random points.
  Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Model& m : ops)
    for (VertexId v : m.vertices()) {
      const Vec3 x = m.position(v);
      lo = {std::min(lo.x, x.x), std::min(lo.y, x.y), std::min(lo.z, x.z)};
      hi = {std::max(hi.x, x.x), std::max(hi.y, x.y), std::max(hi.z, x.z)};
    }
  std::uniform_real_distribution<double> ux(lo.x - 0.5, hi.x + 0.5), uy(lo.y - 0.5, hi.y + 0.5),
      uz(lo.z - 0.5, hi.z + 0.5);
  for (int s = 0; s < 20; ++s) {
    const Vec3 q{ux(rng), uy(rng), uz(rng)};
    std::vector<bool> in;
    bool on_surface = false;
    for (const Model& m : ops) {
      const int w = winding_at(m, q);
      on_surface |= w < 0;
      in.push_back(w > 0);
    }
    const int wu = winding_at(u->model, q), wi = winding_at(i->model, q), wd = winding_at(d->model, q);
    if (on_surface || wu < 0 || wi < 0 || wd < 0) continue;
    bool any = false, all = true;
    for (bool b : in) {
      any |= b;
      all &= b;
    }
    bool diff = in[0];
    for (std::size_t k = 1; k < in.size(); ++k) diff &= !in[k];
    if ((wu > 0) != any || (wi > 0) != all || (wd > 0) != diff) {
      why = "membership of (" + std::to_string(q.x) + ", " + std::to_string(q.y) + ", " + std::to_string(q.z) + ")";
      return false;
    }
  }
  return true;
}

TEST(BooleanProperty, RandomCasesHoldTheIdentities) {
  const int only = env_int("CELLFORGE_BOOLEAN_SEED", -1);
#ifdef CELLFORGE_ASAN
  constexpr int kDefaultCases = 150;  // the sanitized build runs the same code 30-50 times slower
#else
  constexpr int kDefaultCases = 2000;
#endif
  const int cases = only >= 0 ? 1 : env_int("CELLFORGE_BOOLEAN_CASES", kDefaultCases);
  int failures = 0, rounded = 0;
  for (int c = 0; c < cases; ++c) {
    const std::uint64_t seed = only >= 0 ? static_cast<std::uint64_t>(only) : static_cast<std::uint64_t>(c);
    std::string why;
    if (!run_case(seed, why, rounded)) {
      ++failures;
      if (failures <= 20) ADD_FAILURE() << "seed " << seed << ": " << why;
    }
  }
  EXPECT_EQ(failures, 0) << "of " << cases << " cases";
  std::printf("%d cases (%d results), %d failures; %d results with crossings made by rounding\n", cases,
              3 * cases, failures, rounded);
}

// The split along segments alone (the default) and the convex split of earlier
// versions (Options::convex_split) cut the same faces differently; the results are
// the same point sets: both valid, equal volumes and the same points inside, on 500
// of the random cases' operand sets under each operation, regularized and not. The
// segment split makes fewer points in all (and falls back to the convex one in few
// clusters).
TEST(BooleanProperty, SegmentAndConvexSplitsAgree) {
  std::size_t points_segment = 0, points_convex = 0, fallbacks = 0, clusters_cut = 0;
#ifdef CELLFORGE_ASAN
  constexpr std::uint64_t kSeeds = 40;  // the sanitized build is 20 times slower
#else
  constexpr std::uint64_t kSeeds = 500;
#endif
  for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
    std::mt19937_64 rng(seed);
    const std::vector<Model> ops = random_operands(seed, rng);
    std::vector<const Model*> p;
    for (const Model& m : ops) p.push_back(&m);
    for (Op op : {Op::kUnion, Op::kIntersection, Op::kDifference})
      for (bool open : {false, true}) {
        boolean::Options segment{.keep_lower_dim = open}, convex{.keep_lower_dim = open, .convex_split = true};
        auto a = boolean::apply(op, p, segment), b = boolean::apply(op, p, convex);
        ASSERT_TRUE(a && b) << "seed " << seed;
        EXPECT_TRUE(validate(a->model).empty()) << "seed " << seed << " " << to_string(op) << " open " << open;
        EXPECT_TRUE(validate(b->model).empty()) << "seed " << seed;
        const double va = volume_of(a->model), vb = volume_of(b->model);
        EXPECT_NEAR(va, vb, 1e-9 * std::max(1.0, std::abs(vb))) << "seed " << seed << " " << to_string(op);
        EXPECT_EQ(a->report.isolated_points, b->report.isolated_points) << "seed " << seed << " " << to_string(op);
        std::uniform_real_distribution<double> x(-3, 5);
        for (int s = 0; s < 10; ++s) {
          const Vec3 q{x(rng), x(rng), x(rng)};
          const int wa = winding_at(a->model, q), wb = winding_at(b->model, q);
          if (wa >= 0 && wb >= 0) {
            EXPECT_EQ(wa > 0, wb > 0) << "seed " << seed << " at " << q.x << " " << q.y << " " << q.z;
          }
        }
        points_segment += a->report.implicit_points;
        points_convex += b->report.implicit_points;
        fallbacks += a->report.convex_split_clusters;
        clusters_cut += b->report.convex_split_clusters;
      }
  }
  EXPECT_LT(points_segment, points_convex);
  EXPECT_LT(fallbacks * 20, clusters_cut);  // under one cluster in twenty falls back
  std::printf("segment split: %zu implicit points (convex split %zu); %zu of %zu clusters fell back\n",
              points_segment, points_convex, fallbacks, clusters_cut);
}

// Cases the long run found, each failing before its fix: 87679, a box whose edge lies
// along a prism's vertical edge (the box's two faces there were one patch, though the
// prism's faces pass between them); 39270 and 70025, grid boxes whose union has a face
// with a hole touching its boundary at a corner: it could not merge into one face, its
// pieces kept vertices on an input triangle's diagonal (x = 13/6), and rounding moved
// them off it (now the pieces merge as far as they can, inexact edges first).
TEST(BooleanProperty, CasesTheLongRunFound) {
  // 27191, 40035 and 73607: slivers that rounding made cross and no move of one or two
  // units undid (the repair reaches four, then eight, after such a round); 63415 needs
  // sixteen units and a fifth round.
  for (std::uint64_t seed : {87679u, 39270u, 70025u, 27191u, 40035u, 73607u, 63415u}) {
    std::string why;
    int rounded = 0;
    EXPECT_TRUE(run_case(seed, why, rounded)) << "seed " << seed << ": " << why;
  }
}

}  // namespace
}  // namespace cellforge::testing
