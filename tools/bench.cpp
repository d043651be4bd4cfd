// dstrans bench: the thesis's comparisons (Tables 4.1-4.7) measured on this machine, with the error of
// each technique against deferred depth peeling (the thesis's reference), as results.json and report.md.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "gpu.hpp"
#include "image_error.hpp"
#include "output_dir.hpp"
#include "limit.hpp"
#include "paired.hpp"
#include "temporal_bench.hpp"
#include "leaks.hpp"
#include <dstrans/frame/passes.hpp>
#ifdef DSTRANS_HAVE_GL
#include "run_gl.hpp"
#endif
#ifdef DSTRANS_HAVE_VK
#include "run_vk.hpp"
#endif
#include "scene_json.hpp"
#include "scene_lights.hpp"
#include "shipped_files.hpp"

namespace dstrans::cli {

namespace {

using json = nlohmann::ordered_json;

const char* const usage =
    "usage: dstrans bench [--quick] --out DIR [--backend gl|vk [--backend-only]] [--device N|NAME]\n"
    "                     [--width W --height H] [--shadow-size N] [--frames N] [--pairs N]\n"
    "renders glass_room and its variants with every technique and setting the thesis compared, and writes\n"
    "DIR/results.json and DIR/report.md; the sections beyond the thesis's tables also run on the other API\n"
    "where the machine has it, unless --backend-only. --quick measures fewer light counts at a smaller size\n"
    "(320x180, 256^2 shadow maps, 5 frames a run; else 640x360, 512^2, 9), which the other options\n"
    "override. --device chooses the GPU by index or part of its name for both APIs (`--device list` lists\n"
    "them); every record names the device and driver it ran on. A paired comparison times frames of A and B\n"
    "in turns until its 95% interval is within 3% of the ratio or it has timed 20 pairs (--quick; else 60),\n"
    "or --pairs N\n";

// Runs `argv` (found on the PATH) and waits for it: a failure unless it exits 0.
result<bool> run_program(const std::vector<std::string>& argv) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  if (const int e = posix_spawnp(&pid, args[0], nullptr, nullptr, args.data(), environ); e != 0)
    return failure{argv[0] + ": cannot run: " + std::strerror(e)};
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return failure{argv[0] + ": lost: " + std::strerror(errno)};
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) return failure{"the report failed (" + argv[1] + ")"};
  return true;
}

struct config {
  render::technique method;
  std::string scene;  // glass_room, glass_room_17, glass_room_0
  int lights;         // the first this many spot lights of the scene
  render::shadow_mode shadows;
  bool refraction;
  effects force{};  // effects the scene does not use, run anyway to measure what leaving them out saves
};

std::string key(const config& c) {
  std::string forced;
  for (const std::string& e : c.force.names()) forced += "+" + e;
  return std::string(render::technique_name(c.method)) + "/" + c.scene + "/" + std::to_string(c.lights) + "/" + render::shadow_name(c.shadows) + forced +
         "/" + (c.refraction ? "refraction" : "no refraction");
}

// Render targets and bytes a pixel of each technique (Table 4.1), from the layouts it allocates; shadow
// maps are not counted, as in the thesis.
std::pair<int, int> targets_and_bytes(render::technique t) {
  const int gbuffer = thesis_gbuffer::target_count, light = thesis_light_buffer::target_count;
  const int gbuffer_bytes = thesis_gbuffer::bytes_per_pixel, light_bytes = thesis_light_buffer::bytes_per_pixel;
  switch (t) {
    case render::technique::interlaced: return {gbuffer + light, gbuffer_bytes + light_bytes};
    case render::technique::peeling: return {2 * (gbuffer + light), 2 * (gbuffer_bytes + light_bytes)};
    case render::technique::forward:
    case render::technique::forward_depth: {
      int n = 0, bytes = 0;
      for (const target_desc& d : render::forward_targets(t == render::technique::forward_depth)) {
        ++n;
        bytes += info(d.fmt).bytes_per_pixel;
      }
      return {n, bytes};
    }
    case render::technique::reference: {  // the opaque layer, the lists' heads, nodes and tail targets
      int n = gbuffer + light + 1, bytes = gbuffer_bytes + light_bytes + 4 + kbuffer_nodes_per_pixel * kbuffer_node_bytes;
      for (const target_desc& d : kbuffer_tail_targets()) {
        ++n;
        bytes += info(d.fmt).bytes_per_pixel;
      }
      return {n, bytes};
    }
  }
  return {0, 0};
}

// How records name the exact reference (technique reference), which the error figures under "exact" are
// against.
constexpr const char* exact_reference = "exact: every transparent fragment in per-pixel lists, sorted, shaded fully, no refraction";

// The figures of `f` against `exact`, a frame of the exact reference with f's scene and settings, over all
// pixels and over `mask`; where the reference's lists overflowed it is not used: its overflow, no figures.
json exact_errors(const render::frame& f, const render::frame& exact, const std::vector<bool>& mask) {
  if (exact.kbuffer_overflow > 0)
    return {{"overflow", exact.kbuffer_overflow}, {"rmse", nullptr}, {"rmse_transparent", nullptr}, {"flip", nullptr}};
  const render::image_error e = render::compare(f.final_image, exact.final_image, mask);
  return {{"overflow", 0}, {"rmse", e.all.rmse}, {"rmse_transparent", e.masked.rmse}, {"flip", e.all.flip}};
}

// The options of one frame of the exact reference with the settings of `o`: its image is compared, not timed.
render::options exact_options(render::options o) {
  o.method = render::technique::reference;
  o.frames = 1;
  o.force = {};
  return o;
}

// glass_room lit three ways, each light casting shadows, named as the report names them: by 2 of its spot
// lights (as Table 4.3), by a sun alone (a directional light: an orthographic map over the whole scene) and
// by a lamp alone hanging between the shelves (a point light: a cube of six faces in tiles of the map).
std::vector<std::pair<std::string, scene>> shadow_rooms(const scene& room) {
  light sun, lamp;
  sun.kind = light_kind::directional;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  lamp.kind = light_kind::point;
  lamp.position = {0.05f, 2.55f, 0.15f};
  lamp.range = 9.0f;
  std::vector<std::pair<std::string, scene>> rooms = {{"2 spot lights", with_spot_lights(room, 2)}};
  for (light l : {sun, lamp}) {
    l.shadows = true;
    scene alone = with_spot_lights(room, 0);
    alone.lights = {l};
    rooms.push_back({l.kind == light_kind::point ? "a point light" : "a directional light", alone});
  }
  return rooms;
}

// The hair scene seen from `zoom` times closer to the camera's target (S1 measured four zoom levels).
scene zoomed(const scene& s, float zoom) {
  scene out = s;
  out.view.position = s.view.target + (s.view.position - s.view.target) / zoom;
  return out;
}

// S1's table (TECHNIQUES.md): every variant at every k on hair.json at four zooms against the forward
// reference over hair pixels, with weighted blended OIT beside, as result records.
template <class Draw>
result<json> layers_records(const scene& hair, const render::options& base, bool quick, const std::string& backend, Draw&& draw) {
  using L = render::options::layers;
  json records = json::array();
  const std::vector<float> zooms = quick ? std::vector<float>{1.0f} : std::vector<float>{0.75f, 1.0f, 1.5f, 2.5f};
  const std::vector<int> ks = quick ? std::vector<int>{1, 8, 32} : std::vector<int>{1, 2, 4, 8, 16, 32};
  for (float zoom : zooms) {
    const scene s = zoomed(hair, zoom);
    render::options o = base;
    o.kbuffer_variant = L::forward;
    auto reference = draw(s, o);
    if (!reference) return failure{reference.error()};
    std::vector<bool> mask(reference->kbuffer_heads.size());
    for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = reference->kbuffer_heads[i] != 0xffffffffu;
    const render::layer_counts counts = render::count_layers(*reference);
    auto record = [&](L variant, int k, const render::frame& f) {
      const render::image_error e = render::compare(f.final_image, reference->final_image, mask);
      const bool lists = variant != L::wboit;
      // As nvpro's OIT table counts them: the lists' heads and nodes, and the two tail targets.
      const int bytes = (lists ? 4 + kbuffer_nodes_per_pixel * kbuffer_node_bytes : 0) + 8 + 2;
      const double ms = f.pass_ms.at("capture") + f.pass_ms.at("resolve");
      records.push_back(render::with_errors({{"technique", std::string("layers-") + render::layers_name(variant)},
                                             {"scene", "hair"},
                                             {"backend", backend},
                                             {"settings", {{"k", variant == L::deferred || variant == L::tailless ? json(k) : json(nullptr)},
                                                           {"zoom", zoom}, {"hair_pixels", counts.pixels}, {"mean_layers", counts.mean},
                                                           {"width", base.width}, {"height", base.height}, {"frames", f.frames},
                                                           {"overflow", f.kbuffer_overflow}}},
                                             {"frame_ms", f.frame_ms},
                                             {"frame_ms_spread", f.frame_ms_spread},
                                             {"pass_ms", f.pass_ms},
                                             {"layers_ms", ms},
                                             {"bytes_per_pixel", bytes},
                                             {"render_targets", nullptr},
                                             {"reference", "forward reference (every fragment sorted and shaded fully)"},
                                             {"leak_pixels", nullptr}}, e));
    };
    record(L::forward, 64, *reference);
    for (L variant : {L::deferred, L::tailless})
      for (int k : ks) {
        o.kbuffer_variant = variant;
        o.kbuffer_k = k;
        auto f = draw(s, o);
        if (!f) return failure{f.error()};
        record(variant, k, *f);
      }
    for (L variant : {L::cheap, L::wboit}) {
      o.kbuffer_variant = variant;
      auto f = draw(s, o);
      if (!f) return failure{f.error()};
      record(variant, 0, *f);
    }
    std::fprintf(stderr, "hair at zoom %.2f: %zu hair pixels, %.1f layers on average\n", double(zoom), counts.pixels, counts.mean);
  }
  return records;
}

