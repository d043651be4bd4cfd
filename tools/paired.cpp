// Implements paired.hpp.
#include "paired.hpp"

#include <algorithm>
#include <cstdint>

namespace dstrans::cli {

namespace {
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

paired_ratio ratio_of(const std::vector<double>& a, const std::vector<double>& b) {
  paired_ratio r;
  const std::size_t n = std::min(a.size(), b.size());
  if (n == 0) return r;
  r.frames = int(n);
  r.a_ms = median({a.begin(), a.begin() + std::ptrdiff_t(n)});
  r.b_ms = median({b.begin(), b.begin() + std::ptrdiff_t(n)});
  r.ratio = r.a_ms > 0.0 ? r.b_ms / r.a_ms : 0.0;
  // 2000 resamples of the pairs: a pair keeps its two frames together, so noise both shared cancels.
  std::uint64_t state = 0x9e3779b97f4a7c15ull;
  std::vector<double> ratios, ra(n), rb(n);
  for (int k = 0; k < 2000; ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      state = state * 6364136223846793005ull + 1442695040888963407ull;
      const std::size_t j = std::size_t((state >> 33) % n);
      ra[i] = a[j];
      rb[i] = b[j];
    }
    const double ma = median(ra);
    ratios.push_back(ma > 0.0 ? median(rb) / ma : 0.0);
  }
  std::sort(ratios.begin(), ratios.end());
  r.low = ratios[std::size_t(0.025 * double(ratios.size()))];
  r.high = ratios[std::size_t(0.975 * double(ratios.size())) - 1];
  r.spread = r.ratio > 0.0 ? (r.high - r.low) / r.ratio : 0.0;
  return r;
}

result<paired_ratio> time_paired(const frame_clock& a, const frame_clock& b, int warmup, const pair_count& count) {
  std::vector<double> ta, tb;
  for (int i = 0; i < warmup + count.max_frames; ++i) {
    const bool a_first = i % 2 == 0;  // A B, then B A
    result<double> first = a_first ? a() : b();
    if (!first) return failure{first.error()};
    result<double> second = a_first ? b() : a();
    if (!second) return failure{second.error()};
    if (i < warmup) continue;
    ta.push_back(a_first ? *first : *second);
    tb.push_back(a_first ? *second : *first);
    if (int(ta.size()) >= count.min_frames && ratio_of(ta, tb).spread <= count.spread) break;
  }
  return ratio_of(ta, tb);
}

}  // namespace dstrans::cli
