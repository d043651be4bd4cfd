// Implements dstrans_gl_frame.hpp.
#include "dstrans_gl_frame.hpp"

#include <algorithm>
#include <cstddef>

#include <dstrans/frame/culling.hpp>
#include <dstrans/frame/passes.hpp>
#include <dstrans/particles.hpp>

namespace dstrans::gl {

namespace {

using namespace dstrans::render;

// The vertex attribute that carries a light pass's light index: instanced in the renderer's own vertex
// arrays, the generic value while the engine draws.
constexpr GLuint light_index_attribute = 3;
// The engine's texture coordinates (vec2), where the scene samples textures.
constexpr GLuint texture_coordinates_attribute = 4;

template <class T>
GLuint make_buffer(const std::vector<T>& data, const std::string& name) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferStorage(b, GLsizeiptr(std::max<std::size_t>(data.size(), 1) * sizeof(T)), data.empty() ? nullptr : data.data(),
                       GL_DYNAMIC_STORAGE_BIT);
  label(GL_BUFFER, b, name);
  return b;
}

// Binds the light-index attribute of vertex array `vao` to `indices`, one a instance.
void bind_light_index(GLuint vao, GLuint indices) {
  glVertexArrayVertexBuffer(vao, light_index_attribute, indices, 0, sizeof(std::uint32_t));
  glVertexArrayBindingDivisor(vao, light_index_attribute, 1);
  glEnableVertexArrayAttrib(vao, light_index_attribute);
  glVertexArrayAttribIFormat(vao, light_index_attribute, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao, light_index_attribute, light_index_attribute);
}

void apply(const pass_state& s) {
  if (s.depth == depth_test::off) {
    glDisable(GL_DEPTH_TEST);
  } else {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(s.depth == depth_test::less ? GL_LESS : GL_LEQUAL);
  }
  glDepthMask(s.depth_write ? GL_TRUE : GL_FALSE);
  if (s.depth_clamp) glEnable(GL_DEPTH_CLAMP);
  else glDisable(GL_DEPTH_CLAMP);
  if (s.blend == blending::off) {
    glDisable(GL_BLEND);
  } else {
    glEnable(GL_BLEND);
    glBlendEquation(GL_FUNC_ADD);
    if (s.blend == blending::add) glBlendFunc(GL_ONE, GL_ONE);
    else glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, s.blend == blending::layer ? GL_SRC_ALPHA : GL_ONE);
  }
  if (s.cull == culling::off) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(GL_FRONT);
  }
}

}  // namespace

struct renderer::impl {
  scene description;  // without its meshes: the lights, materials and particle systems
  render::options o;
  frame_plan plan;
  particle_plan smoke;
  frame_schedule schedule;
  std::vector<light_block> light_data;  // light_blocks(description), computed once: it walks every vertex
  const pass_shaders* shaders = nullptr;

  // Made once: programs, the renderer's vertex arrays and meshes, blocks, shadow maps, the light volumes.
  std::vector<GLuint> programs, buffers, vertex_arrays, textures;
  std::vector<gl::targets> fixed_targets;
  std::vector<mesh> meshes;  // the point and spot lights' volumes
  GLuint gbuffer_progs[2] = {}, light_progs[3][2] = {}, forward_light_progs[3] = {}, compose_prog = 0, compose_still_prog = 0, ambient_prog = 0,
         shadow_prog = 0, shadow_depth_prog = 0, capture_prog = 0, resolve_prog = 0, bake_prog = 0, bake_shadowed_prog = 0, particle_prog = 0;
  std::vector<GLuint> post_progs, post_blocks;
  GLuint fullscreen_vao = 0, frame_ubo = 0, shadow_ubo = 0, materials = 0, lights = 0, material_textures = 0;
  GLuint material_texels = 0;  // a buffer texture over `materials` (slot::materials)
  std::vector<std::vector<frame_block>> light_frames;  // each light's shadow-map views
  gl::targets shadow_map;
  int pictured_light = -1;  // the light whose shadow colour frame_targets::shadow_picture shows
  GLuint unshadowed_buffer = 0, bake_regions = 0, particle_vao = 0, particle_quads = 0, particle_regions = 0;
  GLuint shadow_layers[2] = {};
  std::map<int, GLuint> shadowed_buffers;  // by light
  std::map<int, GLint> shadow_layer_of;    // by light
  std::size_t particle_vertices = 0;

  // Made for the frame's size.
  frame_targets out;
  GLuint lit_colour_only = 0;  // the forward target's colour and depth, for its light passes
  gl::targets tail, glass_layers;
  std::map<std::string, GLuint> registry;  // the post chain's inputs by name

  std::deque<timer> timers;
  timer whole;
  std::vector<std::string> recorded;
  int frames_drawn = 0;
  // Temporal interlacing: the frames drawn into these targets since they were made, and the last one's block
  // (while a frame's passes are drawn, that frame's).
  std::uint64_t sequence = 0;
  frame_block previous{};

