// GLSL source assembled from shared blocks and generated glue, with every line traceable to its origin.
//
//   dstrans::glsl::source src;
//   src.add_shared(dstrans::text::dst_surface);           // a shared block, once however often added
//   src.add("void main() {}\n", __FILE__, __LINE__);      // generated or hand-written text
//   std::string code = src.str();                         // starts with "#version 450"
//   dstrans::glsl::source old(dstrans::glsl::version::glsl330);   // "#version 330 core", samplers by name
//   dstrans::glsl::dialect gl;                            // an engine's own way of writing GLSL:
//   gl.pixel_rows = dstrans::glsl::rows::from_bottom;     // it passes gl_FragCoord's pixels as they are
//   dstrans::glsl::source mine(gl);
//   src.add_file("my_shaders/compose.frag.glsl", {"DST_TRANSPARENCY"});   // a pass shader, its lines mapped
//                                                         // to that file, its DST_ switches resolved
//   src.add_text(text, "my_pass.frag.glsl", {});          // the same for text already in memory
//   std::string errors = src.map_log(compiler_log);       // "0:12: ..." -> "include/dstrans/x.hpp:40: ..."
#pragma once

#include <cctype>
#include <cstddef>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "detail/shared.hpp"
#include "result.hpp"

namespace dstrans::glsl {

// Where a line of generated GLSL comes from.
struct origin {
  std::string file;
  int line = 0;
};

// Shared code as GLSL: one statement a line, indented, with DST_FN / DST_OUT / DST_INOUT spelled out.
inline std::string format_shared(const char* code) {
  std::string in(code), out;
  // The keywords first, so that formatting sees plain GLSL.
  for (std::size_t i = 0; i < in.size();) {
    auto starts = [&](const char* w) { return in.compare(i, std::char_traits<char>::length(w), w) == 0; };
    const bool boundary = i == 0 || !(std::isalnum(static_cast<unsigned char>(in[i - 1])) || in[i - 1] == '_');
    if (boundary && starts("DST_FN ")) {
      i += 7;
    } else if (boundary && (starts("DST_OUT(") || starts("DST_INOUT("))) {
      const bool inout = starts("DST_INOUT(");
      i += inout ? 10 : 8;
      const std::size_t close = in.find(')', i);
      std::string type = in.substr(i, close - i);
      while (!type.empty() && type.back() == ' ') type.pop_back();
      while (!type.empty() && type.front() == ' ') type.erase(0, 1);
      out += (inout ? "inout " : "out ") + type;
      i = close + 1;
    } else {
      out += in[i++];
    }
  }
  in.swap(out);
  out.clear();
  int depth = 0, parens = 0;
  bool line_start = true;
  auto newline = [&] {
    while (!out.empty() && out.back() == ' ') out.pop_back();
    out += '\n';
    line_start = true;
  };
  for (std::size_t i = 0; i < in.size(); ++i) {
    const char c = in[i];
    if (line_start) {
      if (c == ' ') continue;
      if (c == '}') --depth;
      out.append(std::size_t(2 * (depth > 0 ? depth : 0)), ' ');
      line_start = false;
      if (c == '}') {
        out += '}';
        if (i + 1 < in.size() && in[i + 1] == ';') out += in[++i];
        newline();
        if (depth == 0) out += '\n';
        continue;
      }
    }
    if (c == '(') ++parens;
    if (c == ')') --parens;
    if (c == '{' && parens == 0) {
      out += '{';
      ++depth;
      newline();
    } else if (c == ';' && parens == 0) {
      out += ';';
      newline();
    } else if (c == '}' && parens == 0) {
      newline();
      --i;  // emit it at the start of its own line
    } else {
      out += c;
    }
  }
  if (!line_start) newline();
  return out;
}

}  // namespace dstrans::glsl

namespace dstrans::detail {
// The names formatted shared code defines at its top level: its structs and its functions.
inline std::vector<std::string> top_level_names(const std::string& formatted) {
  std::vector<std::string> names;
  std::istringstream lines(formatted);
  for (std::string line; std::getline(lines, line);) {
    if (line.empty() || line[0] == ' ' || line.back() != '{') continue;
    if (line.rfind("struct ", 0) == 0) {
      names.push_back(line.substr(7, line.find(' ', 7) - 7));
    } else if (const std::size_t open = line.find('('); open != std::string::npos) {
      const std::size_t start = line.rfind(' ', open) + 1;
      names.push_back(line.substr(start, open - start));
    }
  }
  return names;
}

// A shared block as GLSL and the names it defines.
struct formatted_block {
  std::string text;
  std::vector<std::string> names;
};

// `block` formatted once for the program's life: assembling one renderer's shaders asks for every block's
// names once per shader and per block it adds.
inline const formatted_block& formatted(const shared_text& block) {
  static std::mutex lock;
  static std::map<const shared_text*, formatted_block> done;  // a node map: references stay valid
  const std::lock_guard<std::mutex> hold(lock);
  auto at = done.find(&block);
  if (at == done.end()) {
    std::string text = glsl::format_shared(block.code);
    std::vector<std::string> names = top_level_names(text);
    at = done.emplace(&block, formatted_block{std::move(text), std::move(names)}).first;
  }
  return at->second;
}
}  // namespace dstrans::detail