// S2's comparison (TECHNIQUES.md): smoke.json's particles lit per fragment by every light (the reference)
// against light volumes of several grid sizes on each basis: bake time, particle pass time, what the
// particles add to the frame (lighting_ms: the frame less the frame without them, which also counts bake
// work a driver runs under another pass's timestamps), RMSE against the reference on all pixels and on the
// pixels the smoke covers, as result records.
template <class Draw>
result<json> volume_records(const scene& smoke, const render::options& base, bool quick, const std::string& backend, Draw&& draw) {
  using P = render::options::particle_light;
  json records = json::array();
  render::options o = base;
  o.particles = P::forward;
  auto reference = draw(smoke, o);
  if (!reference) return failure{reference.error()};
  scene bare = smoke;
  bare.particles.clear();
  auto without = draw(bare, o);
  if (!without) return failure{without.error()};
  std::vector<bool> mask(std::size_t(o.width) * std::size_t(o.height));
  std::size_t smoke_pixels = 0;
  for (std::size_t i = 0; i < mask.size(); ++i) {
    for (std::size_t c = 0; c < 3; ++c) mask[i] = mask[i] || reference->final_image.rgba[4 * i + c] != without->final_image.rgba[4 * i + c];
    smoke_pixels += mask[i];
  }
  std::size_t particles = 0;
  for (const particle_system& ps : smoke.particles) particles += std::size_t(ps.count);
  auto record = [&](P lighting, int cells, const render::frame& f) {
    const render::image_error e = render::compare(f.final_image, reference->final_image, mask);
    const bool volumes = lighting != P::forward;
    const double bake = volumes ? f.pass_ms.at("bake") : 0.0, particle_ms = f.pass_ms.at("particles");
    records.push_back(render::with_errors({{"technique", std::string("volumes-") + render::particle_light_name(lighting)},
                                           {"scene", "smoke"},
                                           {"backend", backend},
                                           {"settings", {{"cells", volumes ? json(cells) : json(nullptr)},
                                                         {"bytes_per_cell", volumes ? json(render::particle_model(o).bytes_per_cell()) : json(nullptr)},
                                                         {"systems", smoke.particles.size()}, {"particles", particles},
                                                         {"lights", smoke.lights.size()}, {"smoke_pixels", smoke_pixels},
                                                         {"width", base.width}, {"height", base.height}, {"frames", f.frames}}},
                                           {"frame_ms", f.frame_ms},
                                           {"frame_ms_spread", f.frame_ms_spread},
                                           {"pass_ms", f.pass_ms},
                                           {"bake_ms", bake},
                                           {"particles_ms", particle_ms},
                                           {"lighting_ms", f.frame_ms - without->frame_ms},
                                           {"bytes_per_pixel", nullptr},
                                           {"render_targets", nullptr},
                                           {"reference", "forward reference (every particle fragment lit by every light)"},
                                           {"leak_pixels", nullptr}}, e));
  };
  record(P::forward, 0, *reference);
  const std::vector<int> sizes = quick ? std::vector<int>{8, 32} : std::vector<int>{8, 12, 16, 24, 32};
  for (P lighting : {P::six_axes, P::four_axes, P::fourteen_axes, P::moments})
    for (int cells : sizes) {
      o.particles = lighting;
      o.volume_cells = cells;
      auto f = draw(smoke, o);
      if (!f) return failure{f.error()};
      record(lighting, cells, *f);
    }
  std::fprintf(stderr, "smoke: %zu particles over %zu pixels\n", particles, smoke_pixels);
  return records;
}

// `img` at half its size, each pixel the mean of four (a 2x2 box filter, rounded).
render::image halved(const render::image& img) {
  render::image out{img.width / 2, img.height / 2, {}};
  out.rgba.resize(std::size_t(out.width * out.height * 4));
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 4; ++c) {
        int sum = 0;
        for (int j = 0; j < 2; ++j)
          for (int i = 0; i < 2; ++i) sum += img.rgba[std::size_t(((2 * y + j) * img.width + 2 * x + i) * 4 + c)];
        out.rgba[std::size_t((y * out.width + x) * 4 + c)] = std::uint8_t((sum + 2) / 4);
      }
  return out;
}

// S3's post-processing on glass_room (scene "glass_room_post" in the results): each effect's time in a
// chain of all six, and the anti-aliasing's error at glass edges against depth peeling rendered at twice
// the size and box-filtered down (an anti-aliased reference), without it, with S3's plain one and with
// the one aware of the interlace predicate.
template <class Draw>
result<json> post_records(const scene& room, const render::options& base, const std::string& backend, Draw&& draw) {
  json records = json::array();
  using T = render::technique;
  post_effect aa{post_kind::antialias}, bloom{post_kind::bloom}, dof{post_kind::depth_of_field}, blur{post_kind::blur};
  bloom.threshold = 0.7f;
  dof.focus = 6.0f;
  dof.range = 6.0f;
  blur.radius = 2;
  blur.sigma = 1.0f;
  scene s = room;
  s.post = {aa, bloom, dof, blur, post_effect{post_kind::greyscale}, post_effect{post_kind::sepia}};
  render::options o = base;
  auto all = draw(s, o);
  if (!all) return failure{all.error()};
  for (const post_effect& e : s.post) {
    const std::string name = post_name(e.kind);
    records.push_back({{"technique", "post-" + name},
                       {"scene", "glass_room_post"},
                       {"backend", backend},
                       {"settings", {{"width", o.width}, {"height", o.height}, {"frames", all->frames}, {"lights", s.lights.size()}}},
                       {"frame_ms", all->frame_ms},
                       {"frame_ms_spread", all->frame_ms_spread},
                       {"pass_ms", all->pass_ms},
                       {"post_ms", all->pass_ms.at("post " + name)},
                       {"rmse", nullptr},
                       {"rmse_transparent", nullptr},
                       {"ssim", nullptr},
                       {"flip", nullptr}});
  }
  // The anti-aliased reference, and the glass edges: pixels whose 3x3 neighbourhood in the peeled first
  // layer holds both glass and no glass.
  s.post.clear();
  render::options big = o;
  big.method = T::peeling;
  big.width *= 2;
  big.height *= 2;
  big.frames = 1;
  auto fine = draw(s, big);
  if (!fine) return failure{fine.error()};
  const render::image reference = halved(fine->final_image);
  o.method = T::peeling;
  auto peeled = draw(s, o);
  if (!peeled) return failure{peeled.error()};
  const int w = o.width, h = o.height;
  auto glass = [&](int x, int y) {
    x = std::clamp(x, 0, w - 1);
    y = std::clamp(y, 0, h - 1);
    return decode(format::rgba8, peeled->gbuffer[0][std::size_t(y * w + x)]).w < 1.0f;
  };
  std::vector<bool> edges(std::size_t(w * h));
  std::size_t edge_pixels = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      bool some = false, none = false;
      for (int j = -1; j <= 1; ++j)
        for (int i = -1; i <= 1; ++i) (glass(x + i, y + j) ? some : none) = true;
      edges[std::size_t(y * w + x)] = some && none;
      edge_pixels += some && none;
    }
  struct variant {
    const char* name;
    T method;
    std::vector<post_effect> chain;
  };
  post_effect plain = aa;
  plain.interlace = false;
  for (const variant& v : {variant{"interlaced", T::interlaced, {}}, variant{"interlaced+aa", T::interlaced, {plain}},
                           variant{"interlaced+aa-interlace", T::interlaced, {aa}}, variant{"peeling", T::peeling, {}},
                           variant{"peeling+aa", T::peeling, {plain}}}) {
    s.post = v.chain;
    o.method = v.method;
    auto f = draw(s, o);
    if (!f) return failure{f.error()};
    const render::image_error e = render::compare(f->final_image, reference, edges);
    records.push_back(render::with_errors({{"technique", std::string("aa-") + v.name},
                                           {"scene", "glass_room_post"},
                                           {"backend", backend},
                                           {"settings", {{"width", o.width}, {"height", o.height}, {"frames", f->frames}, {"lights", s.lights.size()},
                                                         {"edge_pixels", edge_pixels}}},
                                           {"frame_ms", f->frame_ms},
                                           {"frame_ms_spread", f->frame_ms_spread},
                                           {"pass_ms", f->pass_ms},
                                           {"post_ms", v.chain.empty() ? 0.0 : f->pass_ms.at("post aa")},
                                           {"reference", "depth peeling at twice the size, 2x2 box-filtered"}}, e));
  }
  return records;
}