  ~impl();
  result<GLuint> program(const result<pass_sources>& p, const std::string& name);
  result<bool> make_programs();
  result<bool> make_fixed();
  void make_particles();
  void make_shadow_layers();
  result<bool> make_sized();
  void destroy_sized();

  void run(const scheduled_pass& pass, const draw_geometry& draw);
  void clear(const scheduled_pass& pass, const gl::targets& t) const;
  void bind_textures(int first, const gl::targets& t) const;  // t's textures on units first, first + 1, ...
  void bind_gbuffer(int first, const gl::targets& g) const;
  void bind_shadow_map() const;
  void bind_shadow_layers() const;
  void bind_layers() const;
  void bind_frame_depths() const;
  // Where the resolve and the particles draw: the composed frame, the glass layers around the glass, or
  // the exact reference's particles the tail targets beside the lists.
  const gl::targets& layered_target(pass_step step) const {
    if (plan.exact && step == pass_step::particles) return tail;
    return plan.around_glass ? glass_layers : out.composed;
  }
  void bake(GLuint prog, GLuint lights_buffer) const;
  void run_light(const scheduled_pass& pass) const;
  void run_post(const scheduled_pass& pass) const;
};

renderer::impl::~impl() {
  destroy_sized();
  for (auto& t : fixed_targets) destroy(t);
  for (auto& m : meshes) destroy(m);
  if (!buffers.empty()) glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
  if (!vertex_arrays.empty()) glDeleteVertexArrays(GLsizei(vertex_arrays.size()), vertex_arrays.data());
  for (GLuint p : programs) glDeleteProgram(p);
  if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
}

result<GLuint> renderer::impl::program(const result<pass_sources>& p, const std::string& name) {
  if (!p) return failure{p.error()};
  auto prog = make_program(p->vertex, p->fragment, name);
  if (prog) programs.push_back(*prog);
  return prog;
}

result<bool> renderer::impl::make_programs() {
  const pass_shaders& sh = *shaders;
  const shadow_mode mode = plan.shadows;
  auto keep = [](GLuint& into, const result<GLuint>& p) -> result<bool> {
    if (!p) return failure{p.error()};
    into = *p;
    return true;
  };
  std::vector<result<bool>> made;
  if (plan.forward) {
    made.push_back(keep(ambient_prog, program(forward_pass(sh, forward_stage::ambient, plan.forward_depth, shadow_mode::off, plan.on), "forward ambient pass")));
    for (shadow_mode k : all_lookups)
      if (plan.uses(k))
        made.push_back(keep(forward_light_progs[int(k)],
                            program(forward_pass(sh, forward_stage::light, plan.forward_depth, k, plan.on, o),
                                    std::string("forward light pass") + lookup_label(k))));
    made.push_back(keep(compose_prog, program(forward_pass(sh, forward_stage::blend, plan.forward_depth, shadow_mode::off, plan.on), "forward blend pass")));
  } else {
    for (int k = 0; k < plan.layers; ++k)
      made.push_back(keep(gbuffer_progs[k], program(gbuffer_pass(sh, plan.peeling ? (k ? layer::second : layer::first) : layer::interlaced, plan.on, o),
                                                    "gbuffer pass")));
    made.push_back(keep(compose_prog, program(compose_pass(sh, plan.on, o), "compose pass")));
    if (plan.temporal) made.push_back(keep(compose_still_prog, program(compose_pass(sh, plan.on, o, true), "compose pass still camera")));
    for (shadow_mode k : all_lookups)
      for (int vol = 0; vol < 2 && plan.uses(k); ++vol)
        made.push_back(keep(light_progs[int(k)][vol], program(light_pass(sh, k, vol == 1, o), std::string("light pass") + lookup_label(k) +
                                                                                                  (vol ? " volume" : " fullscreen"))));
  }
  if (mode != shadow_mode::off) made.push_back(keep(shadow_prog, program(shadow_pass(sh, mode, plan.shadow_effects()), "shadow pass")));
  if (plan.depth_only_shadows)
    made.push_back(keep(shadow_depth_prog, program(shadow_pass(sh, mode, effects{}, true), "shadow pass, opaque surfaces")));
  if (plan.lists) {
    made.push_back(keep(capture_prog, program(capture_pass(sh, mode, o, plan.around_glass, plan.on), "capture pass")));
    made.push_back(keep(resolve_prog, program(resolve_pass(sh, mode, o, plan.around_glass), "resolve pass")));
  }
  if (smoke.on) {
    for (const bool shadowed : {false, true}) {
      if (!smoke.baking || (shadowed ? smoke.shadowed_lights.empty() : smoke.unshadowed_lights.empty())) continue;
      auto src = bake_pass(sh, shadowed ? mode : shadow_mode::off, o);
      if (!src) return failure{src.error()};
      auto prog = make_compute_program(*src, shadowed ? "bake pass shadowed" : "bake pass");
      if (prog) programs.push_back(*prog);
      made.push_back(keep(shadowed ? bake_shadowed_prog : bake_prog, prog));
    }
    made.push_back(keep(particle_prog, program(particle_pass(sh, smoke.shadows, o, plan.around_glass), "particle pass")));
  }
  for (const post_pass& pass : plan.post.passes) {
    GLuint p = 0;
    made.push_back(keep(p, program(post_pass_sources(sh, pass, o), "post " + pass.name)));
    post_progs.push_back(p);
  }
  for (const result<bool>& m : made)
    if (!m) return m;
  return true;
}

