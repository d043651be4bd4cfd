// A small OpenGL engine with its own deferred renderer, taking dstrans in one step at a time (README.md):
//   --step 0  the engine as it was: its own G-buffer; glass is skipped, as deferred engines do
//   --step 1  dstrans's G-buffer layout (Table 3.1) and interlaced transparency
//   --step 2  + coloured shadows from the glass (Table 3.3 shadow map, Eq. 3.1)
//   --step 3  + refraction with depth rejection (Eq. 3.3)
//   --step 4  the whole frame through dstrans's renderer (dstrans_gl_frame.hpp), with hair, smoke and a
//             post chain, the engine drawing its own vertex arrays in each geometry pass
// Up to step 3 its meshes, camera, materials, textures, programs and bindings are its own; dstrans brings
// GLSL text (layouts with the engine's hooks, the interlace predicate, shared formulas) and nothing else.
//
//   engine_gl --step 3 --out step3.png
#include <cstdio>
#include <string>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>  // the engine's GL loader would be here

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <dstrans/dstrans.hpp>
#include <dstrans_gl_context.hpp>  // this example's stand-in for the engine's window and context
#include <dstrans_gl_frame.hpp>    // [step 4] the whole frame

#include "../engine_world.hpp"
#include "../example_io.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION  // stb_image_write.h's definitions, here once
#include <stb/stb_image_write.h>

namespace engine {

// ---- The engine's own world -------------------------------------------------------------------------

struct vertex {
  glm::vec3 position, normal;
};
struct mesh {
  GLuint vao = 0, vbo = 0, ibo = 0;
  GLsizei count = 0;
};
struct material {
  glm::vec3 colour;
  float alpha = 1.0f;
  float specular = 0.2f, shininess = 16.0f;
};
struct object {
  mesh shape;
  glm::mat4 model;
  material look;
};
struct spot_light {
  glm::vec3 position, direction, colour;
  float cos_cone;
  glm::mat4 view_proj() const {
    return glm::perspective(glm::acos(cos_cone) * 2.0f, 1.0f, 0.1f, 20.0f) *
           glm::lookAt(position, position + direction, glm::vec3(0, 1, 0));
  }
};

mesh upload(const std::vector<vertex>& v, const std::vector<unsigned>& idx) {
  mesh m;
  glCreateVertexArrays(1, &m.vao);
  glCreateBuffers(1, &m.vbo);
  glCreateBuffers(1, &m.ibo);
  glNamedBufferStorage(m.vbo, GLsizeiptr(v.size() * sizeof(vertex)), v.data(), 0);
  glNamedBufferStorage(m.ibo, GLsizeiptr(idx.size() * sizeof(unsigned)), idx.data(), 0);
  glVertexArrayVertexBuffer(m.vao, 0, m.vbo, 0, sizeof(vertex));
  glVertexArrayElementBuffer(m.vao, m.ibo);
  for (GLuint a = 0; a < 2; ++a) {
    glEnableVertexArrayAttrib(m.vao, a);
    glVertexArrayAttribFormat(m.vao, a, 3, GL_FLOAT, GL_FALSE, a * sizeof(glm::vec3));
    glVertexArrayAttribBinding(m.vao, a, 0);
  }
  m.count = GLsizei(idx.size());
  return m;
}

// A box of `size` centred on the origin; a quad in XY facing +Z.
mesh box(glm::vec3 size) {
  std::vector<vertex> v;
  std::vector<unsigned> idx;
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), w(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      w[(axis + 2) % 3] = 1.0f;
      if (sign < 0) std::swap(u, w);
      const unsigned base = unsigned(v.size());
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)})
        v.push_back({(n + u * c.x + w * c.y) * size * 0.5f, n});
      idx.insert(idx.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  return upload(v, idx);
}
mesh quad(glm::vec2 size) {
  const glm::vec3 n(0, 0, 1);
  const glm::vec2 h = size * 0.5f;
  return upload({{{-h.x, -h.y, 0}, n}, {{h.x, -h.y, 0}, n}, {{h.x, h.y, 0}, n}, {{-h.x, h.y, 0}, n}}, {0, 1, 2, 0, 2, 3});
}

// ---- The engine's own GL plumbing -------------------------------------------------------------------