// The reconstruction sweep on glass_room (scene "glass_room_reconstruct" in the results): each interlace predicate
// with the thesis's partner fetch and with the edge-aware reconstruction, against depth peeling at the
// same settings over all pixels and over the glass the peeled first layer holds.
template <class Draw>
result<json> reconstruct_records(const scene& room, const render::options& base, const std::string& backend, Draw&& draw) {
  json records = json::array();
  render::options o = base;
  o.method = render::technique::peeling;
  auto peeled = draw(room, o);
  if (!peeled) return failure{peeled.error()};
  const std::vector<bool> glass = render::glass_pixels(*peeled);
  auto record = [&](const std::string& technique, const render::options& with, const render::frame& f) {
    const render::image_error e = render::compare(f.final_image, peeled->final_image, glass);
    const bool peeling = with.method == render::technique::peeling;
    const pipeline_plan plan = render::plan_of(room, with).pipeline;
    records.push_back(render::with_errors({{"technique", technique},
                                           {"scene", "glass_room_reconstruct"},
                                           {"backend", backend},
                                           {"settings", {{"predicate", peeling ? json(nullptr) : json(render::predicate_name(with.interlace))},
                                                         {"reconstruction", peeling ? json(nullptr) : json(with.reconstruct ? "edge-aware" : "partner")},
                                                         {"layout", render::layout_name(with.layout)}, {"lights", room.lights.size()}, {"width", with.width},
                                                         {"height", with.height}, {"frames", f.frames}}},
                                           {"frame_ms", f.frame_ms},
                                           {"frame_ms_spread", f.frame_ms_spread},
                                           {"peeling_ms", peeled->frame_ms},
                                           {"bytes_per_pixel", peeling ? 2 * plan.bytes_per_pixel : plan.bytes_per_pixel},  // the plan counts one layer
                                           {"reference", "deferred depth peeling"}}, e));
  };
  record("peeling", o, *peeled);
  o.method = render::technique::interlaced;
  for (render::gbuffer_layout l : {render::gbuffer_layout::thesis, render::gbuffer_layout::compact})
    for (render::predicate p : {render::predicate::rows, render::predicate::columns, render::predicate::checker})
      for (bool reconstruct : {false, true}) {
        o.layout = l;
        o.interlace = p;
        o.reconstruct = reconstruct;
        auto f = draw(room, o);
        if (!f) return failure{f.error()};
        record(std::string("interlaced-") + render::predicate_name(p) + (reconstruct ? "-edge-aware" : "-partner") + "-" +
                   render::layout_name(l),
               o, *f);
      }
  return records;
}

// The light buffer's specular on glass_room with its lights coloured (scene "glass_room_specular"): Table
// 3.2's white specular and the RGB one, in both G-buffer layouts, against depth peeling with RGB specular,
// which keeps every highlight's colour, and against interlacing with RGB specular in the same layout (what
// white specular alone costs). The lights' colours keep a mean of 1, so white specular keeps each
// highlight's brightness and loses only its colour.
template <class Draw>
result<json> specular_records(const scene& room, const render::options& base, const std::string& backend, Draw&& draw) {
  scene coloured = room;
  for (std::size_t i = 0; i < coloured.lights.size(); ++i)
    for (int c = 0; c < 3; ++c)
      coloured.lights[i].colour[c] = 1.0f + 0.8f * std::cos(6.2831853f * (float(i) / float(coloured.lights.size()) + float(c) / 3.0f));
  render::options o = base;
  o.method = render::technique::peeling;
  o.rgb_specular = true;
  auto peeled = draw(coloured, o);
  if (!peeled) return failure{peeled.error()};
  const std::vector<bool> glass = render::glass_pixels(*peeled);
  json records = json::array();
  o.method = render::technique::interlaced;
  const std::vector<bool> everywhere(glass.size(), true);
  for (render::gbuffer_layout l : {render::gbuffer_layout::thesis, render::gbuffer_layout::compact}) {
    o.layout = l;
    std::optional<render::frame> with_rgb;
    for (bool rgb : {true, false}) {
      o.rgb_specular = rgb;
      auto f = draw(coloured, o);
      if (!f) return failure{f.error()};
      if (rgb) with_rgb = *f;
      const render::image_error e = render::compare(f->final_image, peeled->final_image, glass);
      records.push_back(render::with_errors({{"technique", std::string("interlaced-") + (rgb ? "rgb" : "white") + "-" + render::layout_name(l)},
                                             {"scene", "glass_room_specular"},
                                             {"backend", backend},
                                             {"settings", {{"specular", rgb ? "rgb" : "white"}, {"layout", render::layout_name(l)},
                                                           {"lights", coloured.lights.size()}, {"width", o.width}, {"height", o.height},
                                                           {"frames", f->frames}}},
                                             {"frame_ms", f->frame_ms},
                                             {"frame_ms_spread", f->frame_ms_spread},
                                             {"peeling_ms", peeled->frame_ms},
                                             {"bytes_per_pixel", render::plan_of(coloured, o).pipeline.bytes_per_pixel},
                                             {"reference", "deferred depth peeling with RGB specular"},
                                             {"rmse_against_rgb", render::compare(f->final_image, with_rgb->final_image, everywhere).all.rmse}}, e));
    }
  }
  return records;
}

// Soft shadows' error on glass_room lit each way of shadow_rooms (scene "glass_room_shadows"): the hard
// lookup and the 5 x 5 filter against a supersampled reference, a map three times as fine filtered over the
// same width of the scene (15 x 15 texels), over all pixels and over the reference's penumbra: the pixels
// its filter changes, against the same fine map unfiltered, by more than one step of 255.
template <class Draw>
result<json> soft_shadow_records(const scene& room, const render::options& base, const std::string& backend, Draw&& draw) {
  json records = json::array();
  render::options o = base;
  o.shadows = render::shadow_mode::transparent;
  o.refraction = 8.0f;
  for (const auto& [kind, lit] : shadow_rooms(room)) {
    render::options fine = o;
    fine.shadow_size = 3 * o.shadow_size;
    fine.frames = 1;
    auto edges = draw(lit, fine);
    if (!edges) return failure{edges.error()};
    fine.shadow_filter = 15;
    auto reference = draw(lit, fine);
    if (!reference) return failure{reference.error()};
    std::vector<bool> penumbra(std::size_t(o.width * o.height));
    std::size_t penumbra_pixels = 0;
    for (std::size_t i = 0; i < penumbra.size(); ++i) {
      for (std::size_t c = 0; c < 3; ++c)
        penumbra[i] = penumbra[i] || std::abs(int(edges->final_image.rgba[4 * i + c]) - int(reference->final_image.rgba[4 * i + c])) > 1;
      penumbra_pixels += penumbra[i];
    }
    for (int filter : {1, 5}) {
      o.shadow_filter = filter;
      auto f = draw(lit, o);
      if (!f) return failure{f.error()};
      const render::image_error e = render::compare(f->final_image, reference->final_image, penumbra);
      records.push_back(render::with_errors(
          {{"technique", filter == 1 ? "shadows-hard" : "shadows-filtered-5x5"},
           {"scene", "glass_room_shadows"},
           {"backend", backend},
           {"settings", {{"light", kind}, {"shadow_filter", filter}, {"shadow_size", o.shadow_size}, {"lights", lit.lights.size()},
                         {"width", o.width}, {"height", o.height}, {"frames", f->frames}, {"penumbra_pixels", penumbra_pixels}}},
           {"frame_ms", f->frame_ms},
           {"frame_ms_spread", f->frame_ms_spread},
           {"pass_ms", f->pass_ms},
           {"reference", "a map 3x as fine, 15 x 15 texels filtered; masked: its penumbra"}},
          e));
    }
  }
  return records;
}

