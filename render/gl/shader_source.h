#pragma once
// The one builder of GLSL sources. Shader text lives in .glsl files beside its
// renderer, compiled in by cmake/embed_shaders.cmake as GlslFile objects (generated headers such as
// render/volume/glsl_files.h, namespace sortlast::glsl); a renderer composes one stage from them
// the way VTK composes its shader templates:
//
//   #version 450 core
//   #define NAME VALUE           a sorted set: the variant (PREINTEGRATED, GLOW, SIDE 5, ...)
//   #line 10001 1                then each file ("chunk") in the order added, after a #line
//   <first chunk>                directive giving it its own source-string number K = 1, 2, ...
//   #line 20001 2                and its own lines, K * 10000 + its line
//   <second chunk> ...
//
// so the driver's log says `K:LINE(COL)` and locate() turns that back into `file.glsl:LINE(COL)`: a
// compile error names the .glsl file and its line (render/gl/gl_program.h throws it). The line
// alone names the chunk: Mesa reports source string 0 for every error its parser finds after the
// lexer (glsl_parser.yy's YYLLOC_DEFAULT sets it), with the line the #line directive gave. Chunks
// keep their order: the same text in the same order compiles to the same float code, and the
// program variants of one renderer differ only in their defines and optional chunks.
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace sortlast {

// One embedded .glsl file: its path in the source tree and its text.
struct GlslFile {
  std::string_view path;
  std::string_view text;
};

class ShaderSource {
 public:
  // #define name value. Defining a name again with another value throws std::logic_error.
  ShaderSource& define(const std::string& name, const std::string& value = "1");
  ShaderSource& defineIf(bool on, const std::string& name) { return on ? define(name) : *this; }
  // Appends a chunk (once per program: the same file twice throws std::logic_error).
  ShaderSource& add(const GlslFile& chunk);
  ShaderSource& addIf(bool on, const GlslFile& chunk) { return on ? add(chunk) : *this; }

  // What the driver compiles.
  std::string text() const;
  // Lines per chunk in the numbering above (a longer chunk throws std::logic_error in text()).
  static constexpr int kChunkLines = 10000;

  // `log` with every location at the start of a line, Mesa's "K:LINE(COL)" or NVIDIA's
  // "K(LINE)", written as "path:line(COL)" / "path:line": the chunk LINE / kChunkLines (K may be
  // 0 for it, above), line LINE % kChunkLines of its file; LINE < kChunkLines (the version and
  // define lines) becomes "(version and defines):LINE".
  std::string locate(std::string_view log) const;
  // The chunks' paths, comma-separated (a link error names them: its log has no locations).
  std::string paths() const;

 private:
  std::map<std::string, std::string> defines_;
  std::vector<GlslFile> chunks_;
};

}  // namespace sortlast
