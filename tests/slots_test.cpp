// The slot table (dstrans/frame/slots.hpp), the shared blocks (frame/blocks.hpp) and the embedded pass
// shaders (dstrans/pass_shaders.hpp).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <dstrans/frame/blocks.hpp>
#include <dstrans/frame/slots.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans_spirv.hpp>

using namespace dstrans;

TEST_CASE("the slot table is emitted into GLSL as one define per slot", "[slots]") {
  glsl::source src;
  add_slots(src);
  for (const slot_desc& d : slot_table) {
    INFO(d.name);
    CHECK(src.str().find("#define DST_SLOT_" + std::string(d.name) + " " + std::to_string(d.binding) + "\n") !=
          std::string::npos);
    CHECK(binding(d.id) == d.binding);
    CHECK(d.binding + d.count <= slot_bindings());
  }
  CHECK(binding(slot::frame) == 20);
  CHECK(slot_bindings() == 38);
}

TEST_CASE("every pass shader of shaders/glsl is embedded, as the file holds it", "[slots]") {
  const pass_shaders embedded;
  const std::string dir = std::string(DSTRANS_SOURCE_DIR) + "/shaders/glsl";
  const pass_shaders folder(dir);
  CHECK(embedded.embedded());
  CHECK(!folder.embedded());
  std::set<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.insert(entry.path().filename().string());
  const std::vector<std::string> names = pass_shaders::names();
  CHECK(std::set<std::string>(names.begin(), names.end()) == files);
  for (const std::string& name : names) {
    INFO(name);
    std::ifstream in(dir + "/" + name);
    std::ostringstream text;
    text << in.rdbuf();
    auto e = embedded.text(name), f = folder.text(name);
    REQUIRE(e);
    REQUIRE(f);
    CHECK(*e == text.str());
    CHECK(*f == text.str());
  }
  CHECK(embedded.origin("frame.glsl") == "shaders/glsl/frame.glsl");
  CHECK(folder.origin("frame.glsl") == dir + "/frame.glsl");
  CHECK(embedded.text("no_such.glsl").error() == "no pass shader named no_such.glsl is embedded in dstrans");
  CHECK(pass_shaders("/nonexistent").text("frame.glsl").error() == "cannot read GLSL file /nonexistent/frame.glsl");
}

TEST_CASE("a pass shader is added with its switches resolved and its lines mapped to its file", "[slots]") {
  const pass_shaders shaders;
  glsl::source with, without;
  REQUIRE(shaders.add_to(with, "gbuffer.frag.glsl", {"DST_PEEL"}));
  REQUIRE(shaders.add_to(without, "gbuffer.frag.glsl"));
  CHECK(with.str().find("dst_peel_depth") != std::string::npos);
  CHECK(without.str().find("dst_peel_depth") == std::string::npos);
  bool mapped = false;
  for (int line = 1; line <= 400; ++line) mapped = mapped || with.origin_of(line).file == "shaders/glsl/gbuffer.frag.glsl";
  CHECK(mapped);
  glsl::source bad;
  CHECK(!bad.add_text("#if DST_X\n#endif\n", "x.glsl"));
}

TEST_CASE("frame.glsl declares the shared blocks at their slots", "[slots]") {
  glsl::source src;
  add_slots(src);
  REQUIRE(pass_shaders().add_to(src, "frame.glsl"));
  CHECK(src.has(text::dst_frame_data));
  CHECK(src.has(text::dst_material_data));
  CHECK(src.has(text::dst_light_data));
  src.add("layout(location = 0) out vec4 o;\n"
          "void main() { o = frame.ambient + dst_material(1u).specular + lights[0].colour_cos_outer; }\n",
          __FILE__, __LINE__);
  const auto words = spirv::compile(src, spirv::stage::fragment, spirv::api::vulkan);
  INFO(words.error());
  REQUIRE(words);
  const auto refl = spirv::reflect(*words);
  REQUIRE(refl);
  REQUIRE(refl->uniform_buffers.size() == 1);
  CHECK(refl->uniform_buffers[0].binding == binding(slot::frame));
  REQUIRE(refl->texel_buffers.size() == 1);
  CHECK(refl->texel_buffers[0].binding == binding(slot::materials));
  CHECK(refl->samplers.empty());
  REQUIRE(refl->storage_buffers.size() == 1);
  CHECK(refl->storage_buffers[0].binding == binding(slot::lights));
}
