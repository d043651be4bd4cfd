// JSON texts mutated the ways a fuzz test tries them: truncated, deeply nested, huge and tiny numbers,
// wrong types, stray bytes, repeated and unknown keys, huge arrays, pieces cut out.
//
//   std::mt19937 rng(1);
//   const std::string text = dstrans::mutate(read("pane.json"), rng);   // one of the ways, by rng
#pragma once

#include <random>
#include <string>
#include <vector>

namespace dstrans {

// Where values start in `text`: after a ':' or a '[' or a ','.
inline std::vector<std::size_t> value_starts(const std::string& text) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == ':' || text[i] == '[' || text[i] == ',') out.push_back(i + 1);
  return out;
}

// The value that starts at `at` (to the next ',', ']' or '}' at its own level, roughly): its length.
inline std::size_t value_length(const std::string& text, std::size_t at) {
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

// `text` changed one of the ways above, picked by `rng`.
inline std::string mutate(const std::string& text, std::mt19937& rng) {
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

}  // namespace dstrans
