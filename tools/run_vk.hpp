// A scene's frames on Vulkan, as the command line takes them: its meshes drawn through
// dstrans::vk::renderer (dstrans_vk_frame.hpp), recorded into dstrans::vk::device's command buffer and
// submitted, o.frames times, and read back.
#pragma once

#include <dstrans/frame/plan.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>
#include <dstrans_vk.hpp>

#include "frame_output.hpp"
#include "limit.hpp"
#include "paired.hpp"

namespace dstrans::render {

// The last of o.frames frames of `s` on `dev` (times: their medians), with the pass shaders `shaders`.
result<frame> run_vk(vk::device& dev, const scene& s, const options& o, const pass_shaders& shaders);
// One renderer's frames of `frames` on `dev` in turn (each its own camera and objects; the first describes
// the scene to the renderer), each read back with its GPU times.
result<std::vector<frame>> run_vk_sequence(vk::device& dev, const std::vector<scene>& frames, const options& o,
                                           const pass_shaders& shaders);
// One frame a call on `dev`, each the next of `frames` (after the last, the first again; the first describes
// the scene to the renderer), each with its GPU times, through a renderer the clock keeps (paired.hpp); `dev`
// outlives the clock.
result<cli::frame_clock> vk_clock(vk::device& dev, const std::vector<scene>& frames, const options& o, const pass_shaders& shaders);
// Full-screen copies between two RGBA32F images on `dev` (limit.hpp), which outlives the clock: a size past
// their 32 MiB takes as many copies, all in one submission timed by its timestamps.
cli::copy_clock vk_copy_clock(vk::device& dev);

}  // namespace dstrans::render
