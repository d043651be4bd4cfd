// Two configurations timed frame against frame. A and B alternate (A B B A, then again), so whatever else
// the machine does slows both alike, and their ratio comes with a 95% interval from the pairs.
//
//   auto a = dstrans::render::gl_clock({room}, interlaced, shaders), b = dstrans::render::gl_clock({room}, peeling, shaders);
//   auto r = dstrans::cli::time_paired(*a, *b, 2, {15, 60, 0.03});   // 2 warm-up pairs, then 15 to 60 measured
//   std::printf("peeling takes %.2fx [%.2f, %.2f]\n", r->ratio, r->low, r->high);
//   auto lit = dstrans::cli::time_paired(*a, *b, 2, {15, 60, 0.03}, {"light"}, {"light"});   // one timer's ratio
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include <dstrans/frame/schedule.hpp>
#include <dstrans/result.hpp>

namespace dstrans::cli {

// One frame of a configuration: its GPU times in milliseconds (the frame's and each timer's), or why it failed.
using frame_clock = std::function<result<frame_times>()>;

// What a clock reports of one frame's times: the sum of `timers`, or the whole frame where none are named;
// a timer the frame does not have is an error, so that a misnamed one never reads as free.
result<double> timed(const frame_times& t, const std::vector<std::string>& timers);

struct paired_ratio {
  double ratio = 0.0;            // B's median frame over A's
  double low = 0.0, high = 0.0;  // its 95% interval: the pairs resampled (bootstrap, a fixed seed)
  int frames = 0;                // measured pairs
  double a_ms = 0.0, b_ms = 0.0; // the medians
  double spread = 0.0;           // the interval's width over the ratio
  std::map<std::string, double> a_pass_ms, b_pass_ms;  // each timer's median over the same frames
  double a_frame_ms = 0.0, b_frame_ms = 0.0;            // and the whole frame's
};

// How many pairs to measure: at least `min_frames`, then more until the interval's width is at most
// `spread` of the ratio, or `max_frames` are measured.
struct pair_count {
  int min_frames = 15, max_frames = 60;
  double spread = 0.03;
};

// The ratio of B's median to A's over pairs (a[i], b[i]), with its interval; frames 0 where there are no pairs.
paired_ratio ratio_of(const std::vector<double>& a, const std::vector<double>& b);

// What `with` costs beyond `without`, as a clock: each call renders a frame of each, and gives the frame's
// difference and each timer's (a timer `without` lacks counts whole, one only it has is left out), so that
// work a driver runs under another pass's timestamps still counts.
frame_clock difference(frame_clock with, frame_clock without);

// Pairs of A and B as `count` asks, after `warmup` pairs that are not counted, each side's time that of
// its `timers` (timed: the whole frame where none are named).
result<paired_ratio> time_paired(const frame_clock& a, const frame_clock& b, int warmup, const pair_count& count,
                                 const std::vector<std::string>& a_timers = {}, const std::vector<std::string>& b_timers = {});

}  // namespace dstrans::cli
