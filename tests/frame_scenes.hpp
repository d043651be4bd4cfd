// What the frame executor tests share: the example scenes by file name, and small frame options.
#pragma once

#include <catch2/catch.hpp>

#include <string>

#include <dstrans/frame/plan.hpp>
#include <scene_json.hpp>

namespace frame_tests {

inline dstrans::scene example(const std::string& file) {
  auto s = dstrans::load_scene(std::string(DSTRANS_SOURCE_DIR) + "/examples/scenes/" + file);
  INFO(s.error());
  REQUIRE(s);
  return *s;
}

// A `w` x `h` frame with a 256-texel shadow map.
inline dstrans::render::options sized(int w, int h) {
  dstrans::render::options o;
  o.width = w;
  o.height = h;
  o.shadow_size = 256;
  return o;
}

}  // namespace frame_tests
