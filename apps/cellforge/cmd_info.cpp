// `cellforge info FILE [--json] [KEY=VALUE...]`: reads a model file (any format of
// io/) and prints what it is (io/diagnose.h): counts, validity, closedness,
// non-manifold places by id, orientation, degenerate, duplicate and
// self-intersecting faces, volume, area, centroid, bounding box.
#include <iostream>

#include "cellforge/io/diagnose.h"
#include "cellforge/io/mesh_io.h"
#include "command.h"
#include "progress.h"

namespace cellforge::cli {
namespace {

constexpr const char* kSummary =
    "read a model file and report counts, validity, defects and mass properties";
constexpr const char* kUsage =
    "usage: cellforge info FILE [--json] [--strict] [--no-self-intersections] [--no-geometry]\n"
    "                      [--format F] [KEY=VALUE...]\n"
    "  FILE: .stl (ASCII or binary) .obj .off .3mf .json, or - for standard input\n"
    "  (with --format stl|obj|off|3mf|json).\n"
    "  KEY=VALUE import options: weld_tolerance=T (weld positions closer than T;\n"
    "  default 0: only equal ones), merge_coplanar=true (coplanar triangles become\n"
    "  polygon faces), repair_orientation=true, volumes=auto|none; read limits\n"
    "  max_bytes=N and max_3mf_bytes=N (K, M, G suffixes; 0: none; docs/io.md).\n"
    "  --json prints one JSON object with the keys vertices, edges, faces, loops,\n"
    "  volumes, groups, euler_characteristic_surface, euler_characteristic_solid, valid,\n"
    "  closed, manifold, volume, area, centroid, bbox, warnings and the detailed\n"
    "  findings (docs/io.md). Without cells (an open mesh) volume is the signed volume\n"
    "  of the surface, with a warning.\n"
    "  --strict exits 1 (after printing the report) when the model is not valid, when\n"
    "  faces of it intersect (self_intersections) or when a face's loop crosses itself\n"
    "  (self_crossing_faces): what a slicer or a Boolean would refuse. Non-planar faces\n"
    "  (faceted curved primitives are planar only in exact arithmetic) are reported and\n"
    "  do not fail it. On a terminal a run longer than a second shows its stage\n"
    "  on standard error.";

std::string report_json(const io::ImportReport& r) {
  std::string s = "{\"input_positions\": " + std::to_string(r.input_positions) +
                  ", \"input_polygons\": " + std::to_string(r.input_polygons) +
                  ", \"welded_vertices\": " + std::to_string(r.welded_vertices) +
                  ", \"unused_vertices\": " + std::to_string(r.unused_vertices) +
                  ", \"degenerate_dropped\": " + std::to_string(r.degenerate_dropped) +
                  ", \"degenerate_polygons\": [";
  for (std::size_t i = 0; i < r.degenerate_polygons.size(); ++i)
    s += (i ? ", " : "") + std::to_string(r.degenerate_polygons[i]);
  return s + "], \"flipped_faces\": " + std::to_string(r.flipped_faces) +
         ", \"closed_shells\": " + std::to_string(r.closed_shells) + "}";
}

int run(const std::vector<std::string>& args) {
  CLI::App app{kSummary, "cellforge info"};
  std::string file, format;
  std::vector<std::string> options;
  bool json = false, strict = false, no_self = false;
  app.add_option("FILE", file, "the model file, or - for standard input")->required();
  app.add_option("KEY=VALUE", options, "import options and read limits (below)");
  app.add_flag("--json", json, "print one JSON object");
  app.add_flag("--strict", strict,
               "exit 1 when the model is not valid, intersects itself or has a "
               "self-crossing face");
  app.add_flag("--no-self-intersections", no_self, "skip the self-intersection check");
  bool no_geometry = false;
  app.add_flag("--no-geometry", no_geometry, "skip the crossing-loop and planarity findings");
  app.add_option("--format", format, "the format of FILE (needed for -): stl obj off 3mf json");
  app.footer(kUsage);
  if (auto code = parse(app, args)) return *code;
  io::ReadOptions read;
  io::DiagnoseOptions diag;
  diag.self_intersections = !no_self;
  diag.geometry = !no_geometry;
  for (const std::string& a : options) {
    std::string key, value;
    if (!split_key_value(a, key, value)) {
      std::cerr << "cellforge info: unexpected argument '" << a
                << "' (one FILE, then KEY=VALUE options)\n";
      return 2;
    }
    if (Status s = io::set_option(read, key, value); !s) {
      std::cerr << "cellforge info: " << s.error().message << '\n';
      return 2;
    }
  }
  if (!format.empty()) {
    auto f = io::format_from_name(format);
    if (!f) {
      std::cerr << "cellforge info: " << f.error().message << '\n';
      return 2;
    }
    read.format = *f;
  }
  Model m;
  Progress progress("cellforge info");
  progress.stage("reading " + file);
  auto r = io::read_file(m, file, read);
  if (!r) {
    progress.finish();
    std::cerr << "cellforge info: " << r.error().message << '\n';
    return 1;
  }
  diag.progress = [&](std::string_view stage) { progress.stage(std::string(stage)); };
  const io::Diagnosis d = io::diagnose(m, diag);
  progress.finish();
  if (json) {
    std::string out = io::to_json(d);
    const std::size_t end = out.rfind('}');
    out.insert(end, ",\n  \"import\": " + report_json(r->report) + "\n");
    std::cout << out;
  } else {
    std::cout << "file: " << file << '\n' << io::to_text(d);
    const io::ImportReport& rep = r->report;
    std::cout << "import: " << rep.input_polygons << " polygons, " << rep.welded_vertices
              << " distinct positions, " << rep.degenerate_dropped
              << " degenerate polygons dropped, " << rep.flipped_faces << " faces flipped, "
              << rep.closed_shells << " closed shells\n";
  }
  const bool sound = d.valid && d.self_intersections.empty() && d.self_crossing_faces.empty();
  return strict && !sound ? 1 : 0;
}

const CommandRegistration kInfo{Command{"info", kSummary, kUsage, run, true}};

}  // namespace
}  // namespace cellforge::cli