// glass_shelf.gltf (scene "glass_shelf" in the results), glass as glTF describes it: the thesis's method,
// with the edge-aware reconstruction and with temporal interlacing, against depth peeling, with forward
// rendering beside, transparent shadows from every light and refraction on; errors over all pixels and over
// the glass of the peeled first layer. The "-rough" rows blur refraction through rough glass
// (options::rough_refraction), against peeling that blurs alike.
template <class Draw, class DrawSequence>
result<json> gltf_records(const scene& shelf, const render::options& base, const std::string& backend, Draw&& draw,
                          DrawSequence&& draw_sequence) {
  using T = render::technique;
  render::options o = base;
  o.shadows = render::shadow_mode::transparent;
  o.refraction = 8.0f;
  o.method = T::peeling;
  auto peeled = draw(shelf, o);
  if (!peeled) return failure{peeled.error()};
  render::options rough = o;
  rough.rough_refraction = true;
  auto peeled_rough = draw(shelf, rough);
  if (!peeled_rough) return failure{peeled_rough.error()};
  const std::vector<bool> glass = render::glass_pixels(*peeled);
  const std::size_t triangles = flatten(shelf).indices.size() / 3;
  struct variant {
    const char* name;
    T method;
    bool reconstruct, temporal, rough;
  };
  json records = json::array();
  for (const variant& v : {variant{"interlaced", T::interlaced, false, false, false},
                           variant{"interlaced-edge-aware", T::interlaced, true, false, false},
                           variant{"interlaced-temporal", T::interlaced, true, true, false}, variant{"peeling", T::peeling, false, false, false},
                           variant{"forward-depth", T::forward_depth, false, false, false},
                           variant{"interlaced-rough", T::interlaced, false, false, true},
                           variant{"peeling-rough", T::peeling, false, false, true}}) {
    render::options with = o;
    with.method = v.method;
    with.reconstruct = v.reconstruct;
    with.temporal = v.temporal;
    with.rough_refraction = v.rough;
    const render::frame& reference = v.rough ? *peeled_rough : *peeled;
    result<render::frame> f = failure{""};
    if (v.temporal) {  // a still camera: the last of a few frames, the history filled
      auto frames = draw_sequence(std::vector<scene>(3, shelf), with);
      if (!frames) return failure{frames.error()};
      f = frames->back();
    } else {
      f = v.method == T::peeling ? result<render::frame>(reference) : draw(shelf, with);
    }
    if (!f) return failure{f.error()};
    const render::frame_plan plan = render::plan_of(shelf, with);
    const render::image_error e = render::compare(f->final_image, reference.final_image, glass);
    records.push_back(render::with_errors({{"technique", v.name},
                                           {"scene", "glass_shelf"},
                                           {"backend", backend},
                                           {"settings", {{"lights", shelf.lights.size()}, {"width", with.width}, {"height", with.height},
                                                         {"frames", f->frames}, {"triangles", triangles}, {"rough_refraction", v.rough}}},
                                           {"frame_ms", f->frame_ms},
                                           {"frame_ms_spread", f->frame_ms_spread},
                                           {"pass_ms", f->pass_ms},
                                           {"peeling_ms", reference.frame_ms},
                                           {"bytes_per_pixel", v.method == T::peeling ? 2 * plan.pipeline.bytes_per_pixel : plan.pipeline.bytes_per_pixel},
                                           {"reference", v.rough ? "deferred depth peeling, rough refraction" : "deferred depth peeling"}}, e));
  }
  return records;
}

// Glass with hair or smoke on both sides of it (scenes "hair_panes" and "glass_room_smoke" in the results):
// the thesis's method and (not `quick`) the edge-aware reconstruction against depth peeling, each drawing
// the hair and particles around its glass in depth order, and the exact reference (one frame); errors over
// all pixels and over the glass of the peeled first layer, against peeling and against the exact reference.
template <class Draw>
result<json> around_glass_records(const scene& s, const std::string& name, const render::options& base, bool quick,
                                  const std::string& backend, Draw&& draw) {
  using T = render::technique;
  render::options o = base;
  o.method = T::peeling;
  auto peeled = draw(s, o);
  if (!peeled) return failure{peeled.error()};
  const std::vector<bool> glass = render::glass_pixels(*peeled);
  auto exact = draw(s, exact_options(o));
  if (!exact) return failure{exact.error()};
  json records = json::array();
  for (const char* technique : {"interlaced", "interlaced-edge-aware", "peeling", "reference"}) {
    if (quick && std::string(technique) == "interlaced-edge-aware") continue;  // the glTF section times it
    render::options with = o;
    const std::string named = technique;
    with.method = named == "peeling" ? T::peeling : named == "reference" ? T::reference : T::interlaced;
    with.reconstruct = named == "interlaced-edge-aware";
    auto f = with.method == T::peeling ? result<render::frame>(*peeled) : with.method == T::reference ? result<render::frame>(*exact) : draw(s, with);
    if (!f) return failure{f.error()};
    const render::frame_plan plan = render::plan_of(s, with);
    int bytes = plan.pipeline.bytes_per_pixel;  // peeling keeps a second G-buffer and light buffer, nothing else twice
    for (const planned_target& t : plan.pipeline.targets)
      if (with.method == T::peeling && (t.name.rfind("gbuffer.", 0) == 0 || t.name.rfind("light.", 0) == 0)) bytes += t.bytes_per_pixel;
    if (with.method == T::reference) bytes = targets_and_bytes(T::reference).second;  // its lists, not the glass layers
    records.push_back(render::with_errors(
        {{"technique", technique},
         {"scene", name},
         {"backend", backend},
         {"settings", {{"lights", s.lights.size()}, {"width", with.width}, {"height", with.height}, {"frames", f->frames},
                       {"hair", plan.on.has(effect::many_layers)}, {"particle_systems", s.particles.size()}}},
         {"frame_ms", f->frame_ms},
         {"frame_ms_spread", f->frame_ms_spread},
         {"pass_ms", f->pass_ms},
         {"peeling_ms", peeled->frame_ms},
         {"bytes_per_pixel", bytes},
         {"reference", "deferred depth peeling"},
         {"exact_reference", exact_reference},
         {"exact", exact_errors(*f, *exact, glass)}},
        render::compare(f->final_image, peeled->final_image, glass)));
  }
  return records;
}

// How many frames a paired comparison measures (cli::time_paired): with --quick fewer, and at most
// `max_pairs` where one is given (0: none).
pair_count pairs_of(bool quick, int max_pairs) {
  pair_count c = quick ? pair_count{5, 20, 0.03} : pair_count{15, 60, 0.03};
  if (max_pairs > 0) {
    c.max_frames = max_pairs;
    c.min_frames = std::min(c.min_frames, max_pairs);
  }
  return c;
}

// One side of a paired comparison: its options, how its record names it, and the timers compared (the
// whole frame where none are named).
struct paired_side {
  render::options o;
  json settings;
  std::vector<std::string> timers;
};

