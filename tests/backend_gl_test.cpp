// The OpenGL backend on a real driver (Mesa llvmpipe through EGL): formulas agree with the CPU, G-buffers
// hold exactly the CPU's bytes, and bad input gives sentences. Skips with a message without an EGL device;
// KHR_debug errors and warnings fail every test.
#include <catch2/catch.hpp>

#include <dstrans_gl.hpp>
#include <dstrans_gl_context.hpp>

#include "backend_checks.hpp"

using namespace dstrans;

namespace {

// The context for one test case; null (and a message) where this machine has no EGL device.
std::unique_ptr<gl::headless_context> context() {
  auto ctx = gl::headless_context::create();
  if (!ctx) {
    WARN("skipped: no OpenGL 4.5 through EGL here: " << ctx.error());
    return nullptr;
  }
  return std::move(*ctx);
}

void check_quiet(gl::headless_context& ctx) {
  const auto messages = ctx.debug_messages();
  for (const auto& m : messages) UNSCOPED_INFO(m);
  CHECK(messages.empty());
}

template <class L>
void check_gbuffer_write(gl::headless_context& ctx, int width, int height, bool exact) {
  const auto raw = testing::test_surfaces(width, height);
  const auto surfaces = exact ? testing::on_grid<L>(raw) : raw;
  auto targets = gl::make_targets(describe<L>(), width, height, "test gbuffer", false);
  REQUIRE(targets);
  auto program = gl::make_program(glsl::fullscreen_vertex_shader(), testing::gbuffer_writer<L>(width), "test gbuffer write");
  REQUIRE(program);
  words packed;
  for (const surface& s : surfaces) put(s, packed);
  GLuint buffer = 0, vao = 0;
  glCreateBuffers(1, &buffer);
  glNamedBufferStorage(buffer, GLsizeiptr(packed.size() * 4), packed.data(), 0);
  glCreateVertexArrays(1, &vao);
  {
    gl::state_guard keep;
    gl::bind(*targets);
    glUseProgram(*program);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, buffer);
    gl::draw_fullscreen(vao);
  }
  testing::check_texels<L>(surfaces, exact, [&](int t) { return gl::read_texels(*targets, t); });
  glDeleteVertexArrays(1, &vao);
  glDeleteBuffers(1, &buffer);
  glDeleteProgram(*program);
  gl::destroy(*targets);
  check_quiet(ctx);
}

}  // namespace

TEST_CASE("GL: every formula agrees with the CPU on 10,000 inputs", "[gl][formula]") {
  auto ctx = context();
  if (!ctx) return;
  INFO(ctx->renderer());
  gl::formula_runner runner;
  testing::check_every_formula([&](const formula& f, const words& a, std::size_t n) { return runner.run(f, a, n); });
  check_quiet(*ctx);
}

TEST_CASE("GL: a batch past the dispatch limit runs in several dispatches, every result right", "[gl][formula]") {
  auto ctx = context();
  if (!ctx) return;
  gl::formula_runner runner;
  testing::check_large_batch([&](const formula& f, const words& a, std::size_t n) { return runner.run(f, a, n); });
  check_quiet(*ctx);
}

TEST_CASE("GL: every formula's result is finite and within its physical range for 100,000 inputs", "[gl][property]") {
  auto ctx = context();
  if (!ctx) return;
  gl::formula_runner runner;
  testing::check_every_property([&](const formula& f, const words& a, std::size_t n) { return runner.run(f, a, n); });
  check_quiet(*ctx);
}

TEST_CASE("GL: a G-buffer written by a shader holds the CPU's bytes (on the grid) or permitted ones", "[gl][layout]") {
  auto ctx = context();
  if (!ctx) return;
  for (bool exact : {true, false}) {
    check_gbuffer_write<thesis_gbuffer>(*ctx, 37, 23, exact);
    check_gbuffer_write<testing::float_layout>(*ctx, 37, 23, exact);
    check_gbuffer_write<thesis_shadow_map>(*ctx, 16, 9, exact);
    check_gbuffer_write<compact_gbuffer>(*ctx, 37, 23, exact);
  }
}

