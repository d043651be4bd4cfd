// Implements scene_gltf.hpp with tinygltf (Debian's shared libtinygltf), which parses the file and its
// buffers and images; every index it leaves unchecked is checked here before it is followed.
#include "scene_gltf.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <dstrans/frame/plan.hpp>
#include <dstrans/refraction.hpp>
#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include "gltf_types.hpp"
#include "json_input.hpp"

namespace dstrans {

namespace {

struct bad_element {
  std::string message;
};

std::string at(const char* what, std::size_t i) { return std::string(what) + "[" + std::to_string(i) + "]"; }

// `index` as an index into `items`, or an error at `where`.
template <class T>
const T& item(const std::vector<T>& items, int index, const std::string& where) {
  if (index < 0 || std::size_t(index) >= items.size())
    throw bad_element{where + ": " + std::to_string(index) + " is not one of the " + std::to_string(items.size()) + " there are"};
  return items[std::size_t(index)];
}

// One component of type `type` at `p` as the specification reads it: floats as they are, integers as
// integers or, where `normalized`, scaled into [0, 1] (unsigned) or [-1, 1] (signed).
double component(const unsigned char* p, int type, bool normalized) {
  auto read = [&](auto v) {
    std::memcpy(&v, p, sizeof v);
    return v;
  };
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return double(read(float{}));
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? read(std::uint8_t{}) / 255.0 : read(std::uint8_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return normalized ? read(std::uint16_t{}) / 65535.0 : read(std::uint16_t{});
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return double(read(std::uint32_t{}));
    case TINYGLTF_COMPONENT_TYPE_BYTE: return normalized ? std::max(read(std::int8_t{}) / 127.0, -1.0) : read(std::int8_t{});
    case TINYGLTF_COMPONENT_TYPE_SHORT: return normalized ? std::max(read(std::int16_t{}) / 32767.0, -1.0) : read(std::int16_t{});
  }
  return 0.0;
}

// The bytes of `count` elements of `size` bytes, `stride` apart, from `offset` into buffer view `view`,
// checked to lie inside the view and its buffer.
const unsigned char* view_bytes(const tinygltf::Model& m, int view, std::size_t offset, std::size_t count, std::size_t size,
                                std::size_t stride, const std::string& where) {
  const tinygltf::BufferView& v = item(m.bufferViews, view, where + ".bufferView");
  const std::string in = "bufferViews[" + std::to_string(view) + "]";
  const tinygltf::Buffer& b = item(m.buffers, v.buffer, in + ".buffer");
  if (v.byteOffset > b.data.size() || v.byteLength > b.data.size() - v.byteOffset)
    throw bad_element{in + ": bytes " + std::to_string(v.byteOffset) + " to " + std::to_string(v.byteOffset + v.byteLength) +
                      " are past the " + std::to_string(b.data.size()) + " of buffers[" + std::to_string(v.buffer) + "]"};
  if (stride > 252 || (v.byteStride != 0 && stride < size))
    throw bad_element{in + ".byteStride: " + std::to_string(stride) + " is not from " + std::to_string(size) + " to 252"};
  // In 64 bits no product wraps: the budget bounds count (read_accessor) far below 2^56, and stride is below 2^8.
  const std::uint64_t end = count == 0 ? 0 : std::uint64_t(stride) * (count - 1) + size;
  if (offset > v.byteLength || end > v.byteLength - offset)
    throw bad_element{where + ": " + std::to_string(count) + " elements from byte " + std::to_string(offset) + " do not fit the " +
                      std::to_string(v.byteLength) + " bytes of " + in};
  return b.data.data() + v.byteOffset;
}

// Accessor `index` as `count` x `width` numbers, row by row, sparse substitutions applied; its type must
// have `width` components and one of `types` as its component type, and it may have at most `most`
// elements (the budget's: an accessor without a buffer view is zeros of any count the file names).
std::vector<double> read_accessor(const tinygltf::Model& m, int index, int width, std::initializer_list<int> types,
                                  std::size_t most, const std::string& where) {
  const tinygltf::Accessor& a = item(m.accessors, index, where);
  const std::string in = "accessors[" + std::to_string(index) + "]";
  if (tinygltf::GetNumComponentsInType(std::uint32_t(a.type)) != width)
    throw bad_element{in + ".type: " + std::to_string(width) + " components a vertex are needed for " + where};
  if (std::find(types.begin(), types.end(), a.componentType) == types.end())
    throw bad_element{in + ".componentType: " + std::to_string(a.componentType) + " is not a type " + where + " may have"};
  if (a.count > most || (a.sparse.isSparse && std::size_t(std::max(a.sparse.count, 0)) > most))  // count is unset unless sparse
    throw bad_element{in + ".count: " + std::to_string(a.count) + " elements are more than the budget holds (" + std::to_string(most) +
                      "; --budget MIB raises it)"};
  const std::size_t size = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType)));
  std::vector<double> out(a.count * std::size_t(width), 0.0);
  auto fill = [&](const unsigned char* p, std::size_t row) {
    for (int c = 0; c < width; ++c) out[row * std::size_t(width) + std::size_t(c)] = component(p + std::size_t(c) * size, a.componentType, a.normalized);
  };
  if (a.bufferView >= 0) {  // without one the accessor is zeros, before any sparse values
    const tinygltf::BufferView& v = item(m.bufferViews, a.bufferView, in + ".bufferView");
    const std::size_t stride = v.byteStride ? v.byteStride : size * std::size_t(width);
    const unsigned char* base = view_bytes(m, a.bufferView, a.byteOffset, a.count, size * std::size_t(width), stride, in);
    for (std::size_t i = 0; i < a.count; ++i) fill(base + a.byteOffset + i * stride, i);
  }
  if (a.sparse.isSparse) {
    const auto n = std::size_t(std::max(a.sparse.count, 0));
    const int index_type = a.sparse.indices.componentType;
    if (index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        index_type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
      throw bad_element{in + ".sparse.indices.componentType: " + std::to_string(index_type) + " is not an unsigned integer type"};
    const std::size_t index_size = std::size_t(tinygltf::GetComponentSizeInBytes(std::uint32_t(index_type)));
    const unsigned char* rows = view_bytes(m, a.sparse.indices.bufferView, std::size_t(std::max(a.sparse.indices.byteOffset, 0)), n,
                                           index_size, index_size, in + ".sparse.indices");
    const unsigned char* values = view_bytes(m, a.sparse.values.bufferView, std::size_t(std::max(a.sparse.values.byteOffset, 0)), n,
                                             size * std::size_t(width), size * std::size_t(width), in + ".sparse.values");
    for (std::size_t i = 0; i < n; ++i) {
      const double row = component(rows + std::size_t(std::max(a.sparse.indices.byteOffset, 0)) + i * index_size, index_type, false);
      if (row >= double(a.count))
        throw bad_element{in + ".sparse.indices[" + std::to_string(i) + "]: " + std::to_string(std::uint64_t(row)) + " is past its " +
                          std::to_string(a.count) + " elements"};
      fill(values + std::size_t(std::max(a.sparse.values.byteOffset, 0)) + i * size * std::size_t(width), std::size_t(row));
    }
  }
  return out;
}

