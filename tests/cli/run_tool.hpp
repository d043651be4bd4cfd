// Runs the dstrans tool as a script would, for the command-line tests.
#pragma once

#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

namespace cli_testing {

struct run_result {
  int status;
  std::string out;
};

// Runs the dstrans tool with `args`, feeding `input` on stdin; `prefix` goes before it on the shell's
// command line (variables for its environment, or commands such as "ulimit -f 8;").
inline run_result run(const std::string& args, const std::string& input, const std::string& prefix = "") {
  // One file per process: CTest runs test cases in parallel.
  const std::string in_path = std::string(DSTRANS_TEST_DIR) + "/eval_input_" + std::to_string(getpid()) + ".jsonl";
  std::ofstream(in_path) << input;
#ifdef DSTRANS_TOOL_FILTER
  const std::string tool = std::string(DSTRANS_TOOL_FILTER) + " " + DSTRANS_TOOL;
#else
  const std::string tool = DSTRANS_TOOL;
#endif
  const std::string cmd = prefix + " " + tool + " " + args + " < " + in_path + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  REQUIRE(pipe);
  std::string out;
  char buf[4096];
  std::size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, pipe)) > 0) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline std::vector<nlohmann::ordered_json> lines(const std::string& text) {
  std::vector<nlohmann::ordered_json> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(nlohmann::ordered_json::parse(line));
  return out;
}

}  // namespace cli_testing

using cli_testing::lines;
using cli_testing::run;
