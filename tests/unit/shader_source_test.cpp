// The GLSL builder (render/gl/shader_source.h) without a driver: the text it composes, the driver
// logs it locates back to the .glsl files, and the files as cmake/embed_shaders.cmake embeds them.
#include "render/gl/shader_source.h"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "tests/unit/glsl/glsl_files.h"  // generated from tests/unit/glsl/*.glsl
#include "render/gl/glsl_files.h"
#include "render/glow/glsl_files.h"
#include "render/particles/glsl_files.h"
#include "render/surfaces/glsl_files.h"
#include "render/volume/glsl_files.h"

namespace sortlast {
namespace {

const GlslFile kA{"render/x/a.glsl", "float a() { return 1.0; }\n"};
const GlslFile kB{"render/x/b.frag.glsl", "void main() {}"};  // no final newline

TEST(ShaderSource, VersionSortedDefinesThenChunksEachAfterALineDirective) {
  const std::string text = ShaderSource().define("ZED").add(kA).define("ALPHA", "3").add(kB).text();
  EXPECT_EQ(text,
            "#version 450 core\n"
            "#define ALPHA 3\n"
            "#define ZED 1\n"
            "#line 10001 1\n"
            "float a() { return 1.0; }\n"
            "#line 20001 2\n"
            "void main() {}\n");
}

TEST(ShaderSource, VariantsByCondition) {
  EXPECT_EQ(ShaderSource().defineIf(false, "X").addIf(false, kA).add(kB).text(),
            "#version 450 core\n#line 10001 1\nvoid main() {}\n");
  EXPECT_EQ(ShaderSource().defineIf(true, "X").addIf(true, kA).text(),
            "#version 450 core\n#define X 1\n#line 10001 1\nfloat a() { return 1.0; }\n");
}

TEST(ShaderSource, RefusesConflictingDefinesAndRepeatedChunks) {
  ShaderSource s;
  s.define("N", "2").define("N", "2");  // the same value again: fine
  EXPECT_THROW(s.define("N", "3"), std::logic_error);
  s.add(kA);
  EXPECT_THROW(s.add(kA), std::logic_error);
}

TEST(ShaderSource, LocatesMesaAndNvidiaLogLines) {
  ShaderSource s;
  s.define("N").add(kA).add(kB);
  // Mesa (its parser's errors say source 0, its lexer's the source number), NVIDIA, other lines.
  EXPECT_EQ(s.locate("2:20001(14): error: syntax error, unexpected '}'\n"
                     "0:10007(3): warning: unused\n"
                     "0:2(9): preprocessor error: bad define\n"
                     "3:30001(1): error: no such chunk\n"
                     "error: linking failed\n"
                     "2(20012) : error C0000: syntax error"),
            "render/x/b.frag.glsl:1(14): error: syntax error, unexpected '}'\n"
            "render/x/a.glsl:7(3): warning: unused\n"
            "(version and defines):2(9): preprocessor error: bad define\n"
            "3:30001(1): error: no such chunk\n"
            "error: linking failed\n"
            "render/x/b.frag.glsl:12 : error C0000: syntax error");
  EXPECT_EQ(s.paths(), "render/x/a.glsl, render/x/b.frag.glsl");
}

// The embedded text is the file's, byte for byte: escapes_test.glsl holds what would end a raw
// string, trip CMake or make a trigraph (quotes, backslashes, raw-string delimiters, ${...},
// semicolons, ??=, a tab, no final newline), crlf_test.glsl carriage returns; the others are one
// file of each library.
TEST(EmbeddedGlsl, TextIsTheFileByteForByte) {
  for (const GlslFile* f :
       {&glsl::escapes_test, &glsl::crlf_test, &glsl::fullscreen_vert, &glsl::glow_segment,
        &glsl::metaball_common, &glsl::subdiv_limit_frag, &glsl::raycast_march_frag}) {
    std::ifstream in(std::string(SORTLAST_SOURCE_DIR) + "/" + std::string(f->path),
                     std::ios::binary);
    ASSERT_TRUE(in) << f->path;
    std::stringstream file;
    file << in.rdbuf();
    EXPECT_EQ(f->text, file.str()) << f->path;
  }
}

}  // namespace
}  // namespace sortlast
