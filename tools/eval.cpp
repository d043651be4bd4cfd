// dstrans eval: evaluates shared formulas by name on the CPU, or on the GPU through a backend, reading
// JSON lines {"fn": NAME, "args": {...}} and writing one JSON line per input, in order.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <dstrans/formula.hpp>

#ifdef DSTRANS_HAVE_GL
#include <dstrans_gl.hpp>
#endif

#include "cli.hpp"
#include "gpu.hpp"
#include "json_input.hpp"

namespace dstrans::cli {

namespace {

// Ordered, so that fields come out in declaration order and "fn" first.
using json = nlohmann::ordered_json;

const char* const usage =
    "usage: dstrans eval --backend cpu|gl|vk      JSON lines {\"fn\": NAME, \"args\": {...}} on stdin\n"
    "       dstrans eval --list [--json]          every formula, its arguments and result\n"
    "NaN and infinities are written (and may be given) as \"nan\", \"inf\", \"-inf\". An input's \"case\"\n"
    "is echoed in its output line; other keys are ignored (tests/hard_cases.jsonl feeds straight in).\n";

// A type as `eval --list --json` names it: a string, or an object of fields for a struct.
json type_json(const value_type& t) {
  if (t.kind != value_kind::record) return t.name();
  json fields = json::object();
  for (const auto& f : t.fields) fields[f.first] = type_json(f.second);
  return fields;
}

// Bounds on what one input line may hold: a call is a few hundred bytes.
constexpr std::size_t max_line = std::size_t(1) << 20, max_label = 1024;

// A value that does not fit its type: the message names where.
struct bad_value {
  std::string message;
};

float to_float(const json& v, const std::string& where) {
  if (v.is_number()) return v.get<float>();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "nan") return std::nanf("");
    if (s == "inf") return INFINITY;
    if (s == "-inf") return -INFINITY;
  }
  throw bad_value{where + ": expected a number (or \"nan\", \"inf\", \"-inf\"), got " + excerpt(v)};
}

std::int64_t to_integer(const json& v, const std::string& where, std::int64_t lo, std::int64_t hi) {
  // An unsigned JSON number (2^64 - 1, say) would wrap in get<std::int64_t>().
  if (v.is_number_unsigned()) {
    const std::uint64_t u = v.get<std::uint64_t>();
    if (u <= std::uint64_t(hi) && std::int64_t(u) >= lo) return std::int64_t(u);
  } else if (v.is_number_integer()) {
    const std::int64_t i = v.get<std::int64_t>();
    if (i >= lo && i <= hi) return i;
  }
  throw bad_value{where + ": expected a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " +
                  excerpt(v)};
}

void pack(const value_type& t, const json& v, const std::string& where, words& out) {
  auto vector_of = [&](int n) {
    if (!v.is_array() || int(v.size()) != n)
      throw bad_value{where + ": expected " + t.name() + " (an array of " + std::to_string(n) + "), got " + excerpt(v)};
  };
  switch (t.kind) {
    case value_kind::float_: put(to_float(v, where), out); return;
    case value_kind::vec2: case value_kind::vec3: case value_kind::vec4:
      vector_of(t.word_count());
      for (std::size_t i = 0; i < v.size(); ++i) put(to_float(v[i], where + "[" + std::to_string(i) + "]"), out);
      return;
    case value_kind::int_: put(int(to_integer(v, where, INT32_MIN, INT32_MAX)), out); return;
    case value_kind::ivec2:
      vector_of(2);
      for (std::size_t i = 0; i < 2; ++i) put(int(to_integer(v[i], where + "[" + std::to_string(i) + "]", INT32_MIN, INT32_MAX)), out);
      return;
    case value_kind::uint_: put(unsigned(to_integer(v, where, 0, UINT32_MAX)), out); return;
    case value_kind::bool_:
      if (!v.is_boolean()) throw bad_value{where + ": expected true or false, got " + excerpt(v)};
      put(v.get<bool>(), out);
      return;
    case value_kind::record: {
      if (!v.is_object()) throw bad_value{where + ": expected an object " + t.name() + ", got " + excerpt(v)};
      for (const auto& f : t.fields) {
        if (!v.contains(f.first)) throw bad_value{where + ": missing field '" + f.first + "'"};
        pack(f.second, v[f.first], where + "." + f.first, out);
      }
      for (const auto& [key, value] : v.items()) {
        bool known = false;
        for (const auto& f : t.fields) known = known || f.first == key;
        if (!known) throw bad_value{where + ": unknown field '" + key + "'"};
      }
      return;
    }
  }
}

