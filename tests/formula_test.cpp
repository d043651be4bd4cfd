// The formula registry: complete, typed from the one text, evaluable on the CPU, and compilable as GPU
// kernels for GL and Vulkan (glslang; no GPU needed).
#include <catch2/catch.hpp>

#include <set>
#include <sstream>

#include <dstrans/dstrans.hpp>
#include <dstrans_spirv.hpp>

#include "agreement.hpp"

using namespace dstrans;

TEST_CASE("every function of every shared block is reachable by name", "[formula]") {
  std::set<std::string> registered;
  for (const formula& f : formulas()) registered.insert(f.name);
  std::size_t functions = 0;
  for (const shared_text* block : detail::shared_blocks()) {
    if (std::string(block->file).find("include/dstrans/") == std::string::npos) continue;  // tests' own blocks
    for (const std::string& name : glsl::definitions(block->code)) {
      if (std::string(block->code).find("struct " + name) != std::string::npos) continue;  // a record, not a function
      ++functions;
      INFO(block->file << ":" << block->line << " defines " << name);
      CHECK(registered.count(name) == 1);
    }
  }
  CHECK(functions == formulas().size());
  CHECK(find_formula("dst_rows_keep") != nullptr);
  CHECK(find_formula("no_such_formula") == nullptr);
}

TEST_CASE("a shared block brings the blocks it uses, once, before itself", "[formula][glsl]") {
  CHECK(glsl::definitions(text::dst_surface.code) == std::vector<std::string>{"dst_surface", "dst_surface_zero"});
  glsl::source src;
  src.add_shared(text::dst_compose);
  src.add_shared(text::dst_phong);
  CHECK(src.has(text::dst_surface));
  CHECK(src.has(text::dst_light_sample));
  CHECK_FALSE(src.has(text::dst_interlace_rows));
  const std::string code = src.str();
  CHECK(code.find("struct dst_light_sample") < code.find("vec3 dst_shade("));
  CHECK(code.find("struct dst_light_sample") == code.rfind("struct dst_light_sample"));
}

TEST_CASE("each shared block is formatted once, as format_shared and definitions give it", "[formula][glsl]") {
  for (const shared_text* block : detail::shared_blocks()) {
    INFO(block->file << ":" << block->line);
    const detail::formatted_block& once = detail::formatted(*block);
    CHECK(once.text == glsl::format_shared(block->code));
    CHECK(once.names == glsl::definitions(block->code));
    CHECK(&detail::formatted(*block) == &once);
  }
}

TEST_CASE("argument names and types come from the shared text and the C++ signature", "[formula]") {
  const formula* f = find_formula("dst_rows_partner");
  REQUIRE(f);
  REQUIRE(f->args.size() == 2);
  CHECK(f->args[0].first == "p");
  CHECK(f->args[0].second.name() == "ivec2");
  CHECK(f->args[1].first == "size");
  CHECK(f->result.name() == "ivec2");
  CHECK(f->block == &text::dst_interlace_rows);
  const formula* z = find_formula("dst_surface_zero");
  REQUIRE(z);
  CHECK(z->args.empty());
  CHECK(z->result.kind == value_kind::record);
  CHECK(z->result.word_count() == 10);
  CHECK(z->result.fields[2].first == "normal");
  CHECK(detail::parameter_names("DST_FN float g(float f) { return f; } DST_FN float f(DST_OUT(vec3) o, int k) {", "f") ==
        std::vector<std::string>{"o", "k"});
}

TEST_CASE("values pack into words and back", "[formula]") {
  surface s = shader::dst_surface_zero();
  s.diffuse = {0.25f, 0.5f, 1.0f};
  s.depth = 0.75f;
  words w;
  put(s, w);
  put(glm::ivec2(-3, 7), w);
  put(true, w);
  put(4000000000u, w);
  REQUIRE(w.size() == 10 + 2 + 1 + 1);
  const std::uint32_t* p = w.data();
  const surface back = value_traits<surface>::get(p);
  CHECK(back.diffuse == s.diffuse);
  CHECK(back.depth == 0.75f);
  CHECK(value_traits<glm::ivec2>::get(p) == glm::ivec2(-3, 7));
  CHECK(value_traits<bool>::get(p));
  CHECK(value_traits<unsigned>::get(p) == 4000000000u);
}

TEST_CASE("formulas evaluate on the CPU, one call or a batch", "[formula]") {
  const formula* f = find_formula("dst_rows_partner");
  words in;
  put(glm::ivec2(3, 0), in);
  put(glm::ivec2(8, 8), in);
  put(glm::ivec2(3, 5), in);
  put(glm::ivec2(8, 8), in);
  const words one = f->cpu(words(in.begin(), in.begin() + 4));
  CHECK(one == words{3u, 1u});
  CHECK(run_cpu(*f, in, 2) == words{3u, 1u, 3u, 4u});
}

TEST_CASE("every formula's kernel compiles for GL and Vulkan and binds two storage buffers", "[formula][spirv]") {
  for (const formula& f : formulas())
    for (spirv::api a : {spirv::api::opengl, spirv::api::vulkan}) {
      glsl::source src;
      glsl::add_formula_kernel(src, f);
      INFO(f.name << "\n" << src.str());
      const auto words = spirv::compile(src, spirv::stage::compute, a);
      REQUIRE(words);
      const auto refl = spirv::reflect(*words);
      REQUIRE(refl);
      REQUIRE(refl->storage_buffers.size() == 2);
      CHECK(refl->storage_buffers[0].binding == 0);
      CHECK(refl->storage_buffers[1].binding == 1);
    }
}

