// `cellforge convert IN OUT`: reads IN and writes OUT, each in the format its
// extension names (io/mesh_io.h), or standard input and output for '-'. What OUT's
// format cannot hold (wire edges and points in STL, groups in OFF) is said, not
// dropped silently.
#include <iostream>

#include "cellforge/io/mesh_io.h"
#include "command.h"
#include "progress.h"

namespace cellforge::cli {
namespace {

constexpr const char* kSummary = "convert a model between STL, OBJ, OFF, 3MF and JSON";
constexpr const char* kUsage =
    "usage: cellforge convert IN OUT [--ascii] [--triangulate] [--from F] [--to F]\n"
    "                         [KEY=VALUE...]\n"
    "  IN, OUT: .stl .obj .off .3mf .json, by extension (STL input: ASCII or binary,\n"
    "  told apart by content); - is standard input or output, with --from / --to\n"
    "  naming the format. --ascii writes ASCII STL (default binary);\n"
    "  --triangulate writes OBJ/OFF faces as triangles (faces with holes always are).\n"
    "  KEY=VALUE import options as for `cellforge info` (weld_tolerance=T,\n"
    "  merge_coplanar=true, repair_orientation=true, volumes=auto|none, max_bytes=N,\n"
    "  max_3mf_bytes=N). What OUT's format leaves out is printed as a warning.";

int run(const std::vector<std::string>& args) {
  CLI::App app{kSummary, "cellforge convert"};
  std::string in, out, from, to;
  std::vector<std::string> options;
  bool ascii = false;
  io::ReadOptions read;
  io::WriteOptions write;
  app.add_option("IN", in, "the model to read, or - for standard input")->required();
  app.add_option("OUT", out, "the file to write, or - for standard output")->required();
  app.add_option("KEY=VALUE", options, "import options and read limits");
  app.add_flag("--ascii", ascii, "write ASCII STL (default binary)");
  app.add_flag("--triangulate", write.triangulate, "write OBJ/OFF faces as triangles");
  app.add_option("--from", from, "the format of IN (needed for -)");
  app.add_option("--to", to, "the format of OUT (needed for -)");
  app.footer(kUsage);
  if (auto code = parse(app, args)) return *code;
  write.stl_binary = !ascii;
  for (const std::string& a : options) {
    std::string key, value;
    if (!split_key_value(a, key, value)) {
      std::cerr << "cellforge convert: unexpected argument '" << a
                << "' (IN OUT, then KEY=VALUE)\n";
      return 2;
    }
    if (Status s = io::set_option(read, key, value); !s) {
      std::cerr << "cellforge convert: " << s.error().message << '\n';
      return 2;
    }
  }
  for (auto [name, slot] : {std::pair{&from, &read.format}, {&to, &write.format}}) {
    if (name->empty()) continue;
    auto f = io::format_from_name(*name);
    if (!f) {
      std::cerr << "cellforge convert: " << f.error().message << '\n';
      return 2;
    }
    *slot = *f;
  }
  if (!write.format && out != "-") {
    if (auto f = io::format_from_path(out); !f) {
      std::cerr << "cellforge convert: " << f.error().message << '\n';
      return 2;
    }
  }
  if (out == "-" && !write.format) {
    std::cerr << "cellforge convert: writing standard output needs --to FORMAT\n";
    return 2;
  }
  Model m;
  Progress progress("cellforge convert");
  progress.stage("reading " + in);
  auto r = io::read_file(m, in, read);
  if (!r) {
    progress.finish();
    std::cerr << "cellforge convert: " << r.error().message << '\n';
    return 1;
  }
  const io::Format format = write.format ? *write.format : *io::format_from_path(out);
  progress.stage("writing " + out);
  const auto losses = io::format_losses(m, format);
  const Status written = io::write_file(m, out, write);
  progress.finish();
  for (const std::string& loss : losses) std::cerr << "cellforge convert: warning: " << loss << '\n';
  if (!written) {
    std::cerr << "cellforge convert: " << written.error().message << '\n';
    return 1;
  }
  // The summary goes to standard error when the model itself went to standard output.
  (out == "-" ? std::cerr : std::cout)
      << in << " -> " << out << ": " << m.num_vertices() << " vertices, " << m.num_edges()
      << " edges, " << m.num_faces() << " faces, " << m.num_volumes() << " volumes\n";
  return 0;
}

const CommandRegistration kConvert{Command{"convert", kSummary, kUsage, run, true}};

}  // namespace
}  // namespace cellforge::cli