namespace dstrans::glsl {

// The names shared block `code` defines at its top level: its structs and its functions.
inline std::vector<std::string> definitions(const char* code) { return detail::top_level_names(format_shared(code)); }

// The GLSL a source is written in. Before GLSL 4.20 a sampler cannot state its binding: the generators
// then declare it by name alone, and the engine points it at a texture unit with glUniform1i.
enum class version {
  glsl330,  // "#version 330 core"
  glsl410,  // "#version 410 core"
  glsl450,  // "#version 450"
  vulkan,   // "#version 450", compiled with Vulkan semantics (glslang -V)
};

// The version named `name` ("330", "410", "450" or "vulkan"); a failure names those.
inline result<version> version_named(const std::string& name) {
  if (name == "330") return version::glsl330;
  if (name == "410") return version::glsl410;
  if (name == "450") return version::glsl450;
  if (name == "vulkan") return version::vulkan;
  return failure{"unknown GLSL version '" + name + "' (known: 330, 410, 450, vulkan)"};
}

// Which way the pixels an engine hands to dstrans's GLSL count rows. dstrans counts them from the top of the
// image (Vulkan's gl_FragCoord, and GL's with glClipControl(GL_UPPER_LEFT)); GL's default gl_FragCoord
// counts them from the bottom. The interlace predicates and the refraction offset follow this one switch.
enum class rows { from_top, from_bottom };

// How an engine writes its GLSL.
struct dialect {
  version language = version::glsl450;
  bool version_line = true;          // false: the engine puts its own #version line first
  rows pixel_rows = rows::from_top;  // the pixels passed to dst_interlace_keep/_partner and dst_refract
};

// A GLSL translation unit under construction.
class source {
 public:
  // A source written as `d` asks, opening with its version's line unless d.version_line is false.
  explicit source(const dialect& d = {}) : dialect_(d) {
    static const char* const lines[] = {"#version 330 core\n", "#version 410 core\n", "#version 450\n", "#version 450\n"};
    if (d.version_line) add(lines[int(d.language)], __FILE__, __LINE__);
  }
  explicit source(version v) : source(dialect{v}) {}

  version language() const { return dialect_.language; }
  rows pixel_rows() const { return dialect_.pixel_rows; }
  // Whether resources may carry layout(binding = N): GLSL 4.20 and later, and Vulkan.
  bool binds() const { return language() == version::glsl450 || language() == version::vulkan; }

  // Appends `text`, whose first line is line `line` of `file`; its other lines follow on.
  void add(const std::string& text, const std::string& file, int line) {
    int n = 0;
    for (char c : text) n += c == '\n';
    if (!text.empty() && text.back() != '\n') ++n;
    for (int k = 0; k < n; ++k) lines_.push_back({file, line + k});
    code_ += text;
    if (!text.empty() && text.back() != '\n') code_ += '\n';
  }

  // Appends the text of file `path` (a hand-written pass shader) as add_text does; a failure if it
  // cannot be read.
  result<bool> add_file(const std::string& path, const std::vector<std::string>& switches = {}) {
    std::ifstream in(path);
    if (!in) return failure{"cannot read GLSL file " + path};
    std::ostringstream text;
    text << in.rdbuf();
    return add_text(text.str(), path, switches);
  }

