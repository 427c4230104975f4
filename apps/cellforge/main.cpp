// cellforge: the command-line entry point. Subcommands live in cmd_*.cpp.
#include <algorithm>
#include <iostream>

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

}  // namespace
}  // namespace cellforge::cli

int main(int argc, char** argv) {
  using namespace cellforge::cli;
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
    std::cout << c->usage << '\n';
    return 0;
  }
  const Command* c = find(args[0]);
  if (c == nullptr) {
    std::cerr << "cellforge: unknown command '" << args[0] << "'\n\n";
    print_help(std::cerr);
    return 2;
  }
  try {
    return c->run(std::vector<std::string>(args.begin() + 1, args.end()));
  } catch (const std::exception& e) {
    std::cerr << "cellforge " << c->name << ": " << e.what() << '\n';
    return 1;
  }
}