GLuint program(const std::string& vs, const std::string& fs) {
  auto stage = [](GLenum kind, const std::string& text) {
    const GLuint s = glCreateShader(kind);
    const char* src = text.c_str();
    glShaderSource(s, 1, &src, nullptr);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[4096];
      glGetShaderInfoLog(s, sizeof log, nullptr, log);
      std::fprintf(stderr, "engine: shader error:\n%s\n", log);
    }
    return s;
  };
  const GLuint p = glCreateProgram();
  glAttachShader(p, stage(GL_VERTEX_SHADER, vs));
  glAttachShader(p, stage(GL_FRAGMENT_SHADER, fs));
  glLinkProgram(p);
  return p;
}

// A framebuffer over textures of `formats` and a depth texture.
struct targets {
  GLuint fbo = 0, depth = 0;
  std::vector<GLuint> colour;
};
targets make_targets(const std::vector<GLenum>& formats, int w, int h) {
  targets t;
  glCreateFramebuffers(1, &t.fbo);
  std::vector<GLenum> draw;
  for (GLenum f : formats) {
    GLuint tex;
    glCreateTextures(GL_TEXTURE_2D, 1, &tex);
    glTextureStorage2D(tex, 1, f, w, h);
    glNamedFramebufferTexture(t.fbo, GLenum(GL_COLOR_ATTACHMENT0 + t.colour.size()), tex, 0);
    draw.push_back(GLenum(GL_COLOR_ATTACHMENT0 + t.colour.size()));
    t.colour.push_back(tex);
  }
  glCreateTextures(GL_TEXTURE_2D, 1, &t.depth);
  glTextureStorage2D(t.depth, 1, GL_DEPTH_COMPONENT32F, w, h);
  glNamedFramebufferTexture(t.fbo, GL_DEPTH_ATTACHMENT, t.depth, 0);
  glNamedFramebufferDrawBuffers(t.fbo, GLsizei(draw.size()), draw.data());
  return t;
}

// [step 1] The GL format of a dstrans target: the engine allocates dstrans's layouts with its own code.
GLenum gl_format(dstrans::format f) {
  switch (f) {
    case dstrans::format::rgba8: return GL_RGBA8;
    case dstrans::format::rgb10a2: return GL_RGB10_A2;
    case dstrans::format::r32f: return GL_R32F;
    default: return GL_RGBA32F;
  }
}
template <class Layout>
std::vector<GLenum> formats_of() {
  std::vector<GLenum> out;
  for (const dstrans::target_desc& d : dstrans::describe<Layout>()) out.push_back(gl_format(d.fmt));
  return out;
}

// ---- The engine's shaders ----------------------------------------------------------------------------

const char* const header = "#version 450\n";
const char* const geometry_vs = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 0) uniform mat4 view_proj;
layout(location = 1) uniform mat4 model;
out vec3 world_normal;
out vec3 world_position;
void main() {
  vec4 w = model * vec4(position, 1.0);
  world_position = w.xyz;
  world_normal = mat3(model) * normal;
  gl_Position = view_proj * w;
}
)";
// Uniform locations the engine's geometry shaders share: 2 colour, 3 alpha, 4 specular, 5 shininess.
const char* const material_uniforms = R"(
in vec3 world_normal;
in vec3 world_position;
layout(location = 2) uniform vec3 colour;
layout(location = 3) uniform float alpha;
layout(location = 4) uniform float specular;
layout(location = 5) uniform float shininess;
)";

// Step 0: the engine's own G-buffer (albedo + specular, normal + shininess); depth from the attachment.
const char* const own_gbuffer_fs = R"(
layout(location = 0) out vec4 albedo_specular;
layout(location = 1) out vec4 normal_shininess;
void main() {
  albedo_specular = vec4(colour, specular);
  normal_shininess = vec4(normalize(world_normal), shininess);
}
)";

