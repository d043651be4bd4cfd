// A test engine in the shape the deferred-shading tutorials teach, which takes dstrans's interlaced glass,
// refraction and de-interlacing through the documented API and docs/integration.md section 6 only:
// - its shaders are GLSL 330 core (410 and 450 too), with samplers and uniforms found by name;
// - its G-buffer is its own position buffer at location 0 beside dstrans's compact layout at 1 and 2;
// - one lighting pass loops over 32 unshadowed point lights and writes the final colour;
// - light markers are drawn forward after the lighting, against a depth buffer;
// - `using namespace std;` comes before every header.
// It lights with dstrans's Phong and attenuation (a tutorial engine would keep its own), so that its image
// can be checked against `dstrans render` of the same scene, world.json.
//
//   tutorial_engine --out DIR [--glsl-version 330|410|450] [--markers deinterlaced|blit]
// writes into DIR: lit.png (the lighting pass's colour, glass on alternate rows), glass.png (de-interlaced,
// refracted), final.png (with the markers), and the shaders it compiled (*.vert, *.frag). --markers blit
// draws the markers the tutorials' way, against the G-buffer's depth copied by glBlitFramebuffer.
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>
using namespace std;

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <dstrans/dstrans.hpp>
#include <dstrans_gl_context.hpp>  // the engine's window would be here

#include "../../examples/example_io.hpp"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace {

// ---- The world, as world.json describes it to dstrans render ----------------------------------------

struct material {
  glm::vec3 diffuse;
  float alpha, specular, shininess;
};
struct object {
  dstrans::shape mesh;
  glm::vec3 position;
  float yaw_degrees;
  material look;
};
struct point_light {
  glm::vec3 position, colour;
  float range;
};

vector<object> world() {
  const material floor{{0.8f, 0.8f, 0.8f}, 1.0f, 0.2f, 16.0f}, red{{0.8f, 0.2f, 0.1f}, 1.0f, 0.5f, 32.0f},
      column{{0.9f, 0.85f, 0.7f}, 1.0f, 0.3f, 8.0f}, blue_glass{{0.2f, 0.5f, 1.0f}, 0.4f, 0.9f, 64.0f},
      green_glass{{0.2f, 1.0f, 0.3f}, 0.5f, 0.9f, 64.0f};
  return {{dstrans::shape_box({8.0f, 0.1f, 8.0f}), {0.0f, -0.05f, 0.0f}, 0.0f, floor},
          {dstrans::shape_box({0.6f, 0.6f, 0.6f}), {0.6f, 0.3f, -1.0f}, 0.0f, red},
          {dstrans::shape_box({0.3f, 1.2f, 0.3f}), {-1.0f, 0.6f, -0.8f}, 0.0f, column},
          {dstrans::shape_pane({1.4f, 1.0f}), {-0.3f, 0.6f, 0.3f}, 0.0f, blue_glass},
          {dstrans::shape_pane({0.8f, 0.8f}), {1.0f, 0.5f, 0.8f}, 28.6479f, green_glass}};
}

