// Runs the cellforge command line (CELLFORGE_BIN, set by CMake for every test
// program) with arguments, capturing its exit status and its output (stdout and
// stderr together).
#pragma once

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace cellforge::testing {

struct CliRun {
  int status;
  std::string out;
};

inline CliRun run_cli(const std::string& args) {
  const std::string cmd = std::string(CELLFORGE_BIN) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  std::string out;
  std::array<char, 4096> buf;
  while (std::size_t n = std::fread(buf.data(), 1, buf.size(), p)) out.append(buf.data(), n);
  const int status = pclose(p);
  return {WEXITSTATUS(status), out};
}

}  // namespace cellforge::testing
