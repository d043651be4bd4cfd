// Implements run_gl.hpp.
#include "run_gl.hpp"

#include <algorithm>
#include <chrono>
#include <memory>

#include <dstrans/frame/passes.hpp>
#include <dstrans/fullscreen.hpp>
#include <dstrans_gl_frame.hpp>

#include "same_objects.hpp"

namespace dstrans::render {

namespace {

// What the frame's targets hold, as frame_output.hpp keeps it.
void read_back(const gl::renderer& r, const scene& s, frame& out) {
  const options& o = r.options();
  const gl::frame_targets& t = r.targets();
  const int w = o.width, h = o.height;
  gl::state_guard keep;
  if (!r.plan().forward) {
    for (std::size_t k = 0; k < t.gbuffers[0].textures.size(); ++k) out.gbuffer.push_back(gl::read_texels(t.gbuffers[0], int(k)));
    out.light_buffer = gl::read_texels(t.light_buffers[0], 0);
  } else {
    for (std::size_t k = 0; k < t.lit.textures.size(); ++k) out.lit.push_back(gl::read_texels(t.lit, int(k)));
    out.buffers.push_back({"colour", to_image(out.lit[0], t.lit.formats[0], w, h, view_as::rgb)});
    out.buffers.push_back({"normals", to_image(out.lit[1], format::rgb10a2, w, h, view_as::rgb)});
    if (r.plan().forward_depth)
      out.buffers.push_back({"depth", to_image(out.lit[2], format::r32f, w, h, view_as::depth, s.view.near_plane, s.view.far_plane)});
  }
  out.final_texels = gl::read_texels(*t.output, 0);
  if (t.kbuffer_heads) {
    out.kbuffer_heads.resize(std::size_t(w) * std::size_t(h));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // into client memory
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(t.kbuffer_heads, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.kbuffer_heads.size() * 4), out.kbuffer_heads.data());
    std::vector<glm::uvec4> pool(std::size_t(t.kbuffer_capacity) + 1u);
    glGetNamedBufferSubData(t.kbuffer_nodes, 0, GLsizeiptr(pool.size() * sizeof(glm::uvec4)), pool.data());
    out.kbuffer_overflow = pool[0].y;
    pool.resize(std::size_t(std::min(pool[0].x, t.kbuffer_capacity)) + 1u);
    out.kbuffer_nodes.assign(pool.begin() + 1, pool.end());
  }
  if (t.volume_atlas) {
    out.volume_atlas.resize(4 * std::size_t(t.volume_atlas_size.x) * std::size_t(t.volume_atlas_size.y) * std::size_t(t.volume_atlas_size.z));
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(t.volume_atlas, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(out.volume_atlas.size()), out.volume_atlas.data());
  }
  const format final_format = final_target_desc(o.float_targets).fmt, light_format = light_targets(o)[0].fmt;
  out.final_image = to_image(out.final_texels, final_format, w, h, view_as::rgb);
  for (std::size_t k = 0; k < t.gbuffers.size(); ++k) {
    const std::string suffix = k ? "_2" : "";
    const gl::targets &gb = t.gbuffers[k], &lb = t.light_buffers[k];
    out.buffers.push_back({"diffuse" + suffix, to_image(gl::read_texels(gb, 0), format::rgba8, w, h, view_as::rgb)});
    if (o.layout == gbuffer_layout::thesis) {  // the compact layout's normals are octahedral, its depth an attachment
      out.buffers.push_back({"normals" + suffix, to_image(gl::read_texels(gb, 1), format::rgb10a2, w, h, view_as::rgb)});
      out.buffers.push_back({"depth" + suffix, to_image(gl::read_texels(gb, 3), format::r32f, w, h, view_as::depth,
                                                        s.view.near_plane, s.view.far_plane)});
    }
    const std::vector<texel> light = gl::read_texels(lb, 0);
    out.buffers.push_back({"light" + suffix, to_image(light, light_format, w, h, view_as::rgb)});
    out.buffers.push_back({"specular" + suffix, o.rgb_specular ? to_image(gl::read_texels(lb, 1), light_format, w, h, view_as::rgb)
                                                               : to_image(light, light_format, w, h, view_as::alpha)});
  }
  if (t.shadow_picture.framebuffer)
    out.buffers.push_back({"shadow_colour", to_image(gl::read_texels(t.shadow_picture, 0), format::rgba8, o.shadow_size,
                                                     o.shadow_size, view_as::rgb)});
  if (!r.plan().post.passes.empty()) {
    out.buffers.push_back({"composed", to_image(gl::read_texels(t.composed, 0), final_format, w, h, view_as::rgb)});
    for (const std::string& effect : r.plan().post.effects)
      out.buffers.push_back({"post_" + effect, to_image(gl::read_texels(t.post.at(effect), 0), final_format, w, h, view_as::rgb)});
  }
}

}  // namespace

