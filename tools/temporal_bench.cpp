// Implements temporal_bench.hpp.
#include "temporal_bench.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "image_error.hpp"

namespace dstrans::cli {

namespace {

using json = nlohmann::ordered_json;

glm::vec3 turned(glm::vec3 v, float degrees) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::vec3(0, 1, 0)) * glm::vec4(v, 0.0f));
}

struct method {
  const char* name;
  render::technique technique;
  bool temporal, reconstruct;
  render::gbuffer_layout layout;
};
// The first four are the strip's columns; each method is compared with peeling in its own layout (the
// compact layout's normals alone move highlights by a few codes). The temporal method falls back on the
// partner: the previous frame covers nine in ten of the glass pixels, and the edge-aware fallback gained
// under 0.02 RMSE on every path for 2.3 ms of the compose's 7.9 (glass_room, 320x180, llvmpipe).
const method methods[] = {{"thesis", render::technique::interlaced, false, false, render::gbuffer_layout::thesis},
                          {"spatial", render::technique::interlaced, false, true, render::gbuffer_layout::compact},
                          {"temporal", render::technique::interlaced, true, false, render::gbuffer_layout::compact},
                          {"peeling", render::technique::peeling, false, false, render::gbuffer_layout::thesis},
                          {"peeling-compact", render::technique::peeling, false, false, render::gbuffer_layout::compact}};
constexpr std::size_t strip_columns = 4, temporal_method = 2, thesis_peeling = 3, compact_peeling = 4;

render::options options_of(const render::options& base, const method& m) {
  render::options o = base;
  o.method = m.technique;
  o.temporal = m.temporal;
  o.reconstruct = m.reconstruct;
  o.layout = m.layout;
  return o;
}

// A crop of `img`: `size` pixels centred on `centre`, kept inside the image.
render::image crop(const render::image& img, glm::ivec2 centre, glm::ivec2 size) {
  size = glm::min(size, glm::ivec2(img.width, img.height));
  const glm::ivec2 from = glm::clamp(centre - size / 2, glm::ivec2(0), glm::ivec2(img.width, img.height) - size);
  render::image out{size.x, size.y, std::vector<std::uint8_t>(std::size_t(size.x) * std::size_t(size.y) * 4)};
  for (int y = 0; y < size.y; ++y)
    std::copy_n(img.rgba.begin() + 4 * std::ptrdiff_t((from.y + y) * img.width + from.x), 4 * size.x,
                out.rgba.begin() + 4 * std::ptrdiff_t(y * size.x));
  return out;
}

// `tile` into `into` at `at`, each pixel twice as wide and high.
void paste_doubled(render::image& into, const render::image& tile, glm::ivec2 at) {
  for (int y = 0; y < 2 * tile.height; ++y)
    for (int x = 0; x < 2 * tile.width; ++x)
      std::copy_n(tile.rgba.begin() + 4 * std::ptrdiff_t((y / 2) * tile.width + x / 2), 4,
                  into.rgba.begin() + 4 * std::ptrdiff_t((at.y + y) * into.width + at.x + x));
}

// The median frame time of `frames` after the first.
double median_ms(const std::vector<render::frame>& frames) {
  std::vector<double> ms;
  for (std::size_t i = 1; i < frames.size(); ++i) ms.push_back(frames[i].frame_ms);
  std::sort(ms.begin(), ms.end());
  return ms.empty() ? 0.0 : ms.size() % 2 ? ms[ms.size() / 2] : 0.5 * (ms[ms.size() / 2 - 1] + ms[ms.size() / 2]);
}