// A number of an extension's object, `fallback` where it is absent; an error where it is not a finite number.
double ext_number(const tinygltf::Value& object, const char* key, double fallback, const std::string& where) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) throw bad_element{where + "." + key + ": not a finite number"};
  return v.GetNumberAsDouble();
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& map, const char* name) {
  auto it = map.find(name);
  return it == map.end() || !it->second.IsObject() ? nullptr : &it->second;
}

// glTF's material as dstrans's (scene_gltf.hpp says how), and whether any of it is drawn (MASK below the
// cutoff cuts the whole surface away).
std::pair<material, bool> from_gltf(const tinygltf::Material& g, const std::string& where) {
  const auto& pbr = g.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4) throw bad_element{where + ".pbrMetallicRoughness.baseColorFactor: 4 numbers are needed"};
  glm::vec4 base;
  for (int c = 0; c < 4; ++c) {
    const double v = pbr.baseColorFactor[std::size_t(c)];
    if (!std::isfinite(v)) throw bad_element{where + ".pbrMetallicRoughness.baseColorFactor[" + std::to_string(c) + "]: not finite"};
    base[c] = float(std::clamp(v, 0.0, 1.0));
  }
  auto unit = [&](double v, const char* key) {
    if (!std::isfinite(v)) throw bad_element{where + ".pbrMetallicRoughness." + key + ": not finite"};
    return float(std::clamp(v, 0.0, 1.0));
  };
  const float metallic = unit(pbr.metallicFactor, "metallicFactor"), roughness = unit(pbr.roughnessFactor, "roughnessFactor");
  material out;
  out.diffuse = glm::vec3(base);
  out.spec_intensity = (0.04f + 0.96f * metallic) * (1.0f - roughness);
  out.spec_power = shader::dst_phong_power_of_roughness(roughness);
  bool drawn = true;
  if (g.alphaMode == "BLEND") out.alpha = base.a;
  else if (g.alphaMode == "MASK") drawn = double(base.a) >= g.alphaCutoff;
  else if (g.alphaMode != "OPAQUE") throw bad_element{where + ".alphaMode: \"" + key_excerpt(g.alphaMode) + "\" is not OPAQUE, MASK or BLEND"};
  if (const tinygltf::Value* t = extension(g.extensions, "KHR_materials_transmission")) {
    const std::string in = where + ".extensions.KHR_materials_transmission";
    const auto transmission = float(std::clamp(ext_number(*t, "transmissionFactor", 0.0, in), 0.0, 1.0));
    if (transmission > 0.0f) {
      out.alpha *= 1.0f - transmission;
      const tinygltf::Value* ior = extension(g.extensions, "KHR_materials_ior");
      out.refractive = !ior || ext_number(*ior, "ior", 1.5, where + ".extensions.KHR_materials_ior") != 1.0;
      if (const tinygltf::Value* volume = extension(g.extensions, "KHR_materials_volume")) {
        const std::string vin = where + ".extensions.KHR_materials_volume";
        const double thickness = std::max(ext_number(*volume, "thicknessFactor", 0.0, vin), 0.0);
        const double distance = volume->Has("attenuationDistance") ? ext_number(*volume, "attenuationDistance", 0.0, vin) : INFINITY;
        if (!(distance > 0.0)) throw bad_element{vin + ".attenuationDistance: must be above 0"};
        glm::vec3 colour(1.0f);
        if (volume->Has("attenuationColor")) {
          const tinygltf::Value& c = volume->Get("attenuationColor");
          if (!c.IsArray() || c.ArrayLen() != 3) throw bad_element{vin + ".attenuationColor: 3 numbers are needed"};
          for (int k = 0; k < 3; ++k) {
            const tinygltf::Value& x = c.Get(k);
            if (!x.IsNumber() || !std::isfinite(x.GetNumberAsDouble()))
              throw bad_element{vin + ".attenuationColor[" + std::to_string(k) + "]: not a finite number"};
            colour[k] = float(std::clamp(x.GetNumberAsDouble(), 0.0, 1.0));
          }
        }
        out.diffuse *= glm::pow(colour, glm::vec3(float(thickness / distance)));
      }
    }
  }
  return {out, drawn};
}