TEST_CASE("GL: clear errors for layouts the device cannot hold and shaders that do not compile", "[gl]") {
  auto ctx = context();
  if (!ctx) return;
  std::vector<target_desc> nine(9, target_desc{format::r8, {"unused"}});
  auto too_many = gl::make_targets(nine, 8, 8, "wide", false);
  REQUIRE_FALSE(too_many);
  CHECK_THAT(too_many.error(), Catch::Contains("9 render targets") && Catch::Contains("at most 8"));
  auto empty = gl::make_targets(describe<thesis_gbuffer>(), 0, 8, "empty", false);
  REQUIRE_FALSE(empty);
  CHECK_THAT(empty.error(), Catch::Contains("0x8 is not a size"));

  glsl::source fs;
  fs.add("layout(location = 0) out vec4 o;\nvoid main() {\n  o = vec4(missing_value);\n}\n", "broken.frag", 10);
  auto program = gl::make_program(glsl::fullscreen_vertex_shader(), fs, "broken");
  REQUIRE_FALSE(program);
  CHECK_THAT(program.error(), Catch::Contains("broken.frag:12:") && Catch::Contains("missing_value"));
  ctx->debug_messages();  // the driver may report the failed compile itself

  texture_array wide;  // past the context's array layers: refused before anything is made
  wide.width = wide.height = 1;
  wide.layers = 1 << 20;
  wide.levels = {std::vector<std::uint8_t>(4)};
  auto past = gl::make_texture_array(wide, "wide textures");
  REQUIRE_FALSE(past);
  CHECK_THAT(past.error(), Catch::StartsWith("wide textures: 1048576 layers of 1 x 1") && Catch::Contains("exceed the context's array textures"));
}

TEST_CASE("GL: targets, meshes, timers and labels work and state_guard restores the engine's state", "[gl]") {
  auto ctx = context();
  if (!ctx) return;
  auto targets = gl::make_targets(describe<thesis_light_buffer>(), 32, 32, "mesh test", true);
  REQUIRE(targets);
  glsl::source vs, fs;
  vs.add("layout(location = 0) in vec3 position;\nvoid main() { gl_Position = vec4(position * 0.5f, 1.0f); }\n", __FILE__, __LINE__);
  fs.add("layout(location = 0) out vec4 o;\nvoid main() { o = vec4(1.0f); }\n", __FILE__, __LINE__);
  auto program = gl::make_program(vs, fs, "mesh test");
  REQUIRE(program);
  gl::mesh sphere = gl::make_mesh(sphere_mesh(1), "sphere");
  CHECK(sphere.index_count == 240);

  // The engine's state before dstrans runs.
  GLuint engine_vao = 0;
  glCreateVertexArrays(1, &engine_vao);
  glBindVertexArray(engine_vao);
  glViewport(1, 2, 3, 4);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 7);
  scene textured;  // a texture array uploads with the unpack state it needs, which the guard restores
  textured.textures.push_back({3, 2, std::vector<std::uint8_t>(24)});
  for (std::size_t i = 0; i < textured.textures[0].rgba.size(); ++i) textured.textures[0].rgba[i] = std::uint8_t(i * 10);
  const texture_array a = texture_array_of(textured);
  double ms = -1.0;
  GLuint array = 0;
  {
    gl::state_guard keep;
    auto made = gl::make_texture_array(a, "texture array test");
    REQUIRE(made);
    array = *made;
    gl::debug_group group("dstrans test pass");
    gl::bind(*targets);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glClearColor(0, 0, 0, 0);
    glClearDepth(1.0);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glUseProgram(*program);
    gl::timer t;
    t.begin();
    gl::draw(sphere);
    t.end();
    ms = t.milliseconds();
  }
  CHECK(ms >= 0.0);
  GLint vao = 0, viewport[4], src = 0, origin = 0, program_now = 0;
  GLboolean mask = GL_TRUE;
  glGetIntegerv(GL_VERTEX_ARRAY_BINDING, &vao);
  glGetIntegerv(GL_VIEWPORT, viewport);
  glGetIntegerv(GL_BLEND_SRC_RGB, &src);
  glGetIntegerv(GL_CLIP_ORIGIN, &origin);
  glGetIntegerv(GL_CURRENT_PROGRAM, &program_now);
  glGetBooleanv(GL_DEPTH_WRITEMASK, &mask);
  CHECK(GLuint(vao) == engine_vao);
  CHECK(viewport[2] == 3);
  CHECK(glIsEnabled(GL_BLEND));
  CHECK(src == GL_SRC_ALPHA);
  CHECK_FALSE(glIsEnabled(GL_DEPTH_TEST));
  CHECK(mask == GL_FALSE);
  CHECK(origin == GL_LOWER_LEFT);
  CHECK(program_now == 0);
  GLint row_length = 0;
  glGetIntegerv(GL_UNPACK_ROW_LENGTH, &row_length);
  CHECK(row_length == 7);
  std::vector<std::uint8_t> level0(a.levels[0].size()), level1(a.levels[1].size());
  glGetTextureImage(array, 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(level0.size()), level0.data());
  glGetTextureImage(array, 1, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(level1.size()), level1.data());
  CHECK(level0 == a.levels[0]);
  CHECK(level1 == a.levels[1]);
  glDeleteTextures(1, &array);
  glPixelStorei(GL_UNPACK_ROW_LENGTH, 0);

  // The sphere, at half scale, covers the centre and leaves the corners.
  const auto texels = gl::read_texels(*targets, 0);
  CHECK(texels[16 * 32 + 16][0] == 255);
  CHECK(texels[0][0] == 0);
  gl::destroy(sphere);
  gl::destroy(*targets);
  glDeleteProgram(*program);
  glDeleteVertexArrays(1, &engine_vao);
  check_quiet(*ctx);
}

