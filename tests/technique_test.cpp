// The thesis's equations (TECHNIQUES.md S0) on the CPU, against values worked out by hand. The same
// text runs on the GPU in backend_*_test.cpp.
#include <catch2/catch.hpp>

#include <cmath>

#include <dstrans/phong.hpp>
#include <dstrans/refraction.hpp>
#include <dstrans/transparent_shadow.hpp>

using namespace dstrans;
using namespace dstrans::shader;

TEST_CASE("Phong (Eq. 2.1): diffuse N.L, specular (R.V)^n in the light's colour, nothing facing away", "[phong]") {
  const glm::vec3 n(0, 0, 1), light(1.0f, 0.5f, 0.0f);
  const glm::vec3 l = glm::normalize(glm::vec3(1, 0, 1));
  // Mirror direction of l about n is (-1, 0, 1)/sqrt2; looking from there, R.V = 1.
  light_sample s = dst_phong(n, l, glm::normalize(glm::vec3(-1, 0, 1)), 16.0f, light);
  CHECK(s.light.x == Approx(0.70710678f));
  CHECK(s.light.y == Approx(0.35355339f));
  CHECK(s.specular.x == Approx(1.0f));
  CHECK(s.specular.y == Approx(0.5f));
  CHECK(s.specular.z == 0.0f);
  CHECK(dst_encode_white_specular(s.specular) == Approx(0.5f));  // the thesis's light buffer keeps the mean
  // Looking straight down the normal: R.V = cos 45 degrees.
  s = dst_phong(n, l, n, 2.0f, light);
  CHECK(s.specular.x == Approx(0.5f));
  CHECK(s.specular.y == Approx(0.5f * 0.5f));
  // Behind the surface, or grazing: nothing.
  s = dst_phong(n, -l, n, 2.0f, light);
  CHECK(s.light == glm::vec3(0.0f));
  CHECK(s.specular == glm::vec3(0.0f));
  CHECK(dst_phong(n, glm::vec3(1, 0, 0), n, 2.0f, light).light == glm::vec3(0.0f));
  // R.V <= 0 gives no specular for any power, including 0.
  CHECK(dst_phong(n, l, glm::normalize(glm::vec3(1, 0, -1)), 0.0f, light).specular == glm::vec3(0.0f));
  CHECK(dst_phong(n, l, n, 0.0f, light).specular == light);
}

TEST_CASE("attenuation and spot falloff", "[phong]") {
  CHECK(dst_attenuation(0.0f, 10.0f) == 1.0f);
  CHECK(dst_attenuation(5.0f, 10.0f) == 0.25f);
  CHECK(dst_attenuation(10.0f, 10.0f) == 0.0f);
  CHECK(dst_attenuation(20.0f, 10.0f) == 0.0f);
  CHECK(dst_attenuation(-1.0f, 10.0f) == 1.0f);
  CHECK(dst_attenuation(1.0f, 0.0f) == 0.0f);
  CHECK(dst_attenuation(NAN, 10.0f) == 0.0f);
  CHECK(dst_spot_falloff(1.0f, 0.8f, 0.9f) == 1.0f);
  CHECK(dst_spot_falloff(0.85f, 0.8f, 0.9f) == Approx(0.5f));
  CHECK(dst_spot_falloff(0.7f, 0.8f, 0.9f) == 0.0f);
  CHECK(dst_spot_falloff(0.8f, 0.8f, 0.8f) == 1.0f);   // equal cones: a hard edge, lit on it
  CHECK(dst_spot_falloff(0.79f, 0.8f, 0.8f) == 0.0f);
  CHECK(dst_spot_falloff(NAN, 0.8f, 0.9f) == 0.0f);
}