// [step 1] The same through dstrans: the surface goes to Table 3.1's targets by dst_gbuffer_write, and
// glass survives only on the rows the interlace predicate keeps.
const char* const dstrans_gbuffer_fs = R"(
layout(location = 6) uniform ivec2 target_size;
void main() {
  if (alpha < 1.0 && !dst_interlace_keep(ivec2(gl_FragCoord.xy), target_size)) discard;
  dst_surface s = dst_surface_zero();
  s.diffuse = colour;
  s.alpha = alpha;
  vec3 n = normalize(world_normal);
  s.normal = gl_FrontFacing ? n : -n;
  s.spec_intensity = specular;
  s.spec_power = shininess;
  s.depth = gl_FragCoord.z;
  dst_gbuffer_write(s);
}
)";

// The light pass: one spot light over the full screen, into the engine's RGBA16F light buffer.
const char* const light_fs = R"(
layout(location = 0) out vec4 light_out;
layout(location = 0) uniform mat4 inv_view_proj;
layout(location = 1) uniform vec3 light_position;
layout(location = 2) uniform vec3 light_direction;
layout(location = 3) uniform vec3 light_colour;
layout(location = 4) uniform float cos_cone;
layout(location = 5) uniform vec3 eye;
layout(location = 6) uniform mat4 light_view_proj;
layout(binding = 7) uniform sampler2D engine_depth;
void engine_surface(ivec2 p, out vec3 n, out float shininess);
vec3 engine_shadow(vec3 world, vec3 light);
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float depth = texelFetch(engine_depth, p, 0).x;
  if (depth >= 1.0) discard;
  vec2 ndc = (vec2(p) + 0.5) / vec2(textureSize(engine_depth, 0)) * 2.0 - 1.0;
  vec4 h = inv_view_proj * vec4(ndc, depth * 2.0 - 1.0, 1.0);
  vec3 world = h.xyz / h.w;
  vec3 n;
  float shininess;
  engine_surface(p, n, shininess);
  vec3 to_light = normalize(light_position - world);
  float cone = smoothstep(cos_cone, cos_cone + 0.05, dot(-to_light, light_direction));
  vec3 light = engine_shadow(world, light_colour * cone);
  float ndotl = max(dot(n, to_light), 0.0);
  vec3 r = reflect(-to_light, n);
  float spec = ndotl > 0.0 ? pow(max(dot(r, normalize(eye - world)), 0.0), shininess) : 0.0;
  light_out = vec4(light * ndotl, spec * (light.x + light.y + light.z) / 3.0);
}
)";
const char* const own_surface = R"(
layout(binding = 1) uniform sampler2D engine_normal;
void engine_surface(ivec2 p, out vec3 n, out float shininess) {
  vec4 t = texelFetch(engine_normal, p, 0);
  n = t.xyz;
  shininess = t.w;
}
)";
// [step 1] The light pass reads the surface through dstrans's layout; the engine fetches the texels.
const char* const dstrans_surface = R"(
void engine_surface(ivec2 p, out vec3 n, out float shininess) {
  dst_surface s = dst_gbuffer_read(p);
  n = s.normal;
  shininess = s.spec_power;
}
)";
const char* const no_shadow = "vec3 engine_shadow(vec3 world, vec3 light) { return light; }\n";
// [step 2] Coloured shadows: the texel and its interlace partner in Table 3.3's map, decided by Eq. 3.1.
const char* const dstrans_shadow = R"(
vec3 engine_shadow(vec3 world, vec3 light) {
  vec4 h = light_view_proj * vec4(world, 1.0);
  vec3 c = h.xyz / h.w * 0.5 + 0.5;
  ivec2 size = textureSize(engine_shadow_depth, 0);
  ivec2 t = ivec2(c.xy * vec2(size));
  if (h.w <= 0.0 || any(lessThan(t, ivec2(0))) || any(greaterThanEqual(t, size))) return light;
  ivec2 o = dst_interlace_partner(t, size);
  dst_surface a = dst_shadow_read(t), b = dst_shadow_read(o);
  return dst_transparent_shadow(light, c.z, 0.002, a.depth, vec4(a.diffuse, a.alpha), b.depth, vec4(b.diffuse, b.alpha));
}
)";

