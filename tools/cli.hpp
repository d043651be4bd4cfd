// Argument handling shared by the dstrans subcommands.
#pragma once

#include <string>
#include <vector>

#include "scene_json.hpp"

namespace dstrans::cli {

// A usage error: the message is printed with the subcommand's usage, and the tool exits with 2.
struct usage_error {
  std::string message;
};

// The value after option `name` in `args` (removing both), or `fallback` when absent.
std::string take_option(std::vector<std::string>& args, const std::string& name, const std::string& fallback);

// Whether option `name` in `args` (removing both) is "on" (true) or "off" (false); `fallback` when absent,
// a usage_error for any other value.
bool take_on_off(std::vector<std::string>& args, const std::string& name, bool fallback);

// Whether flag `name` is in `args` (removing it).
bool take_flag(std::vector<std::string>& args, const std::string& name);
// What is left of `args` once every known option is taken: the operands, or a usage_error naming the first
// unknown option.
std::vector<std::string> operands(const std::vector<std::string>& args);

// The resource budget of --budget MIB (scene_json.hpp's scene_budget; 1024 MiB when absent).
scene_budget take_budget(std::vector<std::string>& args);

// `text` as a whole number in [lo, hi], or a usage_error naming `what`.
int to_int(const std::string& text, int lo, int hi, const std::string& what);

// Subcommands: each takes the arguments after its name and returns the exit code.
int gen(std::vector<std::string> args);
int eval(std::vector<std::string> args);
int plan(std::vector<std::string> args);
int render(std::vector<std::string> args);
int bench(std::vector<std::string> args);

}  // namespace dstrans::cli