const point_light lights[32] = {
    {{0.900f, 0.250f, -0.200f}, {0.850f, 0.250f, 0.250f}, 2.2f},
    {{2.158f, 0.600f, 0.229f}, {0.842f, 0.186f, 0.321f}, 2.2f},
    {{0.831f, 0.950f, 0.144f}, {0.820f, 0.133f, 0.398f}, 2.2f},
    {{1.829f, 0.250f, 1.022f}, {0.783f, 0.091f, 0.476f}, 2.2f},
    {{0.636f, 0.600f, 0.436f}, {0.733f, 0.064f, 0.554f}, 2.2f},
    {{1.222f, 0.950f, 1.629f}, {0.672f, 0.051f, 0.627f}, 2.2f},
    {{0.344f, 0.250f, 0.631f}, {0.603f, 0.053f, 0.694f}, 2.2f},
    {{0.429f, 0.600f, 1.958f}, {0.528f, 0.071f, 0.751f}, 2.2f},
    {{0.000f, 0.950f, 0.700f}, {0.450f, 0.104f, 0.796f}, 2.2f},
    {{-0.429f, 0.250f, 1.958f}, {0.372f, 0.149f, 0.829f}, 2.2f},
    {{-0.344f, 0.600f, 0.631f}, {0.297f, 0.206f, 0.847f}, 2.2f},
    {{-1.222f, 0.950f, 1.629f}, {0.228f, 0.273f, 0.849f}, 2.2f},
    {{-0.636f, 0.250f, 0.436f}, {0.167f, 0.346f, 0.836f}, 2.2f},
    {{-1.829f, 0.600f, 1.022f}, {0.117f, 0.424f, 0.809f}, 2.2f},
    {{-0.831f, 0.950f, 0.144f}, {0.080f, 0.502f, 0.767f}, 2.2f},
    {{-2.158f, 0.250f, 0.229f}, {0.058f, 0.579f, 0.714f}, 2.2f},
    {{-0.900f, 0.600f, -0.200f}, {0.050f, 0.650f, 0.650f}, 2.2f},
    {{-2.158f, 0.950f, -0.629f}, {0.058f, 0.714f, 0.579f}, 2.2f},
    {{-0.831f, 0.250f, -0.544f}, {0.080f, 0.767f, 0.502f}, 2.2f},
    {{-1.829f, 0.600f, -1.422f}, {0.117f, 0.809f, 0.424f}, 2.2f},
    {{-0.636f, 0.950f, -0.836f}, {0.167f, 0.836f, 0.346f}, 2.2f},
    {{-1.222f, 0.250f, -2.029f}, {0.228f, 0.849f, 0.273f}, 2.2f},
    {{-0.344f, 0.600f, -1.031f}, {0.297f, 0.847f, 0.206f}, 2.2f},
    {{-0.429f, 0.950f, -2.358f}, {0.372f, 0.829f, 0.149f}, 2.2f},
    {{-0.000f, 0.250f, -1.100f}, {0.450f, 0.796f, 0.104f}, 2.2f},
    {{0.429f, 0.600f, -2.358f}, {0.528f, 0.751f, 0.071f}, 2.2f},
    {{0.344f, 0.950f, -1.031f}, {0.603f, 0.694f, 0.053f}, 2.2f},
    {{1.222f, 0.250f, -2.029f}, {0.672f, 0.627f, 0.051f}, 2.2f},
    {{0.636f, 0.600f, -0.836f}, {0.733f, 0.554f, 0.064f}, 2.2f},
    {{1.829f, 0.950f, -1.422f}, {0.783f, 0.476f, 0.091f}, 2.2f},
    {{0.831f, 0.250f, -0.544f}, {0.820f, 0.398f, 0.133f}, 2.2f},
    {{2.158f, 0.600f, -0.629f}, {0.842f, 0.321f, 0.186f}, 2.2f},
};
const glm::vec3 eye(0.0f, 1.6f, 3.6f), ambient(0.05f);
const float refraction_pixels = 8.0f;

// ---- The engine's GL plumbing ----------------------------------------------------------------------

struct mesh {
  GLuint vao = 0, vbo[3] = {};
  GLsizei count = 0;
};
mesh upload(const dstrans::shape& s) {
  mesh m;
  glGenVertexArrays(1, &m.vao);
  glBindVertexArray(m.vao);
  glGenBuffers(3, m.vbo);
  for (GLuint a = 0; a < 2; ++a) {
    const vector<glm::vec3>& v = a == 0 ? s.positions : s.normals;
    glBindBuffer(GL_ARRAY_BUFFER, m.vbo[a]);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(v.size() * sizeof(glm::vec3)), v.data(), GL_STATIC_DRAW);
    glEnableVertexAttribArray(a);
    glVertexAttribPointer(a, 3, GL_FLOAT, GL_FALSE, 0, nullptr);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, m.vbo[2]);
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(s.indices.size() * sizeof(uint32_t)), s.indices.data(), GL_STATIC_DRAW);
  m.count = GLsizei(s.indices.size());
  return m;
}