// The compose pass.
const char* const fullscreen_vs = R"(
void main() { gl_Position = vec4(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0, 0.0, 1.0); }
)";
const char* const own_compose_fs = R"(
layout(location = 0) out vec4 colour_out;
layout(binding = 0) uniform sampler2D engine_albedo;
layout(binding = 6) uniform sampler2D engine_light;
layout(location = 0) uniform vec3 ambient;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(engine_albedo, p, 0), l = texelFetch(engine_light, p, 0);
  colour_out = vec4(a.rgb * (l.rgb + ambient) + a.w * l.w, 1.0);
}
)";
// [step 1] De-interlacing and Eq. 3.3 with dstrans's shared dst_compose; [step 3] refraction.
const char* const dstrans_compose_fs = R"(
layout(location = 0) out vec4 colour_out;
layout(binding = 6) uniform sampler2D engine_light;
layout(location = 0) uniform vec3 ambient;
layout(location = 1) uniform float refraction;
layout(location = 2) uniform mat4 view;
dst_light_sample engine_light_at(ivec2 p) {
  vec4 l = texelFetch(engine_light, p, 0);
  dst_light_sample s;
  s.light = l.rgb;
  s.specular = vec3(l.w);
  return s;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(engine_light, 0);
  ivec2 q = dst_interlace_partner(p, size);
  dst_surface a = dst_gbuffer_read(p), b = dst_gbuffer_read(q);
  if (a.alpha >= 1.0 && b.alpha >= 1.0) {
    colour_out = vec4(dst_shade(a, engine_light_at(p), ambient), 1.0);
    return;
  }
  bool a_glass = a.alpha <= b.alpha;
  dst_surface t = a_glass ? a : b, o = a_glass ? b : a;
  dst_light_sample lt = engine_light_at(a_glass ? p : q), lo = engine_light_at(a_glass ? q : p);
  if (refraction > 0.0) {
    ivec2 m = dst_refract(p, size, mat3(view) * t.normal, refraction);
    ivec2 m2 = dst_interlace_partner(m, size);
    dst_surface r = dst_gbuffer_read(m), r2 = dst_gbuffer_read(m2);
    int from = dst_refraction_source(t.depth, r.alpha, r.depth, r2.alpha, r2.depth);
    if (from != 0) {
      o = from == 1 ? r : r2;
      lo = engine_light_at(from == 1 ? m : m2);
    }
  }
  colour_out = vec4(dst_compose(o, lo, t, lt, ambient), 1.0);
}
)";

// [step 1] dstrans text for a shader: its layouts with the engine's own fetch hooks (sampler bindings are
// the engine's), the interlace predicate, and the shared formulas the engine's code calls.
std::string dstrans_text(bool gbuffer_write, bool shadow_write, bool shadows_read) {
  // The engine's shaders start with their own #version line, and pass GL's pixels as they are (rows from
  // the bottom): dstrans turns them over where its predicates and refraction need rows from the top, so
  // both APIs keep glass on the same rows.
  dstrans::glsl::dialect gl;
  gl.version_line = false;
  gl.pixel_rows = dstrans::glsl::rows::from_bottom;
  dstrans::glsl::source src(gl);
  std::string hooks = "#define DSTRANS_GBUFFER_FETCH\n"
                      "layout(binding = 0) uniform sampler2D engine_gbuffer[4];\n"
                      // Constant indices: GLSL before 4.00, and ES, index sampler arrays no other way.
                      "vec4 dst_gbuffer_fetch(int t, ivec2 p) {\n"
                      "  if (t == 0) return texelFetch(engine_gbuffer[0], p, 0);\n"
                      "  if (t == 1) return texelFetch(engine_gbuffer[1], p, 0);\n"
                      "  if (t == 2) return texelFetch(engine_gbuffer[2], p, 0);\n"
                      "  return texelFetch(engine_gbuffer[3], p, 0);\n"
                      "}\n"
                      "#define DSTRANS_SHADOW_FETCH\n"
                      "layout(binding = 8) uniform sampler2D engine_shadow_depth;\n"
                      "layout(binding = 9) uniform sampler2D engine_shadow_colour;\n"
                      "vec4 dst_shadow_fetch(int t, ivec2 p) {\n"
                      "  return t == 0 ? texelFetch(engine_shadow_depth, p, 0) : texelFetch(engine_shadow_colour, p, 0);\n"
                      "}\n";
  src.add(hooks, __FILE__, __LINE__);
  dstrans::glsl::layout_options o;
  o.sides = gbuffer_write ? dstrans::glsl::side::write : dstrans::glsl::side::read;
  dstrans::glsl::add_layout<dstrans::thesis_gbuffer>(src, "gbuffer", o);
  if (shadow_write || shadows_read) {
    o.sides = shadow_write ? dstrans::glsl::side::write : dstrans::glsl::side::read;
    dstrans::glsl::add_layout<dstrans::thesis_shadow_map>(src, "shadow", o);
  }
  dstrans::glsl::add_interlace<dstrans::interlace::rows>(src);   // dst_interlace_keep/_partner
  dstrans::glsl::add_refraction(src);                             // dst_refract
  for (const dstrans::shared_text* t : {&dstrans::text::dst_compose, &dstrans::text::dst_transparent_shadow}) src.add_shared(*t);
  return src.str();
}

}  // namespace engine

