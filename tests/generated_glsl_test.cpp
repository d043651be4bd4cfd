// Every generated snippet compiles with glslang for OpenGL 4.5 and Vulkan, and SPIRV-Cross reflection of
// the result agrees with the template it came from (output locations and widths, sampler bindings).
#include <catch2/catch.hpp>

#include <dstrans/dstrans.hpp>
#include <dstrans_spirv.hpp>

using namespace dstrans;

namespace {

using float_layout = layout<surface, target<format::rgba16f, field::normal, field::alpha>,
                            target<format::r32f, field::depth>,
                            target<format::rg16f, field::spec_intensity, field::spec_power>>;

const spirv::api apis[] = {spirv::api::opengl, spirv::api::vulkan};
const char* api_name(spirv::api a) { return a == spirv::api::opengl ? "OpenGL 4.5" : "Vulkan"; }

template <class L>
void check_layout(const std::string& name, const std::string& record) {
  for (spirv::api a : apis)
    for (glsl::side sd : {glsl::side::write, glsl::side::read, glsl::side::both}) {
      glsl::layout_options opt;
      opt.sides = sd;
      opt.first_location = 1;
      opt.first_binding = 3;
      glsl::source src;
      glsl::add_layout<L>(src, name, opt);
      const std::string fn = "dst_" + name;
      std::string body = "ivec2 p = ivec2(gl_FragCoord.xy);\n";
      if (sd == glsl::side::write) body += "  " + fn + "_write(" + record + "_zero());\n";
      if (sd == glsl::side::read) body += "  if (" + fn + "_read(p) == " + record + "_zero()) discard;\n";
      if (sd == glsl::side::both) body += "  " + fn + "_write(" + fn + "_read(p));\n";
      src.add("void main() {\n  " + body + "}\n", __FILE__, __LINE__);
      INFO(name << " for " << api_name(a) << "\n" << src.str());
      const auto words = spirv::compile(src, spirv::stage::fragment, a);
      REQUIRE(words);
      const auto refl = spirv::reflect(*words);
      REQUIRE(refl);
      const auto targets = describe<L>();
      const std::size_t n = targets.size();
      CHECK(refl->outputs.size() == (sd == glsl::side::read ? 0 : n));
      CHECK(refl->samplers.size() == (sd == glsl::side::write ? 0 : n));
      for (std::size_t i = 0; i < refl->outputs.size(); ++i) {
        CHECK(refl->outputs[i].location == opt.first_location + int(i));
        CHECK(refl->outputs[i].components == info(targets[i].fmt).channels);
      }
      for (std::size_t i = 0; i < refl->samplers.size(); ++i) {
        CHECK(refl->samplers[i].binding == opt.first_binding + int(i));
        CHECK(refl->samplers[i].set == 0);
      }
    }
}

}  // namespace

TEST_CASE("generated layouts compile for GL and Vulkan and reflect as described", "[glsl][spirv]") {
  check_layout<thesis_gbuffer>("gbuffer", "dst_surface");
  check_layout<thesis_light_buffer>("light", "dst_light_sample");
  check_layout<rgb_light_buffer>("light", "dst_light_sample");
  // White specular in a float target: its one channel still goes through the codec.
  check_layout<layout<light_sample, target<format::rgba32f, field::light, field::specular>>>("light", "dst_light_sample");
  check_layout<thesis_shadow_map>("shadow", "dst_surface");
  check_layout<float_layout>("custom", "dst_surface");
}

TEST_CASE("an engine's own bindings replace the generated ones through the hooks", "[glsl][spirv]") {
  glsl::source src;
  src.add("#define DSTRANS_GBUFFER_FETCH\n#define DSTRANS_GBUFFER_STORE\n"
          "layout(binding = 7) uniform sampler2DArray engine_gbuffer;\n"
          "layout(location = 5) out vec4 engine_out[4];\n"
          "vec4 dst_gbuffer_fetch(int target, ivec2 pixel) { return texelFetch(engine_gbuffer, ivec3(pixel, target), 0); }\n"
          "void dst_gbuffer_store(int target, vec4 v) { engine_out[target] = v; }\n",
          __FILE__, __LINE__);
  glsl::add_layout<thesis_gbuffer>(src, "gbuffer");
  src.add("void main() { dst_gbuffer_write(dst_gbuffer_read(ivec2(gl_FragCoord.xy))); }\n", __FILE__, __LINE__);
  for (spirv::api a : apis) {
    INFO(api_name(a));
    const auto words = spirv::compile(src, spirv::stage::fragment, a);
    REQUIRE(words);
    const auto refl = spirv::reflect(*words);
    REQUIRE(refl);
    REQUIRE(refl->samplers.size() == 1);
    CHECK(refl->samplers[0].binding == 7);
    REQUIRE(refl->outputs.size() == 1);
    CHECK(refl->outputs[0].location == 5);
  }
}

