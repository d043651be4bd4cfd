// Which frames of a sequence hold the same objects, so that a camera moving through a still scene uploads
// its meshes once rather than once a frame.
//
//   const std::vector<std::size_t> from = dstrans::render::first_with_same_objects(frames);
//   for (std::size_t i = 0; i < frames.size(); ++i)
//     meshes.push_back(from[i] == i ? upload(frames[i]) : meshes[from[i]]);
#pragma once

#include <cstddef>
#include <vector>

#include <dstrans/scene.hpp>

namespace dstrans::render {

// Whether a and b hold the same objects, in the same order: equal vertices, indices, texture coordinates,
// transforms and materials (a NaN anywhere makes them differ).
inline bool same_objects(const scene& a, const scene& b) {
  if (a.objects.size() != b.objects.size()) return false;
  for (std::size_t k = 0; k < a.objects.size(); ++k) {
    const object &x = a.objects[k], &y = b.objects[k];
    if (x.material != y.material || x.transform != y.transform || x.geometry.positions != y.geometry.positions ||
        x.geometry.normals != y.geometry.normals || x.geometry.indices != y.geometry.indices || x.geometry.uvs != y.geometry.uvs)
      return false;
  }
  return true;
}

// For each of `frames`, the first frame whose objects are the same as its own (its own index where no
// frame before it has them).
inline std::vector<std::size_t> first_with_same_objects(const std::vector<scene>& frames) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::size_t first = i;
    for (std::size_t j = 0; j < i && first == i; ++j)
      if (out[j] == j && same_objects(frames[j], frames[i])) first = j;
    out.push_back(first);
  }
  return out;
}

}  // namespace dstrans::render
