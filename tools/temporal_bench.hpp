// The temporal benchmark: camera paths over glass_room and a moving pane, each frame of each method compared
// with depth peeling of the same frame, and a strip of crops of the last frames.
//
//   auto t = dstrans::cli::temporal_records(room, options, 8, "gl", draw_sequence, clock, {15, 60, 0.03});
//   results.insert(results.end(), t->records.begin(), t->records.end());   // one a path and method
//   write(png_bytes(t->strip));                       // a row a path: thesis, spatial, temporal, peeling
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include <dstrans/frame/plan.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

#include "frame_output.hpp"
#include "paired.hpp"

namespace dstrans::cli {

// A sequence of frames through one renderer (render::run_gl_sequence, render::run_vk_sequence).
using sequence_draw = std::function<result<std::vector<render::frame>>(const std::vector<scene>&, const render::options&)>;
// A clock over a sequence of frames, a frame a call (render::gl_clock, render::vk_clock).
using sequence_clock = std::function<result<frame_clock>(const std::vector<scene>&, const render::options&)>;

// `room` seen along each path, `frames` frames: a still camera, a slow orbit (half a degree a frame about the
// target), a fast pan (two degrees of yaw a frame), a dolly towards the target through the panes (4% of the
// distance a frame), and a still camera over the first glass object moving 2 cm a frame to the right.
std::vector<std::pair<std::string, std::vector<scene>>> temporal_paths(const scene& room, int frames);

struct temporal_results {
  nlohmann::ordered_json records;  // a path and method each
  render::image strip;             // a row a path: the last frame of thesis, spatial, temporal and peeling
};

// Each path of temporal_paths drawn by the thesis's method (the partner, Table 3.1's layout), the spatial one
// (edge-aware reconstruction, compact layout), the temporal one (temporal interlacing over the partner fetch,
// compact layout) and depth peeling (in both layouts); each frame after the first against peeling's of the
// same frame in the method's layout, on the glass peeling's first layer holds: mean and worst errors, the
// RMSE against Table 3.1's peeling, the frame-to-frame change from the second frame on (on the still path,
// the flicker once the temporal method has a history; null with fewer than three frames), the mean
// FLIP on glass against the exact reference of each frame (null where its lists overflowed), the median
// frame time and bytes a pixel, with Table 3.1 peeling's time beside them. The temporal method's time is
// also taken frame against frame with Table 3.1 peeling's along the path on `clock` (time_paired, `count`
// pairs), as the ratio of its frame to peeling's with a 95% interval.
result<temporal_results> temporal_records(const scene& room, const render::options& base, int frames, const std::string& backend,
                                          const sequence_draw& draw, const sequence_clock& clock, const pair_count& count);

}  // namespace dstrans::cli
