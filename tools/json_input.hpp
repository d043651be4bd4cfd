// JSON from users, read safely: nesting bounded while parsing, and values quoted in error messages only as
// a short excerpt (never dump(), which recurses once a level and copies the whole value).
//
//   auto j = dstrans::parse_bounded<nlohmann::json>(text);   // throws json::exception or json_too_big
//   (a second argument raises the count of values: a glTF file's JSON may hold many more than a scene's)
//   throw bad_field{"camera.fov_y: expected a number, got " + dstrans::excerpt(j["camera"]["fov_y"])};
#pragma once

#include <cstddef>
#include <exception>
#include <string>

#include <nlohmann/json.hpp>

namespace dstrans {

// Scene files and eval lines nest a few levels and hold thousands of values (glass_room.json: about
// 3,000); past these bounds a text is refused while it is parsed, before its tree takes the memory.
inline constexpr int max_json_depth = 32;
inline constexpr std::size_t max_json_values = std::size_t(1) << 21;

struct json_too_big {
  std::string message;
};

template <class Json>
Json parse_bounded(const std::string& text, std::size_t max_values = max_json_values) {
  std::size_t values = 0;
  return Json::parse(text, [&values, max_values](int depth, typename Json::parse_event_t, Json&) {
    if (depth > max_json_depth) throw json_too_big{"nested more than " + std::to_string(max_json_depth) + " levels deep"};
    if (++values > max_values) throw json_too_big{"more than " + std::to_string(max_values) + " values long"};
    return true;
  });
}

// A parse error's message cut to a line (the parser quotes the token it stopped at, which may be long).
inline std::string parse_message(const std::exception& e) {
  const std::string m = e.what();
  return m.size() > 200 ? m.substr(0, 200) + "..." : m;
}

// A key or name from the text as an error quotes it: its first characters.
inline std::string key_excerpt(const std::string& key) { return key.size() > 40 ? key.substr(0, 40) + "..." : key; }

// The value's type and, for a scalar, its first characters: "an array of 3 values", "the string
// \"abc...\"", "1e+40".
template <class Json>
std::string excerpt(const Json& v) {
  constexpr std::size_t shown = 40;
  if (v.is_array()) return "an array of " + std::to_string(v.size()) + (v.size() == 1 ? " value" : " values");
  if (v.is_object()) return "an object of " + std::to_string(v.size()) + (v.size() == 1 ? " key" : " keys");
  if (v.is_string()) {
    const std::string& s = v.template get_ref<const std::string&>();
    // replace: a cut may fall inside a UTF-8 sequence.
    return "the string " + Json(s.substr(0, shown)).dump(-1, ' ', false, Json::error_handler_t::replace) +
           (s.size() > shown ? "..." : "");
  }
  return v.dump();  // a number, a bool or null: short
}

}  // namespace dstrans
