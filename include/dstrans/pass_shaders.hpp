// The reference pipeline's pass shaders (shaders/glsl/ in the source), embedded in the package as text, or
// read from a folder of edited copies for hot reload. Nothing that uses the embedded ones needs the source.
//
//   dstrans::pass_shaders shaders;                              // the embedded text
//   dstrans::pass_shaders edited("/home/me/dstrans/shaders/glsl");  // the same names, read when asked
//   dstrans::glsl::source src;
//   auto ok = shaders.add_to(src, "compose.frag.glsl", {"DST_REFRACTION"});  // as glsl::source::add_text
#pragma once

#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <dstrans/detail/pass_shader_text.hpp>  // generated from shaders/glsl/ by the build
#include "glsl.hpp"
#include "result.hpp"

namespace dstrans {

class pass_shaders {
 public:
  // The embedded shaders.
  pass_shaders() = default;
  // The shaders of `folder`, read each time one is asked for.
  explicit pass_shaders(std::string folder) : folder_(std::move(folder)) {}

  // Whether these are the embedded shaders.
  bool embedded() const { return folder_.empty(); }

  // The names of the embedded shaders ("compose.frag.glsl", ...).
  static std::vector<std::string> names() {
    std::vector<std::string> out;
    for (const detail::pass_shader_text& s : detail::pass_shader_texts) out.push_back(s.name);
    return out;
  }

  // The text of shader `name`, or why there is none.
  result<std::string> text(const std::string& name) const {
    if (embedded()) {
      for (const detail::pass_shader_text& s : detail::pass_shader_texts)
        if (name == s.name) return std::string(s.text);
      return failure{"no pass shader named " + name + " is embedded in dstrans"};
    }
    std::ifstream in(origin(name));
    if (!in) return failure{"cannot read GLSL file " + origin(name)};
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  // What compiler messages call shader `name`: its path in the folder, or shaders/glsl/NAME.
  std::string origin(const std::string& name) const {
    return (embedded() ? std::string("shaders/glsl") : folder_) + "/" + name;
  }

  // Shader `name` appended to `src` with its switches resolved (glsl::source::add_text).
  result<bool> add_to(glsl::source& src, const std::string& name, const std::vector<std::string>& switches = {}) const {
    auto t = text(name);
    if (!t) return failure{t.error()};
    return src.add_text(*t, origin(name), switches);
  }

 private:
  std::string folder_;
};

}  // namespace dstrans