// The node's transform relative to its parent: its matrix, or translation x rotation x scale.
glm::mat4 local_transform(const tinygltf::Node& n, const std::string& where) {
  auto numbers = [&](const std::vector<double>& v, std::size_t size, const char* key) {
    if (!v.empty() && v.size() != size) throw bad_element{where + "." + key + ": " + std::to_string(size) + " numbers are needed"};
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!(std::fabs(v[i]) <= double(std::numeric_limits<float>::max())))
        throw bad_element{where + "." + key + "[" + std::to_string(i) + "]: not a finite float"};
    return !v.empty();
  };
  glm::mat4 m(1.0f);
  if (numbers(n.matrix, 16, "matrix")) {
    for (int i = 0; i < 16; ++i) glm::value_ptr(m)[i] = float(n.matrix[std::size_t(i)]);  // both column-major
    return m;
  }
  if (numbers(n.translation, 3, "translation"))
    m = glm::translate(m, glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2])));
  if (numbers(n.rotation, 4, "rotation"))
    m *= glm::mat4_cast(glm::normalize(
        glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2]))));
  if (numbers(n.scale, 3, "scale")) m = glm::scale(m, glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2])));
  return m;
}

// Triangle corners of a primitive's `mode` over `n` vertex references (its indices, or 0..n-1).
std::vector<std::uint32_t> triangles(const std::vector<std::uint32_t>& refs, int mode, const std::string& where) {
  std::vector<std::uint32_t> out;
  const std::size_t n = refs.size();
  if (mode == TINYGLTF_MODE_TRIANGLES || mode == -1) {
    if (n % 3) throw bad_element{where + ": " + std::to_string(n) + " vertices do not make whole triangles"};
    return refs;
  }
  if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
    for (std::size_t i = 0; i + 2 < n; ++i)  // every other triangle turned back, to keep the strip's winding
      out.insert(out.end(), {refs[i + (i % 2)], refs[i + 1 - (i % 2)], refs[i + 2]});
  else if (mode == TINYGLTF_MODE_TRIANGLE_FAN)
    for (std::size_t i = 1; i + 1 < n; ++i) out.insert(out.end(), {refs[i], refs[i + 1], refs[0]});
  else
    throw bad_element{where + ".mode: " + std::to_string(mode) + " (points or lines) has no surface to shade; dstrans draws triangles"};
  return out;
}

// Where a material's texture coordinates come from: attribute TEXCOORD_<set> (-1: it has no texture),
// mapped by `transform` (KHR_texture_transform's offset, rotation and scale).
struct uv_source {
  int set = -1;
  glm::mat3 transform{1.0f};
};