TEST_CASE("GL: clip-space +y is the image's top row and counter-clockwise triangles face the viewer", "[gl]") {
  auto ctx = context();
  if (!ctx) return;
  auto t = gl::make_targets({target_desc{format::rgba8, {"r", "g", "b", "a"}}}, 8, 8, "facing", false);
  REQUIRE(t);
  glsl::source vs, fs;
  vs.add(testing::facing_vertex_shader, __FILE__, __LINE__);
  fs.add(testing::facing_fragment_shader, __FILE__, __LINE__);
  auto program = gl::make_program(vs, fs, "facing");
  REQUIRE(program);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  {
    gl::state_guard keep;
    gl::bind(*t);
    glEnable(GL_CULL_FACE);
    glCullFace(GL_BACK);
    glFrontFace(GL_CCW);
    glUseProgram(*program);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }
  testing::check_facing(gl::read_texels(*t, 0), 8);
  glDeleteVertexArrays(1, &vao);
  glDeleteProgram(*program);
  gl::destroy(*t);
  check_quiet(*ctx);
}

TEST_CASE("GL: EGL's devices are listed, and a context is made on one by index or by name", "[gl][device]") {
  const auto devices = gl::headless_context::devices();
  REQUIRE(devices);
  if (devices->empty()) {
    WARN("skipped: this EGL has no EGL_EXT_device_enumeration");
    return;
  }
  CHECK(devices->front().rfind("0: ", 0) == 0);
  auto by_index = gl::headless_context::create("0");
  REQUIRE(by_index);
  const std::string renderer = (*by_index)->renderer(), version = (*by_index)->version();
  CHECK(devices->front() == "0: " + renderer + ", " + version);
  CHECK(version.find("4.5") == 0);
  by_index->reset();  // one context at a time
  auto by_name = gl::headless_context::create(renderer.substr(0, 4));
  REQUIRE(by_name);
  CHECK((*by_name)->renderer() == renderer);
  by_name->reset();
  const auto none = gl::headless_context::create("no such device");
  REQUIRE_FALSE(none);
  CHECK(none.error().find("no EGL device named 'no such device'; the devices are:\n  0: " + renderer) == 0);
  const auto out_of_range = gl::headless_context::create(std::to_string(devices->size()));
  REQUIRE_FALSE(out_of_range);
  CHECK(out_of_range.error().find("no EGL device number '" + std::to_string(devices->size()) + "'") == 0);
}