TEST_CASE("transparent shadows (Eq. 3.1, 3.2): opaque blocks, glass filters by min and alpha", "[shadow]") {
  const glm::vec3 light(1.0f, 0.8f, 0.6f);
  const glm::vec4 glass(0.2f, 0.9f, 0.3f, 0.25f), wall(0.5f, 0.5f, 0.5f, 1.0f);
  // Glass at depth 0.3 on the texel, the opaque occluder behind it at 0.7 on the partner.
  CHECK(dst_transparent_shadow(light, 0.2f, 0.0f, 0.3f, glass, 0.7f, wall) == light);  // in front of both
  const glm::vec3 filtered = dst_transparent_shadow(light, 0.5f, 0.0f, 0.3f, glass, 0.7f, wall);
  CHECK(filtered.x == Approx(0.2f * 0.75f));  // min(1, 0.2)
  CHECK(filtered.y == Approx(0.8f * 0.75f));  // min(0.8, 0.9): light is dimmer than the glass colour
  CHECK(filtered.z == Approx(0.3f * 0.75f));
  CHECK(dst_transparent_shadow(light, 0.9f, 0.0f, 0.3f, glass, 0.7f, wall) == glm::vec3(0.0f));  // behind the wall
  // The samples may come in either order: the lower alpha is the glass.
  CHECK(dst_transparent_shadow(light, 0.5f, 0.0f, 0.7f, wall, 0.3f, glass) == filtered);
  // At d_maxA exactly the point is lit through the glass (d_minA < d <= d_maxA); the bias moves it nearer.
  CHECK(dst_transparent_shadow(light, 0.7f, 0.0f, 0.3f, glass, 0.7f, wall) == filtered);
  CHECK(dst_transparent_shadow(light, 0.75f, 0.1f, 0.3f, glass, 0.7f, wall) == filtered);
  CHECK(dst_transparent_shadow(light, 0.35f, 0.1f, 0.3f, glass, 0.7f, wall) == light);
  // The case of Eq. 3.1, and the physically based transmittance I_L C (1 - alpha) beside Eq. 3.2's min.
  CHECK(dst_shadow_case(0.9f, 0.0f, 0.3f, glass, 0.7f, wall) == 0);
  CHECK(dst_shadow_case(0.5f, 0.0f, 0.3f, glass, 0.7f, wall) == 1);
  CHECK(dst_shadow_case(0.2f, 0.0f, 0.3f, glass, 0.7f, wall) == 2);
  CHECK(dst_shadow_texel_transparent(glass, wall));
  CHECK_FALSE(dst_shadow_texel_transparent(wall, glass));
  CHECK(dst_shadow_texel_transparent(wall, wall));  // equal alphas: the texel itself
  const glm::vec3 bright(2.0f), through = dst_transmitted_shadow(bright, 0.5f, 0.0f, 0.3f, glass, 0.7f, wall);
  CHECK(through.x == Approx(2.0f * 0.2f * 0.75f));
  CHECK(through.y == Approx(2.0f * 0.9f * 0.75f));
  CHECK(dst_transparent_shadow(bright, 0.5f, 0.0f, 0.3f, glass, 0.7f, wall).y == Approx(0.9f * 0.75f));  // min clamps
  CHECK(dst_transmitted_shadow(light, 0.9f, 0.0f, 0.3f, glass, 0.7f, wall) == glm::vec3(0.0f));
  CHECK(dst_transmitted_shadow(light, 0.2f, 0.0f, 0.3f, glass, 0.7f, wall) == light);
  // Plain shadow maps: in or out.
  CHECK(dst_opaque_shadow(light, 0.5f, 0.0f, 0.3f) == glm::vec3(0.0f));
  CHECK(dst_opaque_shadow(light, 0.5f, 0.0f, 0.6f) == light);
  CHECK(dst_opaque_shadow(light, 0.5f, 0.25f, 0.3f) == light);
}

TEST_CASE("refraction offset, depth rejection and the compose blend (Eq. 3.3)", "[refraction]") {
  CHECK(dst_refraction_offset(glm::vec3(0.5f, 0.25f, 0.8f), 8.0f) == glm::vec2(4.0f, -2.0f));
  CHECK(dst_refraction_offset(glm::vec3(0.5f, 0.25f, 0.8f), 0.0f) == glm::vec2(0.0f));
  CHECK(dst_refraction_rejected(0.6f, 0.4f));        // the glass is behind the sample: a leak
  CHECK_FALSE(dst_refraction_rejected(0.4f, 0.6f));
  CHECK_FALSE(dst_refraction_rejected(0.5f, 0.5f));  // equal depths are not a leak
  // The moved sample: opaque behind the glass is taken; in front of it, rejected by depth.
  CHECK(dst_refraction_source(0.3f, 1.0f, 0.6f, 0.4f, 0.2f) == 1);  // the moved pixel, opaque, behind the glass
  CHECK(dst_refraction_source(0.3f, 0.4f, 0.2f, 1.0f, 0.6f) == 2);  // its partner when the moved pixel is glass
  CHECK(dst_refraction_source(0.6f, 1.0f, 0.3f, 0.4f, 0.9f) == 0);  // in front of the glass: a leak, rejected
  CHECK(dst_refraction_source(0.3f, 0.4f, 0.6f, 0.4f, 0.6f) == 0);  // glass on both rows: no opaque sample
  // Without depth only glass coverage decides (Figure 4.7): beside the glass a valid sample is rejected,
  // and a foreground sample over glass would be taken.
  CHECK(dst_refraction_accepted_by_mask(1.0f, 0.4f));
  CHECK_FALSE(dst_refraction_accepted_by_mask(1.0f, 1.0f));
  CHECK_FALSE(dst_refraction_accepted_by_mask(0.4f, 0.4f));

  surface o = dst_surface_zero(), t = dst_surface_zero();
  o.diffuse = {1.0f, 1.0f, 1.0f};
  o.spec_intensity = 0.5f;
  t.diffuse = {0.0f, 1.0f, 0.0f};
  t.alpha = 0.25f;
  light_sample lo = dst_light_sample_zero(), lt = dst_light_sample_zero();
  lo.light = {0.5f, 0.5f, 0.5f};
  lo.specular = glm::vec3(0.2f);
  lt.light = {1.0f, 1.0f, 1.0f};
  const glm::vec3 ambient(0.1f);
  CHECK(dst_shade(o, lo, ambient) == glm::vec3(0.6f + 0.1f));
  const glm::vec3 c = dst_compose(o, lo, t, lt, ambient);
  CHECK(c.x == Approx(0.7f * 0.75f));
  CHECK(c.y == Approx(0.7f * 0.75f + 1.1f * 0.25f));
  // alpha 0 shows only the background; alpha 1 only the surface.
  t.alpha = 0.0f;
  CHECK(dst_compose(o, lo, t, lt, ambient) == dst_shade(o, lo, ambient));
  t.alpha = 1.0f;
  CHECK(dst_compose(o, lo, t, lt, ambient) == dst_shade(t, lt, ambient));
}