result<bool> renderer::impl::make_fixed() {
  const shadow_mode mode = plan.shadows;
  glCreateVertexArrays(1, &fullscreen_vao);
  vertex_arrays.push_back(fullscreen_vao);
  label(GL_VERTEX_ARRAY, fullscreen_vao, "full-screen lights");
  std::vector<std::uint32_t> light_ids(description.lights.size());
  for (std::size_t i = 0; i < light_ids.size(); ++i) light_ids[i] = std::uint32_t(i);
  const GLuint light_index = make_buffer(light_ids, "light indices");
  buffers.push_back(light_index);
  bind_light_index(fullscreen_vao, light_index);
  meshes.push_back(make_mesh(sphere_mesh(1), "point light volume"));
  meshes.push_back(make_mesh(cone_mesh(16), "spot light volume"));
  for (const mesh& m : meshes) bind_light_index(m.vertex_array, light_index);

  frame_ubo = make_buffer(std::vector<frame_block>{camera_frame(description, o)}, "camera frame");
  shadow_ubo = make_buffer(std::vector<frame_block>{camera_frame(description, o)}, "light frame");
  GLint most_texels = 0;
  glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &most_texels);
  if (auto ok = materials_fit(description, std::uint64_t(most_texels)); !ok) return ok;
  materials = make_buffer(material_blocks(description), "materials");
  glCreateTextures(GL_TEXTURE_BUFFER, 1, &material_texels);
  glTextureBuffer(material_texels, GL_RGBA32F, materials);
  label(GL_TEXTURE, material_texels, "material texels");
  textures.push_back(material_texels);
  if (plan.on.has(effect::textures)) {
    auto t = make_texture_array(texture_array_of(description), "material textures");
    if (!t) return failure{t.error()};
    material_textures = *t;
    textures.push_back(material_textures);
  }
  lights = make_buffer(light_data, "lights");
  buffers.insert(buffers.end(), {frame_ubo, shadow_ubo, materials, lights});
  for (const light_block& l : light_data) {
    light_frames.emplace_back();
    for (int v = 0; v < shadow_views(l); ++v) light_frames.back().push_back(light_frame(description, l, o, v));
  }

  if (mode != shadow_mode::off) {
    auto sm = mode == shadow_mode::transparent
                  ? make_targets(describe<thesis_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true)
                  : make_targets(describe<opaque_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true);
    if (!sm) return failure{sm.error()};
    shadow_map = *sm;
    fixed_targets.push_back(shadow_map);
    for (std::size_t i = 0; i < plan.lookups.size() && pictured_light < 0; ++i)
      if (plan.lookups[i] != shadow_mode::off) pictured_light = int(i);
    if (mode == shadow_mode::transparent && pictured_light >= 0) {
      auto t = make_targets({describe<thesis_shadow_map>()[1]}, o.shadow_size, o.shadow_size, "shadow picture", false);
      if (!t) return failure{t.error()};
      out.shadow_picture = *t;
      fixed_targets.push_back(*t);
    }
  }
  if (smoke.on) make_particles();
  if (plan.shadow_layers) make_shadow_layers();
  for (const post_pass& pass : plan.post.passes) {
    post_blocks.push_back(make_buffer(std::vector<glm::vec4>{glm::vec4(pass.params[0], pass.params[1], pass.params[2], pass.params[3])},
                                      "post " + pass.name));
    buffers.push_back(post_blocks.back());
  }
  return true;
}

