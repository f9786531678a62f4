// Programs from .glsl files on the GL driver (OSMesa: llvmpipe): a compile error names the .glsl
// file and line it is in (render/gl/shader_source.h's #line directives, located back), a link
// error names the files, and a good program links. Its own executable: it makes a GL context,
// which the unit tests never do.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "tests/unit/glsl/glsl_files.h"  // generated from tests/unit/glsl/*.glsl
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/glsl_files.h"

namespace sortlast {
namespace {

std::unique_ptr<GlContext> context() {
  try {
    return createGlContext("osmesa");
  } catch (const std::exception& e) {
    ADD_FAILURE() << "no GL context: " << e.what();
    return nullptr;
  }
}

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
  auto ctx = context();
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
  auto ctx = context();
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
  auto ctx = context();
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

}  // namespace
}  // namespace sortlast