struct framebuffer {
  GLuint fbo = 0, depth = 0;
  vector<GLuint> colour;
};
// Colour textures of `formats` at attachments 0, 1, ... and, if `with_depth`, a depth texture.
framebuffer make_framebuffer(const vector<GLenum>& formats, bool with_depth, int w, int h) {
  framebuffer f;
  glGenFramebuffers(1, &f.fbo);
  glBindFramebuffer(GL_FRAMEBUFFER, f.fbo);
  vector<GLenum> draw;
  auto texture = [&](GLenum format, GLenum attachment) {
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glTexStorage2D(GL_TEXTURE_2D, 1, format, w, h);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glFramebufferTexture2D(GL_FRAMEBUFFER, attachment, GL_TEXTURE_2D, t, 0);
    return t;
  };
  for (GLenum format : formats) {
    draw.push_back(GLenum(GL_COLOR_ATTACHMENT0 + draw.size()));
    f.colour.push_back(texture(format, draw.back()));
  }
  if (with_depth) f.depth = texture(GL_DEPTH_COMPONENT32F, GL_DEPTH_ATTACHMENT);
  glDrawBuffers(GLsizei(draw.size()), draw.data());
  return f;
}

GLuint compile(GLenum kind, const string& text, const string& name, bool& ok) {
  const GLuint s = glCreateShader(kind);
  const char* src = text.c_str();
  glShaderSource(s, 1, &src, nullptr);
  glCompileShader(s);
  GLint status = 0;
  glGetShaderiv(s, GL_COMPILE_STATUS, &status);
  if (!status) {
    char log[4096];
    glGetShaderInfoLog(s, sizeof log, nullptr, log);
    fprintf(stderr, "tutorial_engine: %s does not compile:\n%s\n", name.c_str(), log);
    ok = false;
  }
  return s;
}

// The programs' sources are written into `dir` as well, where glslang checks them.
GLuint program(const string& dir, const string& vs_name, const string& vs, const string& fs_name, const string& fs, bool& ok) {
  for (const auto& [name, text] : {pair<string, string>{vs_name + ".vert", vs}, {fs_name + ".frag", fs}}) {
    ofstream out(dir + "/" + name);
    out << text;
    if (!out.flush()) {
      fprintf(stderr, "tutorial_engine: cannot write %s/%s\n", dir.c_str(), name.c_str());
      ok = false;
    }
  }
  const GLuint p = glCreateProgram();
  glAttachShader(p, compile(GL_VERTEX_SHADER, vs, vs_name, ok));
  glAttachShader(p, compile(GL_FRAGMENT_SHADER, fs, fs_name, ok));
  glLinkProgram(p);
  GLint linked = 0;
  glGetProgramiv(p, GL_LINK_STATUS, &linked);
  if (!linked) {
    fprintf(stderr, "tutorial_engine: %s + %s do not link\n", vs_name.c_str(), fs_name.c_str());
    ok = false;
  }
  return p;
}
GLint at(GLuint p, const char* name) { return glGetUniformLocation(p, name); }

// ---- The engine's shaders ----------------------------------------------------------------------------

