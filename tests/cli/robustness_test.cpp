// The command line against hostile input and hostile folders: a fuzz run of eval lines, bad options, and
// outputs that are all or nothing (a full disk, a symbolic link, a user's own file, a stale run).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "run_tool.hpp"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

const std::string pane = std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/pane.json";
const std::string small = " --backend gl --width 32 --height 18 --shadow-size 64";

// A fresh folder for one test.
std::string fresh(const std::string& name) {
  const std::string dir = std::string(DSTRANS_TEST_DIR) + "/robust_" + name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::set<std::string> listing(const std::string& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(dir)) out.insert(e.path().filename().string());
  return out;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// An eval line mutated: deep nesting, huge and fractional numbers, wrong types, truncation.
std::string mutate(const std::string& line, std::mt19937& rng) {
  static const std::vector<std::string> values{"18446744073709551615", "-9223372036854775809", "1e308", "0.5", "\"x\"",
                                               "null", "[]", "{}", "true", "[1,2,3,4,5]", "\"nan\"", "-1"};
  std::string s = line;
  const std::size_t colon = s.find(':', rng() % s.size());
  switch (rng() % 6) {
    case 0: return s.substr(0, rng() % s.size());
    case 1: {
      const std::size_t depth = 1 + rng() % 100000;
      if (colon == std::string::npos) return s;
      return s.substr(0, colon + 1) + std::string(depth, '[') + std::string(depth, ']') + "," + s.substr(colon + 1);
    }
    case 2: {
      if (colon == std::string::npos) return s;
      const std::size_t end = s.find_first_of(",}", colon + 1);
      return s.substr(0, colon + 1) + values[rng() % values.size()] + (end == std::string::npos ? "" : s.substr(end));
    }
    case 3: return "{\"case\": " + std::string(1 + rng() % 50000, '[') + "1" + "," + s.substr(1);
    case 4: {
      for (int k = 0; k < 4; ++k) s[rng() % s.size()] = char(32 + rng() % 95);
      return s;
    }
    default: return s;  // as it is: a valid call
  }
}

}  // namespace

TEST_CASE("eval answers 2,400 mutated lines, one line each, and exits cleanly", "[cli][eval][fuzz]") {
  std::vector<std::string> seeds;
  std::ifstream cases(std::string(DSTRANS_SOURCE_DIR) + "/tests/hard_cases.jsonl");
  for (std::string line; std::getline(cases, line);)
    if (!line.empty()) seeds.push_back(line);
  REQUIRE(seeds.size() > 50);
  std::mt19937 rng(7u);
  std::string input;
  std::size_t count = 0;
  for (int i = 0; i < 2400; ++i) {
    std::string line = mutate(seeds[rng() % seeds.size()], rng);
    for (char& c : line)
      if (c == '\n' || c == '\r') c = ' ';
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    input += line + "\n";
    ++count;
  }
  const auto r = run("eval --backend cpu", input);
  REQUIRE(r.status == 0);
  std::istringstream out(r.out);
  std::size_t answered = 0, errors = 0;
  for (std::string line; std::getline(out, line); ++answered) {
    INFO("output line " << answered << ": " << line.substr(0, 200));
    CHECK(line.size() < 4096);  // an error quotes an excerpt, never the whole input
    const json j = json::parse(line);
    CHECK(j.contains("result") != j.contains("error"));
    errors += j.contains("error");
  }
  CHECK(answered == count);
  CHECK(errors > 500);
  CHECK(errors < count);
}

TEST_CASE("eval refuses integers it cannot hold and labels that are not short strings", "[cli][eval]") {
  const auto r = run("eval --backend cpu",
                     "{\"fn\": \"dst_rows_partner\", \"args\": {\"p\": [18446744073709551615, 0], \"size\": [8, 8]}}\n"
                     "{\"fn\": \"dst_transparent\", \"case\": {\"a\": [1]}, \"args\": {\"alpha\": 0.5}}\n");
  REQUIRE(r.status == 0);
  const auto out = lines(r.out);
  REQUIRE(out.size() == 2);
  CHECK_THAT(out[0]["error"].get<std::string>(), Catch::Contains("expected a whole number from -2147483648 to 2147483647, got 18446744073709551615"));
  CHECK_THAT(out[1]["error"].get<std::string>(), Catch::Contains("case: expected a string of at most 1024 bytes, got an object of 1 key"));
}

TEST_CASE("a scene nested 100,000 deep is an error in plan, render and gen, not a crash", "[cli][hostile]") {
  const std::string dir = fresh("deep");
  std::string text = slurp(pane);
  text.replace(text.find("\"fov_y\": 55"), 11, "\"fov_y\": " + std::string(100000, '[') + std::string(100000, ']'));
  std::ofstream(dir + "/deep.json") << text;
  for (const std::string& cmd : {"plan " + dir + "/deep.json", "render " + dir + "/deep.json --out " + dir + "/o" + small,
                                 "gen pipeline " + dir + "/deep.json"}) {
    const auto r = run(cmd, "");
    INFO(cmd << ": " << r.out.substr(0, 300));
    CHECK(r.status == 1);
    CHECK_THAT(r.out, Catch::Contains("deep.json: not a scene file: its JSON is nested more than 32 levels deep"));
  }
}