TEST_CASE("the full-screen triangle covers clip space", "[fullscreen]") {
  CHECK(shader::dst_fullscreen_position(0) == glm::vec2(-1, -1));
  CHECK(shader::dst_fullscreen_position(1) == glm::vec2(3, -1));
  CHECK(shader::dst_fullscreen_position(2) == glm::vec2(-1, 3));
  CHECK(shader::dst_pixel_ndc({0, 0}, {4, 2}) == glm::vec2(-0.75f, 0.5f));  // top left
  CHECK(shader::dst_pixel_ndc({3, 1}, {4, 2}) == glm::vec2(0.75f, -0.5f));  // bottom right
  CHECK(shader::dst_pixel_ndc({0, 0}, {0, 0}) == glm::vec2(0.0f, 0.0f));    // a size below 1 counts as 1
  // Back to the window: every pixel's centre, and the image's corners.
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 5; ++x) {
      const glm::vec2 w = shader::dst_ndc_window(shader::dst_pixel_ndc({x, y}, {5, 3}), {5, 3});
      CHECK(w.x == Approx(x + 0.5f).epsilon(1e-6));
      CHECK(w.y == Approx(y + 0.5f).epsilon(1e-6));
    }
  CHECK(shader::dst_ndc_window({-1.0f, 1.0f}, {5, 3}) == glm::vec2(0.0f, 0.0f));
  CHECK(shader::dst_ndc_window({1.0f, -1.0f}, {5, 3}) == glm::vec2(5.0f, 3.0f));
  for (spirv::api a : {spirv::api::opengl, spirv::api::vulkan}) {
    glsl::source vs = glsl::fullscreen_vertex_shader();
    if (a == spirv::api::vulkan) CHECK(vs.str().find("gl_VertexIndex") != std::string::npos);
    CHECK(spirv::compile(vs, spirv::stage::vertex, a));
  }
}

namespace {
// Every edge of a closed mesh is shared by exactly two triangles, once in each direction.
bool closed(const mesh_data& m) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, int> edges;
  for (std::size_t i = 0; i < m.indices.size(); i += 3)
    for (int k = 0; k < 3; ++k) ++edges[{m.indices[i + std::size_t(k)], m.indices[i + std::size_t((k + 1) % 3)]}];
  for (const auto& [e, n] : edges)
    if (n != 1 || !edges.count({e.second, e.first})) return false;
  return true;
}
}  // namespace

TEST_CASE("light meshes are closed, wound outwards, and enclose their unit shape", "[light_mesh]") {
  for (int level = 0; level <= 3; ++level) {
    const mesh_data m = sphere_mesh(level);
    CHECK(m.indices.size() == 60u << (2 * level));
    CHECK(closed(m));
    for (std::size_t i = 0; i < m.indices.size(); i += 3) {
      const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
      const float plane = glm::dot(glm::normalize(glm::cross(b - a, c - a)), a);
      CHECK(plane >= 1.0f - 1e-5f);  // outward and outside the unit sphere
    }
  }
  for (int segments : {3, 8, 16}) {
    const mesh_data m = cone_mesh(segments);
    CHECK(closed(m));
    // Every direction inside the unit cone (apex 0, radius 1 at z = 1) is inside every side face.
    for (std::size_t i = 0; i < m.indices.size(); i += 3) {
      const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]], c = m.positions[m.indices[i + 2]];
      const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
      for (int k = 0; k < 64; ++k) {
        const float t = 6.2831853f * float(k) / 64.0f;
        CHECK(glm::dot(n, glm::vec3(std::cos(t), std::sin(t), 1.0f) - a) <= 1e-5f);
      }
    }
  }
}

TEST_CASE("every formula's result is finite and within its physical range for 100,000 inputs (CPU)", "[formula][property]") {
  testing::check_every_property([](const formula& f, const words& a, std::size_t n) -> result<words> { return run_cpu(f, a, n); });
}

TEST_CASE("GPU runners' batches split at the device's limits and come back whole, in order", "[formula]") {
  const formula* f = find_formula("dst_light_reach");
  REQUIRE(f);
  const std::size_t words_per_call = argument_words(*f);
  CHECK(words_per_call > 4);
  // The group limit, then the buffer limit (one word of the buffer is the call count), then nothing.
  CHECK(glsl::calls_per_dispatch(*f, 10, std::size_t(1) << 30) == 640);
  CHECK(glsl::calls_per_dispatch(*f, 1000, 4 * (1 + 3 * words_per_call)) == 3);
  CHECK(glsl::calls_per_dispatch(*f, 1000, 4) == 0);
  const std::size_t calls = 1000;
  const words args = testing::random_args(*f, calls, 3u);
  std::vector<std::size_t> sizes;
  const auto split = glsl::run_in_dispatches(*f, args, calls, 4, std::size_t(1) << 30, [&](const words& part, std::size_t n) {
    sizes.push_back(n);
    return result<words>(run_cpu(*f, part, n));
  });
  REQUIRE(split);
  CHECK(*split == run_cpu(*f, args, calls));
  CHECK(sizes == std::vector<std::size_t>{256, 256, 256, 232});
  const auto none = glsl::run_in_dispatches(*f, args, calls, 4, 4, [&](const words&, std::size_t) { return result<words>(words{}); });
  CHECK_FALSE(none);
}