const char* const geometry_vs = R"(
layout (location = 0) in vec3 aPos;
layout (location = 1) in vec3 aNormal;
out vec3 FragPos;
out vec3 Normal;
uniform mat4 model;
uniform mat4 view;
uniform mat4 projection;
void main() {
  vec4 worldPos = model * vec4(aPos, 1.0);
  FragPos = worldPos.xyz;
  Normal = mat3(model) * aNormal;
  gl_Position = projection * view * worldPos;
}
)";
// The engine keeps its position buffer at location 0; dstrans's layout follows at 1 (first_location), and
// glass stays only on the rows dstrans's predicate keeps.
const char* const geometry_fs = R"(
layout (location = 0) out vec3 gPosition;
in vec3 FragPos;
in vec3 Normal;
uniform vec3 diffuse;
uniform float alpha;
uniform float specular;
uniform float shininess;
uniform ivec2 size;
void main() {
  if (dst_transparent(alpha) && !dst_interlace_keep(ivec2(gl_FragCoord.xy), size)) discard;
  gPosition = FragPos;
  dst_surface s = dst_surface_zero();
  s.diffuse = diffuse;
  s.alpha = alpha;
  vec3 n = normalize(Normal);
  s.normal = gl_FrontFacing || !dst_transparent(alpha) ? n : -n;  // glass is lit from both sides
  s.spec_intensity = specular;
  s.spec_power = shininess;
  s.depth = gl_FragCoord.z;
  dst_gbuffer_write(s);
}
)";
const char* const fullscreen_vs = R"(
void main() { gl_Position = vec4(vec2(gl_VertexID & 1, gl_VertexID >> 1) * 4.0 - 1.0, 0.0, 1.0); }
)";
// The engine's lighting pass, writing the final colour: each row lit as the surface it holds.
const char* const lighting_fs = R"(
out vec4 FragColor;
uniform sampler2D gPosition;
struct Light {
  vec3 Position;
  vec3 Color;
  float Radius;
};
const int NR_LIGHTS = 32;
uniform Light lights[NR_LIGHTS];
uniform vec3 viewPos;
uniform vec3 ambient;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec3 FragPos = texelFetch(gPosition, p, 0).rgb;
  dst_surface s = dst_gbuffer_read(p);
  vec3 viewDir = normalize(viewPos - FragPos);
  dst_light_sample sum = dst_light_sample_zero();
  for (int i = 0; i < NR_LIGHTS; ++i) {
    vec4 reach = dst_light_reach(1, lights[i].Position, vec3(0.0), lights[i].Radius, 0.0, 0.0, FragPos);
    dst_light_sample l = dst_phong(s.normal, reach.xyz, viewDir, s.spec_power, lights[i].Color * reach.w);
    sum.light += l.light;
    sum.specular += l.specular;
  }
  FragColor = vec4(dst_shade(s, sum, ambient), 1.0);
}
)";
// The pass the recipe adds: de-interlacing with dst_blend, refraction with dst_refract, and the opaque
// sample's depth for the forward passes that follow.
const char* const deinterlace_fs = R"(
out vec4 FragColor;
uniform sampler2D lit;
uniform mat4 view;
uniform float refraction;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), size = textureSize(lit, 0);
  ivec2 q = dst_interlace_partner(p, size);
  dst_surface a = dst_gbuffer_read(p), b = dst_gbuffer_read(q);
  if (!dst_transparent(a.alpha) && !dst_transparent(b.alpha)) {
    FragColor = vec4(texelFetch(lit, p, 0).rgb, 1.0);
    gl_FragDepth = a.depth;
    return;
  }
  bool a_glass = a.alpha <= b.alpha;
  dst_surface glass = a_glass ? a : b, behind = a_glass ? b : a;
  ivec2 glass_at = a_glass ? p : q, behind_at = a_glass ? q : p;
  gl_FragDepth = behind.depth;
  ivec2 m = dst_refract(p, size, mat3(view) * glass.normal, refraction);
  ivec2 m2 = dst_interlace_partner(m, size);
  dst_surface r = dst_gbuffer_read(m), r2 = dst_gbuffer_read(m2);
  int from = dst_refraction_source(glass.depth, r.alpha, r.depth, r2.alpha, r2.depth);
  if (from != 0) behind_at = from == 1 ? m : m2;
  FragColor = vec4(dst_blend(texelFetch(lit, behind_at, 0).rgb, texelFetch(lit, glass_at, 0).rgb, glass.alpha), 1.0);
}
)";
const char* const marker_vs = R"(
layout (location = 0) in vec3 aPos;
uniform mat4 model;
uniform mat4 view;
uniform mat4 projection;
void main() { gl_Position = projection * view * model * vec4(aPos, 1.0); }
)";
const char* const marker_fs = R"(
out vec4 FragColor;
uniform vec3 lightColor;
void main() { FragColor = vec4(lightColor, 1.0); }
)";