  // Appends `shader` (a hand-written pass shader), its lines mapped to lines of `file`, after the shared
  // blocks it calls; a failure if its switches are tested with #if.
  //
  // Sections under `#ifdef DST_...` / `#ifndef DST_...` (with `#else`, `#endif`) are resolved here, on
  // `switches` (the names that are on): what an absent effect needs is left out of the text, the shared
  // blocks it calls included, so a shader carries no code for an effect it does not run. Other
  // preprocessor lines pass through; `#if` on a DST_ name is an error (write #ifdef).
  result<bool> add_text(const std::string& shader, const std::string& file, const std::vector<std::string>& switches = {}) {
    std::istringstream in(shader);
    const std::string& path = file;
    struct section {
      bool resolved, keep, was_keeping;
    };
    std::vector<section> open;
    bool keeping = true;
    std::vector<std::pair<int, std::string>> kept;  // line number, text
    std::string text, line;
    for (int number = 1; std::getline(in, line); ++number) {
      std::istringstream words(line);
      std::string directive, name;
      words >> directive >> name;
      const bool ours = name.rfind("DST_", 0) == 0;
      auto on = [&] {
        for (const std::string& s : switches)
          if (s == name) return true;
        return false;
      };
      if (directive == "#if" && line.find("DST_") != std::string::npos)
        return failure{path + ":" + std::to_string(number) + ": test dstrans switches with #ifdef or #ifndef"};
      if ((directive == "#ifdef" || directive == "#ifndef") && ours) {
        const bool keep = directive == "#ifdef" ? on() : !on();
        open.push_back({true, keep, keeping});
        keeping = keeping && keep;
        continue;
      }
      if (directive == "#if" || directive == "#ifdef" || directive == "#ifndef") open.push_back({false, true, keeping});
      if (!open.empty() && open.back().resolved && (directive == "#else" || directive == "#endif")) {
        if (directive == "#else") keeping = open.back().was_keeping && !open.back().keep;
        else {
          keeping = open.back().was_keeping;
          open.pop_back();
        }
        continue;
      }
      if (directive == "#endif" && !open.empty()) open.pop_back();
      if (keeping) {
        kept.push_back({number, line});
        text += line + "\n";
      }
    }
    for (const shared_text* block : detail::shared_blocks())
      for (const std::string& name : detail::formatted(*block).names)
        if (uses(text, name)) {
          add_shared(*block);
          break;
        }
    for (const auto& [number, row] : kept) add(row + "\n", path, number);
    return true;
  }

  // Appends a shared block unless it is already in, after the blocks that define what it uses (found by
  // name among all shared blocks); every line maps to the block's DSTRANS_SHARED line.
  void add_shared(const shared_text& block) {
    for (const shared_text* b : shared_)
      if (b == &block) return;
    shared_.push_back(&block);
    for (const shared_text* other : detail::shared_blocks()) {
      if (other == &block) continue;
      for (const std::string& name : detail::formatted(*other).names)
        if (uses(block.code, name)) {
          add_shared(*other);
          break;
        }
    }
    const std::string& text = detail::formatted(block).text;
    for (char c : text)
      if (c == '\n') lines_.push_back({block.file, block.line});
    code_ += text;
  }

  // Whether shared block `block` is part of this source.
  bool has(const shared_text& block) const {
    for (const shared_text* b : shared_)
      if (b == &block) return true;
    return false;
  }

  const std::string& str() const { return code_; }

  // The origin of 1-based line `line` of str(); an empty file when out of range.
  origin origin_of(int line) const {
    if (line < 1 || line > int(lines_.size())) return {};
    return lines_[std::size_t(line - 1)];
  }

  // A compiler log with every "0:LINE" (glslang) or "0:LINE(COL)" (Mesa) position rewritten as the
  // "file:line" of the text it came from, followed by the generated line number.
  std::string map_log(const std::string& log) const {
    std::string out;
    std::size_t i = 0;
    while (i < log.size()) {
      const std::size_t eol = log.find('\n', i);
      const std::string row = log.substr(i, eol == std::string::npos ? std::string::npos : eol - i);
      out += map_row(row);
      if (eol == std::string::npos) break;
      out += '\n';
      i = eol + 1;
    }
    return out;
  }

 private:
  // Whether `code` mentions identifier `name` as a whole word.
  static bool uses(std::string_view code, std::string_view name) {
    auto word = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
    for (std::size_t at = code.find(name); at != std::string_view::npos; at = code.find(name, at + 1))
      if ((at == 0 || !word(code[at - 1])) && (at + name.size() == code.size() || !word(code[at + name.size()])))
        return true;
    return false;
  }

  std::string map_row(const std::string& row) const {
    const std::size_t at = row.find("0:");
    if (at == std::string::npos || (at > 0 && std::isdigit(static_cast<unsigned char>(row[at - 1]))))
      return row;
    std::size_t end = at + 2;
    while (end < row.size() && std::isdigit(static_cast<unsigned char>(row[end]))) ++end;
    if (end == at + 2) return row;
    const int line = std::stoi(row.substr(at + 2, end - at - 2));
    if (end < row.size() && row[end] == '(') end = row.find(')', end) + 1;  // Mesa's column
    const origin o = origin_of(line);
    if (o.file.empty()) return row;
    // glslang puts the severity first ("ERROR: 0:12: msg"), Mesa after ("0:12(5): error: msg").
    const std::string severity = row.compare(0, at, "ERROR: ") == 0     ? " error:"
                                 : row.compare(0, at, "WARNING: ") == 0 ? " warning:"
                                                                        : "";
    const std::string rest = row.compare(end, 1, ":") == 0 ? row.substr(end + 1) : row.substr(end);
    return o.file + ":" + std::to_string(o.line) + ":" + severity + rest + " (generated line " +
           std::to_string(line) + ")";
  }

  dialect dialect_;
  std::string code_;
  std::vector<origin> lines_;
  std::vector<const shared_text*> shared_;
};

}  // namespace dstrans::glsl
