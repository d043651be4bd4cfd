// Post-processing after the deferred frame: a chain of effects, each (name, inputs,
// shader, outputs) over a registry of named textures, expanded into full-screen passes; and the formulas
// the passes share with the CPU.
//
//   std::vector<dstrans::post_effect> chain{{dstrans::post_kind::antialias}, {dstrans::post_kind::bloom}};
//   dstrans::post_plan p = dstrans::plan_post(chain, true);   // true: the frame is interlaced (S0)
//   for (const dstrans::post_pass& pass : p.passes) { /* bind pass.inputs, draw pass.shader into pass.output */ }
//   std::vector<float> w = dstrans::gaussian_weights(4, 2.0f);   // the blur's 9 taps, summing to 1
//
// Names in the registry: "frame" is the image the chain starts from (the composed frame), "gbuffer" the
// G-buffer at its own bindings (depth, normals and alpha for depth of field and anti-aliasing); every
// other name is a target of the chain, allocated only because a pass writes it. Each effect's output is
// named as the effect ("aa", "bloom", a second blur "blur_2") and is the next effect's "frame".
//
// The anti-aliasing is S3's: a pixel's normal and depth against its four neighbours give each neighbour a
// weight (times `strength`), and the pixel becomes the weighted average with itself at weight 1. dst_edge_weight starts where the normals turn by
// 1 / normal_scale in cosine or the view distances differ by 1 / depth_scale of the nearer one (41 degrees
// or 5% by default) and is full at twice that, so that planes and smooth curves get weight 0 and are left
// exactly as they are.
// Aware of the interlace predicate (`interlace`), it compares the surface each pixel shows in front: a
// pixel whose row pair holds glass shows the glass, so the rows inside glass are not mistaken for edges,
// and the glass's silhouette, which the predicate draws in steps of two rows, is.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "detail/shared.hpp"

DSTRANS_SHARED(dst_post,
DST_FN float dst_gaussian(float x, float sigma) {
  if (isnan(sigma) || sigma <= 0.0f) return x == 0.0f ? 1.0f : 0.0f;
  return exp(-x * x / (2.0f * sigma * sigma));
}
DST_FN float dst_luminance(vec3 c) { return dot(c, vec3(0.21f, 0.71f, 0.07f)); }
DST_FN vec3 dst_bright_pass(vec3 c, float threshold) {
  float l = dst_luminance(c);
  if (isnan(l) || l <= threshold || l <= 0.0f) return vec3(0.0f);
  return c * ((l - threshold) / l);
}
DST_FN vec3 dst_greyscale(vec3 c) { return vec3(dst_luminance(c)); }
DST_FN float dst_at_most_one(float v) {
  if (isnan(v)) return 0.0f;
  return v < 1.0f ? v : 1.0f;
}
DST_FN vec3 dst_sepia(vec3 c) {
  return vec3(dst_at_most_one(dot(c, vec3(0.393f, 0.769f, 0.189f))), dst_at_most_one(dot(c, vec3(0.349f, 0.686f, 0.168f))),
              dst_at_most_one(dot(c, vec3(0.272f, 0.534f, 0.131f))));
}
DST_FN float dst_blur_amount(float distance, float focus, float range) {
  float off = abs(distance - focus);
  if (isnan(off)) return 0.0f;
  if (isnan(range) || range <= 0.0f) return off > 0.0f ? 1.0f : 0.0f;
  float amount = off / range;
  if (isnan(amount)) return 1.0f;  // both infinite
  return amount < 1.0f ? amount : 1.0f;
}
DST_FN float dst_edge_weight(vec3 n0, vec3 n1, float d0, float d1, float normal_scale, float depth_scale) {
  float by_normal = (1.0f - dot(n0, n1)) * normal_scale;
  float by_depth = abs(d0 - d1) / max(min(d0, d1), 1e-6f) * depth_scale;
  if (isnan(by_normal)) by_normal = 0.0f;
  if (isnan(by_depth)) by_depth = 0.0f;
  float e = (by_normal > by_depth ? by_normal : by_depth) - 1.0f;
  return e <= 0.0f ? 0.0f : e < 1.0f ? e : 1.0f;
}
)