TEST_CASE("bad command lines name the option at fault", "[cli][hostile]") {
  const std::string dir = fresh("flags");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"render " + pane + " --backend gl --out --float-targets", "option --out needs a value, not the option '--float-targets'"},
      {"render " + pane + " --backend gl --out " + dir + " --frobnicate", "unknown option '--frobnicate'"},
      {"render " + pane + " --backend gl --out " + dir + " --width 64 --width 32", "option --width is given twice"},
      {"render " + pane + " " + pane + " --backend gl --out " + dir, "render takes one scene file, not 2 arguments"},
      {"plan " + pane + " --jsn", "unknown option '--jsn'"},
      {"eval --backend cpu --lst", "unknown option '--lst'"},
      {"gen pipeline " + pane + " --side read", "gen pipeline takes only --out"},
  };
  for (const auto& [cmd, message] : cases) {
    const auto r = run(cmd, "");
    INFO(cmd << ": " << r.out.substr(0, 300));
    CHECK(r.status == 2);
    CHECK_THAT(r.out, Catch::Contains(message));
  }
}

TEST_CASE("files that are not scenes, and outputs that cannot be, are errors before any rendering", "[cli][hostile]") {
  const std::string dir = fresh("paths");
  const std::vector<std::pair<std::string, std::string>> cases{
      {"render " + std::string(DSTRANS_SOURCE_DIR) + " --out " + dir + small, ": a folder, not a scene file"},
      {"plan /dev/zero", "/dev/zero: not a plain file, so not read as a scene file"},
      {"render " + pane + " --out /dev/null/x" + small, "/dev/null/x: cannot make the output folder"},
      {"gen pipeline " + pane + " --out " + pane, ": not a folder"},
  };
  for (const auto& [cmd, message] : cases) {
    const auto r = run(cmd, "");
    INFO(cmd << ": " << r.out.substr(0, 300));
    CHECK(r.status == 1);
    CHECK_THAT(r.out, Catch::Contains(message));
  }
}

TEST_CASE("render's outputs are all or nothing, and never replace what is not its own", "[cli][outputs]") {
  SECTION("a full disk: exit 1, nothing new") {
    const std::string dir = fresh("full");
    // A file-size limit makes the first PNG's write fail as a full disk would (SIGXFSZ ignored: EFBIG).
    const auto r = run("render " + pane + " --out " + dir + " --backend gl --width 320 --height 180 --shadow-size 64", "",
                       "trap '' XFSZ; ulimit -f 8;");
    INFO(r.out);
    CHECK(r.status == 1);
    CHECK_THAT(r.out, Catch::Contains("cannot write: File too large"));
    CHECK(listing(dir).empty());
  }
  SECTION("a symbolic link in the folder is neither followed nor replaced") {
    const std::string dir = fresh("link");
    fs::create_symlink("/dev/full", dir + "/final.png");
    const auto r = run("render " + pane + " --out " + dir + small, "");
    INFO(r.out);
    CHECK(r.status == 1);
    CHECK_THAT(r.out, Catch::Contains("final.png: exists and is not a plain file"));
    CHECK(fs::is_symlink(dir + "/final.png"));
    CHECK(listing(dir) == std::set<std::string>{"final.png"});
  }
  SECTION("a user's own file is not overwritten") {
    const std::string dir = fresh("user");
    std::ofstream(dir + "/final.png") << "mine";
    const auto r = run("render " + pane + " --out " + dir + small, "");
    CHECK(r.status == 1);
    CHECK_THAT(r.out, Catch::Contains("final.png: exists and is not an output of an earlier dstrans run"));
    CHECK(slurp(dir + "/final.png") == "mine");
    CHECK(listing(dir) == std::set<std::string>{"final.png"});
  }
  SECTION("a second scene replaces the first run's files, and frame.json lists exactly what is there") {
    const std::string dir = fresh("rerun");
    REQUIRE(run("render " + std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/smoke.json --out " + dir + small, "").status == 0);
    std::ofstream(dir + "/notes.txt") << "the user's";
    const auto r = run("render " + pane + " --out " + dir + small, "");
    INFO(r.out);
    REQUIRE(r.status == 0);
    const json frame = json::parse(slurp(dir + "/frame.json"));
    std::set<std::string> listed{"notes.txt"};
    for (const auto& f : frame["files"]) listed.insert(f.get<std::string>());
    CHECK(listing(dir) == listed);
    CHECK(slurp(dir + "/notes.txt") == "the user's");
  }
}

TEST_CASE("bench leaves an earlier results.json alone when it cannot run", "[cli][outputs]") {
  const std::string dir = fresh("bench");
  std::ofstream(dir + "/results.json") << "[\"earlier\"]";
  const auto r = run("bench --quick --backend vk --out " + dir, "", "VK_ICD_FILENAMES=/nonexistent.json");
  INFO(r.out);
  CHECK(r.status == 1);
  CHECK(slurp(dir + "/results.json") == "[\"earlier\"]");
  CHECK(listing(dir) == std::set<std::string>{"results.json"});
}