// [step 4] The whole frame: dstrans's renderer runs every pass on the engine's context; the engine hands
// it a description of the world and draws its own vertex arrays (world-space position and normal) when a
// geometry pass asks, the material at attribute 2 as a constant per draw.
int whole_frame(const std::string& out, int w, int h) {
  const dstrans::scene world = example::engine_world();
  struct drawn_mesh {
    engine::mesh shape;
    std::uint32_t material;
    bool hair;
  };
  std::vector<drawn_mesh> meshes;
  for (const dstrans::object& o : world.objects) {
    std::vector<engine::vertex> v;
    for (const example::world_vertex& p : example::world_vertices(world, o)) v.push_back({p.position, p.normal});
    meshes.push_back({engine::upload(v, o.geometry.indices), o.material, world.materials[o.material].hair});
  }
  dstrans::render::options o;  // as dstrans render draws a scene
  o.width = w;
  o.height = h;
  o.shadow_size = 1024;
  o.opaque_shadows_depth_only = true;  // the callback tells opaque materials from the rest (dstrans::draws)
  auto r = dstrans::gl::renderer::create(world, o);
  if (!r) {
    std::fprintf(stderr, "engine_gl: %s\n", r.error().c_str());
    return 1;
  }
  (*r)->render(world.view, [&](const dstrans::scheduled_pass& pass) {
    for (const bool hair : {false, true})  // surfaces first, as dstrans orders them
      for (const drawn_mesh& m : meshes) {
        if (m.hair != hair || !dstrans::draws(pass.draws, world.materials[m.material])) continue;
        glVertexAttribI4ui(2, m.material, 0, 0, 0);
        glBindVertexArray(m.shape.vao);
        glDrawElements(GL_TRIANGLES, m.shape.count, GL_UNSIGNED_INT, nullptr);
      }
  });
  std::vector<unsigned char> pixels;  // RGBA8, rows from the top
  for (const dstrans::texel& t : dstrans::gl::read_texels((*r)->output(), 0)) pixels.insert(pixels.end(), t.begin(), t.begin() + 4);
  for (drawn_mesh& m : meshes) {
    glDeleteVertexArrays(1, &m.shape.vao);
    glDeleteBuffers(1, &m.shape.vbo);
    glDeleteBuffers(1, &m.shape.ibo);
  }
  std::string error;
  if (!example::write_png(out, w, h, pixels.data(), false, error)) {
    std::fprintf(stderr, "engine_gl: %s\n", error.c_str());
    return 1;
  }
  return 0;
}

