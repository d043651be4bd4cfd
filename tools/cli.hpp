// Argument handling shared by the dstrans subcommands.
#pragma once

#include <string>
#include <vector>

namespace dstrans::cli {

// A usage error: the message is printed with the subcommand's usage, and the tool exits with 2.
struct usage_error {
  std::string message;
};

// The value after option `name` in `args` (removing both), or `fallback` when absent.
std::string take_option(std::vector<std::string>& args, const std::string& name, const std::string& fallback);

// `text` as a whole number in [lo, hi], or a usage_error naming `what`.
int to_int(const std::string& text, int lo, int hi, const std::string& what);

// Subcommands: each takes the arguments after its name and returns the exit code.
int gen(std::vector<std::string> args);
int eval(std::vector<std::string> args);
int plan(std::vector<std::string> args);
int render(std::vector<std::string> args);
int bench(std::vector<std::string> args);

}  // namespace dstrans::cli
