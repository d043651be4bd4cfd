// What the frame executor tests share: the example scenes by file name, small frame options, and a pane
// that moves between frames.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

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

// pane.json's blue pane before and after it moves 0.6 to the right, and the scene without it.
struct moved_pane {
  dstrans::scene before, after, without;
};
inline moved_pane moved_pane_scenes() {
  moved_pane m;
  m.before = example("pane.json");
  m.after = m.before;
  m.after.objects[2].transform = glm::translate(glm::mat4(1.0f), glm::vec3(0.6f, 0.0f, 0.0f)) * m.after.objects[2].transform;
  m.without = m.before;
  m.without.objects.erase(m.without.objects.begin() + 2);
  return m;
}

// The pixels where two images of `w` x `h` differ, grown by `grow` pixels in every direction.
inline std::vector<bool> differing(const std::vector<dstrans::texel>& a, const std::vector<dstrans::texel>& b, int w, int h, int grow) {
  std::vector<bool> out(a.size(), false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (a[std::size_t(y * w + x)] == b[std::size_t(y * w + x)]) continue;
      for (int j = std::max(0, y - grow); j <= std::min(h - 1, y + grow); ++j)
        for (int i = std::max(0, x - grow); i <= std::min(w - 1, x + grow); ++i) out[std::size_t(j * w + i)] = true;
    }
  return out;
}

// Checks a temporal frame of the moved pane (`moved`: `before` drawn, then `after`) against the first frame
// of `after` (`fresh`) where the pane was and is not now (where `before` differs from `without`, more than
// 2 pixels from where `after` does): equal there, at least 300 pixels.
inline void check_nothing_left(const std::vector<dstrans::texel>& moved, const std::vector<dstrans::texel>& fresh,
                               const std::vector<dstrans::texel>& before, const std::vector<dstrans::texel>& without, int w, int h) {
  const std::vector<bool> now = differing(fresh, without, w, h, 2), then = differing(before, without, w, h, 0);
  std::size_t left = 0, wrong = 0;
  for (std::size_t i = 0; i < now.size(); ++i)
    if (then[i] && !now[i]) {
      ++left;
      wrong += moved[i] != fresh[i];
    }
  CHECK(left > 300);
  CHECK(wrong == 0);
}

}  // namespace frame_tests