// dstrans's text for one of the engine's shaders, in its dialect: its own #version line first, GL's
// gl_FragCoord as it is (rows from the bottom).
string dstrans_text(dstrans::glsl::version v, bool gbuffer_write) {
  dstrans::glsl::dialect d;
  d.language = v;
  d.version_line = false;
  d.pixel_rows = dstrans::glsl::rows::from_bottom;
  dstrans::glsl::source src(d);
  dstrans::glsl::layout_options o;
  o.sides = gbuffer_write ? dstrans::glsl::side::write : dstrans::glsl::side::read;
  o.first_location = 1;            // after the position buffer
  o.first_binding = 1;             // texture units 1 and 2, set by name below where GLSL has no bindings
  o.depth_attachment_binding = 3;  // the compact layout reads depth from the depth attachment
  dstrans::glsl::add_layout<dstrans::compact_gbuffer>(src, "gbuffer", o);
  dstrans::glsl::add_interlace<dstrans::interlace::rows>(src);
  if (!gbuffer_write) {
    dstrans::glsl::add_refraction(src);
    for (const dstrans::shared_text* t : {&dstrans::text::dst_compose, &dstrans::text::dst_phong, &dstrans::text::dst_light_reach})
      src.add_shared(*t);
  }
  return src.str();
}

// The lit, glass and final images, or a message.
struct images {
  vector<unsigned char> lit, glass, final;
};
// GL's rows from the bottom, as an RGBA8 picture.
vector<unsigned char> read_colour(GLuint fbo, int w, int h) {
  vector<unsigned char> pixels(size_t(w) * size_t(h) * 4);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  return pixels;
}

