// Implements passes.hpp.
#include "passes.hpp"

#include <vector>

#include <dstrans/fullscreen.hpp>

namespace dstrans::render {

namespace {

using I = interlace::rows;

// `src` with the frame interface (and the fragment helpers, for a fragment shader) and then `files`
// appended, the pass shader last; a failure if a file is missing.
result<bool> finish(glsl::source& src, const std::string& dir, std::vector<std::string> files) {
  if (files.back().find(".frag.") != std::string::npos) files.insert(files.begin(), "fragment.glsl");
  files.insert(files.begin(), "frame.glsl");
  for (const std::string& f : files)
    if (auto ok = src.add_file(dir + "/" + f); !ok) return ok;
  return true;
}

void add_shadow_layout(glsl::source& src, shadow_mode mode, glsl::side side) {
  glsl::layout_options o;
  o.sides = side;
  o.first_binding = shadow_binding;
  if (mode == shadow_mode::transparent) glsl::add_layout<thesis_shadow_map>(src, "shadow", o);
  else glsl::add_layout<opaque_shadow_map>(src, "shadow", o);
}

const char* shadow_define(shadow_mode mode) {
  return mode == shadow_mode::transparent ? "#define DST_TRANSPARENT_SHADOWS\n"
         : mode == shadow_mode::opaque    ? "#define DST_OPAQUE_SHADOWS\n"
                                          : "";
}

result<pass_sources> scene_vertex(const std::string& dir, pass_sources p) {
  if (auto ok = finish(p.vertex, dir, {"gbuffer.vert.glsl"}); !ok) return failure{ok.error()};
  return p;
}

}  // namespace

result<pass_sources> gbuffer_pass(const std::string& dir, layer which) {
  pass_sources p;
  if (which == layer::second) p.fragment.add("#define DST_PEEL\n", __FILE__, __LINE__);
  glsl::layout_options o;
  o.sides = glsl::side::write;
  glsl::add_layout<thesis_gbuffer>(p.fragment, "gbuffer", o);
  // The first peeled layer keeps every nearest fragment, transparent or not.
  if (which == layer::interlaced) glsl::add_interlace<I>(p.fragment);
  if (which == layer::first) glsl::add_interlace<interlace::none>(p.fragment);
  if (auto ok = finish(p.fragment, dir, {"gbuffer.frag.glsl"}); !ok) return failure{ok.error()};
  return scene_vertex(dir, std::move(p));
}

result<pass_sources> shadow_pass(const std::string& dir, shadow_mode mode) {
  pass_sources p;
  p.fragment.add(shadow_define(mode), __FILE__, __LINE__);
  add_shadow_layout(p.fragment, mode, glsl::side::write);
  glsl::add_interlace<I>(p.fragment);
  if (auto ok = finish(p.fragment, dir, {"shadow.frag.glsl"}); !ok) return failure{ok.error()};
  return scene_vertex(dir, std::move(p));
}

std::vector<target_desc> light_targets(bool float_targets) {
  return float_targets ? describe<float_light_buffer>() : describe<thesis_light_buffer>();
}

void add_light_layout(glsl::source& src, const std::string& name, bool float_targets, const glsl::layout_options& o) {
  if (float_targets) glsl::add_layout<float_light_buffer>(src, name, o);
  else glsl::add_layout<thesis_light_buffer>(src, name, o);
}

target_desc final_target_desc(bool float_targets) {
  return {float_targets ? format::rgba32f : format::rgba8, {"r", "g", "b", "a"}};
}

result<pass_sources> light_pass(const std::string& dir, shadow_mode mode, bool volume, const options& o) {
  pass_sources p;
  if (volume) p.vertex.add("#define DST_LIGHT_VOLUME\n", __FILE__, __LINE__);
  p.vertex.add_shared(text::dst_fullscreen);
  if (auto ok = finish(p.vertex, dir, {"light.vert.glsl"}); !ok) return failure{ok.error()};
  p.fragment.add(shadow_define(mode), __FILE__, __LINE__);
  if (o.physical_transmittance) p.fragment.add("#define DST_TRANSMITTANCE\n", __FILE__, __LINE__);
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = gbuffer_binding;
  glsl::add_layout<thesis_gbuffer>(p.fragment, "gbuffer", read);
  glsl::layout_options write;
  write.sides = glsl::side::write;
  add_light_layout(p.fragment, "light", o.float_targets, write);
  if (mode != shadow_mode::off) add_shadow_layout(p.fragment, mode, glsl::side::read);
  glsl::add_interlace<I>(p.fragment);
  if (auto ok = finish(p.fragment, dir, {"lighting.glsl", "light.frag.glsl"}); !ok) return failure{ok.error()};
  return p;
}

result<pass_sources> compose_pass(const std::string& dir, const options& o) {
  pass_sources p{glsl::fullscreen_vertex_shader(), {}};
  glsl::layout_options read;
  read.sides = glsl::side::read;
  read.first_binding = gbuffer_binding;
  glsl::add_layout<thesis_gbuffer>(p.fragment, "gbuffer", read);
  read.first_binding = light_binding;
  add_light_layout(p.fragment, "light", o.float_targets, read);
  std::string other = "interlaced.glsl";
  if (o.method == technique::interlaced) {
    glsl::add_interlace<I>(p.fragment);
  } else {
    read.first_binding = gbuffer2_binding;
    glsl::add_layout<thesis_gbuffer>(p.fragment, "gbuffer2", read);
    read.first_binding = light2_binding;
    add_light_layout(p.fragment, "light2", o.float_targets, read);
    other = "peeled.glsl";
  }
  if (auto ok = finish(p.fragment, dir, {other, "compose.frag.glsl"}); !ok) return failure{ok.error()};
  return p;
}

std::vector<target_desc> forward_targets(bool with_depth, bool float_targets) {
  std::vector<target_desc> t{{float_targets ? format::rgba32f : format::rgba8, {"colour.r", "colour.g", "colour.b", "alpha"}},
                             {format::rgb10a2, {"normal.x", "normal.y", "normal.z", "unused"}}};
  if (with_depth) t.push_back({format::r32f, {"depth"}});
  return t;
}

result<pass_sources> forward_pass(const std::string& dir, forward_stage stage, bool with_depth, shadow_mode mode,
                                  bool physical_transmittance) {
  pass_sources p;
  if (with_depth) p.fragment.add("#define DST_FORWARD_DEPTH\n", __FILE__, __LINE__);
  if (stage == forward_stage::light) {
    p.fragment.add(shadow_define(mode), __FILE__, __LINE__);
    if (physical_transmittance) p.fragment.add("#define DST_TRANSMITTANCE\n", __FILE__, __LINE__);
    if (mode != shadow_mode::off) add_shadow_layout(p.fragment, mode, glsl::side::read);
  }
  glsl::add_interlace<I>(p.fragment);
  std::vector<std::string> files;
  switch (stage) {
    case forward_stage::ambient: files = {"forward.glsl", "forward_ambient.frag.glsl"}; break;
    case forward_stage::light: files = {"lighting.glsl", "forward.glsl", "forward_light.frag.glsl"}; break;
    case forward_stage::blend: files = {"forward_blend.frag.glsl"}; break;
  }
  if (auto ok = finish(p.fragment, dir, files); !ok) return failure{ok.error()};
  if (stage == forward_stage::blend) {
    p.vertex = glsl::fullscreen_vertex_shader();
    return p;
  }
  if (auto ok = finish(p.vertex, dir, {"forward.vert.glsl"}); !ok) return failure{ok.error()};
  return p;
}

}  // namespace dstrans::render
