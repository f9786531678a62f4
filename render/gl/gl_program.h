#pragma once
// Compiling and linking GLSL programs from composed sources (render/gl/shader_source.h), and the
// one owner of a linked program with its typed uniform setters. Errors carry the driver's log, its
// locations turned into the .glsl files and lines they name.
#include <functional>
#include <string>
#include <string_view>
#include <unordered_map>

#include <glm/glm.hpp>

#include "render/gl/gl_api.h"
#include "render/gl/shader_source.h"

namespace sortlast {

// Throw std::runtime_error: "GLSL compile error: path.glsl:LINE(COL): error: ..." (the log,
// located), or "GLSL link error (the files): log".
unsigned linkProgram(const GlApi& gl, const ShaderSource& vertex, const ShaderSource& fragment);
unsigned linkComputeProgram(const GlApi& gl, const ShaderSource& compute);

// A linked program, deleted with its owner (a renderer's member; moves, never copies), and its
// uniforms: set(name, value) calls the glUniform* that fits the value's type (int: 1i, unsigned:
// 1ui, float: 1f, vec2/3/4: 2f/3f/4f, ivec4: 4i, mat4: Matrix4fv) on the program in use, as
// glUniform* requires (UseProgram first). Each name's location is looked up once per program and
// kept; a uniform the program lacks (never declared, or optimised away by the driver) has location
// -1, and setting it does nothing, as GL defines. Other value types (double, dvec3, size_t) do not
// convert implicitly: the caller says which GL type the uniform has.
class GlProgram {
 public:
  GlProgram() = default;
  GlProgram(const GlApi& gl, unsigned id) : gl_(&gl), id_(id) {}
  GlProgram(GlProgram&& o) noexcept;
  GlProgram& operator=(GlProgram&& o) noexcept;
  GlProgram(const GlProgram&) = delete;
  GlProgram& operator=(const GlProgram&) = delete;
  ~GlProgram();
  unsigned id() const { return id_; }
  operator unsigned() const { return id_; }

  // glGetUniformLocation on the first call for `name`, the kept location after it.
  int uniformLocation(std::string_view name) const;

  void set(std::string_view name, int v) const;
  void set(std::string_view name, unsigned v) const;
  void set(std::string_view name, float v) const;
  void set(std::string_view name, const glm::vec2& v) const;
  void set(std::string_view name, const glm::vec3& v) const;
  void set(std::string_view name, const glm::dvec2& v) const;  // dvec2 / dvec3 uniforms (GLSL 4.00 doubles)
  void set(std::string_view name, const glm::dvec3& v) const;
  void set(std::string_view name, const glm::vec4& v) const;
  void set(std::string_view name, const glm::ivec4& v) const;
  void set(std::string_view name, const glm::mat4& v) const;

 private:
  // Names looked up by string_view without building a std::string (C++20 heterogeneous lookup).
  struct NameHash {
    using is_transparent = void;
    size_t operator()(std::string_view s) const { return std::hash<std::string_view>()(s); }
  };
  const GlApi* gl_ = nullptr;
  unsigned id_ = 0;
  // Uniform name -> location, filled as names are first set (mutable: a cache of what the linked,
  // unchanging program answers).
  mutable std::unordered_map<std::string, int, NameHash, std::equal_to<>> locations_;
};

}  // namespace sortlast
