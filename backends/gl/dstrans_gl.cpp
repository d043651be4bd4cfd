// Implements dstrans_gl.hpp.
#include "dstrans_gl.hpp"

#include <cstdio>
#include <cstring>

namespace dstrans::gl {

namespace {

// How texel uploads read client memory, besides the alignment.
constexpr GLenum unpack_layout[5] = {GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_IMAGE_HEIGHT,
                                     GL_UNPACK_SKIP_IMAGES};

// A shader's or program's info log (the two getters have the same shape).
std::string info_log(GLuint object, void (*get_iv)(GLuint, GLenum, GLint*),
                     void (*get_log)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint n = 0;
  get_iv(object, GL_INFO_LOG_LENGTH, &n);
  std::string log(std::size_t(n > 0 ? n : 1), '\0');
  get_log(object, GLsizei(log.size()), nullptr, log.data());
  log.resize(std::strlen(log.c_str()));
  return log;
}

result<GLuint> compile(GLenum stage, const glsl::source& src, const std::string& label_text) {
  const GLuint shader = glCreateShader(stage);
  const char* text = src.str().c_str();
  glShaderSource(shader, 1, &text, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    const std::string log = src.map_log(info_log(shader, glGetShaderiv, glGetShaderInfoLog));
    glDeleteShader(shader);
    return failure{label_text + ": " + log};
  }
  label(GL_SHADER, shader, label_text);
  return shader;
}

result<GLuint> link(const std::vector<GLuint>& shaders, const std::string& label_text) {
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) {
    glDetachShader(program, s);
    glDeleteShader(s);
  }
  GLint ok = GL_FALSE;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    const std::string log = info_log(program, glGetProgramiv, glGetProgramInfoLog);
    glDeleteProgram(program);
    return failure{label_text + ": link failed: " + log};
  }
  label(GL_PROGRAM, program, label_text);
  return program;
}

}  // namespace

result<targets> make_targets(const std::vector<target_desc>& layout, int width, int height, const std::string& label_text,
                             bool with_depth) {
  GLint max_size = 0, max_draw = 0, max_attach = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &max_draw);
  glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &max_attach);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    return failure{label_text + ": " + std::to_string(width) + "x" + std::to_string(height) +
                   " is not a size this device can render (1 to " + std::to_string(max_size) + " a side)"};
  const int limit = max_draw < max_attach ? max_draw : max_attach;
  if (int(layout.size()) > limit)
    return failure{label_text + ": the layout has " + std::to_string(layout.size()) + " render targets; this device draws to at most " +
                   std::to_string(limit)};
  for (const target_desc& d : layout) {
    GLint renderable = GL_NONE;
    glGetInternalformativ(GL_TEXTURE_2D, info(d.fmt).gl_internal_format, GL_FRAMEBUFFER_RENDERABLE, 1, &renderable);
    if (renderable != GL_FULL_SUPPORT)
      return failure{label_text + ": this device cannot render to " + info(d.fmt).name + " targets"};
  }
  targets t;
  t.width = width;
  t.height = height;
  glCreateFramebuffers(1, &t.framebuffer);
  label(GL_FRAMEBUFFER, t.framebuffer, label_text);
  std::vector<GLenum> draw_buffers;
  for (std::size_t i = 0; i < layout.size(); ++i) {
    GLuint tex = 0;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, info(layout[i].fmt).gl_internal_format, width, height);
    glTextureParameteri(tex, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(tex, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    label(GL_TEXTURE, tex, label_text + " RT" + std::to_string(i) + " " + info(layout[i].fmt).name);
    glNamedFramebufferTexture(t.framebuffer, GLenum(GL_COLOR_ATTACHMENT0 + i), tex, 0);
    draw_buffers.push_back(GLenum(GL_COLOR_ATTACHMENT0 + i));
    t.textures.push_back(tex);
    t.formats.push_back(layout[i].fmt);
  }
  if (with_depth) {
    glCreateTextures(GL_TEXTURE_2D, 1, &t.depth);
    glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, width, height);
    label(GL_TEXTURE, t.depth, label_text + " depth");
    glNamedFramebufferTexture(t.framebuffer, GL_DEPTH_ATTACHMENT, t.depth, 0);
  }
  glNamedFramebufferDrawBuffers(t.framebuffer, GLsizei(draw_buffers.size()), draw_buffers.data());
  const GLenum status = glCheckNamedFramebufferStatus(t.framebuffer, GL_DRAW_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    destroy(t);
    return failure{label_text + ": the framebuffer is incomplete (status 0x" + [&] {
      char hex[16];
      std::snprintf(hex, sizeof hex, "%04x", status);
      return std::string(hex);
    }() + ")"};
  }
  return t;
}

