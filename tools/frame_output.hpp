// What a rendered frame leaves behind: the final image, the intermediate buffers as images, and the GPU
// time of each pass; written as final.png, <buffer>.png and frame.json.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include <dstrans/format.hpp>
#include <dstrans/result.hpp>

#include "output_dir.hpp"

namespace dstrans::render {

// 8-bit RGBA, rows from the top.
struct image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
};

struct frame {
  image final_image;
  std::vector<texel> final_texels;  // the final target as stored (RGBA8, or RGBA32F with float targets)
  // The raw targets, for checks of a pass against the CPU: deferred, the (first) G-buffer's four and the
  // light buffer's first target (Table 3.2, or float_light_buffer with float targets; with RGB specular, the
  // light without the specular); forward, the lit colour, normal and
  // (with depth) depth targets.
  std::vector<std::vector<texel>> gbuffer;
  std::vector<texel> light_buffer;
  std::vector<std::vector<texel>> lit;
  // The k-buffer as the last frame left it: each pixel's list head (0xffffffff: none), the nodes taken
  // (depth bits, packed tangent, packed colour, next), and the fragments that found no node.
  std::vector<std::uint32_t> kbuffer_heads;
  std::vector<glm::uvec4> kbuffer_nodes;
  std::uint32_t kbuffer_overflow = 0;
  // The light volumes' atlas as the last bake left it (render::particle_atlas's texels, RGBA8, x fastest).
  std::vector<std::uint8_t> volume_atlas;
  std::vector<std::pair<std::string, image>> buffers;  // in the order the passes make them
  std::vector<std::string> schedule;      // the passes the last frame ran, by pass_ms's names, in order
  std::map<std::string, double> pass_ms;  // the median over the frames rendered, per pass
  double frame_ms = 0.0;                   // the median frame: its passes in one submission, first to last
  double frame_ms_spread = 0.0;            // the interquartile range of the frame times
  int frames = 0;
};

// The pixels whose (first) G-buffer holds glass: Table 3.1's alpha below 1.
std::vector<bool> glass_pixels(const frame& f);

// The k-buffer's lists: how many pixels hold fragments, their mean and largest count.
struct layer_counts {
  std::size_t pixels = 0, max = 0;
  double mean = 0.0;
};
layer_counts count_layers(const frame& f);

// Fills `out`'s timings from the pass times of each frame rendered and each frame's whole GPU time as one
// submission (`totals`, one a frame).
void summarize(const std::vector<std::map<std::string, double>>& frames, const std::vector<double>& totals, frame& out);

// What each channel of a buffer shows in its picture.
enum class view_as { rgb, alpha, depth };

// Texels of a target (rows from the top) as a picture: colour channels as stored, one channel as grey,
// or window depth as linear distance from `near_plane` to `far_plane` (white at the far plane, as the
// thesis's Figure 4.3).
image to_image(const std::vector<texel>& texels, format f, int width, int height, view_as how, float near_plane = 0.1f,
               float far_plane = 100.0f);

// `img` as the bytes of a PNG file (empty if it cannot be encoded).
std::string png_bytes(const image& img);
// The PNG file `path` as 8-bit RGBA, or why it cannot be read.
result<image> read_png(const std::string& path);

// Adds final.png and one PNG per buffer to `out`, and frame.json's fields as its manifest (commit() writes it).
result<bool> write_frame(const frame& f, output_dir& out, const std::string& technique, const std::string& backend);

}  // namespace dstrans::render
