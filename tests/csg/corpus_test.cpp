// The .scad corpus of tests/scad/: each file states what building it must give in
// comment lines, checked here against an in-process evaluate + build:
//
//   // expect echo: ECHO: 1, 2     the echo lines, all of them, in order
//   // expect volume: 24           closed-form volume (relative 1e-9)
//   // expect area: 52             surface area (relative 1e-9)
//   // expect counts: faces=6 ...  vertices, edges, faces, volumes
//   // expect bbox: [x, y, z] [x, y, z]
//   // expect valid                the result passes validate()
//   // expect error: TEXT          evaluating or building fails with TEXT in the message
//   // expect warning: TEXT        some warning contains TEXT
//   // expect define: NAME=VALUE   run with -D NAME=VALUE
//   // expect pending: WHAT        WHAT is not implemented yet: the build may fail with
//                                  "not implemented" / "not supported yet"; once it
//                                  builds, the other expectations hold
//   // expect no-openscad: WHY     (for scripts/openscad_compare.sh: not compared)
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cellforge/csg/evaluator.h"
#include "cellforge/csg/tree.h"
#include "cellforge/shape/mass.h"
#include "cellforge/topo/validate.h"

namespace cellforge::csg {
namespace {

const std::string kCorpus = std::string(CELLFORGE_TEST_DATA) + "/../scad";

struct Expectations {
  std::vector<std::string> echoes;
  std::optional<double> volume, area;
  std::vector<std::pair<std::string, std::size_t>> counts;
  std::optional<std::pair<Vec3, Vec3>> bbox;
  bool valid = false;
  std::string error, pending;
  std::vector<std::string> warnings;
  std::vector<std::pair<std::string, std::string>> defines;
};

Vec3 parse_vec(const std::string& s) {
  Vec3 v;
  std::sscanf(s.c_str(), " [%lf , %lf , %lf]", &v.x, &v.y, &v.z);
  return v;
}

Expectations read_expectations(const std::string& path) {
  Expectations e;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    const std::string tag = "// expect ";
    if (line.rfind(tag, 0) != 0) continue;
    const std::string rest = line.substr(tag.size());
    const std::size_t colon = rest.find(": ");
    const std::string key = rest.substr(0, colon);
    const std::string value = colon == std::string::npos ? "" : rest.substr(colon + 2);
    if (key == "echo") e.echoes.push_back(value);
    if (key == "volume") e.volume = std::stod(value);
    if (key == "area") e.area = std::stod(value);
    if (key == "valid") e.valid = true;
    if (key == "error") e.error = value;
    if (key == "pending") e.pending = value;
    if (key == "warning") e.warnings.push_back(value);
    if (key == "define") {
      const std::size_t eq = value.find('=');
      e.defines.emplace_back(value.substr(0, eq), value.substr(eq + 1));
    }
    if (key == "bbox") {
      const std::size_t mid = value.find("] [");
      e.bbox = {parse_vec(value.substr(0, mid + 1)), parse_vec(value.substr(mid + 2))};
    }
    if (key == "counts") {
      std::istringstream s(value);
      std::string item;
      while (s >> item) {
        const std::size_t eq = item.find('=');
        e.counts.emplace_back(item.substr(0, eq), std::stoul(item.substr(eq + 1)));
      }
    }
  }
  return e;
}

bool close(double got, double want) {
  return std::fabs(got - want) <= 1e-9 * std::max(1.0, std::fabs(want));
}

bool is_pending_error(const std::string& message) {
  return message.find("not implemented") != std::string::npos ||
         message.find("not supported yet") != std::string::npos;
}

std::vector<std::string> corpus_files() {
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(kCorpus)) {
    if (entry.path().extension() == ".scad") out.push_back(entry.path().filename().string());
  }
  std::sort(out.begin(), out.end());
  return out;
}

class Corpus : public ::testing::TestWithParam<std::string> {};

TEST_P(Corpus, BuildsAsExpected) {
  const std::string path = kCorpus + "/" + GetParam();
  const Expectations want = read_expectations(path);
  EvalOptions options;
  options.defines = want.defines;
  options.use_default_library_path = false;
  auto evaluated = evaluate_file(path, options);
  std::string error;
  Result<BuildOutput> built = Error{ErrorCode::kInvalidInput, ""};
  if (!evaluated) {
    error = evaluated.error().message;
  } else {
    BuildOptions bo;
    bo.sources = evaluated->sources.get();
    built = build(*evaluated->root, bo);
    if (!built) error = built.error().message;
  }
  if (!want.error.empty()) {
    EXPECT_NE(error.find(want.error), std::string::npos) << "error: " << error;
    return;
  }
  if (!error.empty() && !want.pending.empty() && is_pending_error(error)) {
    GTEST_LOG_(INFO) << GetParam() << ": pending (" << want.pending << "): " << error;
    return;
  }
  ASSERT_TRUE(error.empty()) << error;
  for (const std::string& w : want.warnings) {
    bool found = false;
    for (const std::string& got : evaluated->warnings) found |= got.find(w) != std::string::npos;
    EXPECT_TRUE(found) << "no warning containing: " << w;
  }
  if (!want.echoes.empty() || !evaluated->echoes.empty()) {
    EXPECT_EQ(evaluated->echoes, want.echoes);
  }
  const Model& m = built->model;
  const shape::MassProperties mp =
      m.num_faces() ? shape::mass_properties(m) : shape::MassProperties{};
  if (want.volume) {
    EXPECT_TRUE(close(mp.volume, *want.volume))
        << "volume " << mp.volume << " want " << *want.volume;
  }
  if (want.area) {
    EXPECT_TRUE(close(mp.area, *want.area)) << "area " << mp.area << " want " << *want.area;
  }
  if (want.bbox) {
    for (int i = 0; i < 3; ++i) {
      EXPECT_TRUE(close(mp.bbox_min[i], want.bbox->first[i]))
          << "bbox min[" << i << "] " << mp.bbox_min[i];
      EXPECT_TRUE(close(mp.bbox_max[i], want.bbox->second[i]))
          << "bbox max[" << i << "] " << mp.bbox_max[i];
    }
  }
  for (const auto& [what, n] : want.counts) {
    const std::size_t got = what == "vertices" ? m.num_vertices()
                            : what == "edges"  ? m.num_edges()
                            : what == "faces"  ? m.num_faces()
                                               : m.num_volumes();
    EXPECT_EQ(got, n) << what;
  }
  // Every solid result must be valid; `expect valid` says so for files checked by it alone.
  const auto violations = validate(m);
  EXPECT_TRUE(violations.empty()) << (violations.empty() ? "" : violations[0].message);
}

INSTANTIATE_TEST_SUITE_P(Scad, Corpus, ::testing::ValuesIn(corpus_files()),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string name = info.param.substr(0, info.param.size() - 5);
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

TEST(Corpus, HasAtLeastSixtyFiles) { EXPECT_GE(corpus_files().size(), 60u); }

}  // namespace
}  // namespace cellforge::csg
