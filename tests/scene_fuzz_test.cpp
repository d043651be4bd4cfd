// A seeded fuzz test of the scene loader: the example scenes mutated thousands of ways (truncated, deeply
// nested, huge and tiny numbers, wrong types, stray bytes, repeated and unknown keys). Every case must
// come back as a scene or as a short error, never a crash, a hang or a runaway allocation; the sanitizer
// build runs it too.
#include <catch2/catch.hpp>

#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <dstrans/frame/plan.hpp>
#include <scene_json.hpp>

using namespace dstrans;

namespace {

std::string read(const std::string& name) {
  std::ifstream in(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/" + name);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// Where values start in `text`: after a ':' or a '[' or a ','.
std::vector<std::size_t> value_starts(const std::string& text) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == ':' || text[i] == '[' || text[i] == ',') out.push_back(i + 1);
  return out;
}

// The value that starts at `at` (to the next ',', ']' or '}' at its own level, roughly): its length.
std::size_t value_length(const std::string& text, std::size_t at) {
  int depth = 0;
  std::size_t i = at;
  for (; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '[' || c == '{') ++depth;
    if ((c == ']' || c == '}') && depth-- == 0) break;
    if (c == ',' && depth == 0) break;
  }
  return i - at;
}

std::string mutate(const std::string& text, std::mt19937& rng) {
  static const std::vector<std::string> replacements{
      "1e308", "-1e308", "1e39", "-1e39", "1e-45", "0", "-0", "3.7", "0.5", "-1", "18446744073709551615",
      "9223372036854775808", "\"\"", "\"x\"", "true", "false", "null", "[]", "{}", "[1,2]", "[1,2,3,4,5]",
      "{\"a\":1}", "\"nan\"", "2147483648", "100000", "1000000", "65", "-360.5", "[[[]]]"};
  const std::vector<std::size_t> starts = value_starts(text);
  std::string s = text;
  const int kind = int(rng() % 8);
  const std::size_t at = starts.empty() ? 0 : starts[rng() % starts.size()];
  switch (kind) {
    case 0: return s.substr(0, rng() % (s.size() + 1));  // truncated
    case 1: {  // deeply nested, at a value
      const std::size_t depth = 1 + rng() % 200000;
      return s.substr(0, at) + std::string(depth, '[') + std::string(depth, ']') + s.substr(at + value_length(s, at));
    }
    case 2: case 3: {  // a value replaced
      const std::string& r = replacements[rng() % replacements.size()];
      return s.substr(0, at) + r + s.substr(at + value_length(s, at));
    }
    case 4: {  // stray bytes
      for (int k = 0; k < 1 + int(rng() % 8); ++k) s[rng() % s.size()] = char(rng() % 256);
      return s;
    }
    case 5: {  // a key repeated or an unknown one
      const std::size_t brace = s.find('{', rng() % s.size());
      if (brace == std::string::npos) return s;
      return s.substr(0, brace + 1) + (rng() % 2 ? "\"position\": [0, 0, 0], " : "\"zzz\": {}, ") + s.substr(brace + 1);
    }
    case 6: {  // a huge array where a value goes
      std::string many = "[0";
      for (std::size_t k = rng() % 100000; k > 0; --k) many += ",1";
      return s.substr(0, at) + many + "]" + s.substr(at + value_length(s, at));
    }
    default: {  // a piece cut out
      const std::size_t from = rng() % s.size(), n = rng() % 64;
      return s.erase(from, n);
    }
  }
}

}  // namespace

TEST_CASE("2,500 mutated scene files each load or give a short error", "[scene][fuzz]") {
  // hair.json with fewer strands: a case that loads builds its geometry, and 9,000 strands a case is slow.
  std::string hair = read("hair.json");
  hair.replace(hair.find("\"strands\": 9000"), 15, "\"strands\": 50");
  const std::vector<std::string> seeds{read("pane.json"), read("smoke.json"), hair, read("hard_cases.json")};
  std::mt19937 rng(20261201u);
  std::size_t loaded = 0, refused = 0;
  scene_budget budget;
  budget.bytes = std::size_t(256) << 20;
  for (int i = 0; i < 2500; ++i) {
    const std::string text = mutate(seeds[std::size_t(i) % seeds.size()], rng);
    const auto s = parse_scene(text, "fuzz.json", budget);
    if (s) {
      ++loaded;
      // A scene that loads can be planned.
      const render::frame_plan p = render::plan_of(*s, render::options{});
      CHECK(p.pipeline.bytes_per_pixel > 0);
    } else {
      ++refused;
      INFO("case " << i << ": " << s.error().substr(0, 200));
      CHECK(s.error().rfind("fuzz.json: ", 0) == 0);
      CHECK(s.error().size() < 400);
    }
  }
  // Both outcomes happen: the mutations are neither all harmless nor all fatal.
  CHECK(loaded > 100);
  CHECK(refused > 1000);
}
