// `cellforge db`: the model database (store/). SQLite file by default
// (cellforge.db, or --db FILE); PostgreSQL when --db is a postgresql:// URL.
//
// Models come in and go out through io/: IN is a model file (STL, OBJ, OFF, 3MF,
// native JSON) or one of the bundled Euler-operator examples (example:box,
// example:box_with_hole, example:nonmanifold); OUT is a model file by extension, or
// the canonical dump (topo/dump.h) for '-' and *.txt.
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include "cellforge/io/mesh_io.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/dump.h"
#include "cellforge/topo/examples.h"
#include "command.h"

namespace cellforge::cli {
namespace {

constexpr const char* kUsage =
    "usage: cellforge db save IN --name N [--source FILE] [--object O] [--db DB]\n"
    "       cellforge db load N -o OUT [--version V] [--faces CONDITION] [--db DB]\n"
    "       cellforge db list [--db DB]\n"
    "       cellforge db rm N [--db DB]\n"
    "       cellforge db info N [--version V] [--db DB]\n"
    "       cellforge db sql \"SELECT ...\" [--json] [--timeout S] [--limit N] [--db DB]\n"
    "  DB: an SQLite file (default cellforge.db) or a postgresql:// connection string.\n"
    "  IN: a model file (.stl .obj .off .3mf .json) or example:box |\n"
    "      example:box_with_hole | example:nonmanifold (the bundled Euler examples).\n"
    "  OUT: a model file by extension (.json keeps everything the topology holds),\n"
    "       or the canonical dump (topo/dump.h) for *.txt and '-' (standard output).\n"
    "  Saving a name again adds a version; load and info take the latest unless\n"
    "  --version is given. load --faces loads only the faces satisfying CONDITION,\n"
    "  SQL on the face row f and the volume row v (e.g. \"f.group_key = 1\", or a\n"
    "  spatial query on face_tiles, docs/database.md), as a sheet model. sql runs\n"
    "  one read-only query (tables and views in docs/database.md;\n"
    "  face_edge_points is seed 004's Table 1), cancelled after --timeout seconds\n"
    "  (default 300), printing at most --limit rows (default 10000; 0: all).";

struct Args {
  std::vector<std::string> positional;
  std::map<std::string, std::string> options;  // --name N, -o OUT, ...
  bool json = false;
};

bool parse(const std::vector<std::string>& argv, Args& out, std::string& error) {
  static const char* kValued[] = {"--db",     "--name",  "-o",       "--version", "--source",
                                  "--object", "--faces", "--timeout", "--limit"};
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a == "--json") {
      out.json = true;
      continue;
    }
    bool valued = false;
    for (const char* v : kValued) valued = valued || a == v;
    if (valued) {
      if (i + 1 >= argv.size()) {
        error = a + " needs a value";
        return false;
      }
      out.options[a] = argv[++i];
    } else if (a.size() > 1 && a[0] == '-' && a != "-") {
      error = "unknown option " + a;
      return false;
    } else {
      out.positional.push_back(a);
    }
  }
  return true;
}

int fail(const std::string& message) {
  std::cerr << "cellforge db: " << message << '\n';
  return 1;
}

int usage_error(const std::string& message) {
  std::cerr << "cellforge db: " << message << "\n" << kUsage << '\n';
  return 2;
}

Result<Model> read_input(const std::string& in) {
  Model m;
  Status s;
  if (in == "example:box") {
    auto g = euler_box(m, {0, 0, 0}, {1, 1, 1}, true, "box");
    if (!g) s = g.error();
  } else if (in == "example:box_with_hole") {
    auto g = euler_box_with_hole(m, {0, 0, 0}, {3, 3, 1}, 1, 2, "box_with_hole");
    if (!g) s = g.error();
  } else if (in == "example:nonmanifold") {
    auto g = euler_nonmanifold_example(m, "nonmanifold");
    if (!g) s = g.error();
  } else if (in.rfind("example:", 0) == 0) {
    return Error{ErrorCode::kInvalidInput,
                 "unknown example '" + in +
                     "' (example:box, example:box_with_hole, example:nonmanifold)"};
  } else {
    auto r = io::read_file(m, in);
    if (!r) return r.error();
  }
  if (!s) return s.error();
  return m;
}