TEST_CASE("generated interlace predicates compile for GL and Vulkan", "[glsl][spirv]") {
  auto check = [](auto pred) {
    using I = decltype(pred);
    for (spirv::api a : apis) {
      glsl::source src;
      glsl::add_interlace<I>(src);
      src.add("layout(location = 0) out vec4 o;\n"
              "void main() {\n"
              "  ivec2 p = ivec2(gl_FragCoord.xy), size = ivec2(320, 181);\n"
              "  if (!dst_interlace_keep(p, size)) discard;\n"
              "  o = vec4(vec2(dst_interlace_partner(p, size)), 0.0f, 1.0f);\n"
              "}\n",
              __FILE__, __LINE__);
      INFO(I::name << " for " << api_name(a));
      CHECK(spirv::compile(src, spirv::stage::fragment, a));
    }
  };
  check(interlace::rows{});
  check(interlace::columns{});
  check(interlace::checker{});
  check(interlace::none{});
}

TEST_CASE("two predicates in one shader: the shadow maps' under the generic names, the G-buffer's under its own",
          "[glsl][spirv]") {
  for (spirv::api a : apis) {
    glsl::source src;
    glsl::add_interlace<interlace::rows>(src);
    glsl::add_interlace<interlace::checker>(src, "dst_gbuffer_interlace");
    glsl::add_interlace<interlace::rows>(src, "dst_other");  // the same predicate again: its formulas once
    src.add("layout(location = 0) out vec4 o;\n"
            "void main() {\n"
            "  ivec2 p = ivec2(gl_FragCoord.xy), size = ivec2(320, 181);\n"
            "  if (!dst_interlace_keep(p, size) || !dst_gbuffer_interlace_keep(p, size) || !dst_other_keep(p, size)) discard;\n"
            "  o = vec4(vec2(dst_interlace_partner(p, size)), vec2(dst_gbuffer_interlace_partner(p, size)));\n"
            "}\n",
            __FILE__, __LINE__);
    INFO(api_name(a));
    CHECK(src.str().find("dst_gbuffer_interlace_partner(ivec2 pixel, ivec2 size) { return dst_checker_partner(pixel, size); }") !=
          std::string::npos);
    CHECK(spirv::compile(src, spirv::stage::fragment, a));
  }
}

TEST_CASE("pixels counted from the bottom row reach the predicates and the refraction turned over", "[glsl][spirv]") {
  // The C++ of the turn: the bottom row of a 181-row image is row 180 from the top, and back.
  CHECK(shader::dst_flip_rows(glm::ivec2(3, 0), glm::ivec2(320, 181)) == glm::ivec2(3, 180));
  CHECK(shader::dst_flip_rows(shader::dst_flip_rows(glm::ivec2(7, 42), glm::ivec2(320, 181)), glm::ivec2(320, 181)) == glm::ivec2(7, 42));
  for (const glsl::rows r : {glsl::rows::from_top, glsl::rows::from_bottom}) {
    glsl::dialect d;
    d.pixel_rows = r;
    glsl::source src(d);
    glsl::add_interlace<interlace::rows>(src);
    glsl::add_refraction(src);
    src.add("layout(location = 0) out vec4 o;\n"
            "void main() {\n"
            "  ivec2 p = ivec2(gl_FragCoord.xy), size = ivec2(320, 181);\n"
            "  if (!dst_interlace_keep(p, size)) discard;\n"
            "  o = vec4(vec2(dst_interlace_partner(p, size)), vec2(dst_refract(p, size, vec3(0.0f, 1.0f, 0.0f), 4.0f)));\n"
            "}\n",
            __FILE__, __LINE__);
    const bool turned = src.str().find("dst_rows_keep(dst_flip_rows(pixel, size), size)") != std::string::npos &&
                        src.str().find("dst_flip_rows(dst_refraction_pixel(dst_flip_rows(pixel, size)") != std::string::npos;
    CHECK(turned == (r == glsl::rows::from_bottom));
    for (spirv::api a : apis) {
      INFO(api_name(a));
      CHECK(spirv::compile(src, spirv::stage::fragment, a));
    }
  }
}

TEST_CASE("compile errors name the dstrans source line, reflection rejects garbage", "[spirv]") {
  glsl::source src;
  glsl::add_layout<thesis_light_buffer>(src, "light");
  src.add("void main() {\n  dst_light_write(undeclared_thing);\n}\n", "my_pass.frag", 41);
  const auto words = spirv::compile(src, spirv::stage::fragment, spirv::api::vulkan);
  REQUIRE_FALSE(words);
  CHECK_THAT(words.error(), Catch::Contains("my_pass.frag:42: error:") && Catch::Contains("undeclared_thing"));

  glsl::source linkless;
  linkless.add("float f() { return 1.0f; }\n", "snippet.glsl", 1);
  const auto no_main = spirv::compile(linkless, spirv::stage::compute, spirv::api::opengl);
  REQUIRE_FALSE(no_main);
  CHECK_THAT(no_main.error(), Catch::Contains("entry point"));

  const auto bad = spirv::reflect({0x07230203u, 1u, 2u});
  REQUIRE_FALSE(bad);
  CHECK_THAT(bad.error(), Catch::Contains("SPIR-V reflection failed"));
}
