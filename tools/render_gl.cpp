// Implements render_gl.hpp with the engine-facing GL backend.
#include "render_gl.hpp"

#include <dstrans_gl.hpp>
#include <algorithm>
#include <cstddef>
#include <deque>
#include <memory>

#include <dstrans/particles.hpp>

#include "passes.hpp"

namespace dstrans::render {

namespace {

// GL objects of one frame, released however the frame ends.
struct resources {
  std::vector<GLuint> buffers, vertex_arrays, programs, framebuffers, textures;
  std::vector<gl::targets> targets;
  std::vector<gl::mesh> meshes;
  ~resources() {
    for (auto& t : targets) gl::destroy(t);
    for (auto& m : meshes) gl::destroy(m);
    if (!buffers.empty()) glDeleteBuffers(GLsizei(buffers.size()), buffers.data());
    if (!vertex_arrays.empty()) glDeleteVertexArrays(GLsizei(vertex_arrays.size()), vertex_arrays.data());
    for (GLuint p : programs) glDeleteProgram(p);
    if (!framebuffers.empty()) glDeleteFramebuffers(GLsizei(framebuffers.size()), framebuffers.data());
    if (!textures.empty()) glDeleteTextures(GLsizei(textures.size()), textures.data());
  }
  template <class T>
  GLuint buffer(const std::vector<T>& data, const std::string& name) {
    GLuint b = 0;
    glCreateBuffers(1, &b);
    glNamedBufferStorage(b, GLsizeiptr(std::max<std::size_t>(data.size(), 1) * sizeof(T)),
                         data.empty() ? nullptr : data.data(), GL_DYNAMIC_STORAGE_BIT);
    gl::label(GL_BUFFER, b, name);
    buffers.push_back(b);
    return b;
  }
  result<GLuint> program(const result<pass_sources>& p, const std::string& name) {
    if (!p) return failure{p.error()};
    auto prog = gl::make_program(p->vertex, p->fragment, name);
    if (prog) programs.push_back(*prog);
    return prog;
  }
};

// Binds the per-light instance attribute (location 3, buffer binding 3) of vertex array `vao` to `indices`.
void bind_light_index(GLuint vao, GLuint indices) {
  glVertexArrayVertexBuffer(vao, 3, indices, 0, sizeof(std::uint32_t));
  glVertexArrayBindingDivisor(vao, 3, 1);
  glEnableVertexArrayAttrib(vao, 3);
  glVertexArrayAttribIFormat(vao, 3, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayAttribBinding(vao, 3, 3);
}

}  // namespace

result<frame> render_gl(const scene& s, const options& o, const pass_shaders& shaders, const frame_hooks* hooks) {
  GLint largest = 0, viewport[2] = {0, 0};
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, viewport);
  if (auto ok = fits_device(o, std::min({int(largest), int(viewport[0]), int(viewport[1])})); !ok) return failure{ok.error()};
  resources r;
  gl::state_guard keep;
  const frame_plan plan = plan_of(s, o);
  const shadow_mode mode = plan.shadows;
  const bool any_shadows = mode != shadow_mode::off;

  // Deferred: one G-buffer and light buffer (interlaced), or one a peeled layer. Forward: one lit target.
  const bool forward = plan.forward, with_depth = plan.forward_depth, peeling = plan.peeling;
  const int layers = plan.layers;
  std::vector<GLuint> gbuffer_progs;
  // Light programs by [lookup][volume], forward light programs by [lookup]: only the lookups lights use.
  GLuint compose_prog = 0, light_progs[3][2] = {}, ambient_prog = 0, forward_light_progs[3] = {};
  if (!forward) {
    for (layer which :
         peeling ? std::vector<layer>{layer::first, layer::second} : std::vector<layer>{layer::interlaced}) {
      auto p = r.program(gbuffer_pass(shaders, which, plan.on, o), "gbuffer pass");
      if (!p) return failure{p.error()};
      gbuffer_progs.push_back(*p);
    }
    auto c = r.program(compose_pass(shaders, plan.on, o), "compose pass");
    if (!c) return failure{c.error()};
    compose_prog = *c;
    for (shadow_mode k : all_lookups)
      for (int vol = 0; vol < 2 && plan.uses(k); ++vol) {
        auto p = r.program(light_pass(shaders, k, vol == 1, o),
                           std::string("light pass") + lookup_label(k) + (vol ? " volume" : " fullscreen"));
        if (!p) return failure{p.error()};
        light_progs[int(k)][vol] = *p;
      }
  } else {
    auto a = r.program(forward_pass(shaders, forward_stage::ambient, with_depth, shadow_mode::off),
                       "forward ambient pass");
    if (!a) return failure{a.error()};
    ambient_prog = *a;
    for (shadow_mode k : all_lookups) {
      if (!plan.uses(k)) continue;
      auto p = r.program(forward_pass(shaders, forward_stage::light, with_depth, k, o.physical_transmittance),
                         std::string("forward light pass") + lookup_label(k));
      if (!p) return failure{p.error()};
      forward_light_progs[int(k)] = *p;
    }
    auto b =
        r.program(forward_pass(shaders, forward_stage::blend, with_depth, shadow_mode::off), "forward blend pass");
    if (!b) return failure{b.error()};
    compose_prog = *b;
  }
  GLuint shadow_prog = 0;
  if (any_shadows) {
    auto p = r.program(shadow_pass(shaders, mode, plan.on), "shadow pass");
    if (!p) return failure{p.error()};
    shadow_prog = *p;
  }