result<frame> run_gl(const scene& s, const options& o, const pass_shaders& shaders) {
  auto r = gl::renderer::create(s, o, shaders);
  if (!r) return failure{r.error()};
  const gl::scene_geometry meshes(s);
  std::vector<std::map<std::string, double>> frames;
  std::vector<double> totals;
  frame out;
  for (int n = 0; n < std::max(o.frames, 1); ++n) {
    (*r)->render(s.view, [&](const scheduled_pass& pass) { meshes(pass); });
    frame_times t = (*r)->times();
    frames.push_back(t.pass_ms);
    totals.push_back(t.frame_ms);
    out.schedule = t.schedule;
  }
  summarize(frames, totals, out);
  read_back(**r, s, out);
  return out;
}

result<std::vector<frame>> run_gl_sequence(const std::vector<scene>& frames, const options& o, const pass_shaders& shaders) {
  std::vector<frame> out;
  if (frames.empty()) return out;
  auto r = gl::renderer::create(frames.front(), o, shaders);
  if (!r) return failure{r.error()};
  const std::vector<std::size_t> from = first_with_same_objects(frames);
  std::vector<std::unique_ptr<gl::scene_geometry>> uploaded(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const scene& s = frames[i];
    if (from[i] == i) uploaded[i] = std::make_unique<gl::scene_geometry>(s);
    const gl::scene_geometry& meshes = *uploaded[from[i]];
    (*r)->render(s.view, [&](const scheduled_pass& pass) { meshes(pass); });
    const frame_times t = (*r)->times();
    frame f;
    f.schedule = t.schedule;
    summarize({t.pass_ms}, {t.frame_ms}, f);
    read_back(**r, s, f);
    out.push_back(std::move(f));
  }
  return out;
}

result<cli::frame_clock> gl_clock(const std::vector<scene>& frames, const options& o, const pass_shaders& shaders) {
  if (frames.empty()) return failure{"a frame clock needs at least one frame"};
  auto r = gl::renderer::create(frames.front(), o, shaders);
  if (!r) return failure{r.error()};
  struct running {
    std::unique_ptr<gl::renderer> renderer;
    std::vector<std::shared_ptr<gl::scene_geometry>> meshes;  // a frame each; frames with the same objects share one
    std::vector<camera> views;
    std::size_t next = 0;
  };
  auto on = std::make_shared<running>();
  on->renderer = std::move(*r);
  const std::vector<std::size_t> from = first_with_same_objects(frames);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    on->meshes.push_back(from[i] == i ? std::make_shared<gl::scene_geometry>(frames[i]) : on->meshes[from[i]]);
    on->views.push_back(frames[i].view);
  }
  return cli::frame_clock([on]() -> result<frame_times> {
    const std::size_t i = on->next++ % on->views.size();
    on->renderer->render(on->views[i], [&](const scheduled_pass& pass) { (*on->meshes[i])(pass); });
    return on->renderer->times();
  });
}

cli::copy_clock gl_copy_clock() {
  struct objects {
    GLuint textures[2] = {0, 0}, framebuffer = 0, vertex_array = 0, program = 0;
    ~objects() {
      glDeleteTextures(2, textures);
      glDeleteFramebuffers(1, &framebuffer);
      glDeleteVertexArrays(1, &vertex_array);
      glDeleteProgram(program);
    }
  };
  static constexpr GLsizei width = 1024, rows = 2048;  // 32 MiB of RGBA32F each
  static constexpr std::size_t row_bytes = std::size_t(width) * 16u, chunk = row_bytes * rows;
  auto t = std::make_shared<objects>();
  return [t](std::size_t bytes) -> result<double> {
    if (!t->program) {
      auto program = gl::make_program(glsl::fullscreen_vertex_shader(), cli::copy_fragment_shader(), "copy limit");
      if (!program) return failure{program.error()};
      t->program = *program;
      glCreateTextures(GL_TEXTURE_2D, 2, t->textures);
      const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
      for (GLuint name : t->textures) {
        glTextureStorage2D(name, 1, GL_RGBA32F, width, rows);
        glClearTexImage(name, 0, GL_RGBA, GL_FLOAT, zero);
      }
      glCreateFramebuffers(1, &t->framebuffer);
      glNamedFramebufferTexture(t->framebuffer, GL_COLOR_ATTACHMENT0, t->textures[1], 0);
      glCreateVertexArrays(1, &t->vertex_array);
      if (glGetError() != GL_NO_ERROR) return failure{"cannot make the copy's textures (32 MiB each)"};
    }
    gl::state_guard keep;
    glBindFramebuffer(GL_FRAMEBUFFER, t->framebuffer);
    glUseProgram(t->program);
    glBindImageTexture(0, t->textures[0], 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glEnable(GL_SCISSOR_TEST);
    glViewport(0, 0, width, rows);
    // Timed by the host between two glFinish: llvmpipe's timestamps do not see draws into one framebuffer
    // that is not left between them, and on a GPU the wait adds one round trip to a copy of megabytes.
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    for (std::size_t left = bytes; left > 0; left -= std::min(left, chunk)) {
      glScissor(0, 0, width, GLsizei((std::min(left, chunk) + row_bytes - 1) / row_bytes));
      gl::draw_fullscreen(t->vertex_array);
    }
    glFinish();
    glBindImageTexture(0, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  };
}

}  // namespace dstrans::render
