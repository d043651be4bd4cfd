// The GLSL source builder: shared-code formatting, de-duplication, origins and error mapping.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>

#include <dstrans/gbuffer.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/result.hpp>
#include <dstrans/surface.hpp>

DSTRANS_SHARED(dst_test_block,
DST_FN void dst_test_out(float a, DST_OUT(vec3) o, DST_INOUT( float ) io) { for (int i = 0; i < 2; ++i) { io += a; } o = vec3(a); }
)

using namespace dstrans;

TEST_CASE("shared code is GLSL once the keywords are spelled out", "[glsl]") {
  const std::string text = glsl::format_shared(text::dst_test_block.code);
  CHECK(text ==
        "void dst_test_out(float a, out vec3 o, inout float io) {\n"
        "  for (int i = 0; i < 2; ++i) {\n"
        "    io += a;\n"
        "  }\n"
        "  o = vec3(a);\n"
        "}\n\n");
  // ... and the same text is C++.
  glm::vec3 o;
  float io = 1.0f;
  shader::dst_test_out(2.0f, o, io);
  CHECK(o == glm::vec3(2.0f));
  CHECK(io == 5.0f);
}

TEST_CASE("a shared block records where it was written", "[glsl]") {
  CHECK(std::string(text::dst_test_block.name) == "dst_test_block");
  CHECK(std::string(text::dst_test_block.file).find("glsl_test.cpp") != std::string::npos);
  CHECK(text::dst_test_block.line == 12);
}

TEST_CASE("a source maps every line to its origin and holds each shared block once", "[glsl]") {
  glsl::source src;
  CHECK(src.str() == "#version 450\n");
  src.add_shared(text::dst_surface);
  src.add_shared(text::dst_surface);
  CHECK(src.has(text::dst_surface));
  CHECK_FALSE(src.has(text::dst_light_sample));
  const std::string once = src.str();
  CHECK(once.find("struct dst_surface") == once.rfind("struct dst_surface"));
  const int before = int(std::count(once.begin(), once.end(), '\n'));
  src.add("float a;\nfloat b;", "engine.glsl", 10);
  CHECK(src.origin_of(before + 1).file == "engine.glsl");
  CHECK(src.origin_of(before + 2).line == 11);
  CHECK(src.origin_of(2).file == text::dst_surface.file);
  CHECK(src.origin_of(2).line == text::dst_surface.line);
  CHECK(src.origin_of(0).file.empty());
  CHECK(src.origin_of(before + 3).file.empty());
  CHECK(src.str().back() == '\n');
}

TEST_CASE("a pass shader file is added with its own line numbers", "[glsl]") {
  const std::string path = (std::filesystem::temp_directory_path() / "dstrans_glsl_test_pass.frag.glsl").string();
  std::ofstream(path) << "// a pass\nvoid main() {\n}\n";
  glsl::source src;
  REQUIRE(src.add_file(path));
  CHECK(src.origin_of(3).file == path);
  CHECK(src.origin_of(3).line == 2);
  CHECK(src.str().find("void main()") != std::string::npos);
  const auto missing = src.add_file("no/such/file.glsl");
  REQUIRE_FALSE(missing);
  CHECK(missing.error() == "cannot read GLSL file no/such/file.glsl");
  std::filesystem::remove(path);
}

TEST_CASE("compiler logs are mapped to file:line of the original text", "[glsl]") {
  glsl::source src;
  src.add("void f() {\n  x = 1;\n}\n", "pass.frag", 20);
  // glslang's form and Mesa's form.
  CHECK(src.map_log("ERROR: 0:3: 'x' : undeclared identifier") ==
        "pass.frag:21: error: 'x' : undeclared identifier (generated line 3)");
  CHECK(src.map_log("0:3(3): error: `x' undeclared") == "pass.frag:21: error: `x' undeclared (generated line 3)");
  // Lines without a position, or with one outside the source, pass through.
  CHECK(src.map_log("ERROR: 1 compilation errors.\nERROR: 0:99: z") == "ERROR: 1 compilation errors.\nERROR: 0:99: z");
}

TEST_CASE("result holds a value or a sentence", "[result]") {
  result<int> good(4);
  REQUIRE(good);
  CHECK(good.ok());
  CHECK(*good == 4);
  CHECK(good.error().empty());
  result<std::string> bad(failure{"no display"});
  CHECK_FALSE(bad);
  CHECK(bad.error() == "no display");
  result<std::string> text(std::string("abc"));
  CHECK(text->size() == 3);
}

TEST_CASE("a source opens with its version's line, or with none, and binds samplers only from GLSL 4.20", "[glsl]") {
  CHECK(glsl::source().str() == "#version 450\n");
  CHECK(glsl::source(glsl::version::glsl330).str() == "#version 330 core\n");
  CHECK(glsl::source(glsl::version::glsl410).str() == "#version 410 core\n");
  CHECK(glsl::source(glsl::version::vulkan).str() == "#version 450\n");
  glsl::dialect own_line;
  own_line.language = glsl::version::glsl330;
  own_line.version_line = false;
  CHECK(glsl::source(own_line).str().empty());
  CHECK(glsl::source(own_line).language() == glsl::version::glsl330);
  CHECK(glsl::source().pixel_rows() == glsl::rows::from_top);
  CHECK(!glsl::source(glsl::version::glsl330).binds());
  CHECK(!glsl::source(glsl::version::glsl410).binds());
  CHECK(glsl::source(glsl::version::glsl450).binds());
  CHECK(glsl::source(glsl::version::vulkan).binds());
  for (const char* name : {"330", "410", "450", "vulkan"}) {
    const auto v = glsl::version_named(name);
    REQUIRE(v);
    CHECK(glsl::source(*v).language() == *v);
  }
  const auto bad = glsl::version_named("300 es");
  REQUIRE(!bad);
  CHECK(bad.error() == "unknown GLSL version '300 es' (known: 330, 410, 450, vulkan)");

  // The read side names its samplers, with a binding where the version has them.
  for (const glsl::version v : {glsl::version::glsl330, glsl::version::glsl450}) {
    glsl::source src(v);
    glsl::layout_options o;
    o.sides = glsl::side::read;
    o.first_binding = 5;
    glsl::add_layout<thesis_gbuffer>(src, "gbuffer", o);
    const bool bound = src.str().find("layout(binding = 5) uniform sampler2D dst_gbuffer_tex0;") != std::string::npos;
    CHECK(bound == (v == glsl::version::glsl450));
    CHECK(src.str().find("uniform sampler2D dst_gbuffer_tex3;") != std::string::npos);
  }
}
