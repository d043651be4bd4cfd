// Implements frame_output.hpp with stb_image, stb_image_write and nlohmann-json.
#include "frame_output.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

// Static: a PNG-only stb_image with external names would stand in for the full one a shared library
// (tinygltf's) calls, and its JPEG images would fail to decode.
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace dstrans::render {

image to_image(const std::vector<texel>& texels, format f, int width, int height, view_as how, float near_plane,
               float far_plane) {
  image out{width, height, std::vector<std::uint8_t>(std::size_t(width) * std::size_t(height) * 4)};
  auto byte = [](float v) { return std::uint8_t(unorm_encode(v, 8)); };
  for (std::size_t i = 0; i < texels.size(); ++i) {
    const glm::vec4 v = decode(f, texels[i]);
    glm::vec3 c(v);
    if (how == view_as::alpha) c = glm::vec3(v.w);
    if (how == view_as::depth) {
      const float z = near_plane * far_plane / (far_plane - v.x * (far_plane - near_plane));
      c = glm::vec3(v.x >= 1.0f ? 1.0f : z / far_plane);
    }
    for (int k = 0; k < 3; ++k) out.rgba[4 * i + std::size_t(k)] = byte(c[k]);
    out.rgba[4 * i + 3] = 255;
  }
  return out;
}

std::vector<bool> glass_pixels(const frame& f) {
  std::vector<bool> out(f.gbuffer.empty() ? 0 : f.gbuffer[0].size());
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = decode(format::rgba8, f.gbuffer[0][i]).w < 1.0f;
  return out;
}

namespace {
// The q-quantile (0 to 1) of `v`, interpolated between neighbours.
double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double at = q * double(v.size() - 1);
  const std::size_t lo = std::size_t(at), hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (v[hi] - v[lo]) * (at - double(lo));
}
}  // namespace

void summarize(const std::vector<std::map<std::string, double>>& frames, const std::vector<double>& totals, frame& out) {
  out.frames = int(frames.size());
  out.pass_ms.clear();
  if (frames.empty()) return;
  for (const auto& [pass, ms] : frames.front()) {
    std::vector<double> v;
    for (const auto& f : frames) v.push_back(f.at(pass));
    out.pass_ms[pass] = quantile(v, 0.5);
  }
  out.frame_ms = quantile(totals, 0.5);
  out.frame_ms_spread = quantile(totals, 0.75) - quantile(totals, 0.25);
}

layer_counts count_layers(const frame& f) {
  layer_counts c;
  std::size_t total = 0;
  for (std::uint32_t head : f.kbuffer_heads) {
    std::size_t n = 0;
    for (std::uint32_t at = head; at < f.kbuffer_nodes.size() && n <= f.kbuffer_nodes.size(); at = f.kbuffer_nodes[at].w) ++n;
    if (n == 0) continue;
    ++c.pixels;
    total += n;
    c.max = std::max(c.max, n);
  }
  c.mean = c.pixels ? double(total) / double(c.pixels) : 0.0;
  return c;
}

std::string png_bytes(const image& img) {
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &out, img.width, img.height, 4, img.rgba.data(), img.width * 4)) out.clear();
  return out;
}

result<image> read_png(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  stbi_uc* pixels = stbi_load(path.c_str(), &w, &h, &channels, 4);
  if (!pixels) return failure{path + ": not a PNG file that can be read (" + stbi_failure_reason() + ")"};
  image out{w, h, std::vector<std::uint8_t>(pixels, pixels + std::size_t(w) * std::size_t(h) * 4)};
  stbi_image_free(pixels);
  return out;
}

result<bool> write_frame(const frame& f, output_dir& out, const std::string& technique, const std::string& backend) {
  auto png = [&](const std::string& name, const image& img) -> result<bool> {
    const std::string bytes = png_bytes(img);
    if (bytes.empty()) return failure{out.dir() + "/" + name + ".png: the image cannot be encoded"};
    return out.add(name + ".png", bytes);
  };
  if (auto ok = png("final", f.final_image); !ok) return ok;
  for (const auto& [name, img] : f.buffers)
    if (auto ok = png(name, img); !ok) return ok;
  nlohmann::ordered_json j{{"technique", technique}, {"backend", backend}, {"width", f.final_image.width},
                           {"height", f.final_image.height}, {"pass_ms", f.pass_ms}, {"frame_ms", f.frame_ms},
                           {"frame_ms_spread", f.frame_ms_spread}, {"frames", f.frames}};
  if (!f.kbuffer_heads.empty()) {
    const layer_counts c = count_layers(f);
    j["kbuffer"] = {{"nodes", f.kbuffer_nodes.size()}, {"overflow", f.kbuffer_overflow}, {"pixels", c.pixels},
                    {"mean_layers", c.mean}, {"max_layers", c.max}};
  }
  out.set_manifest(std::move(j));
  return true;
}

}  // namespace dstrans::render