// A primitive's geometry as a dstrans shape (scene_gltf.hpp: normals flat where absent, repaired where bad),
// with the texture coordinates `uv` says.
shape primitive_shape(const tinygltf::Model& m, const tinygltf::Primitive& p, std::size_t most, const uv_source& uv, const std::string& where) {
  auto position = p.attributes.find("POSITION");
  if (position == p.attributes.end()) throw bad_element{where + ".attributes.POSITION: absent"};
  const std::string pos_at = where + ".attributes.POSITION";
  const std::vector<double> xyz =
      read_accessor(m, position->second, 3,
                    {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                     TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
                    most, pos_at);
  const std::size_t vertices = xyz.size() / 3;
  for (std::size_t i = 0; i < xyz.size(); ++i)
    if (!std::isfinite(xyz[i]) || std::fabs(xyz[i]) > double(std::numeric_limits<float>::max()))
      throw bad_element{pos_at + "[" + std::to_string(i / 3) + "]: not a finite position (" + std::to_string(xyz[i]) + ")"};
  std::vector<std::uint32_t> refs;
  if (p.indices >= 0) {
    const std::string idx_at = where + ".indices";
    for (double v : read_accessor(m, p.indices, 1,
                                  {TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT,
                                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT},
                                  most, idx_at)) {
      if (v >= double(vertices))
        throw bad_element{idx_at + "[" + std::to_string(refs.size()) + "]: " + std::to_string(std::uint64_t(v)) + " is past the " +
                          std::to_string(vertices) + " vertices of attributes.POSITION"};
      refs.push_back(std::uint32_t(v));
    }
  } else {
    for (std::size_t i = 0; i < vertices; ++i) refs.push_back(std::uint32_t(i));
  }
  const std::vector<std::uint32_t> corners = triangles(refs, p.mode, where);
  auto vertex = [&](std::uint32_t i) { return glm::vec3(float(xyz[3 * i]), float(xyz[3 * i + 1]), float(xyz[3 * i + 2])); };
  auto face_normal = [&](std::size_t t) {
    const glm::vec3 a = vertex(corners[t]), b = vertex(corners[t + 1]), c = vertex(corners[t + 2]);
    const glm::vec3 n = glm::cross(b - a, c - a);
    const float length = glm::length(n);
    return length > 0.0f && std::isfinite(length) ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);  // a degenerate one draws nothing
  };
  std::vector<glm::vec2> uvs;
  if (uv.set >= 0) {
    const std::string name = "TEXCOORD_" + std::to_string(uv.set), uv_at = where + ".attributes." + name;
    auto found = p.attributes.find(name);
    if (found == p.attributes.end()) throw bad_element{uv_at + ": absent, and its material's baseColorTexture reads it"};
    const std::vector<double> st = read_accessor(
        m, found->second, 2, {TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT},
        most, uv_at);
    if (st.size() / 2 != vertices)
      throw bad_element{uv_at + ": " + std::to_string(st.size() / 2) + " coordinates for " + std::to_string(vertices) + " positions"};
    for (std::size_t i = 0; i < vertices; ++i) {
      if (!(std::fabs(st[2 * i]) <= 1e30 && std::fabs(st[2 * i + 1]) <= 1e30))
        throw bad_element{uv_at + "[" + std::to_string(i) + "]: not finite"};
      uvs.emplace_back(uv.transform * glm::vec3(float(st[2 * i]), float(st[2 * i + 1]), 1.0f));
    }
  }
  shape s;
  auto normal = p.attributes.find("NORMAL");
  if (normal == p.attributes.end()) {  // flat: each triangle's own three vertices
    for (std::size_t t = 0; t < corners.size(); t += 3)
      for (std::size_t k = 0; k < 3; ++k) {
        s.indices.push_back(std::uint32_t(s.positions.size()));
        s.positions.push_back(vertex(corners[t + k]));
        s.normals.push_back(face_normal(t));
        if (!uvs.empty()) s.uvs.push_back(uvs[corners[t + k]]);
      }
    return s;
  }
  const std::vector<double> n = read_accessor(m, normal->second, 3, {TINYGLTF_COMPONENT_TYPE_FLOAT}, most, where + ".attributes.NORMAL");
  if (n.size() != xyz.size())
    throw bad_element{where + ".attributes.NORMAL: " + std::to_string(n.size() / 3) + " normals for " + std::to_string(vertices) + " positions"};
  std::vector<bool> repaired(vertices, false);
  for (std::size_t i = 0; i < vertices; ++i) {
    s.positions.push_back(vertex(std::uint32_t(i)));
    const glm::vec3 v(float(n[3 * i]), float(n[3 * i + 1]), float(n[3 * i + 2]));
    const float length = glm::length(v);
    repaired[i] = !(length > 0.0f) || !std::isfinite(length);
    s.normals.push_back(repaired[i] ? glm::vec3(0.0f) : v / length);
  }
  for (std::size_t t = 0; t < corners.size(); t += 3)
    for (std::size_t k = 0; k < 3; ++k)
      if (repaired[corners[t + k]]) {
        s.normals[corners[t + k]] = face_normal(t);
        repaired[corners[t + k]] = false;
      }
  s.indices = corners;
  s.uvs = std::move(uvs);
  return s;
}

// The wrap mode of a glTF sampler's wrapS or wrapT.
wrap wrap_of(int mode, const std::string& where) {
  switch (mode) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return wrap::repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return wrap::clamp;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return wrap::mirror;
  }
  throw bad_element{where + ": " + std::to_string(mode) + " is not 10497 (REPEAT), 33071 (CLAMP_TO_EDGE) or 33648 (MIRRORED_REPEAT)"};
}