bool render(const string& dir, const string& version_name, dstrans::glsl::version v, bool blit_markers, int w, int h,
            images& out) {
  const string header = "#version " + version_name + " core\n";
  bool ok = true;
  const GLuint geometry = program(dir, "geometry", header + geometry_vs, "geometry", header + dstrans_text(v, true) + geometry_fs, ok);
  const GLuint lighting = program(dir, "fullscreen", header + fullscreen_vs, "lighting", header + dstrans_text(v, false) + lighting_fs, ok);
  const GLuint deinterlace =
      program(dir, "fullscreen", header + fullscreen_vs, "deinterlace", header + dstrans_text(v, false) + deinterlace_fs, ok);
  const GLuint marker = program(dir, "marker", header + marker_vs, "marker", header + marker_fs, ok);
  if (!ok) return false;

  vector<GLenum> gformats{GL_RGBA16F};  // the position buffer
  for (const dstrans::target_desc& t : dstrans::describe<dstrans::compact_gbuffer>()) gformats.push_back(dstrans::info(t.fmt).gl_internal_format);
  const framebuffer gbuffer = make_framebuffer(gformats, true, w, h), lit = make_framebuffer({GL_RGBA16F}, false, w, h),
                    final_image = make_framebuffer({GL_RGBA8}, true, w, h);
  const glm::mat4 view = glm::lookAt(eye, glm::vec3(0.0f, 0.5f, 0.0f), glm::vec3(0, 1, 0));
  const glm::mat4 projection = glm::perspective(glm::radians(55.0f), float(w) / float(h), 0.1f, 30.0f);
  GLuint empty_vao;
  glGenVertexArrays(1, &empty_vao);
  vector<pair<mesh, object>> scene;
  for (object& o : world()) scene.push_back({upload(o.mesh), o});
  const mesh cube = upload(dstrans::shape_box(glm::vec3(0.06f)));
  auto matrices = [&](GLuint p) {
    glUniformMatrix4fv(at(p, "view"), 1, GL_FALSE, glm::value_ptr(view));
    glUniformMatrix4fv(at(p, "projection"), 1, GL_FALSE, glm::value_ptr(projection));
  };

  // Geometry: the position buffer cleared to 0, dstrans's targets as gbuffer_clears says, depth to 1.
  glViewport(0, 0, w, h);
  glBindFramebuffer(GL_FRAMEBUFFER, gbuffer.fbo);
  const float zero[4] = {0, 0, 0, 0};
  glClearBufferfv(GL_COLOR, 0, zero);
  const vector<glm::vec4> clears = dstrans::render::gbuffer_clears(dstrans::render::gbuffer_layout::compact);
  for (size_t i = 0; i < clears.size(); ++i) glClearBufferfv(GL_COLOR, GLint(i + 1), glm::value_ptr(clears[i]));
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glUseProgram(geometry);
  matrices(geometry);
  glUniform2i(at(geometry, "size"), w, h);
  for (const auto& [m, o] : scene) {
    const glm::mat4 model = glm::rotate(glm::translate(glm::mat4(1.0f), o.position), glm::radians(o.yaw_degrees), glm::vec3(0, 1, 0));
    glUniformMatrix4fv(at(geometry, "model"), 1, GL_FALSE, glm::value_ptr(model));
    glUniform3fv(at(geometry, "diffuse"), 1, glm::value_ptr(o.look.diffuse));
    glUniform1f(at(geometry, "alpha"), o.look.alpha);
    glUniform1f(at(geometry, "specular"), o.look.specular);
    glUniform1f(at(geometry, "shininess"), o.look.shininess);
    glBindVertexArray(m.vao);
    glDrawElements(GL_TRIANGLES, m.count, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_DEPTH_TEST);

  // Every pass that reads the G-buffer finds it on units 0 (positions), 1 and 2 (dstrans's targets) and 3 (depth).
  const GLuint units[4] = {gbuffer.colour[0], gbuffer.colour[1], gbuffer.colour[2], gbuffer.depth};
  for (GLuint u = 0; u < 4; ++u) {
    glActiveTexture(GL_TEXTURE0 + u);
    glBindTexture(GL_TEXTURE_2D, units[u]);
  }
  auto gbuffer_samplers = [](GLuint p) {
    glUniform1i(at(p, "dst_gbuffer_tex0"), 1);
    glUniform1i(at(p, "dst_gbuffer_tex1"), 2);
    glUniform1i(at(p, "dst_gbuffer_depth_attachment"), 3);
  };

  // Lighting into the lit colour.
  glBindFramebuffer(GL_FRAMEBUFFER, lit.fbo);
  glUseProgram(lighting);
  gbuffer_samplers(lighting);
  glUniform1i(at(lighting, "gPosition"), 0);
  for (int i = 0; i < 32; ++i) {
    const string l = "lights[" + to_string(i) + "].";
    glUniform3fv(at(lighting, (l + "Position").c_str()), 1, glm::value_ptr(lights[i].position));
    glUniform3fv(at(lighting, (l + "Color").c_str()), 1, glm::value_ptr(lights[i].colour));
    glUniform1f(at(lighting, (l + "Radius").c_str()), lights[i].range);
  }
  glUniform3fv(at(lighting, "viewPos"), 1, glm::value_ptr(eye));
  glUniform3fv(at(lighting, "ambient"), 1, glm::value_ptr(ambient));
  glBindVertexArray(empty_vao);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  out.lit = read_colour(lit.fbo, w, h);

  // De-interlacing into the final image, writing the opaque depth unless the markers take the G-buffer's.
  glBindFramebuffer(GL_FRAMEBUFFER, final_image.fbo);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_ALWAYS);
  glUseProgram(deinterlace);
  gbuffer_samplers(deinterlace);
  glActiveTexture(GL_TEXTURE4);
  glBindTexture(GL_TEXTURE_2D, lit.colour[0]);
  glUniform1i(at(deinterlace, "lit"), 4);
  glUniformMatrix4fv(at(deinterlace, "view"), 1, GL_FALSE, glm::value_ptr(view));
  glUniform1f(at(deinterlace, "refraction"), refraction_pixels);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glDepthFunc(GL_LESS);
  out.glass = read_colour(final_image.fbo, w, h);
  if (blit_markers) {
    glBindFramebuffer(GL_READ_FRAMEBUFFER, gbuffer.fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, final_image.fbo);
    glBlitFramebuffer(0, 0, w, h, 0, 0, w, h, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
    glBindFramebuffer(GL_FRAMEBUFFER, final_image.fbo);
  }

  // The light markers, forward.
  glUseProgram(marker);
  matrices(marker);
  glBindVertexArray(cube.vao);
  for (const point_light& l : lights) {
    glUniformMatrix4fv(at(marker, "model"), 1, GL_FALSE, glm::value_ptr(glm::translate(glm::mat4(1.0f), l.position)));
    glUniform3fv(at(marker, "lightColor"), 1, glm::value_ptr(l.colour));
    glDrawElements(GL_TRIANGLES, cube.count, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_DEPTH_TEST);
  out.final = read_colour(final_image.fbo, w, h);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const char* const usage = "usage: tutorial_engine --out DIR [--glsl-version 330|410|450] [--markers deinterlaced|blit]\n";
  string dir, version_name = "330", markers = "deinterlaced";
  for (int i = 1; i < argc; ++i) {
    const string a = argv[i];
    if (a == "--help" || a == "-h") {
      fputs(usage, stdout);
      return 0;
    }
    if (i + 1 >= argc || (a != "--out" && a != "--glsl-version" && a != "--markers")) {
      fprintf(stderr, "tutorial_engine: %s '%s'\n%s", i + 1 >= argc ? "no value after" : "unknown argument", a.c_str(), usage);
      return 2;
    }
    (a == "--out" ? dir : a == "--glsl-version" ? version_name : markers) = argv[++i];
  }
  const dstrans::result<dstrans::glsl::version> v = dstrans::glsl::version_named(version_name);
  if (dir.empty() || !v || *v == dstrans::glsl::version::vulkan || (markers != "deinterlaced" && markers != "blit")) {
    fprintf(stderr, "tutorial_engine: %s\n%s", dir.empty() ? "--out is needed" : !v || *v == dstrans::glsl::version::vulkan
                                                                                  ? "--glsl-version must be 330, 410 or 450"
                                                                                  : "--markers must be deinterlaced or blit",
            usage);
    return 2;
  }
  auto context = dstrans::gl::headless_context::create();
  if (!context) {
    fprintf(stderr, "tutorial_engine: %s\n", context.error().c_str());
    return 1;
  }
  const int w = 320, h = 180;
  images pictures;
  if (!render(dir, version_name, *v, markers == "blit", w, h, pictures)) return 1;
  for (const string& m : (*context)->debug_messages()) fprintf(stderr, "tutorial_engine: GL: %s\n", m.c_str());
  string error;
  for (const auto& [name, pixels] : {pair<const char*, const vector<unsigned char>*>{"lit", &pictures.lit}, {"glass", &pictures.glass},
                                     {"final", &pictures.final}})
    if (!example::write_png(dir + "/" + name + ".png", w, h, pixels->data(), true, error)) {
      fprintf(stderr, "tutorial_engine: %s\n", error.c_str());
      return 1;
    }
  printf("tutorial_engine: GLSL %s: %s/glass.png\n", version_name.c_str(), dir.c_str());
  return 0;
}
