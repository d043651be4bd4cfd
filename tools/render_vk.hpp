// The thesis's renderer on Vulkan: the same passes and shaders as render_gl, on dstrans::vk::device.
#pragma once

#include <string>

#include <dstrans/pass_shaders.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>
#include <dstrans_vk.hpp>

#include <dstrans/frame/plan.hpp>
#include "frame_output.hpp"

namespace dstrans::render {

// One frame of `s` on `dev` with the pass shaders `shaders`.
result<frame> render_vk(vk::device& dev, const scene& s, const options& o, const pass_shaders& shaders);

}  // namespace dstrans::render