// Image `img`'s bytes (kept encoded by keep_encoded) decoded as RGBA8, at most `budget` bytes of texels.
texture decoded(const tinygltf::Image& img, std::size_t budget, const std::string& where) {
  if (img.image.empty() || img.image.size() > std::size_t(std::numeric_limits<int>::max()))
    throw bad_element{where + ": no image data was read (" + (img.uri.empty() ? "bufferView " + std::to_string(img.bufferView) : key_excerpt(img.uri)) + ")"};
  const int size = int(img.image.size());
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(img.image.data(), size, &w, &h, &channels))
    throw bad_element{where + ": not an image that can be read (" + stbi_failure_reason() + ")"};
  if (std::size_t(w) * std::size_t(h) * 4u > budget)
    throw bad_element{where + ": " + std::to_string(w) + " x " + std::to_string(h) + " texels take " + mib(std::size_t(w) * std::size_t(h) * 4u) +
                      " MiB, over what is left of the budget (" + mib(budget) + " MiB; --budget MIB raises it)"};
  stbi_uc* pixels = stbi_load_from_memory(img.image.data(), size, &w, &h, &channels, 4);
  if (!pixels) throw bad_element{where + ": not an image that can be read (" + stbi_failure_reason() + ")"};
  texture t;
  t.width = w;
  t.height = h;
  t.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4u);
  stbi_image_free(pixels);
  return t;
}

// The extensions this file reads, which a file may require.
const std::set<std::string>& readable_extensions() {
  static const std::set<std::string> k = {"KHR_lights_punctual", "KHR_materials_transmission", "KHR_materials_ior",
                                          "KHR_materials_volume", "KHR_texture_transform"};
  return k;
}

// A punctual light at its node's world transform (scene_gltf.hpp: ranges, intensities, shadows).
light from_gltf(const tinygltf::Light& g, const glm::mat4& world, const std::string& where) {
  light l;
  if (g.type == "directional") l.kind = light_kind::directional;
  else if (g.type == "point") l.kind = light_kind::point;
  else if (g.type == "spot") l.kind = light_kind::spot;
  else throw bad_element{where + ".type: \"" + key_excerpt(g.type) + "\" is not directional, point or spot"};
  if (!g.color.empty()) {
    if (g.color.size() != 3) throw bad_element{where + ".color: 3 numbers are needed"};
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(g.color[std::size_t(c)])) throw bad_element{where + ".color[" + std::to_string(c) + "]: not finite"};
      l.colour[c] = float(std::max(g.color[std::size_t(c)], 0.0));
    }
  }
  if (!std::isfinite(g.intensity) || g.intensity < 0.0) throw bad_element{where + ".intensity: not a finite number at least 0"};
  if (!std::isfinite(g.range) || g.range < 0.0) throw bad_element{where + ".range: not a finite number at least 0"};
  l.position = glm::vec3(world[3]);
  const glm::vec3 forward = -glm::vec3(world[2]);
  if (!std::isfinite(l.position.x + l.position.y + l.position.z) || !std::isfinite(glm::length(forward)))
    throw bad_element{where + ": its node's transform is past the float range"};
  if (!(glm::length(forward) > 0.0f)) throw bad_element{where + ": its node's transform has no direction (-Z is 0)"};
  l.direction = glm::normalize(forward);
  l.shadows = true;
  l.intensity = float(g.intensity);
  if (l.kind == light_kind::directional) return l;
  l.range = float(g.range > 0.0 ? g.range : std::sqrt(255.0 * g.intensity));
  if (!(l.range > 0.0f)) l.range = 1.0f;  // no light: any range draws nothing
  const float quarter = 0.25f * l.range;
  l.intensity = float(g.intensity) / (quarter * quarter * 0.5625f);  // (1 - 1/4)^2 = 0.5625
  if (l.kind == light_kind::spot) {
    const double inner = g.spot.innerConeAngle, outer = g.spot.outerConeAngle;
    if (!(inner >= 0.0 && inner < outer && outer <= 1.5707963267948966))
      throw bad_element{where + ".spot: 0 <= innerConeAngle < outerConeAngle <= pi/2 is needed"};
    l.inner_angle = float(glm::degrees(inner));
    l.outer_angle = float(glm::degrees(outer));
  }
  return l;
}

// A model read into a scene, node by node.
class builder {
 public:
  builder(const tinygltf::Model& m, const scene_budget& budget) : m_(m), budget_(budget) {}

