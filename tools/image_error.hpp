// How far an 8-bit image is from a reference: RMSE and PSNR, SSIM (Wang, Bovik, Sheikh and Simoncelli 2004)
// and LDR-FLIP (Andersson, Nilsson, Akenine-Moller, Oskarsson, Astrom and Fairchild 2020), over all pixels
// and over a mask, as the benchmark reports them.
//
//   dstrans::render::image_error e = dstrans::render::compare(test, reference, glass_pixels);
//   e.all.ssim;     // 1 where the images are equal
//   e.masked.flip;  // 0 where they are equal, towards 1 as the difference grows more visible
//   json record = dstrans::render::with_errors({{"technique", "interlaced"}}, e);   // as results.json keeps them
#pragma once

#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame_output.hpp"

namespace dstrans::render {

// FLIP's observer: 0.7 m from a 0.7 m wide monitor of 3840 pixels, as the paper's default (67 pixels a
// degree).
constexpr double flip_default_ppd = 3840.0 * 3.14159265358979323846 / 180.0;

// Per-pixel SSIM of `a` against `b`: the mean over R, G and B (0-255) of Wang et al.'s index with their
// 11x11 Gaussian window (sigma 1.5) and constants K1 = 0.01, K2 = 0.03, borders replicated (their code
// drops the 5 pixels nearest the border instead). 1 where the windows are equal; symmetric in a and b.
std::vector<double> ssim_map(const image& a, const image& b);

// Per-pixel LDR-FLIP of `test` against `reference` (sRGB), for an observer who sees `ppd` pixels a degree:
// the colour difference after the contrast-sensitivity filters (HyAB in Hunt-adjusted L*a*b*, remapped to
// [0, 1]) raised to 1 less the feature difference (edges and points of the achromatic channel). 0 where
// the images are equal, at most 1; borders replicated as the paper's code does.
std::vector<double> flip_map(const image& test, const image& reference, double ppd = flip_default_ppd);

struct error_figures {
  double rmse = 0.0;  // over 0-255 channel values
  double psnr = INFINITY;  // dB; infinite where the images are equal
  double ssim = 1.0;  // the mean of ssim_map
  double flip = 0.0;  // the mean of flip_map
};
struct image_error {
  error_figures all, masked;  // masked: over the pixels of the mask (none: as over equal images)
};

// The figures of `test` against `reference` (the same size) over every pixel and over `mask` (a flag a pixel).
image_error compare(const image& test, const image& reference, const std::vector<bool>& mask);

// `record` with the figures as results.json keeps them: rmse, psnr (null where infinite), ssim and flip over
// all pixels, and rmse, ssim and flip over the mask's pixels (glass, hair, smoke) as *_transparent.
nlohmann::ordered_json with_errors(nlohmann::ordered_json record, const image_error& e);

}  // namespace dstrans::render
