// cellforge: the command-line entry point. Subcommands live in cmd_*.cpp.
#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "cellforge/geom/memory.h"
#include "command.h"

namespace cellforge::cli {

std::vector<Command>& registry() {
  static std::vector<Command> commands;
  return commands;
}

bool split_key_value(const std::string& arg, std::string& key, std::string& value) {
  const auto eq = arg.find('=');
  if (eq == std::string::npos || eq == 0) return false;
  key = arg.substr(0, eq);
  value = arg.substr(eq + 1);
  return true;
}

std::optional<int> parse(CLI::App& app, const std::vector<std::string>& args) {
  app.set_help_flag("-h,--help", "print this help and exit");
  app.allow_extras(false);
  std::vector<std::string> reversed(args.rbegin(), args.rend());  // CLI11 takes them last first
  try {
    app.parse(reversed);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return 0;
  } catch (const CLI::ParseError& e) {
    std::cerr << app.get_name() << ": " << e.what() << "\n(" << app.get_name()
              << " --help for the options)\n";
    return 2;
  }
  return std::nullopt;
}

CLI::Option* add_count(CLI::App& app, const std::string& name, int& out, int low,
                       const std::string& help) {
  return app.add_option(name, out, help)
      ->check(CLI::Validator(
          [low](std::string& v) -> std::string {
            // CLI11 converts after checks: refuse what is not a plain integer here too.
            std::size_t i = v.size() > 0 && (v[0] == '-' || v[0] == '+') ? 1 : 0;
            if (i == v.size()) return "expected a whole number, got '" + v + "'";
            for (std::size_t k = i; k < v.size(); ++k)
              if (v[k] < '0' || v[k] > '9') return "expected a whole number, got '" + v + "'";
            errno = 0;
            const long long n = std::strtoll(v.c_str(), nullptr, 10);
            if (errno != 0 || n < low || n > INT_MAX)
              return "expected a whole number from " + std::to_string(low) + ", got '" + v + "'";
            return std::string();
          },
          "INT>=" + std::to_string(low)));
}

namespace {

void print_help(std::ostream& os) {
  os << "cellforge " << CELLFORGE_VERSION
     << " - a non-manifold solid modeling kernel (adjacent-dimension cycle structure)\n\n"
        "usage: cellforge COMMAND [ARGS...]\n"
        "       cellforge --version | --help | help COMMAND\n\n"
        "commands:\n";
  auto commands = registry();
  std::sort(commands.begin(), commands.end(),
            [](const Command& a, const Command& b) { return a.name < b.name; });
  for (const Command& c : commands) {
    os << "  " << c.name << std::string(c.name.size() < 10 ? 10 - c.name.size() : 1, ' ')
       << c.summary << '\n';
  }
}

const Command* find(const std::string& name) {
  for (const Command& c : registry()) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

// The bytes of the arguments that name regular files.
std::uintmax_t input_bytes(int argc, char** argv) {
  std::uintmax_t total = 0;
  for (int i = 1; i < argc; ++i) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(argv[i], ec)) continue;
    const std::uintmax_t n = std::filesystem::file_size(argv[i], ec);
    if (!ec) total += n;
  }
  return total;
}

}  // namespace
}  // namespace cellforge::cli

int main(int argc, char** argv) {
  using namespace cellforge::cli;
  // One command, one job: memory freed between stages is kept for the next stage, and
  // a job on large files runs with its heap on huge pages (geom/memory.h: a third less
  // time for two spheres of 262,000 triangles on a virtual machine). Running again
  // costs about 17 ms, more than a small job gains, so only files of 8 MB and more
  // together ask for it.
  if (input_bytes(argc, argv) >= (std::uintmax_t{8} << 20)) cellforge::prefer_huge_pages(argv);
  cellforge::keep_freed_memory();
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    print_help(args.empty() ? std::cerr : std::cout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "cellforge " << CELLFORGE_VERSION << '\n';
    return 0;
  }
  if (args[0] == "help") {
    const Command* c = args.size() > 1 ? find(args[1]) : nullptr;
    if (c == nullptr) {
      print_help(std::cout);
      return args.size() > 1 ? 2 : 0;
    }
    if (c->parses_help) return c->run({"--help"});
    std::cout << c->usage << '\n';
    return 0;
  }
  const Command* c = find(args[0]);
  if (c == nullptr) {
    std::cerr << "cellforge: unknown command '" << args[0] << "'\n\n";
    print_help(std::cerr);
    return 2;
  }
  const std::vector<std::string> rest(args.begin() + 1, args.end());
  if (!c->parses_help) {
    for (const std::string& a : rest) {
      if (a == "--") break;
      if (a == "--help" || a == "-h") {
        std::cout << c->usage << '\n';
        return 0;
      }
    }
  }
  int code = 1;
  try {
    code = c->run(rest);
  } catch (const std::exception& e) {
    std::cerr << "cellforge " << c->name << ": " << e.what() << '\n';
    code = 1;
  }
  // Output that did not reach its file (a full disk, /dev/full, a closed pipe) is a
  // failure: every write to standard output is checked here, at its flush.
  std::cout.flush();
  errno = 0;
  if (!std::cout || std::fflush(stdout) != 0 || std::ferror(stdout)) {
    std::cerr << "cellforge " << c->name << ": cannot write standard output"
              << (errno ? std::string(": ") + std::strerror(errno) : std::string()) << '\n';
    return code == 0 ? 1 : code;
  }
  return code;
}
