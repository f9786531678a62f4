// Programs from .glsl files on the GL driver (OSMesa: llvmpipe): a compile error names the .glsl
// file and line it is in (render/gl/shader_source.h's #line directives, located back), a link
// error names the files, and a good program links; the typed uniform setters set what they are
// given, look each location up once, and pass over a uniform the program lacks. Its own
// executable: it makes a GL context, which the unit tests never do.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "tests/unit/glsl/glsl_files.h"  // generated from tests/unit/glsl/*.glsl
#include "render/gl/gl_context.h"
#include "tests/unit/gl_test_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/glsl_files.h"

namespace sortlast {
namespace {

// The 1-based line of `file` holding `text`.
int lineOf(const GlslFile& file, const std::string& text) {
  const std::string all(file.text);
  const size_t at = all.find(text);
  EXPECT_NE(at, std::string::npos) << text;
  int line = 1;
  for (size_t i = 0; i < at; ++i) line += all[i] == '\n';
  return line;
}

// The message of what f throws ("" if it throws nothing).
template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(GlProgram, CompileErrorNamesTheFileAndLine) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  const std::string message = errorOf([&] {
    linkProgram(
        gl, ShaderSource().add(glsl::fullscreen_vert),
        ShaderSource().define("TEST_VALUE", "2").add(glsl::good_test).add(glsl::broken_test_frag));
  });
  const std::string where = "tests/unit/glsl/broken_test.frag.glsl:" +
                            std::to_string(lineOf(glsl::broken_test_frag, "undeclared_on_purpose"));
  EXPECT_NE(message.find("GLSL compile error: " + where), std::string::npos) << message;
  EXPECT_NE(message.find("undeclared_on_purpose"), std::string::npos) << message;
  std::printf("%s", message.c_str());
  EXPECT_TRUE(message.rfind("2:", 0) != 0 && message.find("\n2:") == std::string::npos)
      << "a source-string number was left: " << message;
}

TEST(GlProgram, LinkErrorNamesTheFiles) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const std::string message = errorOf([&] {
    linkProgram(ctx->gl(), ShaderSource().add(glsl::fullscreen_vert),
                ShaderSource().add(glsl::unlinked_test_frag));
  });
  EXPECT_EQ(message.rfind("GLSL link error (render/gl/fullscreen.vert.glsl; "
                          "tests/unit/glsl/unlinked_test.frag.glsl): ",
                          0),
            0u)
      << message;
}

TEST(GlProgram, GoodChunksLink) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  GlProgram p(
      gl, linkProgram(
              gl, ShaderSource().add(glsl::fullscreen_vert),
              ShaderSource()
                  .define("TEST_VALUE", "2")
                  .add(glsl::good_test)
                  .add(GlslFile{"inline",
                                "out vec4 frag;\nvoid main() { frag = vec4(testValue()); }\n"})));
  EXPECT_NE(p.id(), 0u);
  EXPECT_EQ(gl.GetError(), unsigned(GL_NO_ERROR));
}

// A program with one active uniform of each type the setters take, and one declared but unused
// (not active: location -1).
const GlslFile kUniformsFrag{"uniforms", R"(
uniform int u_int;
uniform uint u_uint;
uniform float u_float;
uniform vec2 u_vec2;
uniform vec3 u_vec3;
uniform vec4 u_vec4;
uniform ivec4 u_ivec4;
uniform mat4 u_mat4;
uniform float u_unused;
out vec4 frag;
void main() {
  frag = vec4(float(u_int) + float(u_uint) + u_float) + vec4(u_vec2, u_vec3.xy) + vec4(u_vec3, 0.0) +
         u_vec4 + vec4(u_ivec4) + u_mat4 * vec4(1.0);
}
)"};

GlProgram uniformsProgram(const GlApi& gl) {
  return GlProgram(gl, linkProgram(gl, ShaderSource().add(glsl::fullscreen_vert),
                                   ShaderSource().add(kUniformsFrag)));
}

// GetUniformLocation behind a counter: how often a GlProgram made with `countingApi` asked.
int location_lookups = 0;
PFNGLGETUNIFORMLOCATIONPROC real_get_uniform_location = nullptr;

GlApi countingApi(const GlApi& gl) {
  GlApi counting = gl;
  real_get_uniform_location = gl.GetUniformLocation;
  location_lookups = 0;
  counting.GetUniformLocation = [](GLuint program, const GLchar* name) -> GLint {
    ++location_lookups;
    return real_get_uniform_location(program, name);
  };
  return counting;
}