// A and B of `s` timed frame against frame (paired.hpp) on `clock`, as a result record (scene `name`): the
// ratio with its 95% interval, the target it is held to (null where none applies), and for each side every
// timer's median, bytes and copy limit (limit.hpp) with the timers B runs as A does (`alike`; where none
// are given, those that move the same bytes on both sides), from which the report bounds the ratio. With
// `without`, each side is what its frame of `s` costs beyond its frame of `without` (cli::difference), in
// time and in bytes.
template <class Clock>
result<json> paired_record(const std::string& comparison, const scene& s, const char* name, const paired_side& a,
                           const paired_side& b, std::optional<std::vector<std::string>> alike, json target, const pair_count& pairs,
                           const std::string& backend, Clock&& clock, limit_meter& meter, const scene* without = nullptr) {
  auto clock_of = [&](const render::options& o) -> result<frame_clock> {
    auto with = clock(s, o);
    if (!with || !without) return with;
    auto bare = clock(*without, o);
    if (!bare) return failure{bare.error()};
    return cli::difference(*with, *bare);
  };
  auto ca = clock_of(a.o);
  if (!ca) return failure{ca.error()};
  auto cb = clock_of(b.o);
  if (!cb) return failure{cb.error()};
  auto r = cli::time_paired(*ca, *cb, 2, pairs, a.timers, b.timers);
  if (!r) return failure{r.error()};
  auto bytes_of = [&](const render::options& o) {
    auto of = [&](const scene& x) {
      const render::frame_plan plan = render::plan_of(x, o);
      return timer_bytes(render::schedule_of(x, plan, o), plan, o);
    };
    auto bytes = of(s);
    if (without)
      for (const auto& [timer, n] : of(*without)) bytes[timer] -= std::min(bytes[timer], n);
    return bytes;
  };
  const auto a_bytes = bytes_of(a.o), b_bytes = bytes_of(b.o);
  auto a_limit = meter.limits(a_bytes);
  if (!a_limit) return failure{a_limit.error()};
  auto b_limit = meter.limits(b_bytes);
  if (!b_limit) return failure{b_limit.error()};
  if (!alike) {
    alike.emplace();
    for (const auto& [timer, n] : a_bytes)
      if (b_bytes.count(timer) && b_bytes.at(timer) == n) alike->push_back(timer);
  }
  return json{{"technique", comparison},
              {"scene", name},
              {"backend", backend},
              {"settings", {{"lights", s.lights.size()}, {"width", a.o.width}, {"height", a.o.height}, {"frames", r->frames}}},
              {"a", a.settings},
              {"b", b.settings},
              {"timers", {{"a", a.timers}, {"b", b.timers}}},
              {"a_ms", r->a_ms},
              {"b_ms", r->b_ms},
              {"ratio", r->ratio},
              {"low", r->low},
              {"high", r->high},
              {"spread", r->spread},
              {"a_pass_ms", r->a_pass_ms},
              {"b_pass_ms", r->b_pass_ms},
              {"a_frame_ms", r->a_frame_ms},
              {"b_frame_ms", r->b_frame_ms},
              {"a_pass_bytes", a_bytes},
              {"b_pass_bytes", b_bytes},
              {"a_limit_ms", *a_limit},
              {"b_limit_ms", *b_limit},
              {"alike", *alike},
              {"rmse", nullptr},
              {"target", target}};
}

// The targets' ratios on glass_room (scene "glass_room_paired"), whole frames, the passes that move the same
// bytes taken as alike.
template <class Clock>
result<json> paired_records(const scene& room, const render::options& base, const std::vector<int>& lights, const pair_count& pairs,
                            const std::string& backend, Clock&& clock, limit_meter& meter) {
  using T = render::technique;
  using S = render::shadow_mode;
  auto with = [&](T t, S shadows, bool refraction) {
    render::options o = base;
    o.method = t;
    o.shadows = shadows;
    o.refraction = refraction ? 8.0f : 0.0f;
    return paired_side{o,
                       {{"technique", render::technique_name(t)}, {"shadows", render::shadow_name(shadows)}, {"refraction", refraction}},
                       {}};
  };
  json records = json::array();
  // `target`: {"at_least" or "at_most": ratio}, or null where no source sets one.
  auto measure_on = [&](const std::string& comparison, const scene& s, const paired_side& a, const paired_side& b,
                        const json& target) -> result<bool> {
    auto r = paired_record(comparison, s, "glass_room_paired", a, b, std::nullopt, target, pairs, backend, clock, meter);
    if (!r) return failure{r.error()};
    records.push_back(*r);
    return true;
  };
  auto measure = [&](const std::string& comparison, int n, const paired_side& a, const paired_side& b, const char* bound,
                     double target, bool applies) {
    return measure_on(comparison, with_spot_lights(room, n), a, b, applies ? json{{bound, target}} : json(nullptr));
  };
  for (int n : lights) {
    if (n > 0)
      if (auto ok = measure("peeling / interlaced, transparent shadows", n, with(T::interlaced, S::transparent, true),
                            with(T::peeling, S::transparent, true), "at_least", 1.6, true);
          !ok)
        return failure{ok.error()};
    if (auto ok = measure("peeling / interlaced, no shadows", n, with(T::interlaced, S::off, true), with(T::peeling, S::off, true),
                          "at_least", 2.0, true);
        !ok)
      return failure{ok.error()};
    if (auto ok = measure("forward-depth / interlaced, no shadows", n, with(T::interlaced, S::off, true),
                          with(T::forward_depth, S::off, true), "at_least", 1.0, n >= 4);
        !ok)
      return failure{ok.error()};
  }
  // Temporal interlacing in the compact layout (24 bytes a pixel) against peeling, at 2 lights, as the
  // temporal benchmark draws it (over the partner fetch).
  paired_side temporal = with(T::interlaced, S::transparent, true);
  temporal.o.temporal = true;
  temporal.o.layout = render::gbuffer_layout::compact;
  temporal.settings["temporal"] = true;
  temporal.settings["layout"] = "compact";
  if (auto ok = measure("peeling / temporal interlaced, transparent shadows", 2, temporal,
                        with(T::peeling, S::transparent, true), "at_least", 1.6, true);
      !ok)
    return failure{ok.error()};
  if (auto ok = measure("refraction / none, no lights", 0, with(T::interlaced, S::off, false), with(T::interlaced, S::off, true),
                        "at_most", 1.05, true);
      !ok)
    return failure{ok.error()};
  for (int n : {2, lights.back()})
    if (auto ok = measure("transparent / opaque shadows", n, with(T::interlaced, S::opaque, true), with(T::interlaced, S::transparent, true),
                          "at_most", n == 2 ? 1.05 : 1.15, n == 2 || n == 64);
        !ok)
      return failure{ok.error()};
  // Beyond the thesis, which measured hard shadows from spot lights only (so no target): each light kind's
  // transparent shadow against its opaque one, hard and averaged over 5 x 5 texels, and what the filter
  // costs at 2 spot lights. The room's ceiling shades its floor from the sun: that row is a cost.
  auto soft = [&](paired_side side) {
    side.o.shadow_filter = 5;
    side.settings["shadow_filter"] = 5;
    return side;
  };
  if (auto ok = measure_on("filtered 5x5 / hard, transparent shadows", with_spot_lights(room, 2), with(T::interlaced, S::transparent, true),
                           soft(with(T::interlaced, S::transparent, true)), nullptr);
      !ok)
    return failure{ok.error()};
  for (const auto& [kind, lit] : shadow_rooms(room)) {
    const paired_side opaque = with(T::interlaced, S::opaque, true), transparent = with(T::interlaced, S::transparent, true);
    if (lit.lights[0].kind != light_kind::spot)  // the spot lights' hard row is Table 4.3's, above
      if (auto ok = measure_on("transparent / opaque shadows, " + kind, lit, opaque, transparent, nullptr); !ok)
        return failure{ok.error()};
    if (auto ok = measure_on("transparent / opaque shadows, filtered 5x5, " + kind, lit, soft(opaque), soft(transparent), nullptr); !ok)
      return failure{ok.error()};
  }
  return records;
}

