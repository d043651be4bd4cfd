// dstrans render: one frame of a scene on a backend, with its buffers and pass times (DESIGN.md).
#include <algorithm>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "gpu.hpp"
#include <dstrans/frame/passes.hpp>
#ifdef DSTRANS_HAVE_GL
#include "run_gl.hpp"
#endif
#ifdef DSTRANS_HAVE_VK
#include "run_vk.hpp"
#endif
#include "scene_json.hpp"

namespace dstrans::cli {

namespace {
const char* const usage =
    "usage: dstrans render <scene.json|.gltf|.glb> --backend gl|vk --out DIR [--width W --height H] [--technique NAME]\n"
    "       [--refraction PIXELS] [--shadows off|opaque|transparent] [--shadow-size N]\n"
    "       [--shadow-bias FRACTION]   a receiver moves this fraction of its distance from the light towards it\n"
    "                           before the shadow test, in linear depth (default 0.005; 0 to 1), so shadows keep\n"
    "                           their shape when a scene is scaled\n"
    "       [--shadow-filter N]   soft shadows: Eq. 3.1 averaged over N x N texels of the map (odd, 1 to 15;\n"
    "                           default 1, hard shadows), each texel paired with its own interlace partner\n"
    "       [--frames N]   render N frames with the same resources; pass times are their medians\n"
    "       [--transmittance thesis|physical]   light through glass: min(I_L, C) (Eq. 3.2) or I_L C\n"
    "       [--float-targets]   light buffers and the final image in RGBA32F: no saturation, NaN kept\n"
    "       [--specular white|rgb]   the light buffer's specular: Table 3.2's one number (4 bytes a pixel), or\n"
    "                           RGB, a coloured light's highlight in its colour (8 bytes)\n"
    "       [--k N] [--layers forward|deferred|tailless|cheap|wboit]   hair (S1): fragments shaded fully, and\n"
    "                           the rest (wboit: weighted blended OIT instead of lists)\n"
    "       [--kbuffer-nodes N]   the per-pixel lists' pool, in nodes (default 16 a pixel); fragments past it\n"
    "                           are blended out of order and counted (frame.json's kbuffer.overflow)\n"
    "       [--particles six-axes|four-axes|fourteen-axes|moments|forward] [--volume-cells N]   particle\n"
    "                           systems (S2): lit from light volumes of N (1 to 64) cells a side on six,\n"
    "                           four or fourteen axes or from the light's moments, or per fragment (the reference)\n"
    "       [--post CHAIN.json]   post-processing after the frame: {\"post\": [...]} as in scene files, in\n"
    "                           place of the scene's own chain (deferred techniques)\n"
    "       [--interlace rows|columns|checker] [--reconstruct partner|edge-aware]   the interlaced G-buffer's\n"
    "                           predicate, and how the compose pass finds a pixel's other layer\n"
    "       [--temporal on|off]   temporal interlacing: the rows that keep glass alternate every frame and the\n"
    "                           compose pass takes a pixel's other layer from the previous frame where it is\n"
    "                           still there (with --frames 2 or more; doubles the G-buffer's bytes)\n"
    "       [--rough-refraction on|off]   rough glass blurs what it refracts, by the roughness its Phong exponent\n"
    "                           says (2 / r^4 - 2, as glTF's roughness is read; 255: clear); up to 15 samples a\n"
    "                           glass pixel (deferred techniques; default off)\n"
    "       [--layout thesis|compact]   the G-buffer: Table 3.1's 16 bytes, or 8 with depth from the attachment\n"
    "       [--budget MIB]   the memory a scene and its frame may take (default 1024), estimated before anything\n"
    "                           is built; a larger scene is refused with its estimate\n"
    "       [--device N|NAME]   the GPU: by index or part of its name (Vulkan's physical devices, EGL's devices);\n"
    "                           `dstrans render --device list` lists them\n"
    "techniques: interlaced (the thesis's single-layer method), peeling (deferred depth peeling, 4.1.2),\n"
    "            forward, forward-depth (multi-pass forward, refraction checked by alpha or depth, 4.1.3),\n"
    "            reference (exact: every transparent fragment sorted per pixel and shaded fully, no refraction)\n"
    "writes DIR/final.png (after the chain), a PNG per buffer and per effect (post_NAME.png), and DIR/frame.json\n"
    "(which lists them); files are written whole and moved in at the end, and only an earlier run's are replaced\n";
}  // namespace

int render(std::vector<std::string> args) {
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
    const std::string backend = take_option(args, "--backend", "");
    const std::string out = take_option(args, "--out", "");
    const std::string post_file = take_option(args, "--post", "");
    const std::string technique = take_option(args, "--technique", "interlaced");
    render::options o;
    o.opaque_shadows_depth_only = true;  // scene_geometry's parts tell opaque surfaces from the rest
    o.width = to_int(take_option(args, "--width", "320"), 1, 8192, "--width");
    o.height = to_int(take_option(args, "--height", "180"), 1, 8192, "--height");
    o.refraction = float(to_int(take_option(args, "--refraction", "8"), 0, 256, "--refraction"));
    o.shadow_size = to_int(take_option(args, "--shadow-size", "1024"), 16, 8192, "--shadow-size");
    o.shadow_filter = to_int(take_option(args, "--shadow-filter", "1"), 1, 15, "--shadow-filter");
    if (o.shadow_filter % 2 == 0) throw usage_error{"--shadow-filter must be odd (the receiver's texel and as many on each side)"};
    o.frames = to_int(take_option(args, "--frames", "1"), 1, 1000, "--frames");
    o.kbuffer_k = to_int(take_option(args, "--k", "8"), 1, 32, "--k");
    o.kbuffer_nodes = std::uint32_t(to_int(take_option(args, "--kbuffer-nodes", "0"), 0, 1 << 30, "--kbuffer-nodes"));
    const std::string layers = take_option(args, "--layers", "deferred");
    if (layers == "forward") o.kbuffer_variant = render::options::layers::forward;
    else if (layers == "tailless") o.kbuffer_variant = render::options::layers::tailless;
    else if (layers == "cheap") o.kbuffer_variant = render::options::layers::cheap;
    else if (layers == "wboit") o.kbuffer_variant = render::options::layers::wboit;
    else if (layers != "deferred")
      throw usage_error{"--layers must be forward, deferred, tailless, cheap or wboit, not '" + layers + "'"};
    const std::string particles = take_option(args, "--particles", "six-axes");
    if (particles == "four-axes") o.particles = render::options::particle_light::four_axes;
    else if (particles == "fourteen-axes") o.particles = render::options::particle_light::fourteen_axes;
    else if (particles == "moments") o.particles = render::options::particle_light::moments;
    else if (particles == "forward") o.particles = render::options::particle_light::forward;
    else if (particles != "six-axes")
      throw usage_error{"--particles must be six-axes, four-axes, fourteen-axes, moments or forward, not '" + particles + "'"};
    const std::string predicate = take_option(args, "--interlace", "rows");
    if (predicate == "columns") o.interlace = render::predicate::columns;
    else if (predicate == "checker") o.interlace = render::predicate::checker;
    else if (predicate != "rows") throw usage_error{"--interlace must be rows, columns or checker, not '" + predicate + "'"};
    const std::string layout = take_option(args, "--layout", "thesis");
    if (layout == "compact") o.layout = render::gbuffer_layout::compact;
    else if (layout != "thesis") throw usage_error{"--layout must be thesis or compact, not '" + layout + "'"};
    const std::string reconstruct = take_option(args, "--reconstruct", "partner");
    if (reconstruct == "edge-aware") o.reconstruct = true;
    else if (reconstruct != "partner") throw usage_error{"--reconstruct must be partner or edge-aware, not '" + reconstruct + "'"};
    o.temporal = take_on_off(args, "--temporal", false);
    o.rough_refraction = take_on_off(args, "--rough-refraction", false);
    o.volume_cells = to_int(take_option(args, "--volume-cells", "16"), 1, 64, "--volume-cells");
    const std::string bias = take_option(args, "--shadow-bias", "");
    try {
      std::size_t used = 0;
      if (!bias.empty()) o.shadow_bias = std::stof(bias, &used);
      if (used != bias.size() || !(o.shadow_bias >= 0.0f && o.shadow_bias <= 1.0f)) throw std::invalid_argument(bias);
    } catch (const std::exception&) {
      throw usage_error{"--shadow-bias must be a number from 0 to 1 (a fraction of the receiver's distance from the "
                        "light), not '" + bias + "'"};
    }
    const std::string transmittance = take_option(args, "--transmittance", "thesis");
    if (transmittance == "physical") o.physical_transmittance = true;
    else if (transmittance != "thesis") throw usage_error{"--transmittance must be thesis or physical, not '" + transmittance + "'"};
    const std::string shadows = take_option(args, "--shadows", "transparent");
    if (shadows == "off") o.shadows = render::shadow_mode::off;
    else if (shadows == "opaque") o.shadows = render::shadow_mode::opaque;
    else if (shadows != "transparent") throw usage_error{"--shadows must be off, opaque or transparent, not '" + shadows + "'"};
    const std::string specular = take_option(args, "--specular", "white");
    if (specular == "rgb") o.rgb_specular = true;
    else if (specular != "white") throw usage_error{"--specular must be white or rgb, not '" + specular + "'"};
    o.float_targets = take_flag(args, "--float-targets");
    const scene_budget budget = take_budget(args);
    args = operands(args);
    if (args.size() != 1)
      throw usage_error{"render takes one scene file, not " + std::to_string(args.size()) + " arguments"};
    if (out.empty()) throw usage_error{"render needs --out DIR"};
    if (technique == "peeling") o.method = render::technique::peeling;
    else if (technique == "forward") o.method = render::technique::forward;
    else if (technique == "forward-depth") o.method = render::technique::forward_depth;
    else if (technique == "reference") o.method = render::technique::reference;
    else if (technique != "interlaced")
      throw usage_error{"unknown technique '" + technique + "' (known: interlaced, peeling, forward, forward-depth, reference)"};
    if (backend != "gl" && backend != "vk") throw usage_error{"--backend must be gl or vk"};
    // The folder is checked before any work: a run that cannot write its outputs stops here.
    auto dir = output_dir::open(out, "frame.json");
    if (!dir) {
      std::fprintf(stderr, "dstrans render: %s\n", dir.error().c_str());
      return 1;
    }
    auto s = load_scene(args[0], budget);
    if (!s) {
      std::fprintf(stderr, "dstrans render: %s\n", s.error().c_str());
      return 1;
    }
    if (const std::size_t need = scene_bytes(*s) + render::frame_bytes(render::plan_of(*s, o), o); need > budget.bytes) {
      std::fprintf(stderr, "dstrans render: %s with a %dx%d frame would take about %zu MiB, over the budget of %zu MiB "
                   "(--budget MIB raises it)\n", args[0].c_str(), o.width, o.height, need >> 20, budget.bytes >> 20);
      return 1;
    }
    if (!post_file.empty()) {
      auto chain = load_post_chain(post_file);
      if (!chain) {
        std::fprintf(stderr, "dstrans render: %s\n", chain.error().c_str());
        return 1;
      }
      s->post = *chain;
    }
    auto g = open_gpu(backend, device);
    if (!g) {
      std::fprintf(stderr, "dstrans render: %s\n", g.error().c_str());
      return 1;
    }
    result<render::frame> f = failure{"no backend"};
#ifdef DSTRANS_HAVE_GL
    if ((*g)->gl) f = render::run_gl(*s, o, pass_shaders());
#endif
#ifdef DSTRANS_HAVE_VK
    if ((*g)->vk) f = render::run_vk(*(*g)->vk, *s, o, pass_shaders());
#endif
    if (!f) {
      std::fprintf(stderr, "dstrans render: %s\n", f.error().c_str());
      return 1;
    }
    auto written = render::write_frame(*f, *dir, technique, backend);
    if (written) written = dir->commit();
    if (!written) {
      std::fprintf(stderr, "dstrans render: %s\n", written.error().c_str());
      return 1;
    }
    std::printf("dstrans render: %s on %s, %dx%d, %.2f ms: %s/final.png\n", args[0].c_str(), backend.c_str(), o.width, o.height,
                f->frame_ms, out.c_str());
    if (f->kbuffer_overflow > 0)
      std::fprintf(stderr, "dstrans render: %u fragments found no node in the lists and were blended out of order%s "
                   "(--kbuffer-nodes N enlarges the pool)\n", f->kbuffer_overflow,
                   o.method == render::technique::reference ? ": this reference is not exact" : "");
    return 0;
  } catch (const usage_error& e) {
    std::fprintf(stderr, "dstrans render: %s\n%s", e.message.c_str(), usage);
    return 2;
  }
}

}  // namespace dstrans::cli