void destroy(targets& t) {
  if (!t.textures.empty()) glDeleteTextures(GLsizei(t.textures.size()), t.textures.data());
  if (t.depth) glDeleteTextures(1, &t.depth);
  if (t.framebuffer) glDeleteFramebuffers(1, &t.framebuffer);
  t = targets{};
}

void bind(const targets& t) {
  glBindFramebuffer(GL_FRAMEBUFFER, t.framebuffer);
  glViewport(0, 0, t.width, t.height);
  glClipControl(GL_UPPER_LEFT, GL_ZERO_TO_ONE);
}

std::vector<texel> read_texels(const targets& t, int index) {
  // Each format is read back in the memory layout its GL type names: bytes for 8-bit UNORM, one packed
  // word for RGB10A2, raw halves and floats.
  const format f = t.formats[std::size_t(index)];
  const format_info fi = info(f);
  static const GLenum formats_by_channels[] = {0, GL_RED, GL_RG, GL_RGB, GL_RGBA};
  GLenum gl_format = formats_by_channels[fi.channels], type = GL_FLOAT;
  if (f == format::rgb10a2) type = GL_UNSIGNED_INT_2_10_10_10_REV;
  else if (fi.kind == channel_kind::unorm) type = GL_UNSIGNED_BYTE;
  else if (fi.bits[0] == 16) type = GL_HALF_FLOAT;
  const std::size_t bpp = std::size_t(fi.bytes_per_pixel), n = std::size_t(t.width) * std::size_t(t.height);
  std::vector<std::uint8_t> bytes(n * bpp);
  // Into client memory, whatever pack buffer and alignment the engine has set.
  GLint pack_buffer = 0, pack_alignment = 4;
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer);
  glGetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glGetTextureImage(t.textures[std::size_t(index)], 0, gl_format, type, GLsizei(bytes.size()), bytes.data());
  glPixelStorei(GL_PACK_ALIGNMENT, pack_alignment);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer));
  std::vector<texel> out(n);
  for (std::size_t i = 0; i < n; ++i) std::memcpy(out[i].data(), &bytes[i * bpp], bpp);
  return out;
}

result<GLuint> make_program(const glsl::source& vertex, const glsl::source& fragment, const std::string& label_text) {
  auto vs = compile(GL_VERTEX_SHADER, vertex, label_text + " (vertex)");
  if (!vs) return failure{vs.error()};
  auto fs = compile(GL_FRAGMENT_SHADER, fragment, label_text + " (fragment)");
  if (!fs) {
    glDeleteShader(*vs);
    return failure{fs.error()};
  }
  return link({*vs, *fs}, label_text);
}

result<GLuint> make_compute_program(const glsl::source& compute, const std::string& label_text) {
  auto cs = compile(GL_COMPUTE_SHADER, compute, label_text + " (compute)");
  if (!cs) return failure{cs.error()};
  return link({*cs}, label_text);
}

