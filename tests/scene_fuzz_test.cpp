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

#include "json_mutations.hpp"

using namespace dstrans;

namespace {

std::string read(const std::string& name) {
  std::ifstream in(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/" + name);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
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
