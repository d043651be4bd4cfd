// The GL frame executor (dstrans_gl_frame.hpp) as an engine runs it: one renderer for many frames and
// sizes, the engine's own vertex arrays in the geometry passes, and nothing made for an absent effect.
#include <catch2/catch.hpp>

#include <cstddef>
#include <string>
#include <vector>

#include <dstrans_gl_context.hpp>
#include <dstrans_gl_frame.hpp>
#include "frame_scenes.hpp"

using namespace dstrans;

namespace {

using frame_tests::example;
using frame_tests::sized;

std::unique_ptr<gl::renderer> make(const scene& s, const render::options& o) {
  auto r = gl::renderer::create(s, o, pass_shaders());  // the shaders live only as long as the call
  INFO(r.error());
  REQUIRE(r);
  return std::move(*r);
}

std::vector<texel> shown(const gl::renderer& r) { return gl::read_texels(r.output(), 0); }

// The scene's meshes as an engine might keep them: one interleaved vertex buffer per object, drawn one
// object at a time, hair objects apart.
struct engine_meshes {
  struct vertex {
    glm::vec3 position;
    std::uint32_t material;
    glm::vec3 normal;
  };
  struct object_mesh {
    GLuint vao = 0, buffers[2] = {0, 0};
    GLsizei count = 0;
    bool hair = false;
  };
  std::vector<object_mesh> objects;
  explicit engine_meshes(const scene& s) {
    for (std::size_t k = 0; k < s.objects.size(); ++k) {
      scene one = s;
      one.objects = {s.objects[k]};
      const scene_mesh m = flatten(one);  // this object in world space
      std::vector<vertex> v;
      for (std::size_t i = 0; i < m.positions.size(); ++i) v.push_back({m.positions[i], m.materials[i], m.normals[i]});
      object_mesh o;
      o.hair = m.hair_first == 0 && !m.indices.empty();
      o.count = GLsizei(m.indices.size());
      glCreateBuffers(2, o.buffers);
      glNamedBufferStorage(o.buffers[0], GLsizeiptr(std::max<std::size_t>(v.size(), 1) * sizeof(vertex)), v.data(), 0);
      glNamedBufferStorage(o.buffers[1], GLsizeiptr(std::max<std::size_t>(m.indices.size(), 1) * 4), m.indices.data(), 0);
      glCreateVertexArrays(1, &o.vao);
      glVertexArrayVertexBuffer(o.vao, 0, o.buffers[0], 0, sizeof(vertex));
      glVertexArrayElementBuffer(o.vao, o.buffers[1]);
      for (GLuint a = 0; a < 3; ++a) {
        glEnableVertexArrayAttrib(o.vao, a);
        glVertexArrayAttribBinding(o.vao, a, 0);
      }
      glVertexArrayAttribFormat(o.vao, 0, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(vertex, position)));
      glVertexArrayAttribFormat(o.vao, 1, 3, GL_FLOAT, GL_FALSE, GLuint(offsetof(vertex, normal)));
      glVertexArrayAttribIFormat(o.vao, 2, 1, GL_UNSIGNED_INT, GLuint(offsetof(vertex, material)));
      objects.push_back(o);
    }
  }
  ~engine_meshes() {
    for (object_mesh& o : objects) {
      glDeleteVertexArrays(1, &o.vao);
      glDeleteBuffers(2, o.buffers);
    }
  }
  // Surfaces before hair, as flatten orders them: the same fragments in the same order.
  void draw(const scheduled_pass& pass) const {
    for (const bool hair : {false, true}) {
      if ((hair && pass.draws == geometry_set::surfaces) || (!hair && pass.draws == geometry_set::hair)) continue;
      for (const object_mesh& o : objects)
        if (o.hair == hair) {
          glBindVertexArray(o.vao);
          glDrawElements(GL_TRIANGLES, o.count, GL_UNSIGNED_INT, nullptr);
        }
    }
  }
};

}  // namespace

TEST_CASE("GL renderer: one renderer draws many frames and sizes, each as a new renderer would", "[render][renderer][gl]") {
  auto ctx = gl::headless_context::create();
  if (!ctx) {
    WARN("skipped GL: " << ctx.error());
    return;
  }
  for (const char* file : {"glass_room.json", "hair.json", "smoke.json"}) {
    INFO(file);
    const scene s = example(file);
    const gl::scene_geometry meshes(s);
    auto draw = [&](const scheduled_pass& pass) { meshes(pass); };
    auto r = make(s, sized(64, 36));
    r->render(s.view, draw);
    const std::vector<texel> first = shown(*r);
    r->render(s.view, draw);
    CHECK(shown(*r) == first);
    const frame_times t = r->times();
    CHECK(t.schedule.size() == r->schedule().passes.size());
    CHECK(t.frame_ms > 0.0);

    REQUIRE(r->resize(80, 45));
    CHECK(r->options().width == 80);
    r->render(s.view, draw);
    auto fresh = make(s, sized(80, 45));
    fresh->render(s.view, draw);
    CHECK(shown(*r) == shown(*fresh));
    REQUIRE(r->resize(64, 36));
    r->render(s.view, draw);
    CHECK(shown(*r) == first);
    CHECK(!r->resize(0, 36));
  }
  for (const auto& m : (*ctx)->debug_messages()) UNSCOPED_INFO(m);
  CHECK((*ctx)->debug_messages().empty());
}