// The atlas (the bake adds into it, the particles sample it), each region's bake block, the lights per
// dispatch; the particles' regions and quads.
void renderer::impl::make_particles() {
  const volume_atlas& atlas = smoke.atlas;
  const glm::ivec3 atlas_size = glm::max(atlas.size, glm::ivec3(1));  // a forced effect with no system
  if (smoke.baking) {
    bake_regions = make_buffer(bake_blocks(atlas, smoke.ranges), "volume regions");
    buffers.push_back(bake_regions);
    unshadowed_buffer = make_buffer(smoke.unshadowed_lights, "volume lights");
    buffers.push_back(unshadowed_buffer);
    for (const volume_light& l : smoke.shadowed_lights) {
      const int i = int(l.cos_inner.y);
      shadowed_buffers[i] = make_buffer(std::vector<volume_light>{l}, "volume light " + std::to_string(i));
      buffers.push_back(shadowed_buffers[i]);
    }
    glCreateTextures(GL_TEXTURE_3D, 1, &out.volume_atlas);
    textures.push_back(out.volume_atlas);
    out.volume_atlas_size = atlas_size;
    glTextureStorage3D(out.volume_atlas, 1, GL_RGBA8, atlas_size.x, atlas_size.y, atlas_size.z);
    glTextureParameteri(out.volume_atlas, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(out.volume_atlas, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(out.volume_atlas, wrap, GL_CLAMP_TO_EDGE);
    label(GL_TEXTURE, out.volume_atlas, "volume atlas");
  }
  particle_regions = make_buffer(render::particle_regions(description, smoke), "particle regions");
  std::size_t count = 0;
  for (const particle_system& ps : description.particles) count += std::size_t(std::max(ps.count, 0));
  particle_quads = make_buffer(std::vector<particle_vertex>(count * 6), "particle quads");
  buffers.insert(buffers.end(), {particle_regions, particle_quads});
  glCreateVertexArrays(1, &particle_vao);
  vertex_arrays.push_back(particle_vao);
  label(GL_VERTEX_ARRAY, particle_vao, "particles");
  glVertexArrayVertexBuffer(particle_vao, 0, particle_quads, 0, sizeof(particle_vertex));
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(particle_vao, a);
    glVertexArrayAttribBinding(particle_vao, a, 0);
  }
  glVertexArrayAttribFormat(particle_vao, 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(particle_vertex, position)));
  glVertexArrayAttribIFormat(particle_vao, 1, 1, GL_UNSIGNED_INT, GLuint(offsetof(particle_vertex, system)));
  glVertexArrayAttribFormat(particle_vao, 2, 4, GL_FLOAT, GL_FALSE, GLuint(offsetof(particle_vertex, corner)));
}

// The shadow maps' layers (frame_plan::shadow_layers), one a shadowed light in light order.
void renderer::impl::make_shadow_layers() {
  for (std::size_t t = 0; t < shadow_map.textures.size(); ++t) {
    glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &shadow_layers[t]);
    textures.push_back(shadow_layers[t]);
    glTextureStorage3D(shadow_layers[t], 1, t == 0 ? GL_R32F : GL_RGBA8, o.shadow_size, o.shadow_size, GLsizei(smoke.shadowed_lights.size()));
    label(GL_TEXTURE, shadow_layers[t], t == 0 ? "shadow layers depth" : "shadow layers colour");
  }
  for (std::size_t k = 0; k < smoke.shadowed_lights.size(); ++k) shadow_layer_of[int(smoke.shadowed_lights[k].cos_inner.y)] = GLint(k);
}

result<bool> renderer::impl::make_sized() {
  for (int k = 0; k < plan.kept_layers(); ++k) {
    const std::string suffix = k ? " 2" : "";
    auto g = make_targets(gbuffer_targets(o.layout), o.width, o.height, "gbuffer" + suffix, true);
    if (!g) return failure{g.error()};
    out.gbuffers.push_back(*g);
    auto l = make_targets(light_targets(o), o.width, o.height, "light buffer" + suffix, false);
    if (!l) return failure{l.error()};
    out.light_buffers.push_back(*l);
  }
  if (plan.forward) {
    auto t = make_targets(forward_targets(plan.forward_depth, o.float_targets), o.width, o.height, "forward", true);
    if (!t) return failure{t.error()};
    out.lit = *t;
    glCreateFramebuffers(1, &lit_colour_only);
    glNamedFramebufferTexture(lit_colour_only, GL_COLOR_ATTACHMENT0, out.lit.textures[0], 0);
    glNamedFramebufferTexture(lit_colour_only, GL_DEPTH_ATTACHMENT, out.lit.depth, 0);
    label(GL_FRAMEBUFFER, lit_colour_only, "forward light passes");
  }
  auto composed = make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "final", false);
  if (!composed) return failure{composed.error()};
  out.composed = *composed;
  registry = {{"frame", out.composed.textures[0]}};
  for (const std::string& name : plan.post.targets) {
    auto t = make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "post " + name, false);
    if (!t) return failure{t.error()};
    out.post[name] = *t;
    registry[name] = t->textures[0];
  }
  out.output = plan.post.passes.empty() ? &out.composed : &out.post.at(plan.post.output);
  if (plan.lists) {
    glCreateTextures(GL_TEXTURE_2D, 1, &out.kbuffer_heads);
    glTextureStorage2D(out.kbuffer_heads, 1, GL_R32UI, o.width, o.height);
    label(GL_TEXTURE, out.kbuffer_heads, "k-buffer heads");
    out.kbuffer_capacity = kbuffer_capacity(o);
    out.kbuffer_nodes = make_buffer(std::vector<glm::uvec4>(std::size_t(out.kbuffer_capacity) + 1u), "k-buffer nodes");
    auto t = make_targets(kbuffer_tail_targets(), o.width, o.height, "k-buffer tail", false);
    if (!t) return failure{t.error()};
    tail = *t;
  }
  if (plan.around_glass) {
    auto t = make_targets(glass_layer_targets(), o.width, o.height, "glass layers", false);
    if (!t) return failure{t.error()};
    glass_layers = *t;
  }
  return true;
}