// S1's and S2's targets, timed in pairs on what the sources compare (scenes "hair_paired" and
// "smoke_paired"): the k-buffer's capture and resolve at k = 8 against shading every fragment at capture
// (with, as "floor", the same for S1's tailless variant),
// and what lighting the particles from a light volume adds to a frame against lighting every particle
// fragment (each side's frame less its frame without particles: llvmpipe runs a dispatch under the
// timestamps of the draw before it, so the bake's own timer misses most of the bake), at the setting of
// `volumes` (this backend's volume records) that is fastest at RMSE at most 5, or the most accurate where
// none is; each with its RMSE from `layers` and `volumes`. Alike: the k-buffer's capture, one program for
// every list variant (only the resolve tells them apart); no pass of the light volumes, whose particle
// shaders differ.
template <class Clock>
result<json> technique_pairs(const scene& hair, const scene& smoke, const json& layers, const json& volumes,
                             const render::options& base, const pair_count& pairs, const std::string& backend, Clock&& clock,
                             limit_meter& meter) {
  using L = render::options::layers;
  using P = render::options::particle_light;
  json records = json::array();
  render::options every = base, kbuffer = base;
  every.kbuffer_variant = L::forward;
  kbuffer.kbuffer_variant = L::deferred;
  kbuffer.kbuffer_k = 8;
  const auto k8 = std::find_if(layers.begin(), layers.end(), [](const json& r) {
    return r["technique"] == "layers-deferred" && r["settings"]["k"] == 8 && r["settings"]["zoom"] == 1.0;
  });
  if (k8 == layers.end()) return failure{"no k-buffer run at k = 8"};
  const std::vector<std::string> capture{"capture", "resolve"};
  auto hair_pair = paired_record("forward / k-buffer, capture and resolve", zoomed(hair, 1.0f), "hair_paired",
                                 {kbuffer, {{"technique", "layers-deferred"}, {"k", 8}}, capture},
                                 {every, {{"technique", "layers-forward"}}, capture}, std::vector<std::string>{"capture"},
                                 {{"at_least", 2.0}, {"rmse_at_most", 9.0}}, pairs, backend, clock, meter);
  if (!hair_pair) return failure{hair_pair.error()};
  (*hair_pair)["rmse"] = (*k8)["rmse_transparent"];
  // The technique's floor at k = 8: S1's tailless, which shades no tail at all, against the same reference
  // timed the same way. The capture both share and the core's full shading bound the ratio there.
  render::options tailless = kbuffer;
  tailless.kbuffer_variant = L::tailless;
  auto floor = paired_record("forward / k-buffer tailless", zoomed(hair, 1.0f), "hair_paired",
                             {tailless, {{"technique", "layers-tailless"}, {"k", 8}}, capture},
                             {every, {{"technique", "layers-forward"}}, capture}, std::vector<std::string>{"capture"}, nullptr, pairs,
                             backend, clock, meter);
  if (!floor) return failure{floor.error()};
  (*hair_pair)["floor"] = {{"technique", "layers-tailless"}, {"ratio", (*floor)["ratio"]}, {"low", (*floor)["low"]}, {"high", (*floor)["high"]}};
  records.push_back(*hair_pair);
  // Fits (RMSE and bytes a cell) before not, then faster (fits) or more accurate; a run the frames' noise
  // left adding nothing is not timed, so never chosen.
  const double rmse_at_most = 5.0, bytes_at_most = 20.0;
  auto fit = [&](const json& r) {
    return r["rmse"].template get<double>() <= rmse_at_most && r["settings"]["bytes_per_cell"].template get<double>() <= bytes_at_most;
  };
  auto better = [&](const json& r, const json* than) {
    if (r["lighting_ms"].template get<double>() <= 0.0) return false;
    if (!than) return true;
    const bool fits = fit(r), was = fit(*than);
    if (fits != was) return fits;
    return fits ? r["lighting_ms"] < (*than)["lighting_ms"] : r["rmse"] < (*than)["rmse"];
  };
  const json* chosen = nullptr;
  for (const json& r : volumes)
    if (r["technique"] != "volumes-forward" && better(r, chosen)) chosen = &r;
  if (!chosen) return failure{"no light volume run added time to its frame"};
  render::options lit = base, volume = base;
  lit.particles = P::forward;
  for (P p : {P::six_axes, P::four_axes, P::fourteen_axes, P::moments})
    if ((*chosen)["technique"] == std::string("volumes-") + render::particle_light_name(p)) volume.particles = p;
  volume.volume_cells = (*chosen)["settings"]["cells"].template get<int>();
  scene bare = smoke;
  bare.particles.clear();
  auto smoke_pair = paired_record("per-fragment / light volumes, the frame beyond one without particles", smoke, "smoke_paired",
                                  {volume, {{"technique", (*chosen)["technique"]}, {"cells", volume.volume_cells}}, {}},
                                  {lit, {{"technique", "volumes-forward"}}, {}}, std::vector<std::string>{},
                                  {{"at_least", 7.0}, {"rmse_at_most", rmse_at_most}, {"bytes_per_cell_at_most", bytes_at_most}},
                                  pairs, backend, clock, meter, &bare);
  if (!smoke_pair) return failure{smoke_pair.error()};
  (*smoke_pair)["rmse"] = (*chosen)["rmse"];
  (*smoke_pair)["bytes_per_cell"] = (*chosen)["settings"]["bytes_per_cell"];
  records.push_back(*smoke_pair);
  return records;
}

}  // namespace