mesh make_mesh(const mesh_data& data, const std::string& label_text) {
  mesh m;
  glCreateBuffers(1, &m.vertices);
  glNamedBufferStorage(m.vertices, GLsizeiptr(data.positions.size() * sizeof(glm::vec3)), data.positions.data(), 0);
  glCreateBuffers(1, &m.indices);
  glNamedBufferStorage(m.indices, GLsizeiptr(data.indices.size() * sizeof(std::uint32_t)), data.indices.data(), 0);
  glCreateVertexArrays(1, &m.vertex_array);
  glVertexArrayVertexBuffer(m.vertex_array, 0, m.vertices, 0, sizeof(glm::vec3));
  glVertexArrayElementBuffer(m.vertex_array, m.indices);
  glEnableVertexArrayAttrib(m.vertex_array, 0);
  glVertexArrayAttribFormat(m.vertex_array, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(m.vertex_array, 0, 0);
  label(GL_BUFFER, m.vertices, label_text + " vertices");
  label(GL_BUFFER, m.indices, label_text + " indices");
  label(GL_VERTEX_ARRAY, m.vertex_array, label_text);
  m.index_count = GLsizei(data.indices.size());
  return m;
}

void destroy(mesh& m) {
  glDeleteVertexArrays(1, &m.vertex_array);
  glDeleteBuffers(1, &m.vertices);
  glDeleteBuffers(1, &m.indices);
  m = mesh{};
}

void draw(const mesh& m) {
  glBindVertexArray(m.vertex_array);
  glDrawElements(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr);
}

void draw_fullscreen(GLuint empty_vertex_array) {
  glBindVertexArray(empty_vertex_array);
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

timer::timer() { glCreateQueries(GL_TIMESTAMP, 2, queries_); }
timer::~timer() { glDeleteQueries(2, queries_); }
void timer::begin() { glQueryCounter(queries_[0], GL_TIMESTAMP); }
void timer::end() { glQueryCounter(queries_[1], GL_TIMESTAMP); }
double timer::milliseconds() const {
  GLuint64 ns[2] = {0, 0};
  glGetQueryObjectui64v(queries_[0], GL_QUERY_RESULT, &ns[0]);
  glGetQueryObjectui64v(queries_[1], GL_QUERY_RESULT, &ns[1]);
  return ns[1] > ns[0] ? double(ns[1] - ns[0]) * 1e-6 : 0.0;
}

void label(GLenum identifier, GLuint name, const std::string& text) {
  glObjectLabel(identifier, name, GLsizei(text.size()), text.c_str());
}

result<GLuint> make_texture_array(const texture_array& a, const std::string& label_text) {
  GLint layers = 0, largest = 0;
  glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &layers);
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  if (a.layers > layers || a.width > largest || a.height > largest)
    return failure{label_text + ": " + std::to_string(a.layers) + " layers of " + std::to_string(a.width) + " x " + std::to_string(a.height) +
                   " RGBA8 texels exceed the context's array textures (" + std::to_string(layers) + " layers of " + std::to_string(largest) + ")"};
  GLuint t = 0;
  glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t);
  glTextureStorage3D(t, GLsizei(a.levels.size()), GL_RGBA8, a.width, a.height, a.layers);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  for (GLenum p : unpack_layout) glPixelStorei(p, 0);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  for (std::size_t l = 0; l < a.levels.size(); ++l) {
    const glm::ivec2 size = a.level_size(int(l));
    glTextureSubImage3D(t, GLint(l), 0, 0, 0, size.x, size.y, a.layers, GL_RGBA, GL_UNSIGNED_BYTE, a.levels[l].data());
  }
  glTextureParameteri(t, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTextureParameteri(t, GL_TEXTURE_WRAP_S, GL_REPEAT);
  glTextureParameteri(t, GL_TEXTURE_WRAP_T, GL_REPEAT);
  label(GL_TEXTURE, t, label_text);
  return t;
}

debug_group::debug_group(const std::string& name) {
  glPushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, GLsizei(name.size()), name.c_str());
}
debug_group::~debug_group() { glPopDebugGroup(); }

