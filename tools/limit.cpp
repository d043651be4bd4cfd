// Implements limit.hpp.
#include "limit.hpp"

#include <algorithm>
#include <vector>

#include <dstrans/frame/passes.hpp>

namespace dstrans::cli {

namespace {
std::size_t bytes_of(const std::vector<target_desc>& targets, std::size_t texels) {
  std::size_t b = 0;
  for (const target_desc& t : targets) b += std::size_t(info(t.fmt).bytes_per_pixel) * texels;
  return b;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

// The plan's targets whose names start with `prefix` ("gbuffer.", "light.", ...), at `texels` each.
std::size_t planned_bytes(const render::frame_plan& plan, const std::string& prefix, std::size_t texels) {
  std::size_t b = 0;
  for (const planned_target& t : plan.pipeline.targets)
    if (starts_with(t.name, prefix) && t.name != "kbuffer.nodes") b += std::size_t(t.bytes_per_pixel) * texels;
  return b;
}
}  // namespace

std::size_t resource_bytes(const std::string& resource, const render::frame_plan& plan, const render::options& o) {
  const std::size_t pixels = std::size_t(o.width) * std::size_t(o.height);
  const std::size_t shadow_texels = std::size_t(o.shadow_size) * std::size_t(o.shadow_size);
  if (resource == "gbuffer" || resource == "gbuffer 2") return planned_bytes(plan, "gbuffer.", pixels);
  if (resource == "light buffer" || resource == "light buffer 2") return planned_bytes(plan, "light.", pixels);
  if (resource == "shadow map") return planned_bytes(plan, "shadow.", shadow_texels);
  if (resource == "shadow layers") {  // a layer of the shadow map's targets for each shadowed light
    const auto layers = std::size_t(std::count_if(plan.lookups.begin(), plan.lookups.end(),
                                                  [](render::shadow_mode m) { return m != render::shadow_mode::off; }));
    return layers * planned_bytes(plan, "shadow.", shadow_texels);
  }
  if (resource == "kbuffer")
    return planned_bytes(plan, "kbuffer.", pixels) + std::size_t(o.kbuffer_k) * std::size_t(kbuffer_node_bytes) * pixels;
  if (resource == "lit") return bytes_of(render::forward_targets(plan.forward_depth, o.float_targets), pixels);
  if (resource == "glass layers") return planned_bytes(plan, "glass.", pixels);
  if (resource == "scene" || resource == "volume atlas") return 0;
  return bytes_of({render::final_target_desc(o.float_targets)}, pixels);  // "frame" and the post chain's targets
}

std::map<std::string, std::size_t> timer_bytes(const frame_schedule& s, const render::frame_plan& plan, const render::options& o) {
  std::map<std::string, std::size_t> out;
  for (const scheduled_pass& pass : s.passes) {
    // A light's pass touches only its own layer of the shadow layers.
    auto bytes = [&](const std::string& r) {
      return r == "shadow layers" && pass.light >= 0 ? resource_bytes("shadow map", plan, o) : resource_bytes(r, plan, o);
    };
    std::size_t touched = 0;
    for (const std::string& r : pass.reads) touched += bytes(r);
    for (const std::string& w : pass.writes) touched += bytes(w);
    out[pass.timer] += touched / 2;
  }
  return out;
}

glsl::source copy_fragment_shader() {
  glsl::source src;
  src.add("layout(binding = 0, rgba32f) uniform readonly image2D dst_copy_source;\n"
          "layout(location = 0) out vec4 dst_copied;\n"
          "void main() { dst_copied = imageLoad(dst_copy_source, ivec2(gl_FragCoord.xy)); }\n",
          __FILE__, __LINE__);
  return src;
}

result<double> limit_meter::copy_ms(std::size_t bytes) {
  if (bytes == 0) return 0.0;
  if (auto at = measured_.find(bytes); at != measured_.end()) return at->second;
  std::vector<double> times;
  for (int k = 0; k < 5; ++k) {
    auto ms = clock_(bytes);
    if (!ms) return failure{ms.error()};
    times.push_back(*ms);
  }
  std::sort(times.begin(), times.end());
  return measured_[bytes] = times[2];
}

result<std::map<std::string, double>> limit_meter::limits(const std::map<std::string, std::size_t>& bytes) {
  std::map<std::string, double> out;
  for (const auto& [timer, b] : bytes) {
    auto ms = copy_ms(b);
    if (!ms) return failure{ms.error()};
    out[timer] = *ms;
  }
  return out;
}

}  // namespace dstrans::cli