int bench(std::vector<std::string> args) {
  if (!args.empty() && (args[0] == "--help" || args[0] == "-h")) {
    std::fputs(usage, stdout);
    return 0;
  }
  try {
    const std::string device = take_option(args, "--device", "");
    if (device == "list") {
      std::fputs(device_list().c_str(), stdout);
      return 0;
    }
    const std::string out = take_option(args, "--out", "");
    const std::string backend = take_option(args, "--backend", "gl");
    const bool backend_only = take_flag(args, "--backend-only");
    const bool quick = take_flag(args, "--quick");
    render::options base;
    base.opaque_shadows_depth_only = true;  // scene_geometry's parts tell opaque surfaces from the rest
    base.width = to_int(take_option(args, "--width", quick ? "320" : "640"), 1, 8192, "--width");
    base.height = to_int(take_option(args, "--height", quick ? "180" : "360"), 1, 8192, "--height");
    base.shadow_size = to_int(take_option(args, "--shadow-size", quick ? "256" : "512"), 16, 8192, "--shadow-size");
    base.frames = to_int(take_option(args, "--frames", quick ? "5" : "9"), 1, 1000, "--frames");
    const std::string max_pairs = take_option(args, "--pairs", "");
    const pair_count pairs = pairs_of(quick, max_pairs.empty() ? 0 : to_int(max_pairs, 1, 1000, "--pairs"));
    for (const std::string& a : operands(args)) throw usage_error{"unknown argument '" + a + "'"};
    if (out.empty()) throw usage_error{"bench needs --out DIR"};
    if (backend != "gl" && backend != "vk") throw usage_error{"--backend must be gl or vk"};
    const auto shipped = shipped_files();  // the scenes and the report script
    if (!shipped) {
      std::fprintf(stderr, "dstrans bench: %s\n", shipped.error().c_str());
      return 1;
    }
    // Checked before the minutes of measuring; results.json and the report replace the previous run's
    // only once all of them are written (bench.json lists them).
    auto dir = output_dir::open(out, "bench.json");
    if (!dir) {
      std::fprintf(stderr, "dstrans bench: %s\n", dir.error().c_str());
      return 1;
    }
    auto g = open_gpu(backend, device);
    if (!g) {
      std::fprintf(stderr, "dstrans bench: %s\n", g.error().c_str());
      return 1;
    }
    // Each pass's limit: a copy of its bytes on the same device, measured in this run.
    limit_meter meter([&]() -> copy_clock {
#ifdef DSTRANS_HAVE_GL
      if ((*g)->gl) return render::gl_copy_clock();
#endif
#ifdef DSTRANS_HAVE_VK
      if ((*g)->vk) return render::vk_copy_clock(*(*g)->vk);
#endif
      return [](std::size_t) -> result<double> { return failure{"no backend"}; };
    }());
    std::map<std::string, std::pair<std::string, std::string>> ran_on{{backend, {(*g)->device, (*g)->driver}}};
    std::map<std::string, scene> scenes;
    for (const char* name : {"glass_room", "glass_room_17", "glass_room_0"}) {
      auto s = load_scene(*shipped + "/scenes/" + name + ".json");
      if (!s) {
        std::fprintf(stderr, "dstrans bench: %s\n", s.error().c_str());
        return 1;
      }
      scenes[name] = *s;
    }

    // The sweep: each table's comparisons, without repeats.
    const std::vector<int> lights = quick ? std::vector<int>{0, 2, 8, 32} : std::vector<int>{0, 2, 4, 8, 16, 32, 64};
    using T = render::technique;
    using S = render::shadow_mode;
    std::vector<config> configs;
    std::map<std::string, bool> seen;
    auto add = [&](config c) {
      if (!seen[key(c)]) configs.push_back(c);
      seen[key(c)] = true;
    };
    for (int n : lights) {
      add({T::interlaced, "glass_room", n, S::off, true});  // Table 4.2
      add({T::interlaced, "glass_room", n, S::off, false});
      if (n > 0) {
        add({T::interlaced, "glass_room", n, S::opaque, true});  // Table 4.3
        add({T::interlaced, "glass_room", n, S::transparent, true});
      }
      for (T t : {T::peeling, T::forward, T::forward_depth})  // Tables 4.4, 4.5
        for (S sh : n > 0 ? std::vector<S>{S::off, S::transparent} : std::vector<S>{S::off}) add({t, "glass_room", n, sh, true});
    }
    const int fixed = quick ? 8 : 16;  // Tables 4.6, 4.7
    for (const char* name : {"glass_room", "glass_room_17", "glass_room_0"})
      for (S sh : {S::off, S::transparent}) add({T::interlaced, name, fixed, sh, true});
    // What an effect glass_room_0 does not use would cost (DESIGN.md principle 5): each one forced in.
    for (effect e : {effect::transparency, effect::refraction, effect::transparent_shadows})
      add({T::interlaced, "glass_room_0", fixed, S::transparent, true, effects{}.with(e)});

    const bool tty = isatty(fileno(stderr));
    std::map<std::string, render::frame> references;
    json results = json::array();
    for (std::size_t k = 0; k < configs.size(); ++k) {
      const config& c = configs[k];
      const scene s = with_spot_lights(scenes.at(c.scene), c.lights);
      auto options_of = [&](render::technique t) {
        render::options o = base;
        o.method = t;
        o.shadows = c.shadows;
        o.refraction = c.refraction ? 8.0f : 0.0f;
        o.force = t == c.method ? c.force : effects{};
        return o;
      };
      auto run = [&](render::technique t) -> result<render::frame> {
        const render::options o = t == T::reference ? exact_options(options_of(t)) : options_of(t);
#ifdef DSTRANS_HAVE_GL
        if ((*g)->gl) return render::run_gl(s, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
        if ((*g)->vk) return render::run_vk(*(*g)->vk, s, o, pass_shaders());
#endif
        return failure{"no backend"};
      };
      auto f = run(c.method);
      if (!f) {
        std::fprintf(stderr, "dstrans bench: %s: %s\n", key(c).c_str(), f.error().c_str());
        return 1;
      }
      // The reference: deferred depth peeling with the same lights, shadows and refraction.
      config rc = c;
      rc.method = T::peeling;
      rc.force = {};
      if (!references.count(key(rc))) {
        auto ref = c.method == T::peeling ? f : run(T::peeling);
        if (!ref) {
          std::fprintf(stderr, "dstrans bench: %s: %s\n", key(rc).c_str(), ref.error().c_str());
          return 1;
        }
        references[key(rc)] = *ref;
      }
      const render::frame& ref = references.at(key(rc));
      // The exact reference with the same lights and shadows (it never refracts), one frame.
      config ec = rc;
      ec.method = T::reference;
      ec.refraction = false;
      if (!references.count(key(ec))) {
        auto exact = run(T::reference);
        if (!exact) {
          std::fprintf(stderr, "dstrans bench: %s: %s\n", key(ec).c_str(), exact.error().c_str());
          return 1;
        }
        references[key(ec)] = *exact;
      }
      // Leak pixels: techniques that reject by depth have none by construction; forward rendering without
      // depth is measured against the buffers of its depth variant at the same settings.
      json leak_pixels = {{"foreground_accepted", 0}, {"background_rejected", 0}};
      if (c.method == T::forward && c.refraction) {
        config dc = c;
        dc.method = T::forward_depth;
        if (!references.count(key(dc))) {
          auto d = run(T::forward_depth);
          if (!d) {
            std::fprintf(stderr, "dstrans bench: %s: %s\n", key(dc).c_str(), d.error().c_str());
            return 1;
          }
          references[key(dc)] = *d;
        }
        render::options o = base;
        o.refraction = 8.0f;
        const render::leaks l = render::count_leaks(references.at(key(dc)), s, o);
        leak_pixels = {{"foreground_accepted", l.foreground_accepted}, {"background_rejected", l.background_rejected}};
      }
      const std::vector<bool> glass = render::glass_pixels(ref);
      const render::image_error e = render::compare(f->final_image, ref.final_image, glass);
      const auto [targets, bytes] = targets_and_bytes(c.method);
      // The memory of the plan's targets at this size (the interlaced pipeline's plan; others by their tables).
      const pipeline_plan plan = render::plan_of(s, options_of(c.method)).pipeline;
      std::int64_t memory = 0;
      for (const planned_target& t : plan.targets)
        if (!t.volume)  // the volume atlas is sized by particle systems, which these scenes do not have
          memory += std::int64_t(t.bytes_per_pixel) *
                  (t.shadow_map ? std::int64_t(base.shadow_size) * base.shadow_size : std::int64_t(base.width) * base.height);
      const render::frame_plan ran = render::plan_of(s, options_of(c.method));
      const auto moved = timer_bytes(render::schedule_of(s, ran, options_of(c.method)), ran, options_of(c.method));
      auto limit = meter.limits(moved);
      if (!limit) {
        std::fprintf(stderr, "dstrans bench: the copies on %s: %s\n", backend.c_str(), limit.error().c_str());
        return 1;
      }
      json rec = render::with_errors({{"technique", render::technique_name(c.method)},
                                      {"scene", c.scene},
                                      {"backend", backend},
                                      {"settings", {{"lights", c.lights}, {"shadows", render::shadow_name(c.shadows)}, {"refraction", c.refraction},
                                                    {"width", base.width}, {"height", base.height}, {"shadow_size", base.shadow_size},
                                                    {"frames", f->frames},
                                                    {"forced", c.force.names()}}},
                                      {"effects", render::plan_of(s, options_of(c.method)).on.names()},
                                      {"triangles", flatten(s).indices.size() / 3},
                                      {"memory_bytes", c.method == T::interlaced ? json(memory) : json(nullptr)},
                                      {"frame_ms", f->frame_ms},
                                      {"frame_ms_spread", f->frame_ms_spread},
                                      {"pass_ms", f->pass_ms},
                                      {"pass_bytes", moved},
                                      {"limit_ms", *limit},
                                      {"bytes_per_pixel", bytes},
                                      {"render_targets", targets},
                                      {"reference", "deferred depth peeling"},
                                      {"exact_reference", exact_reference},
                                      {"exact", exact_errors(*f, references.at(key(ec)), glass)},
                                      {"leak_pixels", leak_pixels}}, e);
      results.push_back(rec);
      std::fprintf(stderr, "%s[%zu/%zu] %s: %.2f ms, RMSE %.2f%s", tty ? "\r\033[K" : "", k + 1, configs.size(), key(c).c_str(),
                   f->frame_ms, e.all.rmse, tty ? "" : "\n");
    }
    if (tty) std::fputc('\n', stderr);
    auto clock = [&](const scene& s, const render::options& o) -> result<frame_clock> {
#ifdef DSTRANS_HAVE_GL
      if ((*g)->gl) return render::gl_clock({s}, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
      if ((*g)->vk) return render::vk_clock(*(*g)->vk, {s}, o, pass_shaders());
#endif
      return failure{"no backend"};
    };
    auto paired = paired_records(scenes.at("glass_room"), base, lights, pairs, backend, clock, meter);
    if (!paired) {
      std::fprintf(stderr, "dstrans bench: paired runs on %s: %s\n", backend.c_str(), paired.error().c_str());
      return 1;
    }
    for (const json& r : *paired) results.push_back(r);
    // S1: many layers on hair.json, S2: light volumes on smoke.json, and the glTF scene, on this backend
    // and on the other where the machine has it.
    auto hair = load_scene(*shipped + "/scenes/hair.json");
    auto smoke = load_scene(*shipped + "/scenes/smoke.json");
    auto shelf = load_scene(*shipped + "/scenes/glass_shelf.gltf");
    auto hair_panes = load_scene(*shipped + "/scenes/hair_panes.json");
    auto room_smoke = load_scene(*shipped + "/scenes/glass_room_smoke.json");
    for (const auto* loaded : {&hair, &smoke, &shelf, &hair_panes, &room_smoke})
      if (!*loaded) {
        std::fprintf(stderr, "dstrans bench: %s\n", loaded->error().c_str());
        return 1;
      }
    {  // glass_shelf.gltf: peeling over interlacing, timed in pairs as the targets are (no source sets one)
      render::options o = base;
      o.shadows = S::transparent;
      o.refraction = 8.0f;
      const json settings = {{"shadows", "transparent"}, {"refraction", true}};
      paired_side interlaced{o, settings, {}}, peeling{o, settings, {}};
      interlaced.settings["technique"] = "interlaced";
      peeling.o.method = T::peeling;
      peeling.settings["technique"] = "peeling";
      // What blurring refraction through rough glass costs: the compose pass alone differs.
      paired_side rough = interlaced;
      rough.o.rough_refraction = true;
      rough.settings["rough_refraction"] = true;
      for (auto [comparison, a, b] : {std::tuple{"peeling / interlaced, transparent shadows", &interlaced, &peeling},
                                      std::tuple{"rough / sharp refraction, interlaced", &interlaced, &rough}}) {
        auto r = paired_record(comparison, *shelf, "glass_shelf_paired", *a, *b, std::nullopt, nullptr, pairs, backend, clock, meter);
        if (!r) {
          std::fprintf(stderr, "dstrans bench: glass_shelf.gltf in pairs on %s: %s\n", backend.c_str(), r.error().c_str());
          return 1;
        }
        results.push_back(*r);
      }
    }
    std::vector<std::pair<std::string, std::string>> strips;  // the temporal benchmark's crops, a PNG a backend
    std::vector<std::string> section_backends{backend};
    if (!backend_only) section_backends.push_back(backend == "gl" ? "vk" : "gl");
    for (const std::string& b : section_backends) {
      auto other = b == backend ? result<std::unique_ptr<gpu>>(failure{"unused"}) : open_gpu(b, device);
      if (b != backend && !other) {
        std::fprintf(stderr, "dstrans bench: hair, smoke and post-processing on %s skipped: %s\n", b.c_str(), other.error().c_str());
        continue;
      }
      const gpu& on = b == backend ? **g : **other;
      ran_on[b] = {on.device, on.driver};
      auto draw = [&](const scene& s, const render::options& o) -> result<render::frame> {
#ifdef DSTRANS_HAVE_GL
        if (on.gl) return render::run_gl(s, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
        if (on.vk) return render::run_vk(*on.vk, s, o, pass_shaders());
#endif
        return failure{"no backend"};
      };
      auto draw_sequence = [&](const std::vector<scene>& frames, const render::options& o) -> result<std::vector<render::frame>> {
#ifdef DSTRANS_HAVE_GL
        if (on.gl) return render::run_gl_sequence(frames, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
        if (on.vk) return render::run_vk_sequence(*on.vk, frames, o, pass_shaders());
#endif
        return failure{"no backend"};
      };
      auto clock_sequence = [&](const std::vector<scene>& frames, const render::options& o) -> result<frame_clock> {
#ifdef DSTRANS_HAVE_GL
        if (on.gl) return render::gl_clock(frames, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
        if (on.vk) return render::vk_clock(*on.vk, frames, o, pass_shaders());
#endif
        return failure{"no backend"};
      };
      auto layers = layers_records(*hair, base, quick, b, draw);
      if (!layers) {
        std::fprintf(stderr, "dstrans bench: hair on %s: %s\n", b.c_str(), layers.error().c_str());
        return 1;
      }
      for (const json& r : *layers) results.push_back(r);
      auto volumes = volume_records(*smoke, base, quick, b, draw);
      if (!volumes) {
        std::fprintf(stderr, "dstrans bench: smoke on %s: %s\n", b.c_str(), volumes.error().c_str());
        return 1;
      }
      for (const json& r : *volumes) results.push_back(r);
      if (b == backend) {
        auto technique_paired = technique_pairs(*hair, *smoke, *layers, *volumes, base, pairs, b, clock, meter);
        if (!technique_paired) {
          std::fprintf(stderr, "dstrans bench: hair and smoke in pairs on %s: %s\n", b.c_str(), technique_paired.error().c_str());
          return 1;
        }
        for (const json& r : *technique_paired) results.push_back(r);
      }
      render::options post_base = base;
      post_base.refraction = 8.0f;
      auto post = post_records(with_spot_lights(scenes.at("glass_room"), fixed), post_base, b, draw);
      if (!post) {
        std::fprintf(stderr, "dstrans bench: post-processing on %s: %s\n", b.c_str(), post.error().c_str());
        return 1;
      }
      for (const json& r : *post) results.push_back(r);
      render::options shadowed = post_base;
      shadowed.shadows = render::shadow_mode::transparent;
      auto layers_sweep = reconstruct_records(with_spot_lights(scenes.at("glass_room"), fixed), shadowed, b, draw);
      if (!layers_sweep) {
        std::fprintf(stderr, "dstrans bench: reconstruction on %s: %s\n", b.c_str(), layers_sweep.error().c_str());
        return 1;
      }
      for (const json& r : *layers_sweep) results.push_back(r);
      auto specular = specular_records(with_spot_lights(scenes.at("glass_room"), fixed), shadowed, b, draw);
      if (!specular) {
        std::fprintf(stderr, "dstrans bench: specular on %s: %s\n", b.c_str(), specular.error().c_str());
        return 1;
      }
      for (const json& r : *specular) results.push_back(r);
      auto gltf = gltf_records(*shelf, base, b, draw, draw_sequence);
      if (!gltf) {
        std::fprintf(stderr, "dstrans bench: glass_shelf.gltf on %s: %s\n", b.c_str(), gltf.error().c_str());
        return 1;
      }
      for (const json& r : *gltf) results.push_back(r);
      for (const auto& [name, s] : {std::pair<const char*, scene>{"hair_panes", *hair_panes},
                                    std::pair<const char*, scene>{"glass_room_smoke", with_spot_lights(*room_smoke, fixed)}}) {
        auto around = around_glass_records(s, name, shadowed, quick, b, draw);
        if (!around) {
          std::fprintf(stderr, "dstrans bench: %s on %s: %s\n", name, b.c_str(), around.error().c_str());
          return 1;
        }
        for (const json& r : *around) results.push_back(r);
      }
      auto soft = soft_shadow_records(scenes.at("glass_room"), base, b, draw);
      if (!soft) {
        std::fprintf(stderr, "dstrans bench: soft shadows on %s: %s\n", b.c_str(), soft.error().c_str());
        return 1;
      }
      for (const json& r : *soft) results.push_back(r);
      auto temporal = temporal_records(with_spot_lights(scenes.at("glass_room"), fixed), shadowed, quick ? 6 : 24, b, draw_sequence,
                                       clock_sequence, pairs);
      if (!temporal) {
        std::fprintf(stderr, "dstrans bench: temporal interlacing on %s: %s\n", b.c_str(), temporal.error().c_str());
        return 1;
      }
      for (const json& r : temporal->records) results.push_back(r);
      strips.push_back({"temporal_" + b + ".png", render::png_bytes(temporal->strip)});
    }
    for (json& r : results) {
      const auto& [name, driver] = ran_on.at(r["backend"].get<std::string>());
      r["device"] = name;
      r["driver"] = driver;
      // A CPU rasteriser's speed scales with them; 0 where the standard library cannot tell.
      r["host_threads"] = std::thread::hardware_concurrency();
    }
    auto written = dir->add("results.json", results.dump(1) + "\n");
    for (const auto& [name, png] : strips)
      if (written) written = dir->add(name, png);
    // report.md and the plot come from results.json alone (bench/report.py, matplotlib); Debian's python3
    // has matplotlib, so it is preferred over another python3 earlier on the PATH. It runs from an
    // argument vector, so no path is ever read by a shell.
    const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
    if (written)
      written = run_program({python, *shipped + "/report.py", dir->staging() + "/results.json",
                             dir->staging()});
    if (written) written = dir->adopt();
    if (written) written = dir->commit();
    if (!written) {
      std::fprintf(stderr, "dstrans bench: %s; nothing was written into %s\n", written.error().c_str(), out.c_str());
      return 1;
    }
    std::printf("dstrans bench: %zu runs on %s: %s/results.json, report.md, accuracy_vs_time.png\n", results.size(),
                backend.c_str(), out.c_str());
    return 0;
  } catch (const usage_error& e) {
    std::fprintf(stderr, "dstrans bench: %s\n%s", e.message.c_str(), usage);
    return 2;
  }
}

}  // namespace dstrans::cli
