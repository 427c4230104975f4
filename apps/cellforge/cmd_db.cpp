// `cellforge db`: the model database (store/). SQLite file by default
// (cellforge.db, or --db FILE); PostgreSQL when --db is a postgresql:// URL.
//
// Models come in and go out through io/: IN is a model file (STL, OBJ, OFF, 3MF,
// native JSON) or one of the bundled Euler-operator examples (example:box,
// example:box_with_hole, example:nonmanifold); OUT is a model file by extension, or
// the canonical dump (topo/dump.h) for '-' and *.txt.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "cellforge/io/mesh_io.h"
#include "cellforge/store/store.h"
#include "cellforge/topo/dump.h"
#include "cellforge/topo/examples.h"
#include "command.h"

namespace cellforge::cli {
namespace {

constexpr const char* kSummary =
    "store, load, list and query models in an SQLite or PostgreSQL database";
constexpr const char* kUsage =
    "usage: cellforge db save IN [--name N] [--source FILE] [--object O] [--format F] [--db DB]\n"
    "       cellforge db load N -o OUT [--version V] [--faces CONDITION] [--format F] [--db DB]\n"
    "       cellforge db list [--db DB]\n"
    "       cellforge db rm N [--version V] [--db DB]\n"
    "       cellforge db info N [--version V] [--db DB]\n"
    "       cellforge db sql \"SELECT ...\" [--json] [--timeout S] [--limit N] [--db DB]\n"
    "  DB: an SQLite file (default cellforge.db) or a postgresql:// connection string.\n"
    "  Only save creates an SQLite file; the other commands say when it is missing.\n"
    "  IN: a model file (.stl .obj .off .3mf .json), - for standard input (with\n"
    "      --format F), or example:box | example:box_with_hole | example:nonmanifold\n"
    "      (the bundled Euler examples). --name defaults to the file's stem (\"part\"\n"
    "      for part.stl, \"box\" for example:box).\n"
    "  OUT: a model file by extension (.json keeps everything the topology holds),\n"
    "       or the canonical dump (topo/dump.h) for *.txt and '-' (standard output;\n"
    "       with --format F, that format instead).\n"
    "  Saving a name again adds a version; load and info take the latest unless\n"
    "  --version is given; rm removes every version, or one with --version.\n"
    "  load --faces loads only the faces satisfying CONDITION,\n"
    "  SQL on the face row f and the volume row v (e.g. \"f.group_key = 1\", or a\n"
    "  spatial query on face_tiles, docs/database.md), as a sheet model. sql runs\n"
    "  one read-only query (tables and views in docs/database.md;\n"
    "  face_edge_points is seed 004's Table 1), cancelled after --timeout seconds\n"
    "  (default 300), printing at most --limit rows (default 10000; 0: all).\n"
    "  --json prints an array of objects: integers and finite reals as numbers,\n"
    "  other reals (inf, NaN) as null, blobs as \"\\\\x\" and hex digits, repeated\n"
    "  column names made unique (\"id\", \"id_2\").\n"
    "  A name that begins with '-' goes after --: cellforge db rm -- -odd.";

int fail(const std::string& message) {
  std::cerr << "cellforge db: " << message << '\n';
  return 1;
}

int usage_error(const std::string& message) {
  std::cerr << "cellforge db: " << message << "\n" << kUsage << '\n';
  return 2;
}

// The model of `in`, and the attachments its file keeps (a JSON file's exact form).
Result<Model> read_input(const std::string& in, const io::ReadOptions& options,
                         std::vector<Attachment>& attachments) {
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
    auto r = io::read_file(m, in, options);
    if (!r) return r.error();
    attachments = std::move(r->attachments);
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

// Length of the valid UTF-8 sequence at s[i] (1 for ASCII), or 0.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  if (c < 0x80) return 1;
  const std::size_t n = c >= 0xC2 && c < 0xE0   ? 2
                        : c >= 0xE0 && c < 0xF0 ? 3
                        : c >= 0xF0 && c < 0xF5 ? 4
                                                : 0;
  if (n == 0 || i + n > s.size()) return 0;
  std::uint32_t cp = c & (0x7F >> n);
  for (std::size_t k = 1; k < n; ++k) {
    const auto b = static_cast<unsigned char>(s[i + k]);
    if ((b & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (b & 0x3F);
  }
  static constexpr std::uint32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < kMin[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

// A JSON string; bytes that are not UTF-8 (text a query made) become U+FFFD.
std::string json_string(const std::string& text) {
  std::string s;
  for (std::size_t i = 0; i < text.size();) {
    const std::size_t n = utf8_length(text, i);
    if (n == 0) {
      s += "\xEF\xBF\xBD";
      ++i;
    } else {
      s.append(text, i, n);
      i += n;
    }
  }
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

// Column names as JSON keys, made unique: a repeated name gets _2, _3, ... (past
// any name the query already has).
std::vector<std::string> unique_keys(const std::vector<std::string>& columns) {
  std::vector<std::string> out;
  const std::set<std::string> taken(columns.begin(), columns.end());
  std::set<std::string> used;
  for (const std::string& c : columns) {
    std::string key = c;
    for (int k = 2; used.count(key) || (key != c && taken.count(key)); ++k)
      key = c + "_" + std::to_string(k);
    used.insert(key);
    out.push_back(key);
  }
  return out;
}

// The JSON value of one answer value.
std::string json_value(const std::optional<std::string>& v, ValueKind kind) {
  if (!v) return "null";
  if (kind == ValueKind::kInteger || kind == ValueKind::kReal) {
    return is_json_number(*v) ? *v : "null";  // Infinity and NaN have no JSON number
  }
  return json_string(*v);  // text, and blobs as \x and hex digits
}

// Prints an answer as it streams in (Store::query_each), as a JSON array of
// objects or as an aligned table. The table's columns are as wide as the header
// and the first kAligned rows, which are held until then (or the end); a later,
// wider value widens its column from there on. Each row callback returns false
// once standard output has failed, which stops the query.
class AnswerPrinter {
 public:
  explicit AnswerPrinter(bool json) : json_(json) {}
  QueryCallbacks callbacks() {
    QueryCallbacks c;
    c.columns = [this](const std::vector<std::string>& columns) { start(columns); };
    c.row = [this](const QueryRow& row) { return add(row); };
    return c;
  }
  // After the last row, or after an error (`complete` false): the rows read
  // before it are printed, without the end of the array or the row count.
  void finish(bool complete) {
    if (!started_) return;
    if (json_) {
      if (complete) std::cout << (rows_ == 0 ? "]\n" : "\n]\n");
      return;
    }
    flush_held();
    if (complete) std::cout << "(" << rows_ << (rows_ == 1 ? " row)\n" : " rows)\n");
  }

 private:
  static constexpr std::size_t kAligned = 1000;

  void start(const std::vector<std::string>& columns) {
    started_ = true;
    columns_ = columns;
    keys_ = unique_keys(columns);
    width_.assign(columns.size(), 0);
    for (std::size_t c = 0; c < columns.size(); ++c) width_[c] = columns[c].size();
    if (json_) std::cout << "[";
  }

  bool add(const QueryRow& row) {
    ++rows_;
    if (json_) {
      std::cout << (rows_ > 1 ? ",\n " : "\n ") << "{";
      for (std::size_t c = 0; c < columns_.size(); ++c) {
        const ValueKind kind = c < row.kinds.size() ? row.kinds[c] : ValueKind::kText;
        std::cout << (c ? ", " : "") << json_string(keys_[c]) << ": "
                  << json_value(row.values[c], kind);
      }
      std::cout << "}";
    } else if (!header_printed_) {
      held_.push_back(row.values);
      if (held_.size() == kAligned) flush_held();
    } else {
      line(row.values);
    }
    return static_cast<bool>(std::cout);
  }

  void flush_held() {
    if (header_printed_) return;
    for (const auto& row : held_) {
      for (std::size_t c = 0; c < row.size() && c < width_.size(); ++c) {
        width_[c] = std::max(width_[c], row[c] ? row[c]->size() : 4);
      }
    }
    print_line([&](std::size_t c) { return columns_[c]; });
    print_line([&](std::size_t c) { return std::string(width_[c], '-'); });
    header_printed_ = true;
    for (const auto& row : held_) line(row);
    held_.clear();
    held_.shrink_to_fit();
  }

  void line(const std::vector<std::optional<std::string>>& row) {
    print_line([&](std::size_t c) { return row[c] ? *row[c] : std::string("NULL"); });
  }

  template <class Cell>
  void print_line(Cell cell) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      const std::string s = cell(c);
      width_[c] = std::max(width_[c], s.size());
      std::cout << (c ? "  " : "") << s
                << std::string(c + 1 < columns_.size() ? width_[c] - s.size() : 0, ' ');
    }
    std::cout << '\n';
  }

  bool json_;
  std::vector<std::string> columns_, keys_;
  std::vector<std::size_t> width_;
  std::vector<std::vector<std::optional<std::string>>> held_;
  bool started_ = false, header_printed_ = false;
  std::size_t rows_ = 0;
};

std::string stem_of(const std::string& in) {
  if (in.rfind("example:", 0) == 0) return in.substr(8);
  return std::filesystem::path(in).stem().string();
}

int run(const std::vector<std::string>& argv) {
  CLI::App app{kSummary, "cellforge db"};
  app.footer(kUsage);
  app.require_subcommand(1, 1);
  std::string db, in, name, source, object, format, out, faces, sql;
  int version = 0;
  bool json = false;
  double timeout = 300;
  std::size_t limit = 10000;
  // --db before or after the subcommand: `db --db x.db list` and `db list --db x.db`.
  app.add_option("--db", db, "an SQLite file (default cellforge.db) or a postgresql:// URL");
  const auto with_db = [&](CLI::App* c) {
    c->add_option("--db", db, "an SQLite file (default cellforge.db) or a postgresql:// URL");
    c->set_help_flag("-h,--help", "print this help and exit");
    return c;
  };
  CLI::App* save = with_db(app.add_subcommand("save", "save a model as a new version"));
  save->add_option("IN", in, "a model file, - for standard input, or example:NAME")->required();
  save->add_option("--name", name, "the volume's name (default: IN's stem)");
  save->add_option("--source", source, "a script file stored with the version");
  save->add_option("--object", object, "an object (scene) that lists the name");
  save->add_option("--format", format, "the format of IN (needed for -)");
  CLI::App* load = with_db(app.add_subcommand("load", "load a version into a file"));
  load->add_option("NAME", name, "the volume's name")->required();
  load->add_option("-o", out, "a model file, *.txt or - for the canonical dump")->required();
  add_count(*load, "--version", version, 1, "the version (default: the latest)");
  load->add_option("--faces", faces, "load only the faces satisfying this SQL condition");
  load->add_option("--format", format, "write OUT in this format (with -: to standard output)");
  CLI::App* list = with_db(app.add_subcommand("list", "the latest version of every name"));
  CLI::App* rm = with_db(app.add_subcommand("rm", "remove a name's versions, or one"));
  rm->add_option("NAME", name, "the volume's name")->required();
  add_count(*rm, "--version", version, 1, "remove only this version");
  CLI::App* info = with_db(app.add_subcommand("info", "what a stored version is"));
  info->add_option("NAME", name, "the volume's name")->required();
  add_count(*info, "--version", version, 1, "the version (default: the latest)");
  CLI::App* query = with_db(app.add_subcommand("sql", "run one read-only SQL query"));
  query->add_option("QUERY", sql, "one SELECT statement")->required();
  query->add_flag("--json", json, "print an array of JSON objects");
  query->add_option("--timeout", timeout, "seconds before the query is cancelled (default 300)");
  query->add_option("--limit", limit, "the most rows printed (default 10000; 0: all)");
  if (auto code = parse(app, argv)) return *code;
  if (!(timeout > 0) || !std::isfinite(timeout))
    return usage_error("--timeout takes seconds above 0");

  // Only save creates a database file: for the others a missing SQLite file is an
  // error, not a new empty database.
  const bool pg = db.rfind("postgresql://", 0) == 0 || db.rfind("postgres://", 0) == 0;
  const std::string file = db.empty() ? "cellforge.db" : db;
  if (!pg && !save->parsed() && !std::filesystem::exists(file))
    return fail("no database " + file + " (db save creates it; --db names another)");
  auto opened = open_store(db);
  if (!opened) return fail(opened.error().message);
  Store& store = *opened.value();

  if (save->parsed()) {
    if (save->count("--name") == 0) {
      if (in == "-") return usage_error("save from standard input needs --name N");
      name = stem_of(in);
    }
    io::ReadOptions read;
    if (!format.empty()) {
      auto f = io::format_from_name(format);
      if (!f) return usage_error(f.error().message);
      read.format = *f;
    }
    PutOptions o;
    auto m = read_input(in, read, o.attachments);
    if (!m) return fail(m.error().message);
    o.object = object;
    if (!source.empty()) {
      auto bytes = io::read_bytes(source);
      if (!bytes) return fail(bytes.error().message);
      o.source.assign(bytes->begin(), bytes->end());
    }
    auto saved = store.put(name, m.value(), o);
    if (!saved) return fail(saved.error().message);
    std::cout << "saved " << saved->name << " version " << saved->version << " (" << saved->type
              << ", " << saved->faces << " faces) in " << store.backend() << '\n';
    return 0;
  }
  if (load->parsed()) {
    io::WriteOptions write;
    if (faces.empty() && version == 0) {  // the latest, named, so that both reads agree
      auto latest = store.info(name, 0);
      if (!latest) return fail(latest.error().message);
      version = latest->version;
    }
    auto m =
        !faces.empty() ? store.get_faces_where(name, faces, version) : store.get(name, version);
    if (!m) return fail(m.error().message);
    if (faces.empty()) {  // the attachments (an exact form) belong to the whole model
      auto attachments = store.get_attachments(name, version);
      if (!attachments) return fail(attachments.error().message);
      write.attachments = std::move(*attachments);
    }
    if (!format.empty()) {
      auto f = io::format_from_name(format);
      if (!f) return usage_error(f.error().message);
      write.format = *f;
    }
    const bool dump =
        !write.format && (out == "-" || (out.size() > 4 && out.substr(out.size() - 4) == ".txt"));
    if (!dump) {
      if (Status s = io::write_file(m.value(), out, write); !s) return fail(s.error().message);
      return 0;
    }
    const std::string text = canonical_dump(m.value());
    if (out == "-") {
      std::cout << text;
      return 0;
    }
    std::ofstream f(out, std::ios::binary);
    f << text;
    f.close();
    if (!f) return fail("cannot write " + out);
    return 0;
  }
  if (list->parsed()) {
    auto l = store.list();
    if (!l) return fail(l.error().message);
    for (const VolumeInfo& v : l.value()) {
      std::cout << v.name << "  version " << v.version << "  " << v.type << "  " << v.faces
                << " faces  " << v.created << '\n';
      if (!std::cout) break;  // main reports the failed write
    }
    return 0;
  }
  if (rm->parsed()) {
    auto n = version > 0 ? store.remove_version(name, version) : store.remove(name);
    if (!n) return fail(n.error().message);
    if (n.value() == 0) {
      return fail(version > 0 ? "no version " + std::to_string(version) + " of '" + name + "'"
                              : "no volume named '" + name + "'");
    }
    if (version > 0)
      std::cout << "removed " << name << " version " << version << '\n';
    else
      std::cout << "removed " << name << " (" << n.value() << " versions)\n";
    return 0;
  }
  if (info->parsed()) {
    auto i = store.info(name, version);
    if (!i) return fail(i.error().message);
    print_info(i.value());
    return 0;
  }
  QueryOptions q;
  q.timeout = timeout;
  q.max_rows = limit;
  AnswerPrinter printer(json);
  auto r = store.query_each(sql, q, printer.callbacks());
  printer.finish(r.ok());
  if (!r) return fail(r.error().message);
  if (r.value()) {
    std::cerr << "cellforge db: only the first " << q.max_rows
              << " rows are printed (--limit N for more, 0 for all)\n";
  }
  return 0;
}

const CommandRegistration registration({"db", kSummary, kUsage, run, true});

}  // namespace
}  // namespace cellforge::cli
