// `cellforge bool OP A B [C ...] -o OUT`: the union, intersection or difference (the
// first minus the others) of solids and sheets read from files, regularized unless
// --keep-lower-dim, written to OUT
// (boolean/boolean.h). --report json prints the counts, validity, volume and the
// time of each stage. A JSON operand that keeps an exact form (boolean/exact.h)
// enters as that form, and a JSON result keeps its own, so that a chain of
// commands is exact end to end (--rounded: operands are their rounded models,
// and the result keeps no exact form).
#include <filesystem>
#include <iostream>

#include "cellforge/boolean/boolean.h"
#include "cellforge/boolean/exact.h"
#include "cellforge/io/mesh_io.h"
#include "cellforge/shape/faceting.h"
#include "cellforge/shape/mass.h"
#include "cellforge/topo/validate.h"
#include "command.h"

namespace cellforge::cli {
namespace {

constexpr const char* kUsage =
    "usage: cellforge bool union|intersection|difference A B [C ...] -o OUT\n"
    "                      [--threads N] [--report json] [--ascii] [--keep-lower-dim]\n"
    "                      [--cells] [--rounded] [KEY=VALUE...]\n"
    "  A, B, ...: solids and sheets in any format `info` reads (.stl .obj .off .3mf\n"
    "  .json); each file is one operand, the union of its cells and sheets. difference\n"
    "  is A minus all others. Regularized unless --keep-lower-dim: then faces, edges and\n"
    "  points of no volume stay (cubes sharing a face intersect in it), and the boundary\n"
    "  the set does not hold is counted as \"excluded\". --cells keeps the faces between\n"
    "  cells of different operands (one group, several volumes).\n"
    "  A .json operand that keeps an exact form (a result of this command) enters\n"
    "  exactly, and a .json OUT keeps the result's exact form beside its rounded\n"
    "  model; --rounded uses and keeps rounded models only.\n"
    "  OUT: .stl .obj .off .3mf .json by extension. --report json prints counts,\n"
    "  validity, volume, the rounding check and seconds per stage as one JSON object.\n"
    "  KEY=VALUE import options as for `cellforge info` (weld_tolerance=T, ...).";

std::string number(double x) { return shape::format_number(x); }

std::string report_json(const boolean::BooleanResult& r, bool valid, double volume) {
  const boolean::Report& p = r.report;
  const boolean::StageTimes& t = p.seconds;
  const Model& m = r.model;
  return "{\"vertices\": " + std::to_string(m.num_vertices()) +
         ", \"edges\": " + std::to_string(m.num_edges()) +
         ", \"faces\": " + std::to_string(m.num_faces()) +
         ", \"volumes\": " + std::to_string(m.num_volumes()) + ", \"valid\": " +
         (valid ? "true" : "false") + ", \"volume\": " + number(volume) +
         ", \"input_triangles\": " + std::to_string(p.input_triangles) +
         ", \"candidate_pairs\": " + std::to_string(p.candidate_pairs) +
         ", \"intersecting_pairs\": " + std::to_string(p.intersecting_pairs) +
         ", \"pieces\": " + std::to_string(p.pieces) + ", \"rays\": " + std::to_string(p.rays) +
         ", \"implicit_points\": " + std::to_string(p.implicit_points) +
         ", \"convex_split_clusters\": " + std::to_string(p.convex_split_clusters) +
         ", \"exact_fallbacks\": " + std::to_string(p.exact_fallbacks) +
         ", \"rounding_self_intersections\": " + std::to_string(p.rounding_self_intersections) +
         ", \"sheet_faces\": " + std::to_string(p.sheet_faces) +
         ", \"inner_faces\": " + std::to_string(p.inner_faces) +
         ", \"wire_edges\": " + std::to_string(p.wire_edges) +
         ", \"isolated_points\": " + std::to_string(p.isolated_points) +
         ", \"excluded\": " + std::to_string(p.excluded) +
         ", \"seconds\": {\"soup\": " + number(t.soup) + ", \"intersect\": " + number(t.intersect) +
         ", \"split\": " + number(t.split) + ", \"classify\": " + number(t.classify) +
         ", \"output\": " + number(t.output) + ", \"check\": " + number(t.check) + "}}";
}

int run(const std::vector<std::string>& args) {
  CLI::App app{"union, intersection or difference of solids and sheets, exactly",
               "cellforge bool"};
  std::string operation, out, report;
  std::vector<std::string> words;
  bool ascii = false, rounded = false;
  boolean::Options options;
  app.add_option("OPERATION", operation, "union, intersection or difference")->required();
  app.add_option("OPERANDS", words, "the operand files, and KEY=VALUE import options");
  app.add_option("-o", out, "the result's file")->required();
  add_count(app, "--threads", options.threads, 1, "threads for the intersection stage");
  app.add_option("--report", report, "json: print counts, validity and stage times");
  app.add_flag("--ascii", ascii, "write ASCII STL");
  app.add_flag("--keep-lower-dim", options.keep_lower_dim,
               "not regularized: keep the faces, edges and points of no volume");
  app.add_flag("--cells", options.cells, "keep the faces between cells of different operands");
  app.add_flag("--rounded", rounded, "ignore and write no exact forms (JSON operands and result)");
  app.footer(kUsage);
  if (auto code = parse(app, args)) return *code;
  boolean::Op op;
  if (operation == "union") {
    op = boolean::Op::kUnion;
  } else if (operation == "intersection") {
    op = boolean::Op::kIntersection;
  } else if (operation == "difference") {
    op = boolean::Op::kDifference;
  } else {
    std::cerr << "cellforge bool: unknown operation '" << operation
              << "' (union, intersection, difference)\n";
    return 2;
  }
  if (!report.empty() && report != "json") {
    std::cerr << "cellforge bool: --report takes 'json'\n";
    return 2;
  }
  const bool json = report == "json";
  std::vector<std::string> inputs;
  io::ReadOptions read;
  io::WriteOptions write;
  write.stl_binary = !ascii;
  for (const std::string& a : words) {
    std::string key, value;
    if (a.find('=') != std::string::npos && split_key_value(a, key, value) &&
        !std::filesystem::exists(a)) {
      if (Status s = io::set_option(read, key, value); !s) {
        std::cerr << "cellforge bool: " << s.error().message << '\n';
        return 2;
      }
    } else {
      inputs.push_back(a);
    }
  }
  if (inputs.size() < 2 || out.empty()) {
    std::cerr << "cellforge bool: needs at least two inputs and -o OUT\n" << kUsage << '\n';
    return 2;
  }
  if (auto f = io::format_from_path(out); !f) {
    std::cerr << "cellforge bool: " << f.error().message << '\n';
    return 2;
  }
  std::vector<boolean::Operand> operands;
  for (const std::string& input : inputs) {
    Model m;
    auto r = io::read_file(m, input, read);
    if (!r) {
      std::cerr << "cellforge bool: " << r.error().message << '\n';
      return 1;
    }
    Result<std::shared_ptr<const boolean::ExactForm>> form = std::shared_ptr<const boolean::ExactForm>();
    if (!rounded) form = boolean::find_exact(r->attachments);
    if (!form) {
      std::cerr << "cellforge bool: " << input << ": " << form.error().message << '\n';
      return 1;
    }
    operands.push_back(*form ? boolean::Operand::of(*form) : boolean::Operand::of(m));
  }
  auto r = boolean::chain(operands, boolean::Expr::over(op, static_cast<int>(operands.size())), options);
  if (!r) {
    std::cerr << "cellforge bool: " << r.error().message << '\n';
    return 1;
  }
  if (!rounded && io::format_from_path(out).value() == io::Format::kJson)
    write.attachments.push_back(boolean::exact_attachment(*r->exact));
  const auto violations = validate(r->model);
  const double volume = r->model.num_faces() ? shape::mass_properties(r->model).volume : 0;
  if (Status s = io::write_file(r->model, out, write); !s) {
    std::cerr << "cellforge bool: " << s.error().message << '\n';
    return 1;
  }
  if (json) {
    std::cout << report_json(*r, violations.empty(), volume) << '\n';
  } else {
    std::cout << boolean::to_string(op) << " of " << inputs.size() << " operands -> " << out << ": "
              << r->model.num_vertices() << " vertices, " << r->model.num_edges() << " edges, "
              << r->model.num_faces() << " faces, " << r->model.num_volumes() << " volumes, volume "
              << volume;
    if (options.keep_lower_dim || options.cells) {
      const boolean::Report& p = r->report;
      std::cout << "; " << p.sheet_faces << " sheet faces, " << p.inner_faces << " inner faces, "
                << p.wire_edges << " wire edges, " << p.isolated_points << " isolated points, "
                << p.excluded << " excluded";
    }
    std::cout << (violations.empty() ? ", valid" : ", INVALID") << '\n';
  }
  if (!violations.empty()) {
    std::cerr << "cellforge bool: the result is invalid (" << violations.size() << " findings):\n";
    for (std::size_t i = 0; i < violations.size() && i < 10; ++i)
      std::cerr << "[" << violations[i].check << "] " << violations[i].message << '\n';
    return 1;
  }
  return 0;
}

const CommandRegistration kBool{
    Command{"bool", "union, intersection or difference of solids and sheets, exactly", kUsage, run, true}};

}  // namespace
}  // namespace cellforge::cli
