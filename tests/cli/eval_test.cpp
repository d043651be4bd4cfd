// dstrans eval end to end, as a script drives it: --list --json describes every formula, and random
// calls written as JSON lines give the same results on --backend gl and vk as on cpu (tests/agreement.hpp).
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <random>
#include <set>
#include <sstream>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include <dstrans/formula.hpp>

#include "../agreement.hpp"
#include "run_tool.hpp"

using json = nlohmann::ordered_json;

namespace {

// A random JSON value of `type` as --list --json names it, within the argument's domain, with 0 and 1
// mixed in.
json random_value(const json& type, const dstrans::input_range& range, std::mt19937& rng) {
  if (type.is_object()) {
    json o = json::object();
    for (const auto& [k, v] : type.items()) o[k] = random_value(v, range, rng);
    return o;
  }
  const std::string t = type.get<std::string>();
  std::uniform_real_distribution<float> real(range.lo, range.hi);
  if (range.unit && t == "vec3") {
    glm::vec3 v;
    do v = {real(rng), real(rng), real(rng)};
    while (glm::dot(v, v) < 1e-4f || glm::dot(v, v) > 1.0f);
    v = glm::normalize(v);
    return json::array({v.x, v.y, v.z});
  }
  std::uniform_int_distribution<int> small(-2, 64);
  // NaN, infinities and the other edge values are exercised call by call in backend_checks.hpp; mixed
  // at random they would mostly meet what GLSL leaves undefined (pow(1, inf), min of NaN), which is
  // for the hard cases to decide formula by formula.
  auto scalar_float = [&]() -> json {
    switch (rng() % 16) {
      case 0: return 0.0;
      case 1: return 1.0;
      default: return double(real(rng));
    }
  };
  if (t == "float") return scalar_float();
  if (t == "int") return small(rng);
  if (t == "uint") return std::uint32_t(rng());
  if (t == "bool") return bool(rng() & 1u);
  json a = json::array();
  const int n = t == "ivec2" ? 2 : t.back() - '0';
  for (int i = 0; i < n; ++i) a.push_back(t == "ivec2" ? json(small(rng)) : scalar_float());
  return a;
}

float as_float(const json& v) {
  if (v.is_string()) return v == "nan" ? NAN : v == "inf" ? INFINITY : -INFINITY;
  return v.get<float>();
}

// Whether two results agree: integers and bools exactly, floats within 2^exponent relative
// (tests/agreement.hpp says which exponent and why).
bool same(const json& a, const json& b, int exponent) {
  if (a.is_object() || a.is_array()) {
    if (a.size() != b.size()) return false;
    auto ib = b.begin();
    for (auto ia = a.begin(); ia != a.end(); ++ia, ++ib)
      if (!same(*ia, *ib, exponent)) return false;
    return true;
  }
  if (a.is_boolean() || (a.is_number_integer() && !b.is_number_float())) return a == b;
  const float x = as_float(a), y = as_float(b);
  if (std::isnan(x) || std::isinf(x)) return std::isnan(x) ? std::isnan(y) : x == y;
  return std::isfinite(y) && std::fabs(x - y) <= std::ldexp(std::fmax(1.0f, std::fabs(x)), exponent);
}

}  // namespace

TEST_CASE("eval --list --json names every formula with its argument and result types", "[cli][eval]") {
  const auto r = run("eval --list --json", "");
  REQUIRE(r.status == 0);
  const json list = json::parse(r.out);
  REQUIRE(list.size() == dstrans::formulas().size());
  for (const json& f : list) {
    const dstrans::formula* reg = dstrans::find_formula(f["fn"].get<std::string>());
    REQUIRE(reg);
    CHECK(f["args"].size() == reg->args.size());
  }
  const json partner = *std::find_if(list.begin(), list.end(), [](const json& f) { return f["fn"] == "dst_rows_partner"; });
  CHECK(partner["args"] == json{{"p", "ivec2"}, {"size", "ivec2"}});
  CHECK(partner["result"] == "ivec2");
}

