#include "render/glow/glow_renderer.h"

#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/glow/glow_gl.h"
#include "render/glow/glsl_files.h"

namespace sortlast {

GlowRenderer::GlowRenderer(const GlApi& gl, int width, int height)
    : gl_(gl), target_(gl, width, height) {
  program_ = GlProgram(gl_, linkProgram(gl_, ShaderSource().add(glsl::fullscreen_vert),
                                        ShaderSource()
                                            .add(glsl::glow_segment)
                                            .add(glsl::glow_emitters)
                                            .add(glsl::glow_along)
                                            .add(glsl::glow_pixel_ray)
                                            .add(glsl::glow_pass_frag)));
  gl_.GenVertexArrays(1, &vao_);
}

GlowRenderer::~GlowRenderer() {
  gl_.DeleteVertexArrays(1, &vao_);
  if (emitters_) gl_.DeleteTextures(1, &emitters_);
}

void GlowRenderer::setEmitters(const std::vector<GlowEmitter>& emitters, double eps, double intensity) {
  // Uploaded only when they change (an orbit that moves them, a served request).
  std::vector<float> texels = glowEmitterTexels(emitters);
  if (texels != texels_) {
    count_ = int(emitters.size());
    if (count_ > 0 && !emitters_) {
      emitters_ = makeFloatTexture(gl_, 3, count_, texels.data());
    } else if (count_ > 0) {
      gl_.ActiveTexture(GL_TEXTURE0);
      gl_.BindTexture(GL_TEXTURE_2D, emitters_);
      gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, 3, count_, 0, GL_RGBA, GL_FLOAT, texels.data());
    }
    texels_ = std::move(texels);
  }
  eps_ = float(eps);
  intensity_ = float(intensity);
}

GlowBrickImage GlowRenderer::render(const Box3& box, const Box3& whole, const Camera& cam,
                                    const SurfaceLayer* surface) {
  GlowBrickImage out;
  const bool has_surface = surface && !surface->rect.empty();
  Rect r = count_ > 0 ? screenRectOf(cam, box) : Rect{};
  if (has_surface) r = r.empty() ? surface->rect : unite(r, surface->rect);
  if (r.empty()) return out;
  target_.begin(r, has_surface ? surface : nullptr);
  if (count_ > 0) {
    gl_.Enable(GL_BLEND);
    gl_.BlendFunc(GL_ONE, GL_ONE);
    gl_.UseProgram(program_);
    setPixelRayUniforms(program_, cam);
    program_.set("u_box_lo", glm::vec3(box.lo));
    program_.set("u_box_hi", glm::vec3(box.hi));
    program_.set("u_box_hi_open", glm::vec3(glm::lessThan(box.hi, whole.hi)));
    program_.set("u_intensity", intensity_);
    program_.set("u_surface", 2);
    program_.set("u_has_surface", has_surface ? 1 : 0);
    if (has_surface) {
      const Rect& sr = surface->rect;
      program_.set("u_surface_rect", glm::ivec4(sr.x, sr.y, sr.w, sr.h));
      gl_.ActiveTexture(GL_TEXTURE2);
      gl_.BindTexture(GL_TEXTURE_2D, surface->surface_texture);
    }
    bindGlowEmitters(gl_, program_, pass(box, whole), 0);
    gl_.BindVertexArray(vao_);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
    gl_.Disable(GL_BLEND);
  }
  out.rect = r;
  out.pixels = target_.finishFloat(r);
  return out;
}

}  // namespace sortlast