TEST(GlProgram, TypedSettersSetTheirValues) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi& gl = ctx->gl();
  const GlProgram p = uniformsProgram(gl);
  gl.UseProgram(p);
  glm::mat4 m(0.0f);
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = 0.5f + float(i);
  p.set("u_int", -7);
  p.set("u_uint", 4000000000u);
  p.set("u_float", 0.1f);
  p.set("u_vec2", glm::vec2(1.5f, -2.25f));
  p.set("u_vec3", glm::vec3(3.0f, 1e-7f, -1e7f));
  p.set("u_vec4", glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
  p.set("u_ivec4", glm::ivec4(-1, 2, -3, 4));
  p.set("u_mat4", m);
  ASSERT_EQ(gl.GetError(), unsigned(GL_NO_ERROR));

  int i1 = 0, i4[4] = {};
  unsigned u1 = 0;
  float f[16] = {};
  gl.GetUniformiv(p, p.uniformLocation("u_int"), &i1);
  EXPECT_EQ(i1, -7);
  gl.GetUniformuiv(p, p.uniformLocation("u_uint"), &u1);
  EXPECT_EQ(u1, 4000000000u);
  gl.GetUniformfv(p, p.uniformLocation("u_float"), f);
  EXPECT_EQ(f[0], 0.1f);
  gl.GetUniformfv(p, p.uniformLocation("u_vec2"), f);
  EXPECT_EQ(glm::vec2(f[0], f[1]), glm::vec2(1.5f, -2.25f));
  gl.GetUniformfv(p, p.uniformLocation("u_vec3"), f);
  EXPECT_EQ(glm::vec3(f[0], f[1], f[2]), glm::vec3(3.0f, 1e-7f, -1e7f));
  gl.GetUniformfv(p, p.uniformLocation("u_vec4"), f);
  EXPECT_EQ(glm::vec4(f[0], f[1], f[2], f[3]), glm::vec4(0.25f, 0.5f, 0.75f, 1.0f));
  gl.GetUniformiv(p, p.uniformLocation("u_ivec4"), i4);
  EXPECT_EQ(glm::ivec4(i4[0], i4[1], i4[2], i4[3]), glm::ivec4(-1, 2, -3, 4));
  gl.GetUniformfv(p, p.uniformLocation("u_mat4"), f);
  for (int i = 0; i < 16; ++i) EXPECT_EQ(f[i], 0.5f + float(i)) << i;  // column-major, as given
  EXPECT_EQ(gl.GetError(), unsigned(GL_NO_ERROR));
}

TEST(GlProgram, LooksEachLocationUpOnce) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi counting = countingApi(ctx->gl());
  GlProgram p = uniformsProgram(counting);
  counting.UseProgram(p);
  for (int i = 0; i < 3; ++i) p.set("u_float", float(i));
  EXPECT_EQ(location_lookups, 1);
  p.set("u_int", 1);
  p.set("u_float", 2.0f);
  EXPECT_EQ(location_lookups, 2);
  // The locations move with the program.
  const GlProgram moved = std::move(p);
  moved.set("u_int", 2);
  moved.set("u_float", 3.0f);
  EXPECT_EQ(location_lookups, 2);
  float f = 0.0f;
  counting.GetUniformfv(moved, moved.uniformLocation("u_float"), &f);
  EXPECT_EQ(f, 3.0f);
  EXPECT_EQ(location_lookups, 2);
}

TEST(GlProgram, AMissingUniformIsSilentlyPassedOver) {
  auto ctx = testGlContext();
  if (!ctx) return;
  const GlApi counting = countingApi(ctx->gl());
  const GlProgram p = uniformsProgram(counting);
  counting.UseProgram(p);
  p.set("u_float", 5.0f);
  // Declared but unused (the driver drops it), and never declared: location -1, no GL error,
  // and the other uniforms keep their values.
  for (int i = 0; i < 2; ++i) {
    p.set("u_unused", 1.0f);
    p.set("u_not_declared", glm::vec3(1.0f));
    p.set("u_not_declared_either", 3);
  }
  EXPECT_EQ(p.uniformLocation("u_unused"), -1);
  EXPECT_EQ(p.uniformLocation("u_not_declared"), -1);
  EXPECT_EQ(location_lookups, 4);  // -1 is kept like any location
  EXPECT_EQ(counting.GetError(), unsigned(GL_NO_ERROR));
  float f = 0.0f;
  counting.GetUniformfv(p, p.uniformLocation("u_float"), &f);
  EXPECT_EQ(f, 5.0f);
}

}  // namespace
}  // namespace sortlast