TEST_CASE("eval gives the same results on gl and vk as on cpu for random calls of every formula", "[cli][eval]") {
  const json list = json::parse(run("eval --list --json", "").out);
  std::mt19937 rng(99);
  std::string input;
  std::size_t calls = 0;
  for (const json& f : list)
    for (int i = 0; i < 200; ++i, ++calls) {
      json args = json::object();
      const dstrans::formula* reg = dstrans::find_formula(f["fn"].get<std::string>());
      std::size_t k = 0;
      for (const auto& [name, type] : f["args"].items()) args[name] = random_value(type, reg->domains[k++], rng);
      input += json{{"fn", f["fn"]}, {"args", args}}.dump() + "\n";
    }
  const auto cpu = run("eval --backend cpu", input);
  REQUIRE(cpu.status == 0);
  const auto reference = lines(cpu.out);
  REQUIRE(reference.size() == calls);
  for (const char* backend : {"gl", "vk"}) {
    const auto gpu = run(std::string("eval --backend ") + backend, input);
    if (gpu.status == 1) {
      WARN("skipped " << backend << ": " << gpu.out);
      continue;
    }
    REQUIRE(gpu.status == 0);
    const auto results = lines(gpu.out);
    REQUIRE(results.size() == calls);
    for (std::size_t i = 0; i < calls; ++i) {
      INFO(backend << " line " << i + 1 << ": cpu " << reference[i].dump() << ", gpu " << results[i].dump());
      REQUIRE(results[i].contains("result"));
      const dstrans::formula& f = *dstrans::find_formula(reference[i]["fn"].get<std::string>());
      if (f.packed_field_bits) {
        REQUIRE(dstrans::testing::codes_agree(reference[i]["result"].get<std::uint32_t>(), results[i]["result"].get<std::uint32_t>(),
                                              f.packed_field_bits));
        continue;
      }
      REQUIRE(same(reference[i]["result"], results[i]["result"], dstrans::testing::tolerance_exponent(f)));
    }
  }
}

TEST_CASE("eval answers bad lines with an error line, in order, and bad options with exit 2", "[cli][eval]") {
  const auto r = run("eval --backend cpu",
                     "{\"fn\": \"dst_rows_keep\", \"args\": {\"p\": [0, 1], \"size\": [4, 4]}}\n"
                     "{\"fn\": \"dst_rows_keep\", \"args\": {\"p\": [0, 1]}}\n"
                     "{\"fn\": \"dst_rows_keep\", \"args\": {\"p\": [0.5, 1], \"size\": [4, 4]}}\n"
                     "{\"fn\": \"dst_encode_normal\", \"args\": {\"n\": [1, 2]}}\n"
                     "{\"fn\": \"dst_encode_normal\", \"args\": {\"n\": [1, 2, 3], \"m\": 1}}\n"
                     "{\"fn\": \"dst_nothing\"}\n"
                     "not json\n"
                     "{\"fn\": \"dst_encode_spec_power\", \"args\": {\"p\": \"-inf\"}}\n");
  REQUIRE(r.status == 0);
  const auto out = lines(r.out);
  REQUIRE(out.size() == 8);
  CHECK(out[0]["result"] == true);
  CHECK(out[1]["error"] == "line 2: args: missing argument 'size'");
  CHECK_THAT(out[2]["error"].get<std::string>(), Catch::Contains("args.p[0]: expected a whole number"));
  CHECK_THAT(out[3]["error"].get<std::string>(), Catch::Contains("args.n: expected vec3 (an array of 3)"));
  CHECK(out[4]["error"] == "line 5: args: unknown argument 'm'");
  CHECK_THAT(out[5]["error"].get<std::string>(), Catch::Contains("unknown formula 'dst_nothing'"));
  CHECK(out[6]["fn"].is_null());
  CHECK_THAT(out[6]["error"].get<std::string>(), Catch::Contains("line 7: not JSON"));
  CHECK(out[7]["result"] == "-inf");

  CHECK(run("eval --backend metal", "").status == 2);
  CHECK(run("eval", "").status == 2);
  CHECK(run("eval --json", "").status == 2);
}

// Each hard case of tests/hard_cases.jsonl, fed to `dstrans eval` as it is, returns the value
// written beside it, on every backend (within 2^-16 of max(1, |value|), the transcendental tolerance).
TEST_CASE("every hard case returns its documented value on cpu, gl and vk", "[cli][eval][hard_cases]") {
  std::ifstream file(std::string(DSTRANS_SOURCE_DIR) + "/tests/hard_cases.jsonl");
  REQUIRE(file);
  const std::string input((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  const auto cases = lines(input);
  REQUIRE(cases.size() >= 60);
  std::set<std::string> names;
  for (const json& c : cases) {
    INFO(c.dump());
    REQUIRE(c.contains("expect"));
    CHECK(names.insert(c["case"].get<std::string>()).second);  // a case is found by its name
  }
  for (const char* backend : {"cpu", "gl", "vk"}) {
    const auto r = run(std::string("eval --backend ") + backend, input);
    if (r.status == 1 && std::string(backend) != "cpu") {
      WARN("skipped " << backend << ": " << r.out);
      continue;
    }
    REQUIRE(r.status == 0);
    const auto results = lines(r.out);
    REQUIRE(results.size() == cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
      INFO(backend << ": " << cases[i]["case"].get<std::string>() << ": got " << results[i].dump());
      CHECK(results[i]["case"] == cases[i]["case"]);
      REQUIRE(results[i].contains("result"));
      CHECK(same(cases[i]["expect"], results[i]["result"], -16));
    }
  }
}
