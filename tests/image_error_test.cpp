// The benchmark's error figures against the properties their papers state: SSIM (Wang et al. 2004) and
// LDR-FLIP (Andersson et al. 2020), and RMSE and PSNR beside them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdint>
#include <functional>

#include <image_error.hpp>

using dstrans::render::image;
using namespace dstrans::render;

namespace {
image make(int w, int h, const std::function<int(int x, int y, int c)>& value) {
  image img{w, h, std::vector<std::uint8_t>(std::size_t(w) * std::size_t(h) * 4, 255)};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c)
        img.rgba[4 * std::size_t(y * w + x) + std::size_t(c)] = std::uint8_t(std::clamp(value(x, y, c), 0, 255));
  return img;
}
// A deterministic texture of values 60 to 190: smooth waves plus fine detail, different in each channel.
int texture(int x, int y, int c) {
  return 125 + int(40.0 * std::sin(0.37 * x + 1.3 * c) * std::cos(0.23 * y) + 25.0 * std::sin(1.7 * x * y + c));
}
// +amount or -amount, by a hash of the pixel.
int noise(int x, int y, int c, int amount) {
  const std::uint32_t h = std::uint32_t(x) * 73856093u ^ std::uint32_t(y) * 19349663u ^ std::uint32_t(c) * 83492791u;
  return (h * 2654435761u >> 16) & 1 ? amount : -amount;
}
double mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / double(v.size());
}
}  // namespace

TEST_CASE("SSIM is 1 for equal images, symmetric, and the luminance term alone for flat ones", "[bench][ssim]") {
  const image a = make(40, 30, texture);
  for (double s : ssim_map(a, a)) REQUIRE(s == Approx(1.0).epsilon(1e-12));
  const image b = make(40, 30, [](int x, int y, int c) { return texture(x, y, c) + noise(x, y, c, 9); });
  const std::vector<double> ab = ssim_map(a, b), ba = ssim_map(b, a);
  for (std::size_t i = 0; i < ab.size(); ++i) REQUIRE(ab[i] == Approx(ba[i]).epsilon(1e-12));
  // Flat windows have no variance: the contrast and structure term is (0 + C2) / (0 + C2).
  const double c1 = 2.55 * 2.55, u = 100.0, v = 120.0;
  const std::vector<double> flat = ssim_map(make(16, 16, [](int, int, int) { return 100; }), make(16, 16, [](int, int, int) { return 120; }));
  for (double s : flat) REQUIRE(s == Approx((2.0 * u * v + c1) / (u * u + v * v + c1)).epsilon(1e-9));
}

TEST_CASE("SSIM tells a brightness shift from noise of the same MSE, and falls as noise or blur grows", "[bench][ssim]") {
  // Wang et al.'s Figure 2: equal MSE, very different SSIM.
  const image ref = make(64, 48, texture);
  const image shifted = make(64, 48, [](int x, int y, int c) { return texture(x, y, c) + 8; });
  const image noisy = make(64, 48, [](int x, int y, int c) { return texture(x, y, c) + noise(x, y, c, 8); });
  const std::vector<bool> all(64 * 48, true);
  const image_error es = compare(shifted, ref, all), en = compare(noisy, ref, all);
  CHECK(es.all.rmse == Approx(8.0));
  CHECK(en.all.rmse == Approx(8.0));
  CHECK(es.all.ssim > 0.99);
  CHECK(en.all.ssim < es.all.ssim - 0.02);
  double before = 1.0;
  for (int amount : {2, 6, 12, 24}) {
    const double s = mean(ssim_map(make(64, 48, [&](int x, int y, int c) { return texture(x, y, c) + noise(x, y, c, amount); }), ref));
    CHECK(s < before);
    before = s;
  }
  before = 1.0;
  for (int radius : {1, 2, 4}) {
    const image blurred = make(64, 48, [&](int x, int y, int c) {
      int sum = 0;
      for (int i = -radius; i <= radius; ++i) sum += texture(x + i, y, c);
      return sum / (2 * radius + 1);
    });
    const double s = mean(ssim_map(blurred, ref));
    CHECK(s < before);
    before = s;
  }
}

