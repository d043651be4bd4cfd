// The dstrans command line (DESIGN.md, "The dstrans command line").
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "cli.hpp"

namespace {

const char* const usage =
    "usage: dstrans <command> [options]\n"
    "commands:\n"
    "  gen <what> [options]   print GLSL: gbuffer <layout>, interlace <predicate>, pipeline <scene>\n"
    "  eval --backend B       evaluate shared formulas by name on cpu, gl or vk (JSON lines)\n"
    "  plan <scene>           the effects a scene calls for, and the passes and targets they need\n"
    "  render <scene>         render a frame and its buffers into --out DIR\n"
    "  bench [--quick]        the thesis's comparisons with times and errors, into --out DIR\n"
    "a scene is a JSON scene file (examples/scenes) or a glTF 2.0 asset (.gltf, .glb)\n"
    "run 'dstrans <command> --help' for a command's options\n";

}  // namespace

namespace dstrans::cli {

std::string take_option(std::vector<std::string>& args, const std::string& name, const std::string& fallback) {
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (args[i] != name) continue;
    if (i + 1 >= args.size()) throw usage_error{"option " + name + " needs a value"};
    std::string value = args[i + 1];
    // A value that looks like an option is the value forgotten ("--out --float-targets").
    if (value.rfind("--", 0) == 0) throw usage_error{"option " + name + " needs a value, not the option '" + value + "'"};
    args.erase(args.begin() + long(i), args.begin() + long(i) + 2);
    if (std::find(args.begin(), args.end(), name) != args.end()) throw usage_error{"option " + name + " is given twice"};
    return value;
  }
  return fallback;
}

bool take_on_off(std::vector<std::string>& args, const std::string& name, bool fallback) {
  const std::string value = take_option(args, name, fallback ? "on" : "off");
  if (value != "on" && value != "off") throw usage_error{name + " must be on or off, not '" + value + "'"};
  return value == "on";
}

bool take_flag(std::vector<std::string>& args, const std::string& name) {
  const auto at = std::find(args.begin(), args.end(), name);
  if (at == args.end()) return false;
  args.erase(at);
  if (std::find(args.begin(), args.end(), name) != args.end()) throw usage_error{"option " + name + " is given twice"};
  return true;
}

std::vector<std::string> operands(const std::vector<std::string>& args) {
  for (const std::string& a : args)
    if (a.rfind("--", 0) == 0) throw usage_error{"unknown option '" + a + "'"};
  return args;
}

scene_budget take_budget(std::vector<std::string>& args) {
  scene_budget b;
  const std::string mib = take_option(args, "--budget", "");
  if (!mib.empty()) b.bytes = std::size_t(to_int(mib, 1, 1 << 20, "--budget")) << 20;
  return b;
}

int to_int(const std::string& text, int lo, int hi, const std::string& what) {
  std::size_t used = 0;
  long v = 0;
  try {
    v = std::stol(text, &used);
  } catch (...) {
    used = 0;
  }
  if (used == 0 || used != text.size() || v < lo || v > hi)
    throw usage_error{what + " must be a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                      ", not '" + text + "'"};
  return int(v);
}

}  // namespace dstrans::cli

int main(int argc, char** argv) {
#ifdef __GLIBC__
  // Mesa's software rasterisers allocate and free their binning memory at every flush. With glibc's
  // default, adaptive thresholds, whether that memory goes back to the kernel and is faulted in again at
  // each flush depends on what the process happens to hold at the top of its heap: on glass_room at
  // 960x540 on llvmpipe it made some runs' frames 1.6 times slower (system time 0.5 s -> 5 s). Fixed
  // thresholds keep freed memory, so that a frame's time depends on the frame.
  mallopt(M_TRIM_THRESHOLD, 256 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
#endif
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::fputs(usage, args.empty() ? stderr : stdout);
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  if (command == "gen") return dstrans::cli::gen(args);
  if (command == "eval") return dstrans::cli::eval(args);
  if (command == "plan") return dstrans::cli::plan(args);
  if (command == "render") return dstrans::cli::render(args);
  if (command == "bench") {
#ifdef DSTRANS_HAVE_BENCH
    return dstrans::cli::bench(args);
#else
    std::fputs("dstrans: this dstrans was built without the benchmark (DSTRANS_BUILD_BENCH=OFF)\n", stderr);
    return 2;
#endif
  }
  std::fprintf(stderr, "dstrans: unknown command '%s'\n%s", command.c_str(), usage);
  return 2;
}