TEST_CASE("GL renderer: the engine's own vertex arrays draw the frame scene_geometry draws", "[render][renderer][gl]") {
  auto ctx = gl::headless_context::create();
  if (!ctx) {
    WARN("skipped GL: " << ctx.error());
    return;
  }
  struct frame_case {
    const char* scene;
    render::technique method;
  };
  for (const frame_case& c : {frame_case{"glass_room.json", render::technique::interlaced}, frame_case{"hair.json", render::technique::interlaced},
                              frame_case{"glass_room.json", render::technique::forward}, frame_case{"glass_room.json", render::technique::peeling},
                              frame_case{"glass_room_lamp.json", render::technique::interlaced}}) {
    INFO(c.scene << ", " << render::technique_name(c.method));
    const scene s = example(c.scene);
    render::options o = sized(64, 36);
    o.method = c.method;
    auto r = make(s, o);
    // scene_geometry culls each pass's objects against its clip volume, the engine here draws them all:
    // the same picture (a point light's cube faces each see a part of the room).
    const gl::scene_geometry meshes(s);
    r->render(s.view, [&](const scheduled_pass& pass) { meshes(pass); });
    const std::vector<texel> reference = shown(*r);
    const engine_meshes engine(s);
    std::vector<std::string> asked;
    r->render(s.view, [&](const scheduled_pass& pass) {
      asked.push_back(pass.label);
      CHECK(pass.kind == pass_kind::geometry);
      CHECK(pass.draws != geometry_set::none);
      engine.draw(pass);
    });
    CHECK(shown(*r) == reference);
    std::vector<std::string> geometry;
    for (const scheduled_pass& pass : r->schedule().passes)
      if (pass.draws != geometry_set::none) geometry.push_back(pass.label);
    CHECK(asked == geometry);
  }
}

TEST_CASE("GL renderer: no target or program for an effect the scene does not use", "[render][renderer][gl]") {
  auto ctx = gl::headless_context::create();
  if (!ctx) {
    WARN("skipped GL: " << ctx.error());
    return;
  }
  const render::options o = sized(64, 36);
  const auto pane = make(example("pane.json"), o);
  CHECK(pane->targets().kbuffer_heads == 0);
  CHECK(pane->targets().volume_atlas == 0);
  CHECK(pane->targets().lit.framebuffer == 0);
  CHECK(pane->targets().gbuffers.size() == 1);
  CHECK(pane->targets().post.empty());
  CHECK(pane->targets().output == &pane->targets().composed);
  const auto hair = make(example("hair.json"), o);
  CHECK(hair->targets().kbuffer_heads != 0);
  CHECK(hair->targets().volume_atlas == 0);
  const auto smoke = make(example("smoke.json"), o);
  CHECK(smoke->targets().kbuffer_heads == 0);
  CHECK(smoke->targets().volume_atlas != 0);
  render::options forward = o;
  forward.method = render::technique::forward;
  const auto lit = make(example("glass_room.json"), forward);
  CHECK(lit->targets().gbuffers.empty());
  CHECK(lit->targets().lit.framebuffer != 0);
}

TEST_CASE("GL renderer: temporal interlacing leaves nothing where a pane moved away", "[render][renderer][gl][temporal]") {
  auto ctx = gl::headless_context::create();
  if (!ctx) {
    WARN("skipped GL: " << ctx.error());
    return;
  }
  const frame_tests::moved_pane m = frame_tests::moved_pane_scenes();
  render::options o = sized(160, 90);
  o.temporal = true;
  const gl::scene_geometry before(m.before), after(m.after), without(m.without);
  // Every renderer describes the scene after the move, so that all draw the same shadows.
  auto first = [&](const gl::scene_geometry& g) {
    auto r = make(m.after, o);
    r->render(m.after.view, [&](const scheduled_pass& pass) { g(pass); });
    return shown(*r);
  };
  auto r = make(m.after, o);
  r->render(m.after.view, [&](const scheduled_pass& pass) { before(pass); });
  r->render(m.after.view, [&](const scheduled_pass& pass) { after(pass); });
  frame_tests::check_nothing_left(shown(*r), first(after), first(before), first(without), 160, 90);
  for (const auto& msg : (*ctx)->debug_messages()) UNSCOPED_INFO(msg);
  CHECK((*ctx)->debug_messages().empty());
}
