// Implements image_error.hpp from the papers' definitions: SSIM's window statistics and FLIP's colour and
// feature pipelines, each Gaussian filter applied as two one-dimensional passes.
#include "image_error.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace dstrans::render {

namespace {

constexpr double pi = 3.14159265358979323846;

// One channel of an image, rows from the top.
struct plane {
  int width = 0, height = 0;
  std::vector<double> v;
};

// `line` (n values, `stride` apart) correlated with kernel k (of odd length, centred) into `out` (the same
// stride), borders replicated: the taps read a padded copy, so that none is clamped.
void correlate(const double* line, int n, std::size_t stride, const std::vector<double>& k, std::vector<double>& padded,
               double* out) {
  const int r = int(k.size() / 2);
  padded.resize(std::size_t(n + 2 * r));
  for (int i = 0; i < n + 2 * r; ++i) padded[std::size_t(i)] = line[std::size_t(std::clamp(i - r, 0, n - 1)) * stride];
  for (int x = 0; x < n; ++x) {
    const double* taps = padded.data() + x;
    double s = 0.0;
    for (std::size_t i = 0; i < k.size(); ++i) s += k[i] * taps[i];
    out[std::size_t(x) * stride] = s;
  }
}

// `p` correlated with kx along rows and ky along columns (both of odd length, centred), borders replicated.
plane filter(const plane& p, const std::vector<double>& kx, const std::vector<double>& ky) {
  plane rows{p.width, p.height, std::vector<double>(p.v.size())}, out = rows;
  std::vector<double> padded;
  const std::size_t w = std::size_t(p.width);
  for (std::size_t y = 0; y < std::size_t(p.height); ++y)
    correlate(p.v.data() + y * w, p.width, 1, kx, padded, rows.v.data() + y * w);
  for (std::size_t x = 0; x < w; ++x) correlate(rows.v.data() + x, p.height, w, ky, padded, out.v.data() + x);
  return out;
}

// exp(-x^2 / (2 sigma^2)) for x from -radius to radius, summing to 1 where `normalise`.
std::vector<double> gaussian(int radius, double sigma, bool normalise) {
  std::vector<double> k;
  double sum = 0.0;
  for (int x = -radius; x <= radius; ++x) {
    k.push_back(std::exp(-double(x * x) / (2.0 * sigma * sigma)));
    sum += k.back();
  }
  if (normalise)
    for (double& w : k) w /= sum;
  return k;
}

plane channel(const image& img, int c, double scale) {
  plane p{img.width, img.height, std::vector<double>(std::size_t(img.width) * std::size_t(img.height))};
  for (std::size_t i = 0; i < p.v.size(); ++i) p.v[i] = double(img.rgba[4 * i + std::size_t(c)]) * scale;
  return p;
}

// Colour spaces as the FLIP paper uses them: linear sRGB (D65) to CIE XYZ and back; YCxCz and L*a*b*
// relative to the D65 white.
using vec3d = std::array<double, 3>;
constexpr vec3d white{0.950428545, 1.0, 1.088900371};

vec3d linear_to_xyz(vec3d c) {
  return {(10135552.0 * c[0] + 8788810.0 * c[1] + 4435075.0 * c[2]) / 24577794.0,
          (2613072.0 * c[0] + 8788810.0 * c[1] + 887015.0 * c[2]) / 12288897.0,
          (1425312.0 * c[0] + 8788810.0 * c[1] + 70074185.0 * c[2]) / 73733382.0};
}
vec3d xyz_to_linear(vec3d c) {
  return {3.241003275 * c[0] - 1.537398934 * c[1] - 0.498615861 * c[2],
          -0.969224334 * c[0] + 1.875930071 * c[1] + 0.041554224 * c[2],
          0.055639423 * c[0] - 0.204011202 * c[1] + 1.057148933 * c[2]};
}
double srgb_to_linear(double v) { return v > 0.04045 ? std::pow((v + 0.055) / 1.055, 2.4) : v / 12.92; }

vec3d xyz_to_ycxcz(vec3d c) {
  const double x = c[0] / white[0], y = c[1], z = c[2] / white[2];
  return {116.0 * y - 16.0, 500.0 * (x - y), 200.0 * (y - z)};
}
vec3d ycxcz_to_xyz(vec3d c) {
  const double y = (c[0] + 16.0) / 116.0;
  return {(y + c[1] / 500.0) * white[0], y, (y - c[2] / 200.0) * white[2]};
}
// L*a*b* with Hunt's adjustment of the chroma by the lightness (a and b scaled by L / 100).
vec3d hunt_lab(vec3d linear) {
  const vec3d xyz = linear_to_xyz(linear);
  const double d = 6.0 / 29.0;
  vec3d f;
  for (int i = 0; i < 3; ++i) {
    const double t = xyz[std::size_t(i)] / white[std::size_t(i)];
    f[std::size_t(i)] = t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
  }
  const double l = 116.0 * f[1] - 16.0;
  return {l, 0.01 * l * 500.0 * (f[0] - f[1]), 0.01 * l * 200.0 * (f[1] - f[2])};
}
double hyab(vec3d a, vec3d b) { return std::fabs(a[0] - b[0]) + std::hypot(a[1] - b[1], a[2] - b[2]); }

// The image in YCxCz, a plane a channel.
std::array<plane, 3> opponent(const image& img) {
  std::array<plane, 3> out;
  for (plane& p : out) p = {img.width, img.height, std::vector<double>(std::size_t(img.width) * std::size_t(img.height))};
  for (std::size_t i = 0; i < out[0].v.size(); ++i) {
    vec3d c;
    for (std::size_t k = 0; k < 3; ++k) c[k] = srgb_to_linear(double(img.rgba[4 * i + k]) / 255.0);
    const vec3d o = xyz_to_ycxcz(linear_to_xyz(c));
    for (std::size_t k = 0; k < 3; ++k) out[k].v[i] = o[k];
  }
  return out;
}

// The contrast sensitivity of channel `c` (achromatic, red-green, blue-yellow) as a sum of Gaussians
// a sqrt(pi / b) exp(-pi^2 r^2 / b) over visual angle r in degrees, sampled at `ppd` and normalised to sum 1.
std::array<plane, 3> csf_filtered(const std::array<plane, 3>& ycxcz, double ppd) {
  struct term {
    double a, b;
  };
  const std::array<std::array<term, 2>, 3> terms{{{{{1.0, 0.0047}, {0.0, 1e-5}}}, {{{1.0, 0.0053}, {0.0, 1e-5}}},
                                                 {{{34.1, 0.04}, {13.5, 0.025}}}}};
  const int radius = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * pi * pi)) * ppd));
  std::array<plane, 3> out;
  for (std::size_t c = 0; c < 3; ++c) {
    plane sum{ycxcz[c].width, ycxcz[c].height, std::vector<double>(ycxcz[c].v.size(), 0.0)};
    double total = 0.0;
    for (const term& t : terms[c]) {
      if (t.a == 0.0) continue;
      // exp(-pi^2 (x^2 + y^2) / (ppd^2 b)) = g(x) g(y), a Gaussian of sigma ppd sqrt(b / 2) / pi.
      const std::vector<double> g = gaussian(radius, ppd * std::sqrt(t.b / 2.0) / pi, false);
      double g_sum = 0.0;
      for (double w : g) g_sum += w;
      const double weight = t.a * std::sqrt(pi / t.b);
      const plane f = filter(ycxcz[c], g, g);
      for (std::size_t i = 0; i < sum.v.size(); ++i) sum.v[i] += weight * f.v[i];
      total += weight * g_sum * g_sum;
    }
    for (double& v : sum.v) v /= total;
    out[c] = std::move(sum);
  }
  return out;
}

