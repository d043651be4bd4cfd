// How far a pass is from what the machine can do: the bytes its resources hold, and the time of a copy
// that reads and writes as many bytes, measured on the same device in the same run.
//
//   const auto plan = dstrans::render::plan_of(s, o);
//   const auto bytes = dstrans::cli::timer_bytes(dstrans::render::schedule_of(s, plan, o), plan, o);
//   dstrans::cli::limit_meter meter(dstrans::render::gl_copy_clock());
//   auto ms = meter.limits(bytes);   // the "light" timer's passes would take ms->at("light") as copies
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>

#include <dstrans/frame/plan.hpp>
#include <dstrans/frame/schedule.hpp>
#include <dstrans/glsl.hpp>
#include <dstrans/result.hpp>

namespace dstrans::cli {

// Bytes of a schedule resource at the options' size ("gbuffer", "light buffer 2", "shadow map", "kbuffer",
// "lit", "frame", a post target): its targets' texels summed. The k-buffer's node pool counts k nodes a
// pixel, what the resolve reads; the shadow layers, a copy of the shadow map's targets a shadowed light.
// The scene's meshes and the light volumes' texels count nothing: they are sized by the scene, not the
// screen, and a screen copy does not bound them.
std::size_t resource_bytes(const std::string& resource, const render::frame_plan& plan, const render::options& o);

// For each timer of the schedule, the bytes its passes move: for each pass half of what its reads and
// writes hold together (of the shadow layers, a light's pass touches its own), so that a copy of that many
// bytes reads and writes as many as the pass touches.
std::map<std::string, std::size_t> timer_bytes(const frame_schedule& s, const render::frame_plan& plan, const render::options& o);

// The copy, as a full-screen pass draws it: each pixel of the RGBA32F target the texel of the RGBA32F image
// at image unit (binding) 0, so that it reads and writes through the same paths the passes do.
glsl::source copy_fragment_shader();

// A copy of `bytes` on the GPU: its time in milliseconds, or why it failed.
using copy_clock = std::function<result<double>(std::size_t bytes)>;

// Copy times, each the median of five copies of that size, measured once a size and kept.
class limit_meter {
 public:
  explicit limit_meter(copy_clock clock) : clock_(std::move(clock)) {}
  result<double> copy_ms(std::size_t bytes);
  // Each timer's bytes as a copy's time (0 for none).
  result<std::map<std::string, double>> limits(const std::map<std::string, std::size_t>& bytes);

 private:
  copy_clock clock_;
  std::map<std::size_t, double> measured_;
};

}  // namespace dstrans::cli
