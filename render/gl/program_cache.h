#pragma once
// The one program-variant cache: a renderer that draws with variants of its program
// from frame to frame or brick to brick (the ray caster: ADAPTIVE, PREINTEGRATED, SHADING, GLOW;
// slicing: PREINTEGRATED, SHADING) names each variant by flag bits of its own and gives a recipe
// that turns flags into sources (its #defines and optional chunks, render/gl/shader_source.h).
// Each variant is linked on its first use and deleted with the cache, which the renderer owns.
// A program fixed when its renderer is made (a metaball pass, the grid's ANISOTROPIC variant, the
// glow pass, the surfaces' passes) is a plain GlProgram (render/gl/gl_program.h).
#include <functional>
#include <map>
#include <utility>

#include "render/gl/gl_program.h"
#include "render/gl/shader_source.h"

namespace sortlast {

struct ProgramSources {
  ShaderSource vertex, fragment;
};

class ProgramCache {
 public:
  using Recipe = std::function<ProgramSources(unsigned flags)>;
  ProgramCache(const GlApi& gl, Recipe recipe) : gl_(gl), recipe_(std::move(recipe)) {}

  // The program of variant `flags`, linked now if this is its first use (throws as linkProgram).
  const GlProgram& get(unsigned flags) {
    auto at = programs_.find(flags);
    if (at == programs_.end()) {
      const ProgramSources s = recipe_(flags);
      at = programs_.emplace(flags, GlProgram(gl_, linkProgram(gl_, s.vertex, s.fragment))).first;
    }
    return at->second;
  }

 private:
  const GlApi& gl_;
  Recipe recipe_;
  std::map<unsigned, GlProgram> programs_;
};

}  // namespace sortlast
