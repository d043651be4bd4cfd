// The thesis's layouts: G-buffer (Table 3.1), light accumulation buffer (Table 3.2)
// and transparent shadow map (Table 3.3); a compact G-buffer beside Table 3.1's, and an RGB-specular light
// buffer beside Table 3.2's.
//
//   static_assert(dstrans::thesis_gbuffer::bytes_per_pixel == 16);
//   static_assert(dstrans::compact_gbuffer::bytes_per_pixel == 8);   // and depth from the depth attachment
//   dstrans::glsl::source src;
//   dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer");
#pragma once

#include "layout.hpp"

namespace dstrans {

// Table 3.1: 4 targets, 16 bytes a pixel.
using thesis_gbuffer = layout<surface,
                              target<format::rgba8, field::diffuse, field::alpha>,
                              target<format::rgb10a2, field::normal, unused<1>>,
                              target<format::rgba8, field::spec_intensity, field::spec_power, unused<2>>,
                              target<format::r32f, field::depth>>;

// Beyond the thesis: the same information in 8 bytes a pixel, 12 with the light buffer. The
// normal in two channels octahedrally (at most 0.94 degrees off, measured), the specular terms beside
// it, and no depth target: the pass that needs depth samples the depth attachment, which every renderer has.
using compact_gbuffer = layout<surface,
                               target<format::rgba8, field::diffuse, field::alpha>,
                               target<format::rgba8, field::normal_octahedral, field::spec_intensity, field::spec_power>>;

// Table 3.2: light RGB and the white specular response, 4 bytes a pixel. Additive blending into RGBA8
// saturates at 1, as in the thesis.
using thesis_light_buffer = layout<light_sample, target<format::rgba8, field::light, field::specular>>;

// Beyond the thesis: the specular response in RGB, so that a coloured light's highlight keeps its colour;
// 8 bytes a pixel in two targets.
using rgb_light_buffer = layout<light_sample, target<format::rgba8, field::light, unused<1>>,
                                target<format::rgba8, field::specular_rgb, unused<1>>>;

// Table 3.3: the occluder's depth, and the colour and alpha of a transparent occluder, 8 bytes a texel.
using thesis_shadow_map = layout<surface,
                                 target<format::r32f, field::depth>,
                                 target<format::rgba8, field::diffuse, field::alpha>>;

}  // namespace dstrans