int main(int argc, char** argv) {
  const char* const usage = "usage: engine_gl [--step 0|1|2|3|4] [--out image.png]\n";
  int step = 3;
  std::string out = "engine_gl.png";
  if (const int stop = example::engine_arguments(argc, argv, "engine_gl", usage, step, out); stop >= 0) return stop;
  auto context = dstrans::gl::headless_context::create();  // the engine's window would be here
  if (!context) {
    std::fprintf(stderr, "engine_gl: %s\n", context.error().c_str());
    return 1;
  }
  using namespace engine;
  const int w = 320, h = 180, shadow_size = 512;
  if (step == 4) {
    const int rc = whole_frame(out, w, h);
    for (const std::string& m : (*context)->debug_messages()) std::fprintf(stderr, "engine_gl: GL: %s\n", m.c_str());
    if (rc == 0) std::printf("engine_gl: step 4: %s\n", out.c_str());
    return rc;
  }

  // The world: a floor, a red box, a blue and a green pane of glass, a spot light.
  std::vector<object> world{
      {box({8.0f, 0.1f, 8.0f}), glm::translate(glm::mat4(1), {0, -0.05f, 0}), {{0.8f, 0.8f, 0.8f}}},
      {box({0.6f, 0.6f, 0.6f}), glm::translate(glm::mat4(1), {0.6f, 0.3f, -1.0f}), {{0.8f, 0.2f, 0.1f}, 1.0f, 0.5f, 32.0f}},
      {quad({1.4f, 1.0f}), glm::translate(glm::mat4(1), {-0.3f, 0.6f, 0.3f}), {{0.2f, 0.5f, 1.0f}, 0.4f, 0.9f, 64.0f}},
      {quad({0.8f, 0.8f}), glm::rotate(glm::translate(glm::mat4(1), {1.0f, 0.5f, 0.8f}), 0.5f, {0, 1, 0}),
       {{0.2f, 1.0f, 0.3f}, 0.5f, 0.9f, 64.0f}}};
  const spot_light spot{{-1.0f, 3.5f, 2.5f}, glm::normalize(glm::vec3(0.4f, -1.0f, -0.9f)), {1.6f, 1.5f, 1.4f}, 0.8f};
  const glm::vec3 eye(0.0f, 1.6f, 3.6f), ambient(0.08f);
  const glm::mat4 view = glm::lookAt(eye, glm::vec3(0, 0.5f, 0), glm::vec3(0, 1, 0));
  const glm::mat4 proj = glm::perspective(glm::radians(55.0f), float(w) / float(h), 0.1f, 30.0f);

  // The engine's passes, their shaders assembled from its own text and, from step 1, dstrans's.
  const bool dstrans_gbuffer = step >= 1, shadows = step >= 2;
  const std::string gbuffer_fs = dstrans_gbuffer ? dstrans_text(true, false, false) + material_uniforms + dstrans_gbuffer_fs
                                                 : std::string(material_uniforms) + own_gbuffer_fs;
  const GLuint geometry = program(header + std::string(geometry_vs), header + gbuffer_fs);
  const GLuint shadow_geometry =
      program(header + std::string(geometry_vs), header + dstrans_text(false, true, false) +
                                                       "#define dst_gbuffer_write dst_shadow_write\n" + material_uniforms +
                                                       dstrans_gbuffer_fs);
  const GLuint lighting =
      program(header + std::string(fullscreen_vs),
              header + (dstrans_gbuffer ? dstrans_text(false, false, shadows) + dstrans_surface : std::string(own_surface)) +
                  light_fs + (shadows ? dstrans_shadow : no_shadow));
  const GLuint compose = program(header + std::string(fullscreen_vs),
                                 header + (dstrans_gbuffer ? dstrans_text(false, false, false) + dstrans_compose_fs
                                                           : std::string(own_compose_fs)));

  const targets gbuffer = make_targets(dstrans_gbuffer ? formats_of<dstrans::thesis_gbuffer>()
                                                       : std::vector<GLenum>{GL_RGBA8, GL_RGBA16F},
                                       w, h);
  const targets light_buffer = make_targets({GL_RGBA16F}, w, h), final_image = make_targets({GL_RGBA8}, w, h);
  const targets shadow_map = make_targets(formats_of<dstrans::thesis_shadow_map>(), shadow_size, shadow_size);
  GLuint empty_vao;
  glCreateVertexArrays(1, &empty_vao);

  auto draw_world = [&](GLuint prog, const glm::mat4& view_proj, bool with_glass, glm::ivec2 size) {
    glUseProgram(prog);
    glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(view_proj));
    if (with_glass) glUniform2i(6, size.x, size.y);  // [step 1] the interlace predicate's image size
    for (const object& o : world) {
      if (o.look.alpha < 1.0f && !with_glass) continue;
      glUniformMatrix4fv(1, 1, GL_FALSE, glm::value_ptr(o.model));
      glUniform3fv(2, 1, glm::value_ptr(o.look.colour));
      glUniform1f(3, o.look.alpha);
      glUniform1f(4, o.look.specular);
      glUniform1f(5, o.look.shininess);
      glBindVertexArray(o.shape.vao);
      glDrawElements(GL_TRIANGLES, o.shape.count, GL_UNSIGNED_INT, nullptr);
    }
  };
  const float far_colour[4] = {1, 1, 1, 1}, black[4] = {0, 0, 0, 1}, zero[4] = {0, 0, 0, 0};

  // Geometry: the engine skipped glass until dstrans could keep it in the G-buffer.
  glEnable(GL_DEPTH_TEST);
  glViewport(0, 0, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.fbo);
  for (GLint i = 0; i < GLint(gbuffer.colour.size()); ++i) glClearNamedFramebufferfv(gbuffer.fbo, GL_COLOR, i, i == 3 ? far_colour : black);
  glClear(GL_DEPTH_BUFFER_BIT);
  for (GLuint i = 0; i < gbuffer.colour.size(); ++i) glBindTextureUnit(i, gbuffer.colour[i]);
  draw_world(geometry, proj * view, dstrans_gbuffer, {w, h});

  // [step 2] The shadow map, with the same interlaced glass, seen from the light.
  if (shadows) {
    glBindFramebuffer(GL_FRAMEBUFFER, shadow_map.fbo);
    glViewport(0, 0, shadow_size, shadow_size);
    glClearNamedFramebufferfv(shadow_map.fbo, GL_COLOR, 0, far_colour);
    glClearNamedFramebufferfv(shadow_map.fbo, GL_COLOR, 1, far_colour);
    glClear(GL_DEPTH_BUFFER_BIT);
    draw_world(shadow_geometry, spot.view_proj(), true, {shadow_size, shadow_size});
    glViewport(0, 0, w, h);
  }

  // Light: one full-screen pass for the spot light.
  glDisable(GL_DEPTH_TEST);
  glBindFramebuffer(GL_FRAMEBUFFER, light_buffer.fbo);
  glClearNamedFramebufferfv(light_buffer.fbo, GL_COLOR, 0, zero);
  glUseProgram(lighting);
  glUniformMatrix4fv(0, 1, GL_FALSE, glm::value_ptr(glm::inverse(proj * view)));
  glUniform3fv(1, 1, glm::value_ptr(spot.position));
  glUniform3fv(2, 1, glm::value_ptr(spot.direction));
  glUniform3fv(3, 1, glm::value_ptr(spot.colour));
  glUniform1f(4, spot.cos_cone);
  glUniform3fv(5, 1, glm::value_ptr(eye));
  glUniformMatrix4fv(6, 1, GL_FALSE, glm::value_ptr(spot.view_proj()));
  glBindTextureUnit(7, gbuffer.depth);
  glBindTextureUnit(8, shadow_map.colour[0]);
  glBindTextureUnit(9, shadow_map.colour[1]);
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);

  // Compose into the engine's final image.
  glBindFramebuffer(GL_FRAMEBUFFER, final_image.fbo);
  glUseProgram(compose);
  glUniform3fv(0, 1, glm::value_ptr(ambient));
  if (dstrans_gbuffer) {
    glUniform1f(1, step >= 3 ? 8.0f : 0.0f);  // [step 3] refraction strength in pixels
    glUniformMatrix4fv(2, 1, GL_FALSE, glm::value_ptr(view));
  }
  glBindTextureUnit(6, light_buffer.colour[0]);
  glDrawArrays(GL_TRIANGLES, 0, 3);

  std::vector<unsigned char> pixels(std::size_t(w * h * 4));
  glGetTextureImage(final_image.colour[0], 0, GL_RGBA, GL_UNSIGNED_BYTE, GLsizei(pixels.size()), pixels.data());
  std::string error;
  if (!example::write_png(out, w, h, pixels.data(), true, error)) {  // flipped: GL's rows start at the bottom
    std::fprintf(stderr, "engine_gl: %s\n", error.c_str());
    return 1;
  }
  for (const std::string& m : (*context)->debug_messages()) std::fprintf(stderr, "engine_gl: GL: %s\n", m.c_str());
  std::printf("engine_gl: step %d: %s\n", step, out.c_str());
  return 0;
}
