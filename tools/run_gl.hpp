// A scene's frames on OpenGL, as the command line takes them: its meshes drawn through
// dstrans::gl::renderer (dstrans_gl_frame.hpp) in the current context, o.frames times, and read back.
#pragma once

#include <dstrans/frame/plan.hpp>
#include <dstrans/pass_shaders.hpp>
#include <dstrans/result.hpp>
#include <dstrans/scene.hpp>

#include "frame_output.hpp"
#include "limit.hpp"
#include "paired.hpp"

namespace dstrans::render {

// The last of o.frames frames of `s` (times: their medians), with the pass shaders `shaders`.
result<frame> run_gl(const scene& s, const options& o, const pass_shaders& shaders);
// One renderer's frames of `frames` in turn (each its own camera and objects; the first describes the
// scene to the renderer), each read back with its GPU times.
result<std::vector<frame>> run_gl_sequence(const std::vector<scene>& frames, const options& o, const pass_shaders& shaders);
// One frame a call, each the next of `frames` (after the last, the first again; the first describes the scene
// to the renderer), each with its GPU times, through a renderer the clock keeps (paired.hpp).
result<cli::frame_clock> gl_clock(const std::vector<scene>& frames, const options& o, const pass_shaders& shaders);
// Full-screen copies between two RGBA32F textures in the current context (limit.hpp): a size past their 32 MiB
// takes as many copies, timed by the host between two glFinish.
cli::copy_clock gl_copy_clock();

}  // namespace dstrans::render
