// The thesis's renderer on OpenGL 4.5 (TECHNIQUES.md S0): G-buffer with interlaced transparency, light
// accumulation with transparent shadow maps, compose with refraction. Draws in the current context.
#pragma once

#include <functional>
#include <map>
#include <string>

#include <dstrans/pass_shaders.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

#include <dstrans/frame/plan.hpp>
#include "frame_output.hpp"

namespace dstrans::render {

// What an interactive caller (examples/viewer) does around each frame: `before` may move the camera and
// returns false to stop (it is asked before frame 0 too); `after` gets the framebuffer that holds the
// final image (row 0 at the top) and the frame's pass times.
struct frame_hooks {
  std::function<bool(int frame, camera& view)> before;
  std::function<void(unsigned framebuffer, const std::map<std::string, double>& pass_ms)> after;
};

// One frame of `s` (o.frames frames, or as many as hooks->before allows) with the pass shaders `shaders`.
result<frame> render_gl(const scene& s, const options& o, const pass_shaders& shaders,
                        const frame_hooks* hooks = nullptr);

}  // namespace dstrans::render