  // The k-buffer (many layers: hair) after the deferred frame; forward rendering draws no hair.
  const bool many = plan.on.has(effect::many_layers) && !forward;
  GLuint capture_prog = 0, resolve_prog = 0;
  if (many) {
    auto c = r.program(capture_pass(shaders, mode, o), "capture pass");
    if (!c) return failure{c.error()};
    capture_prog = *c;
    auto rs = r.program(resolve_pass(shaders, mode, o), "resolve pass");
    if (!rs) return failure{rs.error()};
    resolve_prog = *rs;
  }

  // Light volumes (S2): particle systems over the deferred frame, lit from the atlas baked each frame (all
  // unshadowed lights in one dispatch a region, each shadowed spot light in its own right after its shadow
  // pass), or by the forward reference, which needs every shadow map at once: each is copied into a layer.
  const particle_plan smoke = particle_plan_of(s, plan, o);
  const bool particles = smoke.on, particle_reference = smoke.reference, baking = smoke.baking;
  const volume_atlas& atlas = smoke.atlas;
  const std::vector<volume_light>& shadowed_lights = smoke.shadowed_lights;
  const std::vector<volume_light>& unshadowed_lights = smoke.unshadowed_lights;
  GLuint bake_prog = 0, bake_shadowed_prog = 0, particle_prog = 0;
  if (particles) {
    for (const bool shadowed : {false, true}) {
      if (!baking || (shadowed ? shadowed_lights.empty() : unshadowed_lights.empty())) continue;
      auto src = bake_pass(shaders, shadowed ? mode : shadow_mode::off, o);
      if (!src) return failure{src.error()};
      auto prog = gl::make_compute_program(*src, shadowed ? "bake pass shadowed" : "bake pass");
      if (!prog) return failure{prog.error()};
      r.programs.push_back(*prog);
      (shadowed ? bake_shadowed_prog : bake_prog) = *prog;
    }
    auto p = r.program(particle_pass(shaders, smoke.shadows, o), "particle pass");
    if (!p) return failure{p.error()};
    particle_prog = *p;
  }

