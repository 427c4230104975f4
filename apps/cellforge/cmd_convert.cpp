// `cellforge convert IN OUT`: reads IN and writes OUT, each in the format its
// extension names (io/mesh_io.h).
#include <iostream>

#include "cellforge/io/mesh_io.h"
#include "command.h"

namespace cellforge::cli {
namespace {

constexpr const char* kUsage =
    "usage: cellforge convert IN OUT [--ascii] [--triangulate] [KEY=VALUE...]\n"
    "  IN, OUT: .stl .obj .off .3mf .json, by extension (STL input: ASCII or binary,\n"
    "  told apart by content). --ascii writes ASCII STL (default binary);\n"
    "  --triangulate writes OBJ/OFF faces as triangles (faces with holes always are).\n"
    "  KEY=VALUE import options as for `cellforge info` (weld_tolerance=T,\n"
    "  merge_coplanar=true, repair_orientation=true, volumes=auto|none).";

int run(const std::vector<std::string>& args) {
  std::vector<std::string> files;
  io::ReadOptions read;
  io::WriteOptions write;
  for (const std::string& a : args) {
    std::string key, value;
    if (a == "--ascii") {
      write.stl_binary = false;
    } else if (a == "--triangulate") {
      write.triangulate = true;
    } else if (split_key_value(a, key, value)) {
      if (Status s = io::set_option(read.import, key, value); !s) {
        std::cerr << "cellforge convert: " << s.error().message << "\n" << kUsage << '\n';
        return 2;
      }
    } else if (!a.empty() && a[0] != '-') {
      files.push_back(a);
    } else {
      std::cerr << "cellforge convert: unexpected argument '" << a << "'\n" << kUsage << '\n';
      return 2;
    }
  }
  if (files.size() != 2) {
    std::cerr << kUsage << '\n';
    return 2;
  }
  if (auto f = io::format_from_path(files[1]); !f) {
    std::cerr << "cellforge convert: " << f.error().message << '\n';
    return 2;
  }
  Model m;
  auto r = io::read_file(m, files[0], read);
  if (!r) {
    std::cerr << "cellforge convert: " << r.error().message << '\n';
    return 1;
  }
  if (Status s = io::write_file(m, files[1], write); !s) {
    std::cerr << "cellforge convert: " << s.error().message << '\n';
    return 1;
  }
  std::cout << files[0] << " -> " << files[1] << ": " << m.num_vertices() << " vertices, "
            << m.num_edges() << " edges, " << m.num_faces() << " faces, " << m.num_volumes()
            << " volumes\n";
  return 0;
}

const CommandRegistration kConvert{
    Command{"convert", "convert a model between STL, OBJ, OFF, 3MF and JSON", kUsage, run}};

}  // namespace
}  // namespace cellforge::cli