TEST_CASE("rough glass: roughness to the Phong exponent and back, the blur's radius and its taps", "[refraction]") {
  // glTF's roughness as the exponent 2 / r^4 - 2 within [1, 255], and back.
  CHECK(dst_phong_power_of_roughness(0.5f) == Approx(30.0f));
  CHECK(dst_phong_power_of_roughness(0.0f) == 255.0f);
  CHECK(dst_phong_power_of_roughness(0.29f) == 255.0f);  // clearer than 8 bits tell
  CHECK(dst_phong_power_of_roughness(1.0f) == 1.0f);
  for (float r = 0.3f; r <= 0.9f; r += 0.05f)
    CHECK(dst_roughness_of_phong_power(dst_phong_power_of_roughness(r)) == Approx(r).epsilon(1e-5));
  // What the G-buffer stores, 8 bits of [0, 255]: every code below 255 reads back rough, 255 clear.
  CHECK(dst_roughness_of_phong_power(dst_decode_spec_power(254.0f / 255.0f)) == Approx(0.2972f).epsilon(1e-3));
  CHECK(dst_roughness_of_phong_power(dst_decode_spec_power(1.0f)) == 0.0f);

  // Roughness 0.5 spreads the light tan(0.25) wide a unit behind the glass; seen from 2 units away with
  // 100 pixels a unit at unit depth: 100 tan(0.25) / 2 pixels.
  CHECK(dst_refraction_blur_pixels(0.5f, 1.0f, 2.0f, 100.0f, 64.0f) == Approx(50.0f * std::tan(0.25f)));
  CHECK(dst_refraction_blur_pixels(0.5f, 1.0f, 2.0f, 100.0f, 4.0f) == 4.0f);   // the limit
  CHECK(dst_refraction_blur_pixels(0.0f, 1.0f, 2.0f, 100.0f, 64.0f) == 0.0f);  // clear glass
  CHECK(dst_refraction_blur_pixels(0.5f, 2.0f, 2.0f, 100.0f, 64.0f) == 0.0f);  // touching the glass
  // The spread is at most 1 radian, however large the roughness.
  CHECK(dst_refraction_blur_pixels(5.0f, 1.0f, 2.0f, 100.0f, 100.0f) == Approx(50.0f * std::tan(1.0f)));

  // 15 taps, weights summing to 1, within the unit disc, centred, and mirrored about the x axis.
  float weight = 0.0f;
  glm::vec2 mean(0.0f);
  for (int i = 0; i < 15; ++i) {
    const glm::vec3 tap = dst_refraction_blur_tap(i);
    CHECK(tap.z > 0.0f);
    CHECK(glm::length(glm::vec2(tap.x, tap.y)) <= 1.0f + 1e-6f);
    weight += tap.z;
    mean += glm::vec2(tap.x, tap.y) * tap.z;
    bool mirrored = false;
    for (int j = 0; j < 15; ++j) {
      const glm::vec3 other = dst_refraction_blur_tap(j);
      mirrored = mirrored || (std::fabs(other.x - tap.x) < 1e-6f && std::fabs(other.y + tap.y) < 1e-6f && other.z == tap.z);
    }
    CHECK(mirrored);
  }
  CHECK(weight == Approx(1.0f));
  CHECK(glm::length(mean) < 1e-6f);
  CHECK(dst_refraction_blur_tap(15) == glm::vec3(0.0f));
  CHECK(dst_refraction_blur_tap(-1) == glm::vec3(0.0f));
}