TEST_CASE("FLIP is 0 for equal images, symmetric, within [0, 1], and black against white is its colour term", "[bench][flip]") {
  const image a = make(40, 30, texture);
  for (double f : flip_map(a, a)) REQUIRE(f == 0.0);
  const image b = make(40, 30, [](int x, int y, int c) { return texture(x, y, c) + noise(x, y, c, 30) + (x > 20 ? 40 : 0); });
  const std::vector<double> ab = flip_map(a, b), ba = flip_map(b, a);
  for (std::size_t i = 0; i < ab.size(); ++i) {
    REQUIRE(ab[i] == Approx(ba[i]).margin(1e-12));
    REQUIRE(ab[i] >= 0.0);
    REQUIRE(ab[i] <= 1.0);
  }
  // Flat images have no features; the colour term by the paper's formulas: HyAB(black, white) = 100 and
  // HyAB(green, blue) = 203.3 in Hunt-adjusted L*a*b*, raised to 0.7 (25.12 and 41.28), and 25.12 lies
  // above 0.4 x 41.28, so 0.95 + (25.12 - 16.51) / (41.28 - 16.51) x 0.05.
  for (double f : flip_map(make(12, 8, [](int, int, int) { return 0; }), make(12, 8, [](int, int, int) { return 255; })))
    REQUIRE(f == Approx(0.96738).margin(2e-4));
}

TEST_CASE("FLIP hides detail too fine for the observer and grows with noise", "[bench][flip]") {
  // A one-pixel checker against the grey of the same mean luminance: seen from far (many pixels a degree)
  // the eye averages it; seen from near it does not.
  const image checker = make(48, 48, [](int x, int y, int) { return (x + y) % 2 ? 255 : 0; });
  const image grey = make(48, 48, [](int, int, int) { return 188; });  // sRGB 188 is half of white's luminance
  const double far = mean(flip_map(grey, checker, 200.0)), near = mean(flip_map(grey, checker, 10.0));
  CHECK(far < 0.5 * near);
  const image ref = make(64, 48, texture);
  double before = 0.0;
  for (int amount : {2, 6, 12, 24}) {
    const double f = mean(flip_map(make(64, 48, [&](int x, int y, int c) { return texture(x, y, c) + noise(x, y, c, amount); }), ref));
    CHECK(f > before);
    before = f;
  }
}

TEST_CASE("compare gives every figure over all pixels and over the mask; an empty mask is no difference", "[bench]") {
  const image ref = make(32, 16, texture);
  const image test = make(32, 16, [](int x, int y, int c) { return texture(x, y, c) + (x < 16 ? 20 : 0); });
  std::vector<bool> left(32 * 16), none(32 * 16, false);
  for (std::size_t i = 0; i < left.size(); ++i) left[i] = i % 32 < 16;
  const image_error e = compare(test, ref, left);
  CHECK(e.masked.rmse == Approx(20.0));
  CHECK(e.all.rmse == Approx(20.0 / std::sqrt(2.0)));
  CHECK(e.all.psnr == Approx(20.0 * std::log10(255.0 / e.all.rmse)));
  CHECK(e.masked.ssim < e.all.ssim);
  CHECK(e.masked.flip > e.all.flip);
  const image_error empty = compare(test, ref, none);
  CHECK(empty.masked.rmse == 0.0);
  CHECK(std::isinf(empty.masked.psnr));
  CHECK(empty.masked.ssim == 1.0);
  CHECK(empty.masked.flip == 0.0);
  // One pixel is enough for every figure to be finite.
  const image_error one = compare(make(1, 1, [](int, int, int) { return 10; }), make(1, 1, [](int, int, int) { return 250; }), {true});
  CHECK(std::isfinite(one.all.ssim));
  CHECK(std::isfinite(one.all.flip));
  CHECK(one.all.flip > 0.5);
}
