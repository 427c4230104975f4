// The cellforge command's subcommands. Each cmd_<name>.cpp registers its
// subcommands at start-up with a static CommandRegistration; main.cpp dispatches.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace cellforge::cli {

struct Command {
  std::string name;     // "make", "info", "db", ...
  std::string summary;  // one line for --help
  std::string usage;    // printed by `cellforge help NAME` and on usage errors
  // Receives the arguments after the subcommand name; returns the exit code.
  std::function<int(const std::vector<std::string>&)> run;
};

std::vector<Command>& registry();

struct CommandRegistration {
  explicit CommandRegistration(Command c) { registry().push_back(std::move(c)); }
};

// Splits "key=value" arguments; returns false for an argument without '='.
bool split_key_value(const std::string& arg, std::string& key, std::string& value);

}  // namespace cellforge::cli