void renderer::impl::destroy_sized() {
  for (auto* t : {&out.lit, &out.composed, &tail, &glass_layers}) destroy(*t);
  for (auto& t : out.gbuffers) destroy(t);
  for (auto& t : out.light_buffers) destroy(t);
  for (auto& [name, t] : out.post) destroy(t);
  out.gbuffers.clear();
  out.light_buffers.clear();
  out.post.clear();
  sequence = 0;  // new targets hold no previous frame
  out.output = nullptr;
  if (lit_colour_only) glDeleteFramebuffers(1, &lit_colour_only);
  if (out.kbuffer_heads) glDeleteTextures(1, &out.kbuffer_heads);
  if (out.kbuffer_nodes) glDeleteBuffers(1, &out.kbuffer_nodes);
  lit_colour_only = out.kbuffer_heads = out.kbuffer_nodes = 0;
}

// A G-buffer's textures at `first` and up (the compact layout's depth attachment at its depth slot).
void renderer::impl::bind_textures(int first, const gl::targets& t) const {
  for (std::size_t k = 0; k < t.textures.size(); ++k) glBindTextureUnit(GLuint(first) + GLuint(k), t.textures[k]);
}

void renderer::impl::bind_gbuffer(int first, const gl::targets& g) const {
  bind_textures(first, g);
  if (o.layout == gbuffer_layout::compact) glBindTextureUnit(GLuint(first + gbuffer_depth_slot), g.depth);
}

void renderer::impl::bind_shadow_map() const { bind_textures(binding(slot::shadow_map), shadow_map); }

void renderer::impl::bind_shadow_layers() const {
  for (GLuint t = 0; t < 2; ++t)
    if (shadow_layers[t]) glBindTextureUnit(GLuint(binding(slot::shadow_layers)) + t, shadow_layers[t]);
}

// What the k-buffer passes read and write: the lists, the G-buffer, the shadow map.
void renderer::impl::bind_layers() const {
  glBindImageTexture(binding(slot::kbuffer_heads), out.kbuffer_heads, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::kbuffer_nodes), out.kbuffer_nodes);
  bind_frame_depths();
  bind_shadow_map();
}

// The G-buffers the k-buffer and particle passes read: the first, and around peeling's glass the second.
void renderer::impl::bind_frame_depths() const {
  bind_gbuffer(binding(slot::gbuffer), out.gbuffers[0]);
  if (plan.around_glass && plan.peeling) bind_gbuffer(binding(slot::gbuffer2), out.gbuffers[1]);
}

// One bake dispatch over every region, with the lights in `lights_buffer`, reading the shadow map.
void renderer::impl::bake(GLuint prog, GLuint lights_buffer) const {
  bind_shadow_map();
  glUseProgram(prog);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::volume_lights), lights_buffer);
  glBindImageTexture(binding(slot::volume_image), out.volume_atlas, 0, GL_TRUE, 0, GL_READ_WRITE, GL_RGBA8);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::volume_regions), bake_regions);
  const glm::ivec3 groups = bake_groups(smoke.atlas);
  glDispatchCompute(GLuint(groups.x), GLuint(groups.y), GLuint(groups.z));
  glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
}

void renderer::impl::clear(const scheduled_pass& pass, const gl::targets& t) const {
  glDepthMask(GL_TRUE);  // clears obey the depth write mask
  for (std::size_t k = 0; k < pass.clears.size(); ++k) glClearNamedFramebufferfv(t.framebuffer, GL_COLOR, GLint(k), &pass.clears[k].x);
  const float far_plane = 1.0f;
  if (pass.clear_depth) glClearNamedFramebufferfv(t.framebuffer, GL_DEPTH, 0, &far_plane);
}

void renderer::impl::run_light(const scheduled_pass& pass) const {
  const int i = pass.light;
  const shadow_mode lookup = plan.lookups[std::size_t(i)];
  bind(out.light_buffers[std::size_t(pass.index)]);
  bind_gbuffer(binding(slot::gbuffer), out.gbuffers[std::size_t(pass.index)]);
  if (lookup != shadow_mode::off) bind_shadow_map();
  const volume v = volume_of(description.lights[std::size_t(i)], o);
  glUseProgram(light_progs[int(lookup)][v == volume::fullscreen ? 0 : 1]);
  if (v == volume::fullscreen) {
    glBindVertexArray(fullscreen_vao);
    glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, 1, GLuint(i));
  } else {
    // Back faces, depth clamped: each pixel the volume covers is lit once (dstrans/frame/plan.hpp, volume).
    const mesh& m = meshes[v == volume::sphere ? 0 : 1];
    glBindVertexArray(m.vertex_array);
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, m.index_count, GL_UNSIGNED_INT, nullptr, 1, GLuint(i));
  }
}