// The mean of each figure over `errors`.
render::image_error mean_of(const std::vector<render::image_error>& errors) {
  render::image_error m;
  m.all = m.masked = {0.0, 0.0, 0.0, 0.0};
  for (const render::image_error& e : errors)
    for (auto [sum, one] : {std::pair{&m.all, &e.all}, std::pair{&m.masked, &e.masked}}) {
      sum->rmse += one->rmse / double(errors.size());
      sum->ssim += one->ssim / double(errors.size());
      sum->flip += one->flip / double(errors.size());
    }
  m.all.psnr = m.all.rmse > 0.0 ? 20.0 * std::log10(255.0 / m.all.rmse) : INFINITY;
  m.masked.psnr = m.masked.rmse > 0.0 ? 20.0 * std::log10(255.0 / m.masked.rmse) : INFINITY;
  return m;
}

}  // namespace

std::vector<std::pair<std::string, std::vector<scene>>> temporal_paths(const scene& room, int frames) {
  std::vector<std::pair<std::string, std::vector<scene>>> paths{{"still", {}}, {"orbit", {}}, {"pan", {}}, {"dolly", {}}, {"moving pane", {}}};
  std::size_t pane = 0;
  while (pane < room.objects.size() && !(room.objects[pane].material < room.materials.size() &&
                                         room.materials[room.objects[pane].material].transparent()))
    ++pane;
  for (int i = 0; i < frames; ++i) {
    const float t = float(i);
    for (auto& [name, sequence] : paths) {
      scene s = room;
      camera& c = s.view;
      if (name == "orbit") c.position = c.target + turned(c.position - c.target, 0.5f * t);
      if (name == "pan") c.target = c.position + turned(c.target - c.position, 2.0f * t);
      if (name == "dolly") c.position = c.target + (c.position - c.target) * (1.0f - 0.04f * t);
      if (name == "moving pane" && pane < s.objects.size())
        s.objects[pane].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.02f * t, 0.0f, 0.0f)) * s.objects[pane].transform;
      sequence.push_back(std::move(s));
    }
  }
  return paths;
}

