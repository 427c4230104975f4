// `cellforge build IN.scad|IN.json -o OUT [-o OUT2 ...]`: evaluates an OpenSCAD script
// (or the JSON form of a CSG tree, docs/csg.md) and builds it exactly (csg/); echo
// lines go to standard output, warnings and errors to standard error. Exit codes: 0
// success, 1 a model or input error, 2 a usage error.
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <future>
#include <iostream>
#include <optional>
#include <sstream>
#include <vector>

#include "cellforge/csg/evaluator.h"
#include "cellforge/csg/tree.h"
#include "cellforge/csg/tree_json.h"
#include "cellforge/io/mesh_io.h"
#include "cellforge/shape/faceting.h"
#include "cellforge/shape/mass.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/validate.h"
#include "command.h"

namespace cellforge::cli {
namespace {

constexpr const char* kUsage =
    "usage: cellforge build IN.scad|IN.json -o OUT [-o OUT ...] [-D NAME=VALUE ...]\n"
    "                       [--save NAME] [--db DB] [--report json] [--ascii] [--tree OUT.json]\n"
    "                       [--cache DIR | --no-cache] [--threads N]\n"
    "  IN: an OpenSCAD script, or a CSG tree in cellforge's JSON form (docs/csg.md).\n"
    "  OUT: .stl .obj .off .3mf .json by extension (several -o allowed; none: only check).\n"
    "  -D NAME=VALUE: sets a top-level variable as `openscad -D` does (VALUE is an\n"
    "  expression; strings need their quotes). --save NAME stores the result and the\n"
    "  script in the model database (--db, default cellforge.db). --report json prints\n"
    "  counts, validity, volume, area, centroid, bounding box and seconds per stage.\n"
    "  --tree OUT.json writes the evaluated CSG tree. --cache DIR keeps each top-level\n"
    "  part built under its content key, so a rebuild after an edit rebuilds only the\n"
    "  parts it changed (default: $XDG_CACHE_HOME/cellforge or ~/.cache/cellforge;\n"
    "  --no-cache builds everything). --threads N: threads for the Booleans (default:\n"
    "  every hardware thread; the result is the same at any count).\n"
    "  Exit: 0 ok, 1 model or input error, 2 usage error.";

struct BuildArgs {
  std::string input;
  std::vector<std::string> outputs;
  std::vector<std::pair<std::string, std::string>> defines;
  std::string save, db, tree, cache;
  bool no_cache = false;
  bool json_report = false;
  bool ascii = false;
  int threads = 0;  // 0: every hardware thread
};

// The one place that reads the command line: fills `out`, or returns the exit code
// (0 after --help, 2 for a usage error, with the message printed).
std::optional<int> parse_args(const std::vector<std::string>& args, BuildArgs& out) {
  CLI::App app{"evaluate an OpenSCAD script (or CSG JSON) and build it exactly", "cellforge build"};
  std::string report;
  std::vector<std::string> defines;
  app.add_option("IN", out.input, "an OpenSCAD script, or a CSG tree as JSON (docs/csg.md)")
      ->required();
  app.add_option("-o", out.outputs, "a result file: .stl .obj .off .3mf .json (repeatable)")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("-D", defines, "NAME=VALUE: set a top-level variable, as openscad -D")
      ->expected(1)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  app.add_option("--save", out.save, "store the result and its script under NAME");
  app.add_option("--db", out.db, "the model database (default cellforge.db)");
  app.add_option("--report", report, "json: counts, validity, mass properties, seconds");
  app.add_option("--tree", out.tree, "write the evaluated CSG tree as JSON");
  app.add_option("--cache", out.cache, "the cache folder of built parts");
  app.add_flag("--no-cache", out.no_cache, "build every part");
  app.add_flag("--ascii", out.ascii, "write ASCII STL (default binary)");
  add_count(app, "--threads", out.threads, 1, "threads for the Booleans (default: every hardware thread)");
  app.footer(kUsage);
  if (auto code = parse(app, args)) return code;
  auto usage_error = [](const std::string& message) {
    std::cerr << "cellforge build: " << message << "\nRun with --help for more information.\n";
    return 2;
  };
  if (!report.empty() && report != "json") return usage_error("--report takes 'json'");
  out.json_report = report == "json";
  for (const std::string& d : defines) {
    std::string key, val;
    if (!split_key_value(d, key, val)) return usage_error("-D takes NAME=VALUE, not '" + d + "'");
    out.defines.emplace_back(key, val);
  }
  for (const std::string& o : out.outputs) {
    if (auto f = io::format_from_path(o); !f) return usage_error(f.error().message);
  }
  if (out.no_cache && !out.cache.empty()) return usage_error("--cache and --no-cache together");
  if (!out.no_cache && out.cache.empty()) {
    const char* xdg = std::getenv("XDG_CACHE_HOME");
    const char* home = std::getenv("HOME");
    if (xdg != nullptr && *xdg != '\0') {
      out.cache = std::string(xdg) + "/cellforge";
    } else if (home != nullptr && *home != '\0') {
      out.cache = std::string(home) + "/.cache/cellforge";
    }
  }
  return std::nullopt;
}

std::string num(double x) { return shape::format_number(x); }
std::string vec(Vec3 v) { return "[" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + "]"; }

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

int run(const std::vector<std::string>& argv) {
  using Clock = std::chrono::steady_clock;
  auto since = [](Clock::time_point t) {
    return std::chrono::duration<double>(Clock::now() - t).count();
  };
  BuildArgs a;
  if (auto code = parse_args(argv, a)) return *code;
  const auto t0 = Clock::now();
  csg::NodePtr root;
  std::shared_ptr<csg::Sources> sources;
  std::size_t echoes = 0, warnings = 0;
  std::string script;
  if (ends_with(a.input, ".json")) {
    std::ifstream in(a.input, std::ios::binary);
    if (!in) {
      std::cerr << "cellforge build: cannot read '" << a.input << "'\n";
      return 1;
    }
    std::ostringstream s;
    s << in.rdbuf();
    script = s.str();
    auto tree = csg::tree_from_json(script);
    if (!tree) {
      std::cerr << a.input << ": " << tree.error().message << '\n';
      return 1;
    }
    root = *tree;
  } else {
    csg::EvalOptions options;
    options.defines = a.defines;
    options.on_echo = [&](const std::string& line) {
      ++echoes;
      std::cout << line << '\n';
    };
    options.on_warning = [&](const std::string& text) {
      ++warnings;
      std::cerr << text << '\n';
    };
    auto r = csg::evaluate_file(a.input, options);
    if (!r) {
      std::cerr << r.error().message << '\n';
      return 1;
    }
    root = r->root;
    sources = r->sources;
    if (!a.save.empty()) script = sources->file(0).text;
  }
  const double eval_seconds = since(t0);
  if (!a.tree.empty()) {
    std::ofstream out(a.tree, std::ios::binary);
    out << csg::tree_to_json(*root) << '\n';
    if (!out) {
      std::cerr << "cellforge build: cannot write '" << a.tree << "'\n";
      return 1;
    }
  }
  const auto t1 = Clock::now();
  csg::BuildOptions bo;
  bo.sources = sources.get();
  bo.cache_dir = a.cache;
  bo.threads = a.threads;
  const bool tty = isatty(STDERR_FILENO) != 0;
  if (tty) {
    bo.progress = [](std::size_t done, std::size_t total) {
      if (total < 2) return;
      const std::size_t width = 30, filled = width * done / total;
      std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] "
                << done << "/" << total << " parts" << (done == total ? "\n" : "") << std::flush;
    };
  }
  auto built = csg::build(*root, bo);
  if (!built) {
    std::cerr << built.error().message << '\n';
    return 1;
  }
  const double build_seconds = since(t1);
  const Model& m = built->model;
  // The check runs beside the writing (both only read the model) unless one thread
  // was asked for; the sums only when something prints them.
  std::future<std::vector<Violation>> checked =
      std::async(a.threads == 1 ? std::launch::deferred : std::launch::async, [&m] { return validate(m); });
  const shape::MassProperties mp =
      m.num_faces() && (a.json_report || tty) ? shape::mass_properties(m) : shape::MassProperties{};
  const auto t2 = Clock::now();
  io::WriteOptions w;
  w.stl_binary = !a.ascii;
  // color(): written to 3MF (the other formats have no colors).
  for (const auto& c : built->face_colors) {
    if (c) {
      w.face_colors = built->face_colors;
      break;
    }
  }
  for (const std::string& o : a.outputs) {
    if (Status s = io::write_file(m, o, w); !s) {
      std::cerr << "cellforge build: " << s.error().message << '\n';
      return 1;
    }
  }
  if (!a.save.empty()) {
    auto store = open_store(a.db);
    if (!store) {
      std::cerr << "cellforge build: " << store.error().message << '\n';
      return 1;
    }
    PutOptions po;
    po.source = script;
    auto info = (*store)->put(a.save, m, po);
    if (!info) {
      std::cerr << "cellforge build: " << info.error().message << '\n';
      return 1;
    }
  }
  const double write_seconds = since(t2);
  const std::vector<Violation> violations = checked.get();
  const csg::BuildStats& st = built->stats;
  if (a.json_report) {
    std::cout << "{\"vertices\": " << m.num_vertices() << ", \"edges\": " << m.num_edges()
              << ", \"faces\": " << m.num_faces() << ", \"volumes\": " << m.num_volumes()
              << ", \"dimension\": " << built->dimension
              << ", \"valid\": " << (violations.empty() ? "true" : "false")
              << ", \"volume\": " << num(mp.volume) << ", \"area\": " << num(mp.area)
              << ", \"centroid\": " << vec(mp.centroid) << ", \"bbox\": [" << vec(mp.bbox_min)
              << ", " << vec(mp.bbox_max) << "], \"echoes\": " << echoes
              << ", \"warnings\": " << warnings << ", \"leaves\": " << st.leaves
              << ", \"booleans\": " << st.booleans
              << ", \"boolean_operands\": " << st.boolean_operands
              << ", \"booleans_in_frame\": " << st.booleans_in_frame
              << ", \"parts_apart\": " << st.parts_apart
              << ", \"cache_hits\": " << st.cache_hits << ", \"cache_misses\": " << st.cache_misses
              << ", \"memo_hits\": " << st.memo_hits
              << ", \"seconds\": {\"evaluate\": " << num(eval_seconds)
              << ", \"build\": " << num(build_seconds) << ", \"leaves\": " << num(st.leaf_seconds)
              << ", \"boolean\": " << num(st.boolean_seconds)
              << ", \"write\": " << num(write_seconds) << "}, \"boolean_list\": [";
    for (std::size_t i = 0; i < st.boolean_list.size(); ++i) {
      const csg::BooleanStats& b = st.boolean_list[i];
      std::cout << (i ? ", " : "") << "{\"operands\": " << b.operands << ", \"triangles\": " << b.triangles
                << ", \"candidate_pairs\": " << b.candidate_pairs << ", \"cutting_pairs\": " << b.cutting_pairs
                << ", \"pieces\": " << b.pieces << ", \"rays\": " << b.rays << ", \"points\": " << b.points
                << ", \"seconds\": {\"soup\": " << num(b.soup) << ", \"pairs\": " << num(b.intersect)
                << ", \"split\": " << num(b.split) << ", \"classify\": " << num(b.classify)
                << ", \"output\": " << num(b.output) << ", \"check\": " << num(b.check)
                << ", \"total\": " << num(b.total) << "}}";
    }
    std::cout << "]}\n";
  } else if (tty) {
    std::cerr << a.input << ": " << m.num_faces() << " faces, " << m.num_volumes()
              << " volumes, volume " << num(mp.volume)
              << (violations.empty() ? ", valid" : ", INVALID") << ", "
              << num(eval_seconds + build_seconds) << " s\n";
  }
  if (!violations.empty()) {
    std::cerr << "cellforge build: the result is invalid (" << violations.size() << " findings):\n";
    for (std::size_t i = 0; i < violations.size() && i < 10; ++i)
      std::cerr << "[" << violations[i].check << "] " << violations[i].message << '\n';
    return 1;
  }
  return 0;
}

const CommandRegistration kBuild{Command{
    "build", "evaluate an OpenSCAD script (or CSG JSON) and build it exactly", kUsage, run, true}};

}  // namespace
}  // namespace cellforge::cli