void renderer::impl::run_post(const scheduled_pass& pass) const {
  const std::size_t k = std::size_t(pass.index);
  const post_pass& p = plan.post.passes[k];
  bind(out.post.at(p.output));
  glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::post_params), post_blocks[k]);
  bind_gbuffer(binding(slot::gbuffer), out.gbuffers[0]);
  GLuint unit = binding(slot::post_input);
  for (const std::string& in : p.inputs)
    if (in != "gbuffer") glBindTextureUnit(unit++, registry.at(in));
  glUseProgram(post_progs[k]);
  draw_fullscreen(fullscreen_vao);
}

// One pass of the schedule: its target and clears, its state, its bindings and its draw.
void renderer::impl::run(const scheduled_pass& pass, const draw_geometry& draw) {
  debug_group group(pass.label);
  glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
  const int i = pass.light;
  switch (pass.step) {
    case pass_step::gbuffer: {
      const gl::targets& g = out.gbuffers[std::size_t(pass.index)];
      bind(g);
      clear(pass, g);
      apply(pass.state);
      if (pass.index) glBindTextureUnit(GLuint(binding(slot::peel_depth)), o.layout == gbuffer_layout::compact ? out.gbuffers[0].depth
                                                                                                                : out.gbuffers[0].textures[3]);
      glUseProgram(gbuffer_progs[pass.index]);
      draw(pass);
      break;
    }
    case pass_step::ambient:
      bind(out.lit);
      clear(pass, out.lit);
      apply(pass.state);
      glUseProgram(ambient_prog);
      draw(pass);
      break;
    case pass_step::shadow:
      bind(shadow_map);
      clear(pass, shadow_map);
      apply(pass.state);
      glNamedBufferSubData(shadow_ubo, 0, sizeof(frame_block), &light_frames[std::size_t(i)][std::size_t(pass.index)]);
      glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), shadow_ubo);
      glUseProgram(pass.draws == geometry_set::opaque ? shadow_depth_prog : shadow_prog);
      if (pass.area.z > 0) {  // a cube face's tile; rows from the top are GL's with glClipControl(GL_UPPER_LEFT)
        glViewport(pass.area.x, pass.area.y, pass.area.z, pass.area.w);
        glScissor(pass.area.x, pass.area.y, pass.area.z, pass.area.w);
        glEnable(GL_SCISSOR_TEST);
      }
      draw(pass);
      if (pass.area.z > 0) glDisable(GL_SCISSOR_TEST);
      if (i == pictured_light && out.shadow_picture.framebuffer && frames_drawn == 0)  // once: the lights do not move
        glCopyImageSubData(shadow_map.textures[1], GL_TEXTURE_2D, 0, 0, 0, 0, out.shadow_picture.textures[0], GL_TEXTURE_2D, 0, 0, 0, 0,
                           o.shadow_size, o.shadow_size, 1);
      break;
    case pass_step::forward_light:
      glBindFramebuffer(GL_FRAMEBUFFER, lit_colour_only);
      glViewport(0, 0, o.width, o.height);
      apply(pass.state);
      if (plan.lookups[std::size_t(i)] != shadow_mode::off) bind_shadow_map();
      glUseProgram(forward_light_progs[int(plan.lookups[std::size_t(i)])]);
      glVertexAttribI4ui(light_index_attribute, GLuint(i), 0, 0, 0);
      draw(pass);
      break;
    case pass_step::light:
      apply(pass.state);
      run_light(pass);
      break;
    case pass_step::bake:
      bake(bake_prog, unshadowed_buffer);
      break;
    case pass_step::bake_light:
      bake(bake_shadowed_prog, shadowed_buffers.at(i));
      break;
    case pass_step::shadow_layer:
      for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
        glCopyImageSubData(shadow_map.textures[t], GL_TEXTURE_2D, 0, 0, 0, 0, shadow_layers[t], GL_TEXTURE_2D_ARRAY, 0, 0, 0,
                           shadow_layer_of.at(i), o.shadow_size, o.shadow_size, 1);
      break;
    case pass_step::compose:
    case pass_step::blend:
      bind(out.composed);
      apply(pass.state);
      if (plan.forward) {
        bind_textures(binding(slot::forward_lit), out.lit);
      } else {
        bind_gbuffer(binding(slot::gbuffer), out.gbuffers[0]);
        bind_textures(binding(slot::light), out.light_buffers[0]);
        if (plan.kept_layers() == 2) {  // peeling's second layer, or the previous frame's
          bind_gbuffer(binding(slot::gbuffer2), out.gbuffers[1]);
          bind_textures(binding(slot::light2), out.light_buffers[1]);
        }
        if (plan.around_glass) bind_textures(binding(slot::glass_layers), glass_layers);
      }
      glUseProgram(still_camera(previous) ? compose_still_prog : compose_prog);
      draw_fullscreen(fullscreen_vao);
      break;
    case pass_step::capture: {
      const GLuint empty = 0xffffffffu;
      glClearTexImage(out.kbuffer_heads, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
      const glm::uvec4 header(0u, 0u, out.kbuffer_capacity, 0u);
      glNamedBufferSubData(out.kbuffer_nodes, 0, sizeof header, &header);
      bind(tail);
      clear(pass, tail);
      apply(pass.state);
      bind_layers();
      bind_shadow_layers();
      glUseProgram(capture_prog);
      draw(pass);
      break;
    }
    case pass_step::resolve:
      glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
      bind(layered_target(pass.step));
      clear(pass, layered_target(pass.step));
      apply(pass.state);
      bind_layers();
      for (GLuint t = 0; t < 2; ++t) glBindTextureUnit(GLuint(binding(slot::kbuffer_tail)) + t, tail.textures[t]);
      glUseProgram(resolve_prog);
      draw_fullscreen(fullscreen_vao);
      break;
    case pass_step::particles:
      glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
      bind(layered_target(pass.step));
      clear(pass, layered_target(pass.step));
      apply(pass.state);
      if (plan.exact) bind_layers();
      else bind_frame_depths();
      if (out.volume_atlas) glBindTextureUnit(GLuint(binding(slot::volume_atlas)), out.volume_atlas);
      if (smoke.shadows != shadow_mode::off) bind_shadow_map();
      bind_shadow_layers();
      glUseProgram(particle_prog);
      glBindVertexArray(particle_vao);
      glDrawArrays(GL_TRIANGLES, 0, GLsizei(particle_vertices));
      break;
    case pass_step::post:
      apply(pass.state);
      run_post(pass);
      break;
  }
}

