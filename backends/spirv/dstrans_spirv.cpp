// Implements dstrans_spirv.hpp with glslang's C++ API and SPIRV-Cross' core compiler.
#include "dstrans_spirv.hpp"

#include <algorithm>
#include <exception>
#include <mutex>

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>
#include <spirv_cross/spirv_cross.hpp>

namespace dstrans::spirv {

namespace {

// glslang keeps process-wide tables; they are made once and live until exit, as glslang intends.
void initialize_once() {
  static std::once_flag once;
  std::call_once(once, [] { glslang::InitializeProcess(); });
}

EShLanguage language(stage st) {
  switch (st) {
    case stage::vertex: return EShLangVertex;
    case stage::fragment: return EShLangFragment;
    case stage::compute: return EShLangCompute;
  }
  return EShLangFragment;
}

}  // namespace

result<std::vector<std::uint32_t>> compile(const glsl::source& src, stage st, api target) {
  initialize_once();
  const EShLanguage lang = language(st);
  glslang::TShader shader(lang);
  const char* text = src.str().c_str();
  shader.setStrings(&text, 1);
  const bool vk = target == api::vulkan;
  shader.setEnvInput(glslang::EShSourceGlsl, lang, vk ? glslang::EShClientVulkan : glslang::EShClientOpenGL, 450);
  shader.setEnvClient(vk ? glslang::EShClientVulkan : glslang::EShClientOpenGL,
                      vk ? glslang::EShTargetVulkan_1_2 : glslang::EShTargetOpenGL_450);
  shader.setEnvTarget(glslang::EShTargetSpv, vk ? glslang::EShTargetSpv_1_5 : glslang::EShTargetSpv_1_0);
  const auto messages = EShMessages(EShMsgSpvRules | (vk ? int(EShMsgVulkanRules) : 0));
  if (!shader.parse(GetDefaultResources(), 450, false, messages))
    return failure{src.map_log(shader.getInfoLog())};
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) return failure{src.map_log(program.getInfoLog())};
  std::vector<std::uint32_t> words;
  glslang::SpvOptions options;
  options.validate = true;
  glslang::GlslangToSpv(*program.getIntermediate(lang), words, &options);
  return words;
}

result<reflection> reflect(const std::vector<std::uint32_t>& words) {
  try {
    spirv_cross::Compiler compiler(words);
    const spirv_cross::ShaderResources res = compiler.get_shader_resources();
    reflection out;
    auto variables = [&](const auto& list, std::vector<interface_variable>& into) {
      for (const auto& r : list)
        into.push_back({int(compiler.get_decoration(r.id, spv::DecorationLocation)), r.name,
                        int(compiler.get_type(r.type_id).vecsize)});
      std::sort(into.begin(), into.end(), [](auto& a, auto& b) { return a.location < b.location; });
    };
    auto resources = [&](const auto& list, std::vector<resource>& into) {
      for (const auto& r : list)
        into.push_back({int(compiler.get_decoration(r.id, spv::DecorationDescriptorSet)),
                        int(compiler.get_decoration(r.id, spv::DecorationBinding)), r.name});
      std::sort(into.begin(), into.end(),
                [](auto& a, auto& b) { return a.set != b.set ? a.set < b.set : a.binding < b.binding; });
    };
    variables(res.stage_inputs, out.inputs);
    variables(res.stage_outputs, out.outputs);
    // A samplerBuffer is a sampled image of Dim Buffer, which Vulkan binds as a uniform texel buffer.
    std::vector<spirv_cross::Resource> sampled, texels;
    for (const auto& r : res.sampled_images)
      (compiler.get_type(r.type_id).image.dim == spv::DimBuffer ? texels : sampled).push_back(r);
    resources(sampled, out.samplers);
    resources(texels, out.texel_buffers);
    resources(res.uniform_buffers, out.uniform_buffers);
    resources(res.storage_buffers, out.storage_buffers);
    resources(res.storage_images, out.storage_images);
    return out;
  } catch (const std::exception& e) {
    return failure{std::string("SPIR-V reflection failed: ") + e.what()};
  }
}

}  // namespace dstrans::spirv