  scene build() {
    for (std::size_t i = 0; i < m_.materials.size(); ++i) {
      auto [mat, drawn] = from_gltf(m_.materials[i], at("materials", i));
      uv_sources_.push_back(drawn ? add_texture(m_.materials[i], mat, at("materials", i)) : uv_source{});
      s_.materials.push_back(mat);
      drawn_.push_back(drawn);
    }
    std::vector<int> roots;
    if (!m_.scenes.empty() || m_.defaultScene >= 0) {
      roots = item(m_.scenes, std::max(m_.defaultScene, 0), "scene").nodes;
    } else {  // no scene: every node that no node holds
      std::vector<bool> held(m_.nodes.size(), false);
      for (const tinygltf::Node& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && std::size_t(c) < held.size()) held[std::size_t(c)] = true;
      for (std::size_t i = 0; i < held.size(); ++i)
        if (!held[i]) roots.push_back(int(i));
    }
    for (int r : roots) visit(r, glm::mat4(1.0f), "nodes");
    if (s_.objects.empty()) throw bad_element{"no triangles to draw in its scene"};
    const auto [centre, radius] = bounds();
    if (!camera_) frame(centre, radius);
    // Depth precision is what G-buffer positions and shadow lookups are made from, and a file's zfar is
    // often a million times its znear: the planes close in to the scene's bounding sphere (nothing is lost).
    const float distance = glm::length(s_.view.position - centre), margin = 1.01f * radius;
    s_.view.far_plane = std::min(s_.view.far_plane, distance + margin);
    if (distance - margin > s_.view.near_plane) s_.view.near_plane = std::max(distance - margin, 1e-3f * s_.view.far_plane);
    if (s_.lights.empty()) {  // glTF viewers light a file without lights; from above the camera's right
      light sun;
      const glm::vec3 forward = glm::normalize(s_.view.target - s_.view.position), right = glm::normalize(glm::cross(forward, s_.view.up()));
      sun.direction = glm::normalize(forward + 0.5f * right - glm::vec3(0.0f, 1.0f, 0.0f));
      sun.shadows = true;
      s_.lights.push_back(sun);
    }
    return s_;
  }

 private:
  void visit(int index, const glm::mat4& parent, const std::string& from) {
    const tinygltf::Node& n = item(m_.nodes, index, from);
    const std::string where = at("nodes", std::size_t(index));
    if (std::find(path_.begin(), path_.end(), index) != path_.end()) throw bad_element{where + ": the node is its own ancestor"};
    path_.push_back(index);
    const glm::mat4 world = parent * local_transform(n, where);
    if (n.mesh >= 0) add_mesh(n.mesh, world, where);
    if (n.camera >= 0) add_camera(n.camera, world, where + ".camera");
    if (const tinygltf::Value* l = extension(n.extensions, "KHR_lights_punctual")) {
      const std::string in = where + ".extensions.KHR_lights_punctual.light";
      if (!l->Has("light") || !l->Get("light").IsInt()) throw bad_element{in + ": an index is needed"};
      const int i = l->Get("light").GetNumberAsInt();
      s_.lights.push_back(from_gltf(item(m_.lights, i, in), world, "extensions.KHR_lights_punctual.lights[" + std::to_string(i) + "]"));
    }
    for (std::size_t c = 0; c < n.children.size(); ++c) visit(n.children[c], world, where + ".children[" + std::to_string(c) + "]");
    path_.pop_back();
  }

  // The primitives of mesh `index`, held by node `node` at `world`. A transform that flattens its mesh
  // (scale 0, as glTF hides a node) draws nothing; one that takes it past the float range is an error.
  void add_mesh(int index, const glm::mat4& world, const std::string& node) {
    const tinygltf::Mesh& mesh = item(m_.meshes, index, node + ".mesh");
    const float det = glm::determinant(glm::mat3(world));
    if (!std::isfinite(det)) throw bad_element{node + ": its transform is past the float range"};
    if (det == 0.0f) return;
    for (std::size_t i = 0; i < mesh.primitives.size(); ++i) {
      const tinygltf::Primitive& p = mesh.primitives[i];
      const std::string where = at("meshes", std::size_t(index)) + "." + at("primitives", i);
      std::uint32_t mat;
      if (p.material >= 0) {
        item(m_.materials, p.material, where + ".material");
        if (!drawn_[std::size_t(p.material)]) continue;
        mat = std::uint32_t(p.material);
      } else {  // the specification's default: white, fully rough
        if (!default_material_) {
          default_material_ = std::uint32_t(s_.materials.size());
          s_.materials.push_back(from_gltf(tinygltf::Material{}, "the default material").first);
        }
        mat = *default_material_;
      }
      // Each element read costs its numbers as doubles and then its vertex: the budget bounds them all.
      shape geometry = primitive_shape(m_, p, budget_.bytes / 32, p.material >= 0 ? uv_sources_[std::size_t(p.material)] : uv_source{}, where);
      if (!finite_in_world(geometry, world)) throw bad_element{node + ": its transform takes " + where + " past the float range"};
      vertices_ += geometry.positions.size();
      if (used() > budget_.bytes)  // checked as it grows: nodes may share a mesh many times
        throw bad_element{where + ": the scene would take about " + mib(used()) + " MiB by here (" + std::to_string(vertices_) +
                          " vertices), over the budget of " + mib(budget_.bytes) + " MiB (--budget MIB raises it)"};
      s_.objects.push_back({std::move(geometry), world, mat});
    }
  }

  // The bytes of the vertices and texels read so far.
  std::size_t used() const { return vertices_ * bytes_per_vertex + texel_bytes_; }