renderer::renderer(std::unique_ptr<impl> p) : p_(std::move(p)) {}
renderer::~renderer() = default;

result<std::unique_ptr<renderer>> renderer::create(const scene& description, const render::options& o, const pass_shaders& shaders) {
  GLint largest = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  if (auto ok = fits_device(o, std::min({int(largest), int(viewport[0]), int(viewport[1])})); !ok) return failure{ok.error()};
  state_guard keep;
  auto p = std::make_unique<impl>();
  p->description = description;
  p->o = o;
  p->plan = plan_of(description, o);
  p->light_data = light_blocks(description);
  p->smoke = particle_plan_of(description, p->plan, o, p->light_data);
  p->schedule = schedule_of(description, p->plan, o, p->light_data);
  p->shaders = &shaders;
  for (auto step : {&impl::make_programs, &impl::make_fixed, &impl::make_sized})
    if (auto ok = ((*p).*step)(); !ok) return failure{ok.error()};
  p->shaders = nullptr;  // every program is made: the frame reads no shader
  for (object& ob : p->description.objects) ob.geometry = {};
  p->description.textures = {};  // uploaded: the frame reads none
  return std::unique_ptr<renderer>(new renderer(std::move(p)));
}

result<bool> renderer::resize(int width, int height) {
  render::options sized = p_->o;
  sized.width = width;
  sized.height = height;
  GLint largest = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  if (auto ok = fits_device(sized, int(largest)); !ok) return ok;
  state_guard keep;
  p_->destroy_sized();
  p_->o = sized;
  return p_->make_sized();
}

void renderer::render(const camera& view, const draw_geometry& draw) {
  impl& r = *p_;
  state_guard keep;
  frame_block camera_block = sequence_frame(camera_frame(r.description, view, r.o), r.previous, r.sequence, r.plan, r.o);
  glNamedBufferSubData(r.frame_ubo, 0, sizeof camera_block, &camera_block);
  set_camera_view(r.schedule, camera_block.view_proj);
  // Temporal interlacing draws into the other G-buffer and light buffer each frame; the last frame's become
  // the second layer, which the compose pass reads.
  if (r.plan.temporal && r.sequence > 0) {
    std::swap(r.out.gbuffers[0], r.out.gbuffers[1]);
    std::swap(r.out.light_buffers[0], r.out.light_buffers[1]);
  }
  r.previous = camera_block;
  ++r.sequence;
  if (r.smoke.on) {
    const std::vector<particle_vertex> quads = particle_quads(r.description, view);
    r.particle_vertices = quads.size();
    if (!quads.empty()) glNamedBufferSubData(r.particle_quads, 0, GLsizeiptr(quads.size() * sizeof(particle_vertex)), quads.data());
  }
  glBindTextureUnit(GLuint(binding(slot::materials)), r.material_texels);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::lights), r.lights);
  if (r.material_textures) glBindTextureUnit(GLuint(binding(slot::material_textures)), r.material_textures);
  if (r.smoke.on) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::particle_regions), r.particle_regions);
  glDisable(GL_SCISSOR_TEST);
  glFrontFace(GL_CCW);
  r.recorded.clear();
  r.whole.begin();
  const float zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (const std::string& name : r.schedule.cleared)
    if (name == "volume atlas") glClearTexImage(r.out.volume_atlas, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    else
      for (std::size_t k = 0; k < r.out.light_buffers[name == "light buffer" ? 0 : 1].textures.size(); ++k)
        glClearNamedFramebufferfv(r.out.light_buffers[name == "light buffer" ? 0 : 1].framebuffer, GL_COLOR, GLint(k), zero);
  for (const scheduled_pass& pass : r.schedule.passes) {
    if (r.recorded.size() == r.timers.size()) r.timers.emplace_back();
    timer& t = r.timers[r.recorded.size()];
    r.recorded.push_back(pass.timer);
    t.begin();
    r.run(pass, draw);
    t.end();
  }
  r.whole.end();
  ++r.frames_drawn;
}

