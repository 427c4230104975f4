// The cellforge command's subcommands. Each cmd_<name>.cpp registers its
// subcommands at start-up with a static CommandRegistration; main.cpp dispatches.
//
// Arguments are parsed with CLI11 (Debian's libcli11-dev), the same rules for every
// command. A command file adopts it in three steps:
//
//   int run(const std::vector<std::string>& args) {
//     CLI::App app{kSummary, "cellforge info"};   // the summary and the name in help
//     std::string file;
//     app.add_option("FILE", file, "the model file, or - for standard input")->required();
//     app.add_flag("--json", json, "print one JSON object");
//     app.footer(kDetails);                       // longer help after the options
//     if (auto code = parse(app, args)) return *code;
//     ...
//   }
//   const CommandRegistration kInfo{Command{"info", kSummary, kDetails, run, true}};
//
// parse() then gives the command `--` (what follows is positional: names beginning
// with '-' can be given), --help and -h (print the help, exit 0), and an error for an
// unknown option, a missing or malformed value ("--version 1.5"), or a missing
// positional ("cellforge info: ...", exit 2). The last field of Command tells main
// that the command prints its own help; for a command that does not (yet), main
// answers `cellforge NAME --help` and `cellforge help NAME` with its usage text.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace cellforge::cli {

struct Command {
  std::string name;     // "make", "info", "db", ...
  std::string summary;  // one line for --help
  std::string usage;    // printed by `cellforge help NAME` and on usage errors
  // Receives the arguments after the subcommand name; returns the exit code.
  std::function<int(const std::vector<std::string>&)> run;
  bool parses_help = false;  // run() answers --help itself (through parse() below)
};

std::vector<Command>& registry();

struct CommandRegistration {
  explicit CommandRegistration(Command c) { registry().push_back(std::move(c)); }
};

// Splits "key=value" arguments; returns false for an argument without '='.
bool split_key_value(const std::string& arg, std::string& key, std::string& value);

// Parses `args` (the words after the command name) into `app`. Returns nothing when
// the command should go on; otherwise the exit code, after printing the help (0) or
// the error and a pointer to --help (2) on standard error.
std::optional<int> parse(CLI::App& app, const std::vector<std::string>& args);

// An integer option whose value must be a whole number from `low` (CLI11 already
// refuses "1.5", "1e3" and "1abc" for an int).
CLI::Option* add_count(CLI::App& app, const std::string& name, int& out, int low,
                       const std::string& help);

}  // namespace cellforge::cli