result<temporal_results> temporal_records(const scene& room, const render::options& base, int frames, const std::string& backend,
                                          const sequence_draw& draw, const sequence_clock& clock, const pair_count& count) {
  temporal_results out{json::array(), {}};
  const auto paths = temporal_paths(room, std::max(frames, 2));
  // Tiles of a third of the image, doubled, with white gaps between them (wider between the methods).
  const glm::ivec2 tile(base.width / 3, base.height / 3), tiles(int(strip_columns), int(paths.size())), gap(2, 1);
  const glm::ivec2 strip = 2 * (tiles * tile + (tiles - 1) * gap);
  out.strip = {strip.x, strip.y, std::vector<std::uint8_t>(std::size_t(strip.x) * std::size_t(strip.y) * 4, 255)};
  for (std::size_t p = 0; p < paths.size(); ++p) {
    const auto& [path, sequence] = paths[p];
    std::vector<std::vector<render::frame>> drawn;
    for (const method& m : methods) {
      auto f = draw(sequence, options_of(base, m));
      if (!f) return failure{path + ", " + m.name + ": " + f.error()};
      drawn.push_back(std::move(*f));
    }
    const std::vector<render::frame>& peeled = drawn[thesis_peeling];
    const double peeling_ms = median_ms(peeled);
    auto peeling_clock = clock(sequence, options_of(base, methods[thesis_peeling]));
    if (!peeling_clock) return failure{path + ", peeling's clock: " + peeling_clock.error()};
    auto temporal_clock = clock(sequence, options_of(base, methods[temporal_method]));
    if (!temporal_clock) return failure{path + ", temporal's clock: " + temporal_clock.error()};
    auto paired = time_paired(*peeling_clock, *temporal_clock, 2, count);
    if (!paired) return failure{path + ", timed in pairs: " + paired.error()};
    const json against_peeling = {{"ratio", paired->ratio}, {"low", paired->low}, {"high", paired->high}, {"frames", paired->frames}};
    // The exact reference of each frame (technique reference, which never refracts); not used where its lists
    // overflowed on some frame.
    render::options exact_options = base;
    exact_options.method = render::technique::reference;
    auto exact = draw(sequence, exact_options);
    if (!exact) return failure{path + ", exact reference: " + exact.error()};
    std::uint64_t overflow = 0;
    for (const render::frame& f : *exact) overflow += f.kbuffer_overflow;
    for (std::size_t k = 0; k < drawn.size(); ++k) {
      const method& m = methods[k];
      const std::vector<render::frame>& reference = drawn[m.layout == render::gbuffer_layout::thesis ? thesis_peeling : compact_peeling];
      std::vector<render::image_error> errors;
      double worst = 0.0, worst_flip = 0.0, change = 0.0, against_thesis = 0.0, flip_exact = 0.0;
      // The change from the first frame to the second is the temporal method's history arriving, not flicker.
      const std::size_t changes = drawn[k].size() > 2 ? drawn[k].size() - 2 : 0;
      for (std::size_t i = 1; i < drawn[k].size(); ++i) {
        const std::vector<bool> glass = render::glass_pixels(peeled[i]);
        errors.push_back(render::compare(drawn[k][i].final_image, reference[i].final_image, glass));
        against_thesis += render::compare(drawn[k][i].final_image, peeled[i].final_image, glass).masked.rmse / double(drawn[k].size() - 1);
        worst = std::max(worst, errors.back().masked.rmse);
        worst_flip = std::max(worst_flip, errors.back().masked.flip);
        if (i >= 2) change += render::compare(drawn[k][i].final_image, drawn[k][i - 1].final_image, glass).masked.rmse / double(changes);
        flip_exact += render::compare(drawn[k][i].final_image, (*exact)[i].final_image, glass).masked.flip / double(drawn[k].size() - 1);
      }
      const int bytes = render::plan_of(sequence.front(), options_of(base, m)).pipeline.bytes_per_pixel * (m.technique == render::technique::peeling ? 2 : 1);
      out.records.push_back(render::with_errors({{"technique", std::string("temporal-") + m.name},
                                                 {"scene", "glass_room_path"},
                                                 {"backend", backend},
                                                 {"settings", {{"path", path}, {"method", m.name}, {"frames", sequence.size()},
                                                               {"layout", render::layout_name(m.layout)},
                                                               {"reconstruction", m.reconstruct ? "edge-aware" : "partner"},
                                                               {"temporal", m.temporal}, {"lights", room.lights.size()},
                                                               {"width", base.width}, {"height", base.height}}},
                                                 {"frame_ms", median_ms(drawn[k])},
                                                 {"peeling_ms", peeling_ms},
                                                 {"paired_against_peeling", k == temporal_method ? against_peeling : json(nullptr)},
                                                 {"bytes_per_pixel", bytes},
                                                 {"reference", "deferred depth peeling of the same frame, in the same layout"},
                                                 {"rmse_transparent_against_thesis_peeling", against_thesis},
                                                 {"worst_rmse_transparent", worst},
                                                 {"worst_flip_transparent", worst_flip},
                                                 {"frame_change_transparent", changes ? json(change) : json(nullptr)},
                                                 {"exact_overflow", overflow},
                                                 {"flip_transparent_against_exact", overflow ? json(nullptr) : json(flip_exact)}},
                                                mean_of(errors)));
      if (k >= strip_columns) continue;
      // The last frame's glass, cropped where peeling's glass lies on average.
      const std::vector<bool> glass = render::glass_pixels(peeled.back());
      glm::dvec2 sum(0.0);
      std::size_t n = 0;
      for (std::size_t i = 0; i < glass.size(); ++i)
        if (glass[i]) {
          sum += glm::dvec2(double(i % std::size_t(base.width)), double(i / std::size_t(base.width)));
          ++n;
        }
      const glm::ivec2 centre = n ? glm::ivec2(sum / double(n)) : glm::ivec2(base.width, base.height) / 2;
      paste_doubled(out.strip, crop(drawn[k].back().final_image, centre, tile),
                    2 * glm::ivec2(int(k), int(p)) * (tile + gap));
    }
  }
  return out;
}

}  // namespace dstrans::cli