std::string format(const Vec3& v) {
  std::ostringstream os;
  os << std::setprecision(17) << v.x << ' ' << v.y << ' ' << v.z;
  return os.str();
}

void print_info(const VolumeInfo& v) {
  std::cout << std::setprecision(17) << "name: " << v.name << "\nversion: " << v.version
            << "\ntype: " << v.type << "\ncreated: " << v.created
            << "\ncentroid: " << format(v.centroid) << "\nvolume: " << v.volume
            << "\narea: " << v.area << "\nbbox: " << format(v.bbox_min) << " / "
            << format(v.bbox_max) << "\nvertices: " << v.vertices << "\nedges: " << v.edges
            << "\nfaces: " << v.faces << "\nloops: " << v.loops << "\ncells: " << v.cells
            << "\ngroups: " << v.groups << '\n';
  for (const Attribute& a : v.parameters)
    std::cout << "parameter: " << a.key << " = " << a.value << '\n';
  if (!v.source.empty()) std::cout << "source:\n" << v.source << '\n';
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += static_cast<char>(c);
    } else if (c < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", c);
      out += buf;
    } else {
      out += static_cast<char>(c);
    }
  }
  return out + "\"";
}

// A value that reads back as the same JSON number is printed bare.
bool is_json_number(const std::string& s) {
  std::size_t i = 0;
  if (i < s.size() && s[i] == '-') ++i;
  if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) return false;
  if (s[i] == '0' && i + 1 < s.size() && std::isdigit(static_cast<unsigned char>(s[i + 1]))) {
    return false;
  }
  while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  if (i < s.size() && s[i] == '.') {
    if (++i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) return false;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    if (++i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (i >= s.size() || !std::isdigit(static_cast<unsigned char>(s[i]))) return false;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
  }
  return i == s.size();
}

void print_json(const QueryResult& r) {
  std::cout << "[";
  for (std::size_t k = 0; k < r.rows.size(); ++k) {
    std::cout << (k ? ",\n " : "\n ") << "{";
    for (std::size_t c = 0; c < r.columns.size(); ++c) {
      const auto& v = r.rows[k][c];
      std::cout << (c ? ", " : "") << json_string(r.columns[c]) << ": "
                << (!v                   ? "null"
                    : is_json_number(*v) ? *v
                                         : json_string(*v));
    }
    std::cout << "}";
  }
  std::cout << (r.rows.empty() ? "]\n" : "\n]\n");
}

void print_table(const QueryResult& r) {
  std::vector<std::size_t> width(r.columns.size());
  for (std::size_t c = 0; c < r.columns.size(); ++c) width[c] = r.columns[c].size();
  for (const auto& row : r.rows) {
    for (std::size_t c = 0; c < row.size(); ++c) {
      width[c] = std::max(width[c], row[c] ? row[c]->size() : 4);
    }
  }
  auto line = [&](auto cell) {
    for (std::size_t c = 0; c < r.columns.size(); ++c) {
      const std::string s = cell(c);
      std::cout << (c ? "  " : "") << s
                << std::string(c + 1 < r.columns.size() ? width[c] - s.size() : 0, ' ');
    }
    std::cout << '\n';
  };
  line([&](std::size_t c) { return r.columns[c]; });
  line([&](std::size_t c) { return std::string(width[c], '-'); });
  for (const auto& row : r.rows) line([&](std::size_t c) { return row[c] ? *row[c] : "NULL"; });
  std::cout << "(" << r.rows.size() << (r.rows.size() == 1 ? " row)\n" : " rows)\n");
}