state_guard::state_guard(const std::vector<GLuint>& storage_blocks) {
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &draw_fb_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &read_fb_);
  glGetIntegerv(GL_VIEWPORT, viewport_);
  glGetIntegerv(GL_CLIP_ORIGIN, &clip_origin_);
  glGetIntegerv(GL_CLIP_DEPTH_MODE, &clip_depth_);
  glGetIntegerv(GL_DEPTH_FUNC, &depth_func_);
  glGetIntegerv(GL_BLEND_SRC_RGB, &blend_src_rgb_);
  glGetIntegerv(GL_BLEND_DST_RGB, &blend_dst_rgb_);
  glGetIntegerv(GL_BLEND_SRC_ALPHA, &blend_src_a_);
  glGetIntegerv(GL_BLEND_DST_ALPHA, &blend_dst_a_);
  glGetIntegerv(GL_BLEND_EQUATION_RGB, &blend_eq_rgb_);
  glGetIntegerv(GL_BLEND_EQUATION_ALPHA, &blend_eq_a_);
  glGetIntegerv(GL_CULL_FACE_MODE, &cull_face_);
  glGetIntegerv(GL_FRONT_FACE, &front_face_);
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vertex_array_);
  glGetIntegerv(GL_ACTIVE_TEXTURE, &active_texture_);
  glGetIntegerv(GL_PACK_ALIGNMENT, &pack_alignment_);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &unpack_alignment_);
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_buffer_);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_buffer_);
  for (int k = 0; k < 5; ++k) glGetIntegerv(unpack_layout[k], &unpack_layout_[k]);
  glGetIntegerv(GL_UNIFORM_BUFFER_BINDING, &uniform_buffer_);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &storage_buffer_);
  glGetVertexAttribIuiv(3, GL_CURRENT_VERTEX_ATTRIB, light_index_);
  auto save_buffer = [&](GLenum target, GLenum binding, GLenum start, GLenum size, GLuint index) {
    buffer_range r{target, index, 0, 0, 0};
    glGetIntegeri_v(binding, index, &r.name);
    glGetInteger64i_v(start, index, &r.start);
    glGetInteger64i_v(size, index, &r.size);
    buffers_.push_back(r);
  };
  for (const slot_desc& d : slot_table)
    for (GLuint i = GLuint(d.binding); i < GLuint(d.binding + d.count); ++i) switch (d.kind) {
        case slot_kind::texture:
        case slot_kind::texel_buffer: {
          texture_unit u{i, 0, 0, 0, 0};
          glActiveTexture(GL_TEXTURE0 + i);
          glGetIntegerv(GL_TEXTURE_BINDING_2D, &u.texture_2d);
          glGetIntegerv(GL_TEXTURE_BINDING_3D, &u.texture_3d);
          glGetIntegerv(GL_TEXTURE_BINDING_2D_ARRAY, &u.texture_2d_array);
          glGetIntegerv(GL_TEXTURE_BINDING_BUFFER, &u.texture_buffer);
          textures_.push_back(u);
          break;
        }
        case slot_kind::image: {
          image_unit u{i, 0, 0, 0, 0, 0, 0};
          glGetIntegeri_v(GL_IMAGE_BINDING_NAME, i, &u.name);
          glGetIntegeri_v(GL_IMAGE_BINDING_LEVEL, i, &u.level);
          glGetIntegeri_v(GL_IMAGE_BINDING_LAYERED, i, &u.layered);
          glGetIntegeri_v(GL_IMAGE_BINDING_LAYER, i, &u.layer);
          glGetIntegeri_v(GL_IMAGE_BINDING_ACCESS, i, &u.access);
          glGetIntegeri_v(GL_IMAGE_BINDING_FORMAT, i, &u.format);
          images_.push_back(u);
          break;
        }
        case slot_kind::uniform_block:
          save_buffer(GL_UNIFORM_BUFFER, GL_UNIFORM_BUFFER_BINDING, GL_UNIFORM_BUFFER_START, GL_UNIFORM_BUFFER_SIZE, i);
          break;
        case slot_kind::storage_block:
          save_buffer(GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                      GL_SHADER_STORAGE_BUFFER_SIZE, i);
          break;
      }
  for (GLuint i : storage_blocks)
    save_buffer(GL_SHADER_STORAGE_BUFFER, GL_SHADER_STORAGE_BUFFER_BINDING, GL_SHADER_STORAGE_BUFFER_START,
                GL_SHADER_STORAGE_BUFFER_SIZE, i);
  glActiveTexture(GLenum(active_texture_));
  depth_test_ = glIsEnabled(GL_DEPTH_TEST);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &depth_mask_);
  blend_ = glIsEnabled(GL_BLEND);
  cull_ = glIsEnabled(GL_CULL_FACE);
  scissor_ = glIsEnabled(GL_SCISSOR_TEST);
  depth_clamp_ = glIsEnabled(GL_DEPTH_CLAMP);
}