namespace dstrans {

enum class post_kind { blur, bloom, depth_of_field, greyscale, sepia, antialias };

// The effect's name in the chain, the scene file and the plan: blur, bloom, dof, greyscale, sepia, aa.
inline const char* post_name(post_kind k) {
  switch (k) {
    case post_kind::blur: return "blur";
    case post_kind::bloom: return "bloom";
    case post_kind::depth_of_field: return "dof";
    case post_kind::greyscale: return "greyscale";
    case post_kind::sepia: return "sepia";
    case post_kind::antialias: return "aa";
  }
  return "";
}

struct post_effect {
  post_kind kind = post_kind::blur;
  int radius = 4;          // blur, bloom, depth of field: taps each side of the separable Gaussian
  float sigma = 2.0f;      // its standard deviation in pixels
  float threshold = 0.8f;  // bloom: the luminance the bright pass keeps above
  float intensity = 1.0f;  // bloom: how much of the blurred bright pass is added back
  float focus = 5.0f;      // depth of field: the sharp distance from the camera, world units
  float range = 2.0f;      // depth of field: how much farther or nearer the image is fully blurred
  float normal_scale = 4.0f, depth_scale = 20.0f;  // anti-aliasing: edge where 1 - cos or the relative gap exceeds 1 / scale
  // anti-aliasing: a neighbour's weight across a full edge. A third suits an image rendered with one sample
  // a pixel: a 2x2-supersampled edge leaves half its pixels unmixed and half mixed 50:50, and 1/3 of the
  // neighbour mixes 25%, the least squared error between the two (1 would mix 50% everywhere).
  float strength = 1.0f / 3.0f;
  bool interlace = true;   // anti-aliasing: compare the surfaces in front (on an interlaced frame)
};

// A full-screen pass of an expanded chain: its shader file (one of dstrans::pass_shaders), the registry names it reads
// (texture inputs in order, "gbuffer" at the G-buffer's bindings) and the one it writes, its #ifdef
// switches, and its parameters (x, y, z, w as the shader reads them).
struct post_pass {
  std::string effect, name, shader;
  std::vector<std::string> inputs;
  std::string output;
  std::vector<std::string> switches;
  float params[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

struct post_plan {
  std::vector<post_pass> passes;
  std::vector<std::string> targets;  // every name a pass writes, each once: what the chain allocates
  std::vector<std::string> effects;  // each effect's name, which is also its output's
  std::string output = "frame";      // what the chain ends with
};

// The passes of `chain`; `interlaced`: the frame is the thesis's interlaced one, so anti-aliasing that
// asks for it compares the surfaces in front (DST_AA_INTERLACE).
inline post_plan plan_post(const std::vector<post_effect>& chain, bool interlaced) {
  post_plan p;
  std::string in = "frame";
  auto add = [&](const std::string& effect, const std::string& name, const std::string& shader,
                 std::vector<std::string> inputs, std::vector<std::string> switches, float x, float y, float z, float w) {
    post_pass pass{effect, name, shader, std::move(inputs), name, std::move(switches)};
    pass.params[0] = x;
    pass.params[1] = y;
    pass.params[2] = z;
    pass.params[3] = w;
    p.passes.push_back(pass);
    p.targets.push_back(name);
  };
  auto blur = [&](const std::string& effect, const std::string& from, const std::string& to, const post_effect& e) {
    add(effect, to + ".horizontal", "post_blur.frag.glsl", {from}, {}, float(e.radius), e.sigma, 1.0f, 0.0f);
    add(effect, to, "post_blur.frag.glsl", {to + ".horizontal"}, {}, float(e.radius), e.sigma, 0.0f, 1.0f);
  };
  for (const post_effect& e : chain) {
    std::string name = post_name(e.kind);
    int same = 1;
    for (const std::string& earlier : p.effects) same += earlier == name || earlier.rfind(name + "_", 0) == 0;
    if (same > 1) name += "_" + std::to_string(same);
    switch (e.kind) {
      case post_kind::blur: blur(name, in, name, e); break;
      case post_kind::bloom:
        add(name, name + ".bright", "post_bright.frag.glsl", {in}, {}, e.threshold, 0.0f, 0.0f, 0.0f);
        blur(name, name + ".bright", name + ".blur", e);
        add(name, name, "post_add.frag.glsl", {in, name + ".blur"}, {}, e.intensity, 0.0f, 0.0f, 0.0f);
        break;
      case post_kind::depth_of_field:
        blur(name, in, name + ".blur", e);
        add(name, name, "post_dof.frag.glsl", {in, name + ".blur", "gbuffer"}, {}, e.focus, e.range, 0.0f, 0.0f);
        break;
      case post_kind::greyscale: add(name, name, "post_tone.frag.glsl", {in}, {}, 0.0f, 0.0f, 0.0f, 0.0f); break;
      case post_kind::sepia: add(name, name, "post_tone.frag.glsl", {in}, {"DST_SEPIA"}, 0.0f, 0.0f, 0.0f, 0.0f); break;
      case post_kind::antialias:
        add(name, name, "post_aa.frag.glsl", {in, "gbuffer"},
            interlaced && e.interlace ? std::vector<std::string>{"DST_AA_INTERLACE"} : std::vector<std::string>{},
            e.normal_scale, e.depth_scale, e.strength, 0.0f);
        break;
    }
    p.effects.push_back(name);
    in = name;
  }
  p.output = in;
  return p;
}

// The separable Gaussian's taps from -radius to radius, normalised to sum to 1 (as the blur pass does).
inline std::vector<float> gaussian_weights(int radius, float sigma) {
  std::vector<float> w;
  float sum = 0.0f;
  for (int i = -radius; i <= radius; ++i) {
    w.push_back(shader::dst_gaussian(float(i), sigma));
    sum += w.back();
  }
  for (float& x : w) x /= sum;
  return w;
}

}  // namespace dstrans