int run(const std::vector<std::string>& argv) {
  Args a;
  std::string error;
  if (!parse(argv, a, error)) return usage_error(error);
  if (a.positional.empty()) return usage_error("which db command?");
  const std::string cmd = a.positional[0];
  const auto arg = [&](std::size_t i) { return i < a.positional.size() ? a.positional[i] : ""; };
  const auto option = [&](const char* k) {
    const auto it = a.options.find(k);
    return it == a.options.end() ? std::string() : it->second;
  };
  int version = 0;
  if (const std::string v = option("--version"); !v.empty()) {
    try {
      version = std::stoi(v);
    } catch (const std::exception&) {
      return usage_error("--version takes a number");
    }
    if (version < 1) return usage_error("--version takes a number from 1");
  }
  const std::size_t wanted = cmd == "list" ? 1 : 2;
  if (a.positional.size() != wanted) return usage_error("wrong number of arguments for " + cmd);

  auto opened = open_store(option("--db"));
  if (!opened) return fail(opened.error().message);
  Store& store = *opened.value();

  if (cmd == "save") {
    if (!a.options.count("--name")) return usage_error("save needs --name N");
    auto m = read_input(arg(1));
    if (!m) return fail(m.error().message);
    PutOptions o;
    o.object = option("--object");
    if (const std::string src = option("--source"); !src.empty()) {
      std::ifstream f(src, std::ios::binary);
      if (!f) return fail("cannot read " + src);
      o.source.assign(std::istreambuf_iterator<char>(f), {});
    }
    auto info = store.put(option("--name"), m.value(), o);
    if (!info) return fail(info.error().message);
    std::cout << "saved " << info->name << " version " << info->version << " (" << info->type
              << ", " << info->faces << " faces) in " << store.backend() << '\n';
    return 0;
  }
  if (cmd == "load") {
    const std::string out = option("-o");
    if (out.empty()) return usage_error("load needs -o OUT");
    auto m = a.options.count("--faces") ? store.get_faces_where(arg(1), option("--faces"), version)
                                        : store.get(arg(1), version);
    if (!m) return fail(m.error().message);
    const bool dump = out == "-" || (out.size() > 4 && out.substr(out.size() - 4) == ".txt");
    if (!dump) {
      if (Status s = io::write_file(m.value(), out); !s) return fail(s.error().message);
      return 0;
    }
    const std::string text = canonical_dump(m.value());
    if (out == "-") {
      std::cout << text;
      return 0;
    }
    std::ofstream f(out, std::ios::binary);
    if (!(f << text)) return fail("cannot write " + out);
    return 0;
  }
  if (cmd == "list") {
    auto l = store.list();
    if (!l) return fail(l.error().message);
    for (const VolumeInfo& v : l.value()) {
      std::cout << v.name << "  version " << v.version << "  " << v.type << "  " << v.faces
                << " faces  " << v.created << '\n';
    }
    return 0;
  }
  if (cmd == "rm") {
    auto n = store.remove(arg(1));
    if (!n) return fail(n.error().message);
    if (n.value() == 0) return fail("no volume named '" + arg(1) + "'");
    std::cout << "removed " << arg(1) << " (" << n.value() << " versions)\n";
    return 0;
  }
  if (cmd == "info") {
    auto info = store.info(arg(1), version);
    if (!info) return fail(info.error().message);
    print_info(info.value());
    return 0;
  }
  if (cmd == "sql") {
    QueryOptions q;
    q.max_rows = 10000;
    try {
      std::size_t used = 0;
      if (const std::string t = option("--timeout"); !t.empty()) {
        q.timeout = std::stod(t, &used);
        if (used != t.size() || !(q.timeout > 0)) throw std::invalid_argument(t);
      }
      if (const std::string n = option("--limit"); !n.empty()) {
        q.max_rows = std::stoul(n, &used);
        if (used != n.size() || n[0] == '-') throw std::invalid_argument(n);
      }
    } catch (const std::exception&) {
      return usage_error("--timeout takes seconds above 0, --limit a count of rows");
    }
    auto r = store.query(arg(1), q);
    if (!r) return fail(r.error().message);
    a.json ? print_json(r.value()) : print_table(r.value());
    if (r->truncated) {
      std::cerr << "cellforge db: only the first " << q.max_rows
                << " rows are printed (--limit N for more, 0 for all)\n";
    }
    return 0;
  }
  return usage_error("unknown db command '" + cmd + "'");
}

const CommandRegistration registration({
    "db",
    "store, load, list and query models in an SQLite or PostgreSQL database",
    kUsage,
    run,
});

}  // namespace
}  // namespace cellforge::cli