  // The scene as one mesh, the light indices, the volume meshes, and the blocks of frame.glsl.
  const scene_mesh m = flatten(s);
  GLuint scene_vao = 0, fullscreen_vao = 0;
  glCreateVertexArrays(1, &scene_vao);
  glCreateVertexArrays(1, &fullscreen_vao);
  r.vertex_arrays = {scene_vao, fullscreen_vao};
  gl::label(GL_VERTEX_ARRAY, scene_vao, "scene");
  gl::label(GL_VERTEX_ARRAY, fullscreen_vao, "full-screen lights");
  const GLuint positions = r.buffer(m.positions, "scene positions"), normals = r.buffer(m.normals, "scene normals"),
               materials = r.buffer(m.materials, "scene materials"), indices = r.buffer(m.indices, "scene indices");
  glVertexArrayVertexBuffer(scene_vao, 0, positions, 0, sizeof(glm::vec3));
  glVertexArrayVertexBuffer(scene_vao, 1, normals, 0, sizeof(glm::vec3));
  glVertexArrayVertexBuffer(scene_vao, 2, materials, 0, sizeof(std::uint32_t));
  for (GLuint a = 0; a < 3; ++a) {
    glEnableVertexArrayAttrib(scene_vao, a);
    glVertexArrayAttribBinding(scene_vao, a, a);
  }
  glVertexArrayAttribFormat(scene_vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(scene_vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(scene_vao, 2, 1, GL_UNSIGNED_INT, 0);
  glVertexArrayElementBuffer(scene_vao, indices);

  std::vector<std::uint32_t> light_ids(s.lights.size());
  for (std::size_t i = 0; i < light_ids.size(); ++i) light_ids[i] = std::uint32_t(i);
  const GLuint light_index = r.buffer(light_ids, "light indices");
  bind_light_index(fullscreen_vao, light_index);
  bind_light_index(scene_vao, light_index);
  r.meshes.push_back(gl::make_mesh(sphere_mesh(1), "point light volume"));
  r.meshes.push_back(gl::make_mesh(cone_mesh(16), "spot light volume"));
  for (const gl::mesh& mesh : r.meshes) bind_light_index(mesh.vertex_array, light_index);

  frame_block camera = camera_frame(s, o);
  camera.params.z = float(hair_shadow_light(plan));
  const GLuint frame_ubo = r.buffer(std::vector<frame_block>{camera}, "camera frame");
  const GLuint shadow_ubo = r.buffer(std::vector<frame_block>{camera}, "light frame");
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::materials), r.buffer(material_blocks(s), "materials"));
  const std::vector<light_block> light_data = light_blocks(s);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::lights), r.buffer(light_data, "lights"));

  std::vector<gl::targets> gbuffers, light_buffers;
  for (int k = 0; k < layers; ++k) {
    const std::string suffix = k ? " 2" : "";
    auto g = gl::make_targets(gbuffer_targets(o.layout), o.width, o.height, "gbuffer" + suffix, true);
    if (!g) return failure{g.error()};
    r.targets.push_back(*g);
    gbuffers.push_back(*g);
    auto l = gl::make_targets(light_targets(o.float_targets), o.width, o.height, "light buffer" + suffix, false);
    if (!l) return failure{l.error()};
    r.targets.push_back(*l);
    light_buffers.push_back(*l);
  }
  // A G-buffer's textures at `first` and up (the compact layout's depth attachment at its depth slot), and
  // the texture that holds its depth.
  auto bind_gbuffer = [&](int first, const gl::targets& g) {
    for (std::size_t t = 0; t < g.textures.size(); ++t) glBindTextureUnit(GLuint(first) + GLuint(t), g.textures[t]);
    if (o.layout == gbuffer_layout::compact) glBindTextureUnit(GLuint(first + gbuffer_depth_slot), g.depth);
  };
  auto depth_of = [&](const gl::targets& g) { return o.layout == gbuffer_layout::compact ? g.depth : g.textures[3]; };

  // The forward target, and a framebuffer over its colour and depth alone for the light passes.
  gl::targets lit;
  GLuint lit_colour_only = 0;
  if (forward) {
    auto t = gl::make_targets(forward_targets(with_depth, o.float_targets), o.width, o.height, "forward", true);
    if (!t) return failure{t.error()};
    lit = *t;
    r.targets.push_back(lit);
    glCreateFramebuffers(1, &lit_colour_only);
    r.framebuffers.push_back(lit_colour_only);
    glNamedFramebufferTexture(lit_colour_only, GL_COLOR_ATTACHMENT0, lit.textures[0], 0);
    glNamedFramebufferTexture(lit_colour_only, GL_DEPTH_ATTACHMENT, lit.depth, 0);
    gl::label(GL_FRAMEBUFFER, lit_colour_only, "forward light passes");
  }
  auto final_target =
      gl::make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "final", false);
  if (!final_target) return failure{final_target.error()};
  r.targets.push_back(*final_target);
  gl::targets shadow_map;
  if (any_shadows) {
    auto sm = mode == shadow_mode::transparent
                  ? gl::make_targets(describe<thesis_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true)
                  : gl::make_targets(describe<opaque_shadow_map>(), o.shadow_size, o.shadow_size, "shadow map", true);
    if (!sm) return failure{sm.error()};
    shadow_map = *sm;
    r.targets.push_back(shadow_map);
  }

  // The lists' heads, the node pool (a header of count, overflow, capacity, then the nodes), the tail.
  GLuint heads = 0, nodes = 0;
  gl::targets tail;
  const std::uint32_t capacity = kbuffer_capacity(o);
  if (many) {
    glCreateTextures(GL_TEXTURE_2D, 1, &heads);
    r.textures.push_back(heads);
    glTextureStorage2D(heads, 1, GL_R32UI, o.width, o.height);
    gl::label(GL_TEXTURE, heads, "k-buffer heads");
    nodes = r.buffer(std::vector<glm::uvec4>(std::size_t(capacity) + 1u), "k-buffer nodes");
    auto t = gl::make_targets(kbuffer_tail_targets(), o.width, o.height, "k-buffer tail", false);
    if (!t) return failure{t.error()};
    tail = *t;
    r.targets.push_back(tail);
  }
  // The atlas's texels (the bake adds into them), the 3D texture they are copied to, each region's bake
  // block, the lights per dispatch; the particles' regions and quads; the shadow maps' layers.
  GLuint volume_texels = 0, atlas_texture = 0, particle_vao = 0, particle_quads_buffer = 0, unshadowed_buffer = 0;
  GLuint shadow_layers[2] = {};
  std::vector<GLuint> region_blocks, shadowed_buffers;
  std::size_t particle_vertices = 0;
  const glm::ivec3 atlas_size = glm::max(atlas.size, glm::ivec3(1));  // a forced effect with no system
  const std::size_t atlas_texels = std::size_t(atlas_size.x) * std::size_t(atlas_size.y) * std::size_t(atlas_size.z);
  auto upload_quads = [&](const dstrans::camera& c) {
    const std::vector<particle_vertex> quads = particle_quads(s, c);
    particle_vertices = quads.size();
    if (!quads.empty()) glNamedBufferSubData(particle_quads_buffer, 0, GLsizeiptr(quads.size() * sizeof(particle_vertex)), quads.data());
  };
  if (particles) {
    if (baking) {
      volume_texels = r.buffer(std::vector<glm::vec4>(atlas_texels), "volume texels");
      for (std::size_t k = 0; k < atlas.regions.size(); ++k)
        region_blocks.push_back(r.buffer(std::vector<volume_bake_block>{bake_block(atlas, k)}, "volume region " + std::to_string(k)));
      unshadowed_buffer = r.buffer(unshadowed_lights, "volume lights");
      for (const volume_light& l : shadowed_lights)
        shadowed_buffers.push_back(r.buffer(std::vector<volume_light>{l}, "volume light " + std::to_string(int(l.cos_inner.y))));
      glCreateTextures(GL_TEXTURE_3D, 1, &atlas_texture);
      r.textures.push_back(atlas_texture);
      glTextureStorage3D(atlas_texture, 1, GL_RGBA32F, atlas_size.x, atlas_size.y, atlas_size.z);
      glTextureParameteri(atlas_texture, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
      glTextureParameteri(atlas_texture, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
      for (GLenum wrap : {GL_TEXTURE_WRAP_S, GL_TEXTURE_WRAP_T, GL_TEXTURE_WRAP_R}) glTextureParameteri(atlas_texture, wrap, GL_CLAMP_TO_EDGE);
      gl::label(GL_TEXTURE, atlas_texture, "volume atlas");
    } else if (any_shadows && !shadowed_lights.empty()) {
      for (std::size_t t = 0; t < shadow_map.textures.size(); ++t) {
        glCreateTextures(GL_TEXTURE_2D_ARRAY, 1, &shadow_layers[t]);
        r.textures.push_back(shadow_layers[t]);
        glTextureStorage3D(shadow_layers[t], 1, t == 0 ? GL_R32F : GL_RGBA8, o.shadow_size, o.shadow_size,
                           GLsizei(shadowed_lights.size()));
        gl::label(GL_TEXTURE, shadow_layers[t], t == 0 ? "shadow layers depth" : "shadow layers colour");
      }
    }
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::particle_regions),
                     r.buffer(particle_regions(s, atlas), "particle regions"));
    std::size_t count = 0;
    for (const particle_system& ps : s.particles) count += std::size_t(std::max(ps.count, 0));
    particle_quads_buffer = r.buffer(std::vector<particle_vertex>(count * 6), "particle quads");
    glCreateVertexArrays(1, &particle_vao);
    r.vertex_arrays.push_back(particle_vao);
    gl::label(GL_VERTEX_ARRAY, particle_vao, "particles");
    glVertexArrayVertexBuffer(particle_vao, 0, particle_quads_buffer, 0, sizeof(particle_vertex));
    for (GLuint a = 0; a < 3; ++a) {
      glEnableVertexArrayAttrib(particle_vao, a);
      glVertexArrayAttribBinding(particle_vao, a, 0);
    }
    glVertexArrayAttribFormat(particle_vao, 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(particle_vertex, position)));
    glVertexArrayAttribIFormat(particle_vao, 1, 1, GL_UNSIGNED_INT, GLuint(offsetof(particle_vertex, system)));
    glVertexArrayAttribFormat(particle_vao, 2, 4, GL_FLOAT, GL_FALSE, GLuint(offsetof(particle_vertex, corner)));
    upload_quads(s.view);
  }
  // The post-processing chain (post.hpp): a program and a parameter block a pass, a target a name the
  // passes write, and the registry of names to textures ("frame": the composed image).
  const post_plan& post = plan.post;
  std::vector<GLuint> post_progs, post_blocks;
  std::map<std::string, gl::targets> post_targets;
  std::map<std::string, GLuint> registry{{"frame", final_target->textures[0]}};
  for (const post_pass& pass : post.passes) {
    auto p = r.program(post_pass_sources(shaders, pass, o), "post " + pass.name);
    if (!p) return failure{p.error()};
    post_progs.push_back(*p);
    post_blocks.push_back(r.buffer(std::vector<glm::vec4>{glm::vec4(pass.params[0], pass.params[1], pass.params[2], pass.params[3])},
                                   "post " + pass.name));
  }
  for (const std::string& name : post.targets) {
    auto t = gl::make_targets({final_target_desc(o.float_targets)}, o.width, o.height, "post " + name, false);
    if (!t) return failure{t.error()};
    r.targets.push_back(*t);
    post_targets[name] = *t;
    registry[name] = t->textures[0];
  }
  const gl::targets& shown = post.passes.empty() ? *final_target : post_targets.at(post.output);

  // One bake dispatch a region, with the lights in `lights`, reading the camera's frame and the shadow map.
  auto bake = [&](GLuint prog, GLuint lights) {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
    for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
      glBindTextureUnit(GLuint(binding(slot::shadow_map)) + GLuint(t), shadow_map.textures[t]);
    glUseProgram(prog);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::volume_lights), lights);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::volume_texels), volume_texels);
    for (std::size_t k = 0; k < atlas.regions.size(); ++k) {
      const glm::ivec4 d = atlas.regions[k].dims;
      glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::volume_region), region_blocks[k]);
      glDispatchCompute(GLuint(d.x + 3) / 4, GLuint(d.y + 3) / 4, GLuint(d.z + 3) / 4);
    }
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  };

  auto bind_layers = [&] {
    glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
    glBindImageTexture(binding(slot::kbuffer_heads), heads, 0, GL_FALSE, 0, GL_READ_WRITE, GL_R32UI);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding(slot::kbuffer_nodes), nodes);
    bind_gbuffer(binding(slot::gbuffer), gbuffers[0]);
    for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
      glBindTextureUnit(GLuint(binding(slot::shadow_map)) + GLuint(t), shadow_map.textures[t]);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_CULL_FACE);
    glEnable(GL_BLEND);
  };

  frame out;
  // The first shadowed light's map is the one pictured (Figure 4.4 of the thesis shows one): its colour is
  // copied here before the next light's shadow pass draws over it.
  gl::targets shadow_picture;
  if (mode == shadow_mode::transparent &&
      std::any_of(plan.lookups.begin(), plan.lookups.end(), [](shadow_mode lookup) { return lookup != shadow_mode::off; })) {
    auto t = gl::make_targets({describe<thesis_shadow_map>()[1]}, o.shadow_size, o.shadow_size, "shadow picture", false);
    if (!t) return failure{t.error()};
    shadow_picture = *t;
    r.targets.push_back(shadow_picture);
  }
  // A frame's passes go to the GPU without waiting: each between two timestamps, read when the frame is done.
  std::deque<gl::timer> timers;
  gl::timer whole;
  std::vector<std::string> recorded;
  std::map<std::string, double> current;  // this frame's pass times
  std::vector<std::map<std::string, double>> frames;
  std::vector<double> totals;  // each frame's whole GPU time
  auto timed = [&](const std::string& pass, auto&& draw) {
    if (recorded.size() == timers.size()) timers.emplace_back();
    gl::timer& timer = timers[recorded.size()];
    recorded.push_back(pass);
    timer.begin();
    draw();
    timer.end();
  };
  const float clear_far[4] = {1.0f, 1.0f, 1.0f, 1.0f}, clear_opaque_black[4] = {0.0f, 0.0f, 0.0f, 1.0f},
              clear_zero[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  dstrans::camera view = s.view;
  for (int n = 0; hooks ? hooks->before(n, view) : n < std::max(o.frames, 1); ++n) {
    current.clear();
    recorded.clear();
    whole.begin();
    if (hooks) {
      frame_block moved = camera_frame(view, s.ambient, o);
      moved.params.z = camera.params.z;
      glNamedBufferSubData(frame_ubo, 0, sizeof moved, &moved);
      if (particles) upload_quads(view);
    }
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glFrontFace(GL_CCW);

    // G-buffers: empty pixels are opaque black at the far plane. The second peeled layer reads the first's depth.
    for (int k = 0; k < layers; ++k)
      timed("gbuffer", [&] {
        gl::debug_group g(k ? "gbuffer pass, second layer" : "gbuffer pass");
        const gl::targets& gb = gbuffers[std::size_t(k)];
        gl::bind(gb);
        glDepthMask(GL_TRUE);  // clears obey the depth write mask, which the light passes turn off
        const std::vector<glm::vec4> clears = gbuffer_clears(o.layout);
        for (std::size_t t = 0; t < clears.size(); ++t) glClearNamedFramebufferfv(gb.framebuffer, GL_COLOR, GLint(t), &clears[t].x);
        glClearNamedFramebufferfv(gb.framebuffer, GL_DEPTH, 0, clear_far);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
        if (k) glBindTextureUnit(GLuint(binding(slot::peel_depth)), depth_of(gbuffers[0]));
        glUseProgram(gbuffer_progs[std::size_t(k)]);
        glBindVertexArray(scene_vao);
        glDrawElements(GL_TRIANGLES, GLsizei(m.hair_first), GL_UNSIGNED_INT, nullptr);
      });

    // Forward: the ambient pass fills colour, normal and depth; empty pixels are opaque black.
    if (forward)
      timed("ambient", [&] {
        gl::debug_group g("forward ambient pass");
        gl::bind(lit);
        glDepthMask(GL_TRUE);  // clears obey the depth write mask, which the light passes turn off
        glClearNamedFramebufferfv(lit.framebuffer, GL_COLOR, 0, clear_opaque_black);
        glClearNamedFramebufferfv(lit.framebuffer, GL_COLOR, 1, clear_zero);
        if (with_depth) glClearNamedFramebufferfv(lit.framebuffer, GL_COLOR, 2, clear_far);
        glClearNamedFramebufferfv(lit.framebuffer, GL_DEPTH, 0, clear_far);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        glDisable(GL_CULL_FACE);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
        glUseProgram(ambient_prog);
        glBindVertexArray(scene_vao);
        glDrawElements(GL_TRIANGLES, GLsizei(m.hair_first), GL_UNSIGNED_INT, nullptr);
      });

    // Lights, each shadowed spot light right after its own shadow pass (one shadow map serves them all),
    // into each layer's light buffer, or (forward) over all geometry again into the lit colour.
    for (const gl::targets& lb : light_buffers) glClearNamedFramebufferfv(lb.framebuffer, GL_COLOR, 0, clear_zero);
    if (baking) glClearNamedBufferData(volume_texels, GL_RGBA32F, GL_RGBA, GL_FLOAT, nullptr);
    if (bake_prog)
      timed("bake", [&] {
        gl::debug_group g("bake pass");
        bake(bake_prog, unshadowed_buffer);
      });
    std::size_t shadow_layer = 0;
    for (std::size_t i = 0; i < s.lights.size(); ++i) {
      const light& l = s.lights[i];
      const shadow_mode lookup = plan.lookups[i];
      const bool shadowed = lookup != shadow_mode::off;
      if (shadowed) {
        timed("shadow", [&] {
          gl::debug_group g("shadow pass, light " + std::to_string(i));
          gl::bind(shadow_map);
          glDepthMask(GL_TRUE);  // clears obey the depth write mask, which the light passes turn off
          glClearNamedFramebufferfv(shadow_map.framebuffer, GL_COLOR, 0, clear_far);
          if (mode == shadow_mode::transparent)
            glClearNamedFramebufferfv(shadow_map.framebuffer, GL_COLOR, 1, clear_far);
          glClearNamedFramebufferfv(shadow_map.framebuffer, GL_DEPTH, 0, clear_far);
          glDisable(GL_BLEND);
          glEnable(GL_DEPTH_TEST);
          glDepthMask(GL_TRUE);
          glDisable(GL_CULL_FACE);
          const frame_block lf = light_frame(s, light_data[i], o);
          glNamedBufferSubData(shadow_ubo, 0, sizeof lf, &lf);
          glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), shadow_ubo);
          glUseProgram(shadow_prog);
          glBindVertexArray(scene_vao);
          glDrawElements(GL_TRIANGLES, GLsizei(m.indices.size()), GL_UNSIGNED_INT, nullptr);
        });
        if (shadow_picture.framebuffer && shadow_layer == 0 && n == 0)  // once: the lights do not move
          glCopyImageSubData(shadow_map.textures[1], GL_TEXTURE_2D, 0, 0, 0, 0, shadow_picture.textures[0], GL_TEXTURE_2D, 0,
                             0, 0, 0, o.shadow_size, o.shadow_size, 1);
        if (baking)
          timed("bake", [&] {
            gl::debug_group g("bake pass, light " + std::to_string(i));
            bake(bake_shadowed_prog, shadowed_buffers[shadow_layer]);
          });
        if (particle_reference)
          timed("particles", [&] {
            for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
              glCopyImageSubData(shadow_map.textures[t], GL_TEXTURE_2D, 0, 0, 0, 0, shadow_layers[t], GL_TEXTURE_2D_ARRAY, 0,
                                 0, 0, GLint(shadow_layer), o.shadow_size, o.shadow_size, 1);
          });
        ++shadow_layer;
      }
      if (forward)
        timed("light", [&] {
          gl::debug_group g("forward light pass, light " + std::to_string(i));
          glBindFramebuffer(GL_FRAMEBUFFER, lit_colour_only);
          glViewport(0, 0, o.width, o.height);
          glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
          glEnable(GL_DEPTH_TEST);
          glDepthFunc(GL_LEQUAL);
          glDepthMask(GL_FALSE);
          glDisable(GL_CULL_FACE);
          glEnable(GL_BLEND);
          glBlendFunc(GL_ONE, GL_ONE);
          if (shadowed)
            for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
              glBindTextureUnit(GLuint(binding(slot::shadow_map)) + GLuint(t), shadow_map.textures[t]);
          glUseProgram(forward_light_progs[int(lookup)]);
          glBindVertexArray(scene_vao);
          glDrawElementsInstancedBaseInstance(GL_TRIANGLES, GLsizei(m.hair_first), GL_UNSIGNED_INT, nullptr, 1,
                                              GLuint(i));
        });
      for (int k = 0; k < layers; ++k)
        timed("light", [&] {
          gl::debug_group g("light pass, light " + std::to_string(i) + (k ? ", second layer" : ""));
          gl::bind(light_buffers[std::size_t(k)]);
          glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
          glDisable(GL_DEPTH_TEST);
          glDepthMask(GL_FALSE);
          glEnable(GL_BLEND);
          glBlendFunc(GL_ONE, GL_ONE);
          bind_gbuffer(binding(slot::gbuffer), gbuffers[std::size_t(k)]);
          if (shadowed)
            for (std::size_t t = 0; t < shadow_map.textures.size(); ++t)
              glBindTextureUnit(GLuint(binding(slot::shadow_map)) + GLuint(t), shadow_map.textures[t]);
          const volume v = volume_of(l, o);
          glUseProgram(light_progs[int(lookup)][v == volume::fullscreen ? 0 : 1]);
          if (v == volume::fullscreen) {
            glDisable(GL_CULL_FACE);
            glBindVertexArray(fullscreen_vao);
            glDrawArraysInstancedBaseInstance(GL_TRIANGLES, 0, 3, 1, GLuint(i));
          } else {
            // Back faces, depth clamped: each pixel the volume covers is lit once (dstrans/frame/plan.hpp, volume).
            glEnable(GL_CULL_FACE);
            glCullFace(GL_FRONT);
            glEnable(GL_DEPTH_CLAMP);
            const gl::mesh& mesh = r.meshes[v == volume::sphere ? 0 : 1];
            glBindVertexArray(mesh.vertex_array);
            glDrawElementsInstancedBaseInstance(GL_TRIANGLES, mesh.index_count, GL_UNSIGNED_INT, nullptr, 1, GLuint(i));
            glDisable(GL_DEPTH_CLAMP);
            glCullFace(GL_BACK);
          }
        });
    }

    if (baking)
      timed("bake", [&] {
        gl::debug_group g("bake pass, into the atlas");
        glMemoryBarrier(GL_PIXEL_BUFFER_BARRIER_BIT);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, volume_texels);
        glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
        glTextureSubImage3D(atlas_texture, 0, 0, 0, 0, atlas_size.x, atlas_size.y, atlas_size.z, GL_RGBA, GL_FLOAT, nullptr);
        glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
      });

    timed(forward ? "blend" : "compose", [&] {
      gl::debug_group g(forward ? "forward blend pass" : "compose pass");
      gl::bind(*final_target);
      glDisable(GL_BLEND);
      glDisable(GL_CULL_FACE);
      glDisable(GL_DEPTH_TEST);
      glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
      if (forward)
        for (std::size_t t = 0; t < lit.textures.size(); ++t) glBindTextureUnit(GLuint(binding(slot::forward_lit)) + GLuint(t), lit.textures[t]);
      else
        bind_gbuffer(binding(slot::gbuffer), gbuffers[0]);
      if (!forward) glBindTextureUnit(GLuint(binding(slot::light)), light_buffers[0].textures[0]);
      if (peeling) {
        bind_gbuffer(binding(slot::gbuffer2), gbuffers[1]);
        glBindTextureUnit(GLuint(binding(slot::light2)), light_buffers[1].textures[0]);
      }
      glUseProgram(compose_prog);
      gl::draw_fullscreen(fullscreen_vao);
    });
    if (many) {
      timed("capture", [&] {
        gl::debug_group g("capture pass");
        const GLuint empty = 0xffffffffu;
        glClearTexImage(heads, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, &empty);
        const glm::uvec4 header(0u, 0u, capacity, 0u);
        glNamedBufferSubData(nodes, 0, sizeof header, &header);
        gl::bind(tail);
        for (GLint t = 0; t < 2; ++t) glClearNamedFramebufferfv(tail.framebuffer, GL_COLOR, t, clear_zero);
        bind_layers();
        glBlendFunc(GL_ONE, GL_ONE);
        glUseProgram(capture_prog);
        glBindVertexArray(scene_vao);
        glDrawElements(GL_TRIANGLES, GLsizei(m.indices.size() - m.hair_first), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(m.hair_first * sizeof(std::uint32_t)));
      });
      timed("resolve", [&] {
        gl::debug_group g("resolve pass");
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
        gl::bind(*final_target);
        bind_layers();
        // The resolve writes the hair premultiplied, and in alpha what the frame behind keeps.
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
        for (GLuint t = 0; t < 2; ++t) glBindTextureUnit(GLuint(binding(slot::kbuffer_tail)) + t, tail.textures[t]);
        glUseProgram(resolve_prog);
        gl::draw_fullscreen(fullscreen_vao);
      });
    }
    if (particles)
      timed("particles", [&] {
        gl::debug_group g("particle pass");
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
        gl::bind(*final_target);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
        bind_gbuffer(binding(slot::gbuffer), gbuffers[0]);
        if (baking) glBindTextureUnit(GLuint(binding(slot::volume_atlas)), atlas_texture);
        for (GLuint t = 0; t < 2; ++t)
          if (shadow_layers[t]) glBindTextureUnit(GLuint(binding(slot::shadow_layers)) + t, shadow_layers[t]);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glEnable(GL_BLEND);
        // The particles write their colour premultiplied, and in alpha what the frame behind keeps.
        glBlendFuncSeparate(GL_ONE, GL_SRC_ALPHA, GL_ZERO, GL_ONE);
        glUseProgram(particle_prog);
        glBindVertexArray(particle_vao);
        glDrawArrays(GL_TRIANGLES, 0, GLsizei(particle_vertices));
      });
    for (std::size_t k = 0; k < post.passes.size(); ++k)
      timed("post " + post.passes[k].effect, [&] {
        const post_pass& pass = post.passes[k];
        gl::debug_group g("post " + pass.name);
        gl::bind(post_targets.at(pass.output));
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glDisable(GL_CULL_FACE);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::frame), frame_ubo);
        glBindBufferBase(GL_UNIFORM_BUFFER, binding(slot::post_params), post_blocks[k]);
        bind_gbuffer(binding(slot::gbuffer), gbuffers[0]);
        GLuint unit = binding(slot::post_input);
        for (const std::string& in : pass.inputs)
          if (in != "gbuffer") glBindTextureUnit(unit++, registry.at(in));
        glUseProgram(post_progs[k]);
        gl::draw_fullscreen(fullscreen_vao);
      });
    whole.end();
    for (std::size_t k = 0; k < recorded.size(); ++k) current[recorded[k]] += timers[k].milliseconds();
    totals.push_back(whole.milliseconds());
    frames.push_back(current);
    if (hooks) hooks->after(shown.framebuffer, current);
  }
  if (frames.empty()) return failure{"no frame was drawn"};
  summarize(frames, totals, out);
  out.schedule = recorded;

  const int w = o.width, h = o.height;
  if (!forward) {
    for (std::size_t t = 0; t < gbuffers[0].textures.size(); ++t) out.gbuffer.push_back(gl::read_texels(gbuffers[0], int(t)));
    out.light_buffer = gl::read_texels(light_buffers[0], 0);
  } else {
    for (std::size_t t = 0; t < lit.textures.size(); ++t) out.lit.push_back(gl::read_texels(lit, int(t)));
    out.buffers.push_back({"colour", to_image(gl::read_texels(lit, 0), lit.formats[0], w, h, view_as::rgb)});
    out.buffers.push_back({"normals", to_image(gl::read_texels(lit, 1), format::rgb10a2, w, h, view_as::rgb)});
    if (with_depth)
      out.buffers.push_back({"depth", to_image(gl::read_texels(lit, 2), format::r32f, w, h, view_as::depth,
                                               s.view.near_plane, s.view.far_plane)});
  }
  out.final_texels = gl::read_texels(shown, 0);
  if (many) {
    out.kbuffer_heads.resize(std::size_t(o.width) * std::size_t(o.height));
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // into client memory (the guard restores the engine's)
    glPixelStorei(GL_PACK_ALIGNMENT, 4);
    glGetTextureImage(heads, 0, GL_RED_INTEGER, GL_UNSIGNED_INT, GLsizei(out.kbuffer_heads.size() * 4), out.kbuffer_heads.data());
    std::vector<glm::uvec4> pool(std::size_t(capacity) + 1u);
    glGetNamedBufferSubData(nodes, 0, GLsizeiptr(pool.size() * sizeof(glm::uvec4)), pool.data());
    out.kbuffer_overflow = pool[0].y;
    pool.resize(std::size_t(std::min(pool[0].x, capacity)) + 1u);
    out.kbuffer_nodes.assign(pool.begin() + 1, pool.end());
  }
  if (baking) {
    out.volume_texels.resize(atlas_texels);
    glGetNamedBufferSubData(volume_texels, 0, GLsizeiptr(atlas_texels * sizeof(glm::vec4)), out.volume_texels.data());
  }
  const format final_format = final_target_desc(o.float_targets).fmt, light_format = light_targets(o.float_targets)[0].fmt;
  out.final_image = to_image(out.final_texels, final_format, w, h, view_as::rgb);
  for (int k = 0; k < layers; ++k) {
    const std::string suffix = k ? "_2" : "";
    const gl::targets &gb = gbuffers[std::size_t(k)], &lb = light_buffers[std::size_t(k)];
    out.buffers.push_back({"diffuse" + suffix, to_image(gl::read_texels(gb, 0), format::rgba8, w, h, view_as::rgb)});
    if (o.layout == gbuffer_layout::thesis) {  // the compact layout's normals are octahedral, its depth an attachment
      out.buffers.push_back({"normals" + suffix, to_image(gl::read_texels(gb, 1), format::rgb10a2, w, h, view_as::rgb)});
      out.buffers.push_back({"depth" + suffix, to_image(gl::read_texels(gb, 3), format::r32f, w, h, view_as::depth,
                                                        s.view.near_plane, s.view.far_plane)});
    }
    out.buffers.push_back({"light" + suffix, to_image(gl::read_texels(lb, 0), light_format, w, h, view_as::rgb)});
    out.buffers.push_back({"specular" + suffix, to_image(gl::read_texels(lb, 0), light_format, w, h, view_as::alpha)});
  }
  if (shadow_picture.framebuffer)
    out.buffers.push_back({"shadow_colour", to_image(gl::read_texels(shadow_picture, 0), format::rgba8, o.shadow_size,
                                                     o.shadow_size, view_as::rgb)});
  if (!post.passes.empty()) {
    out.buffers.push_back({"composed", to_image(gl::read_texels(*final_target, 0), final_format, w, h, view_as::rgb)});
    for (const std::string& effect : post.effects)
      out.buffers.push_back({"post_" + effect, to_image(gl::read_texels(post_targets.at(effect), 0), final_format, w, h, view_as::rgb)});
  }
  return out;
}

}  // namespace dstrans::render