json float_json(float f) {
  if (std::isnan(f)) return "nan";
  if (std::isinf(f)) return f > 0 ? "inf" : "-inf";
  return double(f);
}

json unpack(const value_type& t, const std::uint32_t*& p) {
  switch (t.kind) {
    case value_kind::float_: return float_json(value_traits<float>::get(p));
    case value_kind::int_: return value_traits<int>::get(p);
    case value_kind::uint_: return value_traits<unsigned>::get(p);
    case value_kind::bool_: return value_traits<bool>::get(p);
    case value_kind::ivec2: {
      json a = json::array();
      for (int i = 0; i < 2; ++i) a.push_back(value_traits<int>::get(p));
      return a;
    }
    case value_kind::record: {
      json o = json::object();
      for (const auto& f : t.fields) o[f.first] = unpack(f.second, p);
      return o;
    }
    default: {
      json a = json::array();
      for (int i = 0; i < t.word_count(); ++i) a.push_back(float_json(value_traits<float>::get(p)));
      return a;
    }
  }
}

// Runs a batch of calls of one formula on the chosen backend.
using runner = std::function<result<words>(const formula&, const words&, std::size_t)>;

result<runner> make_runner(const std::string& backend) {
  if (backend == "cpu") return runner([](const formula& f, const words& a, std::size_t n) -> result<words> { return run_cpu(f, a, n); });
  if (backend != "gl" && backend != "vk") throw usage_error{"--backend must be cpu, gl or vk, not '" + backend + "'"};
  auto opened = open_gpu(backend);
  if (!opened) return failure{opened.error()};
  std::shared_ptr<gpu> g = std::move(*opened);
#ifdef DSTRANS_HAVE_GL
  if (g->gl) {
    // The runner's programs go before the context: members are destroyed in reverse order.
    struct gl_state {
      std::shared_ptr<gpu> context;
      gl::formula_runner programs;
    };
    auto state = std::make_shared<gl_state>();
    state->context = g;
    return runner([state](const formula& f, const words& a, std::size_t n) { return state->programs.run(f, a, n); });
  }
#endif
#ifdef DSTRANS_HAVE_VK
  return runner([g](const formula& f, const words& a, std::size_t n) { return g->vk->run_formula(f, a, n); });
#else
  return failure{"no backend"};
#endif
}

int list(bool as_json) {
  json all = json::array();
  for (const formula& f : formulas()) {
    json args = json::object();
    for (const auto& a : f.args) args[a.first] = type_json(a.second);
    all.push_back({{"fn", f.name}, {"args", args}, {"result", type_json(f.result)}});
  }
  if (as_json) {
    std::puts(all.dump().c_str());
    return 0;
  }
  for (const formula& f : formulas()) {
    std::string sig = f.result.name() + " " + f.name + "(";
    for (std::size_t i = 0; i < f.args.size(); ++i) sig += (i ? ", " : "") + f.args[i].second.name() + " " + f.args[i].first;
    std::printf("%s)    [%s:%d]\n", sig.c_str(), f.block->file, f.block->line);
  }
  return 0;
}

}  // namespace