// Edge (first derivative) or point (second derivative) strength of the normalised achromatic channel:
// the magnitude of the responses along x and y to the paper's Gaussian-derivative kernels, positive
// weights summing to 1 and negative ones to -1.
plane features(const plane& y, double ppd, bool points) {
  const double sd = 0.5 * 0.082 * ppd;
  const int radius = int(std::ceil(3.0 * sd));
  const std::vector<double> g = gaussian(radius, sd, true);
  std::vector<double> d;
  double positive = 0.0, negative = 0.0;
  for (int x = -radius; x <= radius; ++x) {
    const double w = std::exp(-double(x * x) / (2.0 * sd * sd)) * (points ? double(x * x) / (sd * sd) - 1.0 : -double(x));
    d.push_back(w);
    (w > 0.0 ? positive : negative) += std::fabs(w);
  }
  for (double& w : d) w /= w > 0.0 ? positive : negative;
  const plane fx = filter(y, d, g), fy = filter(y, g, d);
  plane out{y.width, y.height, std::vector<double>(y.v.size())};
  for (std::size_t i = 0; i < out.v.size(); ++i) out.v[i] = std::hypot(fx.v[i], fy.v[i]);
  return out;
}

}  // namespace

std::vector<double> ssim_map(const image& a, const image& b) {
  const std::vector<double> g = gaussian(5, 1.5, true);
  const double c1 = (0.01 * 255.0) * (0.01 * 255.0), c2 = (0.03 * 255.0) * (0.03 * 255.0);
  std::vector<double> out(std::size_t(a.width) * std::size_t(a.height), 0.0);
  for (int c = 0; c < 3; ++c) {
    const plane x = channel(a, c, 1.0), y = channel(b, c, 1.0);
    plane xx = x, yy = y, xy = x;
    for (std::size_t i = 0; i < x.v.size(); ++i) {
      xx.v[i] = x.v[i] * x.v[i];
      yy.v[i] = y.v[i] * y.v[i];
      xy.v[i] = x.v[i] * y.v[i];
    }
    const plane mx = filter(x, g, g), my = filter(y, g, g), sxx = filter(xx, g, g), syy = filter(yy, g, g),
                sxy = filter(xy, g, g);
    for (std::size_t i = 0; i < out.size(); ++i) {
      const double ux = mx.v[i], uy = my.v[i];
      const double vx = sxx.v[i] - ux * ux, vy = syy.v[i] - uy * uy, cov = sxy.v[i] - ux * uy;
      out[i] += (2.0 * ux * uy + c1) * (2.0 * cov + c2) / ((ux * ux + uy * uy + c1) * (vx + vy + c2)) / 3.0;
    }
  }
  return out;
}