frame_times renderer::times() const {
  if (p_->recorded.empty()) return {};
  std::vector<double> ms;
  for (std::size_t k = 0; k < p_->recorded.size(); ++k) ms.push_back(p_->timers[k].milliseconds());
  return times_of(p_->schedule, ms, p_->whole.milliseconds());
}

const frame_schedule& renderer::schedule() const { return p_->schedule; }
const render::frame_plan& renderer::plan() const { return p_->plan; }
const render::options& renderer::options() const { return p_->o; }
const frame_targets& renderer::targets() const { return p_->out; }

scene_geometry::scene_geometry(const scene& s) {
  const scene_mesh m = flatten(s);
  hair_first_ = m.hair_first;
  index_count_ = m.indices.size();
  parts_ = m.parts;
  buffers_[0] = make_buffer(m.positions, "scene positions");
  buffers_[1] = make_buffer(m.normals, "scene normals");
  buffers_[2] = make_buffer(m.materials, "scene materials");
  buffers_[3] = make_buffer(m.indices, "scene indices");
  if (!m.uvs.empty()) buffers_[4] = make_buffer(m.uvs, "scene texture coordinates");
  glCreateVertexArrays(1, &vertex_array_);
  label(GL_VERTEX_ARRAY, vertex_array_, "scene");
  glVertexArrayVertexBuffer(vertex_array_, 0, buffers_[0], 0, sizeof(glm::vec3));
  glVertexArrayVertexBuffer(vertex_array_, 1, buffers_[1], 0, sizeof(glm::vec3));
  glVertexArrayVertexBuffer(vertex_array_, 2, buffers_[2], 0, sizeof(std::uint32_t));
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(vertex_array_, a);
    glVertexArrayAttribBinding(vertex_array_, a, a);
  }
  glVertexArrayAttribFormat(vertex_array_, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(vertex_array_, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(vertex_array_, 2, 1, GL_UNSIGNED_INT, 0);
  if (buffers_[4]) {
    glVertexArrayVertexBuffer(vertex_array_, texture_coordinates_attribute, buffers_[4], 0, sizeof(glm::vec2));
    glEnableVertexArrayAttrib(vertex_array_, texture_coordinates_attribute);
    glVertexArrayAttribBinding(vertex_array_, texture_coordinates_attribute, texture_coordinates_attribute);
    glVertexArrayAttribFormat(vertex_array_, texture_coordinates_attribute, 2, GL_FLOAT, GL_FALSE, 0);
  }
  glVertexArrayElementBuffer(vertex_array_, buffers_[3]);
}

scene_geometry::~scene_geometry() {
  glDeleteVertexArrays(1, &vertex_array_);
  glDeleteBuffers(5, buffers_);
}

void scene_geometry::operator()(const scheduled_pass& pass) const {
  const std::vector<index_run> runs = visible_runs(parts_, hair_first_, index_count_, pass);
  if (runs.empty()) return;
  glBindVertexArray(vertex_array_);
  // The runs that may cull their back faces are drawn as one call with GL_BACK culled, the others as one
  // with the caller's culling, which is then left as it was.
  for (const bool cull : {false, true}) {
    std::vector<GLsizei> counts;
    std::vector<const void*> offsets;
    for (const index_run& run : runs)
      if (run.cull_back == cull) {
        counts.push_back(GLsizei(run.count));
        offsets.push_back(reinterpret_cast<const void*>(run.first * sizeof(std::uint32_t)));
      }
    if (counts.empty()) continue;
    if (!cull) {
      glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(), GLsizei(counts.size()));
      continue;
    }
    const GLboolean culled_before = glIsEnabled(GL_CULL_FACE);
    GLint face_before = GL_BACK;
    glGetIntegerv(GL_CULL_FACE_MODE, &face_before);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glMultiDrawElements(GL_TRIANGLES, counts.data(), GL_UNSIGNED_INT, offsets.data(), GLsizei(counts.size()));
    if (!culled_before) glDisable(GL_CULL_FACE);
    glCullFace(GLenum(face_before));
  }
}

}  // namespace dstrans::gl