  // Material `g`'s base colour texture as `mat`'s (decoded once however many materials use it; scene_gltf.hpp
  // says how alpha and MASK use it), and where its texture coordinates come from.
  uv_source add_texture(const tinygltf::Material& g, material& mat, const std::string& where) {
    const tinygltf::TextureInfo& info = g.pbrMetallicRoughness.baseColorTexture;
    if (info.index < 0) return {};
    const std::string in = where + ".pbrMetallicRoughness.baseColorTexture";
    uv_source uv = texture_transform(info, in);
    if (uv.set < 0) throw bad_element{in + ".texCoord: " + std::to_string(uv.set) + " is not a set"};
    const tinygltf::Texture& t = item(m_.textures, info.index, in + ".index");
    const std::string tin = at("textures", std::size_t(info.index));
    auto [known, inserted] = texture_of_.try_emplace(info.index, int(s_.textures.size()));
    if (inserted) {
      const tinygltf::Image& img = item(m_.images, t.source, tin + ".source");
      texture decoded_texture = decoded(img, budget_.bytes - std::min(budget_.bytes, used()), at("images", std::size_t(t.source)));
      if (t.sampler >= 0) {
        const tinygltf::Sampler& sm = item(m_.samplers, t.sampler, tin + ".sampler");
        const std::string sin = at("samplers", std::size_t(t.sampler));
        decoded_texture.wrap_s = wrap_of(sm.wrapS, sin + ".wrapS");
        decoded_texture.wrap_t = wrap_of(sm.wrapT, sin + ".wrapT");
      }
      texel_bytes_ += decoded_texture.rgba.size();
      s_.textures.push_back(std::move(decoded_texture));
    }
    mat.texture = known->second;
    if (g.alphaMode == "MASK" && g.alphaCutoff > 0.0) {
      mat.alpha_cutoff = float(g.alphaCutoff);
      mat.alpha *= float(std::clamp(g.pbrMetallicRoughness.baseColorFactor[3], 0.0, 1.0));
    }
    // A blended material whose factors leave it opaque is still glass where its texels are not.
    const std::vector<std::uint8_t>& texels = s_.textures[std::size_t(mat.texture)].rgba;
    bool translucent = false;
    for (std::size_t k = 3; k < texels.size() && !translucent; k += 4) translucent = texels[k] < 255;
    if (g.alphaMode == "BLEND" && !shader::dst_transparent(mat.alpha) && translucent) mat.alpha = 254.0f / 255.0f;
    return uv;
  }

  // The texture coordinates of `info`: its set, and KHR_texture_transform's offset, rotation and scale (the
  // extension's T R S, which may name another set).
  static uv_source texture_transform(const tinygltf::TextureInfo& info, const std::string& where) {
    uv_source uv{info.texCoord, glm::mat3(1.0f)};
    const tinygltf::Value* t = extension(info.extensions, "KHR_texture_transform");
    if (!t) return uv;
    const std::string in = where + ".extensions.KHR_texture_transform";
    auto pair = [&](const char* key, double fallback) {
      if (!t->Has(key)) return glm::vec2(float(fallback));
      const tinygltf::Value& v = t->Get(key);
      if (!v.IsArray() || v.ArrayLen() != 2) throw bad_element{in + "." + key + ": 2 numbers are needed"};
      glm::vec2 out;
      for (int k = 0; k < 2; ++k) {
        const tinygltf::Value& x = v.Get(k);
        if (!x.IsNumber() || !(std::fabs(x.GetNumberAsDouble()) <= 1e30))
          throw bad_element{in + "." + key + "[" + std::to_string(k) + "]: not a finite number"};
        out[k] = float(x.GetNumberAsDouble());
      }
      return out;
    };
    const glm::vec2 offset = pair("offset", 0.0), scale = pair("scale", 1.0);
    const auto rotation = float(ext_number(*t, "rotation", 0.0, in));
    if (t->Has("texCoord")) uv.set = int(std::clamp(ext_number(*t, "texCoord", 0.0, in), -1.0, 1e6));
    const float c = std::cos(rotation), s = std::sin(rotation);
    // Column-major: T R S with R = [c s; -s c] as the extension writes it row by row.
    const glm::mat3 translate(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1), rotate(c, -s, 0, s, c, 0, 0, 0, 1), stretch(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
    uv.transform = translate * rotate * stretch;
    return uv;
  }

  void add_camera(int index, const glm::mat4& world, const std::string& from) {
    const tinygltf::Camera& c = item(m_.cameras, index, from);
    if (camera_ || c.type != "perspective") return;  // the first perspective camera; scene_gltf.hpp
    const std::string where = at("cameras", std::size_t(index)) + ".perspective";
    const auto& p = c.perspective;
    if (!(p.yfov > 0.0 && p.yfov < 3.14159 && p.znear > 0.0 && std::isfinite(p.znear) && std::isfinite(p.zfar) &&
          (p.zfar == 0.0 || p.zfar > p.znear)))
      throw bad_element{where + ": 0 < yfov < pi and 0 < znear < zfar (or zfar absent) are needed"};
    s_.view.position = glm::vec3(world[3]);
    const glm::vec3 forward = -glm::vec3(world[2]);
    if (!std::isfinite(s_.view.position.x + s_.view.position.y + s_.view.position.z) || !std::isfinite(glm::length(forward)))
      throw bad_element{from + ": its node's transform is past the float range"};
    if (!(glm::length(forward) > 0.0f)) throw bad_element{from + ": its node's transform has no direction (-Z is 0)"};
    s_.view.target = s_.view.position + glm::normalize(forward);
    s_.view.fov_y = float(glm::degrees(p.yfov));
    s_.view.near_plane = float(p.znear);
    s_.view.far_plane = float(p.zfar > 0.0 ? p.zfar : 1000.0 * p.znear);
    camera_ = true;
  }

  // The centre and radius of a sphere around every object (the renderer's, which fits shadow maps to it),
  // with a radius of at least 1e-3, for a camera to frame.
  std::pair<glm::vec3, float> bounds() const {
    const render::frame_detail::bounds b = render::frame_detail::scene_bounds(s_);
    return {b.centre, std::max(b.radius, 1e-3f)};
  }

  // A camera 45 degrees wide that sees the whole bounding sphere, from the front, above and right.
  void frame(glm::vec3 centre, float radius) {
    const float distance = radius / std::sin(glm::radians(22.5f)) * 1.1f;
    s_.view.fov_y = 45.0f;
    s_.view.target = centre;
    s_.view.position = centre + distance * glm::normalize(glm::vec3(0.4f, 0.5f, 1.0f));
    s_.view.near_plane = distance * 0.01f;
    s_.view.far_plane = distance + 2.0f * radius;
  }

  const tinygltf::Model& m_;
  const scene_budget& budget_;
  scene s_;
  std::vector<bool> drawn_;
  std::vector<uv_source> uv_sources_;   // by material
  std::map<int, int> texture_of_;       // glTF texture to scene texture
  std::size_t texel_bytes_ = 0;
  std::optional<std::uint32_t> default_material_;
  std::vector<int> path_;
  std::size_t vertices_ = 0;
  bool camera_ = false;
};

// tinygltf's reading of the buffers and images a .gltf names: each held to the budget's file size, and
// every path taken as it is written (no expansion of ~ or variables).
bool read_limited(std::vector<unsigned char>* out, std::string* error, const std::string& path, void* limit) {
  auto bytes = read_input_file(path, "glTF buffer or image", *static_cast<const std::size_t*>(limit));
  if (!bytes) {
    *error += bytes.error() + "\n";
    return false;
  }
  out->assign(bytes->begin(), bytes->end());
  return true;
}
std::string as_written(const std::string& path, void*) { return path; }

// tinygltf's image decoding, put off: the bytes are kept as they are, and only base colour textures are
// decoded (builder::add_texture), each held to what is left of the budget.
bool keep_encoded(tinygltf::Image* image, int, std::string*, std::string*, int, int, const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->as_is = true;
  return true;
}

}  // namespace