std::vector<double> flip_map(const image& test, const image& reference, double ppd) {
  const double qc = 0.7, qf = 0.5, pc = 0.4, pt = 0.95;
  const std::array<plane, 3> ref = opponent(reference), tst = opponent(test);
  const std::array<plane, 3> ref_f = csf_filtered(ref, ppd), tst_f = csf_filtered(tst, ppd);
  // The largest colour difference: green against blue.
  const double cmax = std::pow(hyab(hunt_lab({0.0, 1.0, 0.0}), hunt_lab({0.0, 0.0, 1.0})), qc);
  auto lab = [](const std::array<plane, 3>& p, std::size_t i) {
    vec3d c = xyz_to_linear(ycxcz_to_xyz({p[0].v[i], p[1].v[i], p[2].v[i]}));
    for (double& v : c) v = std::clamp(v, 0.0, 1.0);
    return hunt_lab(c);
  };
  // The achromatic channel normalised to [0, 1]: the luminance relative to white.
  auto luminance = [](const plane& y) {
    plane out = y;
    for (double& v : out.v) v = (v + 16.0) / 116.0;
    return out;
  };
  const plane ry = luminance(ref[0]), ty = luminance(tst[0]);
  const plane re = features(ry, ppd, false), te = features(ty, ppd, false), rp = features(ry, ppd, true),
              tp = features(ty, ppd, true);
  std::vector<double> out(ref[0].v.size());
  for (std::size_t i = 0; i < out.size(); ++i) {
    const double e = std::pow(hyab(lab(ref_f, i), lab(tst_f, i)), qc);
    const double colour = e < pc * cmax ? pt / (pc * cmax) * e : pt + (e - pc * cmax) / (cmax - pc * cmax) * (1.0 - pt);
    const double feature = std::pow(std::max(std::fabs(re.v[i] - te.v[i]), std::fabs(rp.v[i] - tp.v[i])) / std::sqrt(2.0), qf);
    out[i] = std::pow(colour, 1.0 - feature);
  }
  return out;
}

image_error compare(const image& test, const image& reference, const std::vector<bool>& mask) {
  const std::vector<double> ssim = ssim_map(test, reference), flip = flip_map(test, reference);
  struct sums {
    double squares = 0.0, ssim = 0.0, flip = 0.0;
    std::size_t pixels = 0;
  } all, masked;
  for (std::size_t i = 0; i < ssim.size(); ++i) {
    double d2 = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = double(test.rgba[4 * i + c]) - double(reference.rgba[4 * i + c]);
      d2 += d * d;
    }
    for (sums* s : {&all, mask[i] ? &masked : nullptr}) {
      if (!s) continue;
      s->squares += d2;
      s->ssim += ssim[i];
      s->flip += flip[i];
      ++s->pixels;
    }
  }
  auto figures = [](const sums& s) {
    error_figures f;
    if (s.pixels == 0) return f;
    f.rmse = std::sqrt(s.squares / double(3 * s.pixels));
    f.psnr = f.rmse > 0.0 ? 20.0 * std::log10(255.0 / f.rmse) : INFINITY;
    f.ssim = s.ssim / double(s.pixels);
    f.flip = s.flip / double(s.pixels);
    return f;
  };
  return {figures(all), figures(masked)};
}

nlohmann::ordered_json with_errors(nlohmann::ordered_json record, const image_error& e) {
  record["rmse"] = e.all.rmse;
  record["rmse_transparent"] = e.masked.rmse;
  record["psnr"] = std::isfinite(e.all.psnr) ? nlohmann::ordered_json(e.all.psnr) : nlohmann::ordered_json(nullptr);
  record["ssim"] = e.all.ssim;
  record["ssim_transparent"] = e.masked.ssim;
  record["flip"] = e.all.flip;
  record["flip_transparent"] = e.masked.flip;
  return record;
}

}  // namespace dstrans::render
