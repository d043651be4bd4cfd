// The thesis's renderer on OpenGL 4.5 (TECHNIQUES.md S0): G-buffer with interlaced transparency, light
// accumulation with transparent shadow maps, compose with refraction. Draws in the current context.
#pragma once

#include <string>

#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

#include "frame_data.hpp"
#include "frame_output.hpp"

namespace dstrans::render {

// One frame of `s`; `shader_dir` holds the pass shaders (shaders/glsl).
result<frame> render_gl(const scene& s, const options& o, const std::string& shader_dir);

}  // namespace dstrans::render
