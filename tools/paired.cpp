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

result<double> timed(const frame_times& t, const std::vector<std::string>& timers) {
  if (timers.empty()) return t.frame_ms;
  double sum = 0.0;
  for (const std::string& name : timers) {
    const auto found = t.pass_ms.find(name);
    if (found == t.pass_ms.end()) return failure{"the frame has no timer '" + name + "'"};
    sum += found->second;
  }
  return sum;
}

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

frame_clock difference(frame_clock with, frame_clock without) {
  return [with = std::move(with), without = std::move(without)]() -> result<frame_times> {
    result<frame_times> a = with();
    if (!a) return a;
    result<frame_times> b = without();
    if (!b) return b;
    frame_times d = *a;
    d.frame_ms -= b->frame_ms;
    for (auto& [timer, ms] : d.pass_ms)
      if (const auto found = b->pass_ms.find(timer); found != b->pass_ms.end()) ms -= found->second;
    return d;
  };
}

result<paired_ratio> time_paired(const frame_clock& a, const frame_clock& b, int warmup, const pair_count& count,
                                 const std::vector<std::string>& a_timers, const std::vector<std::string>& b_timers) {
  std::vector<double> ta, tb, fa, fb;
  std::map<std::string, std::vector<double>> pa, pb;
  auto keep = [](const frame_times& t, const std::vector<std::string>& timers, std::vector<double>& total,
                 std::vector<double>& frames, std::map<std::string, std::vector<double>>& passes) -> result<bool> {
    auto ms = timed(t, timers);
    if (!ms) return failure{ms.error()};
    total.push_back(*ms);
    frames.push_back(t.frame_ms);
    for (const auto& [timer, pass_ms] : t.pass_ms) passes[timer].push_back(pass_ms);
    return true;
  };
  for (int i = 0; i < warmup + count.max_frames; ++i) {
    const bool a_first = i % 2 == 0;  // A B, then B A
    result<frame_times> first = a_first ? a() : b();
    if (!first) return failure{first.error()};
    result<frame_times> second = a_first ? b() : a();
    if (!second) return failure{second.error()};
    if (i < warmup) continue;
    if (auto ok = keep(a_first ? *first : *second, a_timers, ta, fa, pa); !ok) return failure{ok.error()};
    if (auto ok = keep(a_first ? *second : *first, b_timers, tb, fb, pb); !ok) return failure{ok.error()};
    if (int(ta.size()) >= count.min_frames && ratio_of(ta, tb).spread <= count.spread) break;
  }
  paired_ratio r = ratio_of(ta, tb);
  for (const auto& [timer, v] : pa) r.a_pass_ms[timer] = median(v);
  for (const auto& [timer, v] : pb) r.b_pass_ms[timer] = median(v);
  if (!fa.empty()) {
    r.a_frame_ms = median(fa);
    r.b_frame_ms = median(fb);
  }
  return r;
}

}  // namespace dstrans::cli