state_guard::~state_guard() {
  auto enable = [](GLenum cap, GLboolean on) { on ? glEnable(cap) : glDisable(cap); };
  glUseProgram(GLuint(program_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(draw_fb_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, GLuint(read_fb_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  glClipControl(GLenum(clip_origin_), GLenum(clip_depth_));
  glDepthFunc(GLenum(depth_func_));
  glBlendFuncSeparate(GLenum(blend_src_rgb_), GLenum(blend_dst_rgb_), GLenum(blend_src_a_), GLenum(blend_dst_a_));
  glBlendEquationSeparate(GLenum(blend_eq_rgb_), GLenum(blend_eq_a_));
  glCullFace(GLenum(cull_face_));
  glFrontFace(GLenum(front_face_));
  glBindVertexArray(GLuint(vertex_array_));
  glVertexAttribI4uiv(3, light_index_);
  glPixelStorei(GL_PACK_ALIGNMENT, pack_alignment_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, unpack_alignment_);
  for (int k = 0; k < 5; ++k) glPixelStorei(unpack_layout[k], unpack_layout_[k]);
  for (const texture_unit& u : textures_) {
    glActiveTexture(GL_TEXTURE0 + u.unit);
    glBindTexture(GL_TEXTURE_2D, GLuint(u.texture_2d));
    glBindTexture(GL_TEXTURE_3D, GLuint(u.texture_3d));
    glBindTexture(GL_TEXTURE_2D_ARRAY, GLuint(u.texture_2d_array));
    glBindTexture(GL_TEXTURE_BUFFER, GLuint(u.texture_buffer));
  }
  glActiveTexture(GLenum(active_texture_));
  for (const image_unit& u : images_)
    glBindImageTexture(u.unit, GLuint(u.name), u.level, GLboolean(u.layered), u.layer, GLenum(u.access), GLenum(u.format));
  // In reverse, so that a binding saved twice (a slot and a caller's storage block) ends as it was.
  for (auto r = buffers_.rbegin(); r != buffers_.rend(); ++r) {
    if (r->name != 0 && r->size > 0) glBindBufferRange(r->target, r->index, GLuint(r->name), r->start, r->size);
    else glBindBufferBase(r->target, r->index, GLuint(r->name));
  }
  glBindBuffer(GL_UNIFORM_BUFFER, GLuint(uniform_buffer_));
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, GLuint(storage_buffer_));
  glBindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_buffer_));
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_buffer_));
  enable(GL_DEPTH_TEST, depth_test_);
  glDepthMask(depth_mask_);
  enable(GL_BLEND, blend_);
  enable(GL_CULL_FACE, cull_);
  enable(GL_SCISSOR_TEST, scissor_);
  enable(GL_DEPTH_CLAMP, depth_clamp_);
}

formula_runner::~formula_runner() {
  for (auto& [name, program] : programs_) glDeleteProgram(program);
}

result<words> formula_runner::run(const formula& f, const words& args, std::size_t calls) {
  auto it = programs_.find(f.name);
  if (it == programs_.end()) {
    glsl::source src;
    glsl::add_formula_kernel(src, f);
    auto program = make_compute_program(src, "dstrans eval " + f.name);
    if (!program) return failure{program.error()};
    it = programs_.emplace(f.name, *program).first;
  }
  GLint max_groups = 0;
  GLint64 max_block = 0;
  glGetIntegeri_v(GL_MAX_COMPUTE_WORK_GROUP_COUNT, 0, &max_groups);
  glGetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
  return glsl::run_in_dispatches(f, args, calls, std::size_t(max_groups), std::size_t(max_block),
                                 [&](const words& part, std::size_t n) { return run_dispatch(it->second, f, part, n); });
}

result<words> formula_runner::run_dispatch(GLuint program, const formula& f, const words& args, std::size_t calls) {
  words in;
  in.reserve(args.size() + 1);
  in.push_back(std::uint32_t(calls));
  in.insert(in.end(), args.begin(), args.end());
  const std::size_t out_words = calls * std::size_t(f.result.word_count());
  GLuint buffers[2];
  glCreateBuffers(2, buffers);
  glNamedBufferStorage(buffers[0], GLsizeiptr(in.size() * 4), in.data(), 0);
  glNamedBufferStorage(buffers[1], GLsizeiptr((out_words ? out_words : 1) * 4), nullptr, GL_MAP_READ_BIT);
  {
    state_guard keep({0, 1});
    glUseProgram(program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffers[0]);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[1]);
    glDispatchCompute(GLuint((calls + 63) / 64), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  words out(out_words);
  if (out_words) glGetNamedBufferSubData(buffers[1], 0, GLsizeiptr(out_words * 4), out.data());
  glDeleteBuffers(2, buffers);
  return out;
}

}  // namespace dstrans::gl