int eval(std::vector<std::string> args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(usage, stdout);
    return 0;
  }
  try {
    const std::string backend = take_option(args, "--backend", "");
    const bool listing = take_flag(args, "--list"), as_json = take_flag(args, "--json");
    for (const std::string& a : operands(args)) throw usage_error{"unknown argument '" + a + "'"};
    if (listing) return list(as_json);
    if (as_json) throw usage_error{"--json goes with --list"};
    if (backend.empty()) throw usage_error{"eval needs --backend cpu, gl or vk"};
    auto run = make_runner(backend);
    if (!run) {
      std::fprintf(stderr, "dstrans eval: %s\n", run.error().c_str());
      return 1;
    }
    // Read every call first, so that a GPU backend evaluates each formula in one dispatch.
    struct call {
      const formula* f = nullptr;
      json fn = nullptr;
      json label = nullptr;  // the input's "case", echoed so that a file of cases reads back by name
      std::string error;
      std::size_t index = 0;  // among the calls of f
    };
    std::vector<call> calls;
    std::map<const formula*, std::pair<words, std::size_t>> batches;
    std::string line;
    for (int number = 1; std::getline(std::cin, line); ++number) {
      if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
      call c;
      try {
        if (line.size() > max_line) throw bad_value{"longer than " + std::to_string(max_line) + " bytes"};
        const json in = parse_bounded<json>(line);
        if (!in.is_object() || !in.contains("fn") || !in["fn"].is_string()) throw bad_value{"expected {\"fn\": NAME, \"args\": {...}}"};
        const std::string& fn = in["fn"].get_ref<const std::string&>();
        if (fn.size() > max_label) throw bad_value{"fn: " + excerpt(in["fn"]) + " is no formula's name"};
        c.fn = in["fn"];
        if (in.contains("case")) {
          const json& label = in["case"];
          if (!label.is_string() || label.get_ref<const std::string&>().size() > max_label)
            throw bad_value{"case: expected a string of at most " + std::to_string(max_label) + " bytes, got " + excerpt(label)};
          c.label = label;
        }
        c.f = find_formula(fn);
        if (!c.f) throw bad_value{"unknown formula '" + fn + "' (see dstrans eval --list)"};
        const json a = in.contains("args") ? in["args"] : json::object();
        if (!a.is_object()) throw bad_value{"args: expected an object"};
        words packed;
        for (const auto& [name, type] : c.f->args) {
          if (!a.contains(name)) throw bad_value{"args: missing argument '" + name + "'"};
          pack(type, a[name], "args." + name, packed);
        }
        for (const auto& [key, value] : a.items()) {
          bool known = false;
          for (const auto& arg : c.f->args) known = known || arg.first == key;
          if (!known) throw bad_value{"args: unknown argument '" + key + "'"};
        }
        auto& batch = batches[c.f];
        c.index = batch.second++;
        batch.first.insert(batch.first.end(), packed.begin(), packed.end());
      } catch (const json::exception& e) {
        c.f = nullptr;
        c.error = "line " + std::to_string(number) + ": not JSON: " + parse_message(e);
      } catch (const json_too_big& e) {
        c.f = nullptr;
        c.error = "line " + std::to_string(number) + ": not a call: its JSON is " + e.message;
      } catch (const bad_value& e) {
        c.f = nullptr;
        c.error = "line " + std::to_string(number) + ": " + e.message;
      }
      calls.push_back(c);
    }
    std::map<const formula*, result<words>> results;
    for (auto& [f, batch] : batches) results.emplace(f, (*run)(*f, batch.first, batch.second));
    for (const call& c : calls) {
      json out{{"fn", c.fn}};
      if (!c.label.is_null()) out["case"] = c.label;
      if (!c.f) {
        out["error"] = c.error;
      } else if (const auto& r = results.at(c.f); !r) {
        out["error"] = r.error();
      } else {
        const std::uint32_t* p = r->data() + c.index * std::size_t(c.f->result.word_count());
        out["result"] = unpack(c.f->result, p);
      }
      std::puts(out.dump().c_str());
    }
    return 0;
  } catch (const usage_error& e) {
    std::fprintf(stderr, "dstrans eval: %s\n%s", e.message.c_str(), usage);
    return 2;
  }
}

}  // namespace dstrans::cli