bool finite_in_world(const shape& s, const glm::mat4& transform) {
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const glm::vec3 w = glm::vec3(transform * glm::vec4(s.positions[v], 1.0f));
    const float n = glm::length(normal_matrix * s.normals[v]);
    if (!std::isfinite(w.x + w.y + w.z) || !std::isfinite(n) || !(n > 0.0f)) return false;
  }
  return true;
}

bool is_gltf_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".gltf" || ext == ".glb";
}

result<scene> load_gltf(const std::string& path, const scene_budget& budget) {
  auto bytes = read_input_file(path, "glTF file", budget.file_bytes);
  if (!bytes) return failure{bytes.error()};
  tinygltf::TinyGLTF loader;
  std::size_t limit = budget.file_bytes;
  loader.SetFsCallbacks({tinygltf::FileExists, as_written, read_limited, tinygltf::WriteWholeFile, &limit});
  loader.SetImageLoader(keep_encoded, nullptr);
  tinygltf::Model model;
  std::string error, warning;
  const std::string base = std::filesystem::absolute(path).parent_path().string();
  const bool binary = bytes->size() >= 4 && bytes->compare(0, 4, "glTF") == 0;
  // Types and required extensions first: tinygltf would read a property of the wrong type as absent.
  if (const std::optional<std::string> text = binary ? glb_json(*bytes) : *bytes)
    if (auto wrong = gltf_json_error(*text, readable_extensions())) return failure{path + ": " + *wrong};
  const bool ok = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, reinterpret_cast<const unsigned char*>(bytes->data()),
                                                       unsigned(bytes->size()), base)
                         : loader.LoadASCIIFromString(&model, &error, &warning, bytes->data(), unsigned(bytes->size()), base);
  if (!ok) {
    while (!error.empty() && std::isspace(static_cast<unsigned char>(error.back()))) error.pop_back();
    if (error.size() > 300) error = error.substr(0, 300) + "...";  // it may quote a long URI or token
    return failure{path + ": " + (error.empty() ? std::string("not a glTF 2.0 file") : error)};
  }
  try {
    return builder(model, budget).build();
  } catch (const bad_element& e) {
    return failure{path + ": " + e.message};
  }
}

}  // namespace dstrans
