#include "render/particles/metaball_renderer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "io/particles.h"
#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/particles/glsl_files.h"

namespace sortlast {

namespace {

constexpr float kInf = 1e30f;

// Texture units, fixed for every program: each sampler uniform names its own unit.
enum Unit { kStateUnit = 0, kHitUnit, kNextUnit, kPotUnit, kPyramidUnit, kPot2Unit };
// Image units, as declared in the shaders' layout(binding = ...).
enum ImageUnit { kStateImage = 0, kHitImage, kBaseImage, kNextImage, kSurfaceImage, kBelowImage, kLevelImage };

unsigned makeTexture(const GlApi& gl, GLenum format, int w, int h, int levels = 1) {
  unsigned t = 0;
  gl.GenTextures(1, &t);
  gl.BindTexture(GL_TEXTURE_2D, t);
  gl.TexStorage2D(GL_TEXTURE_2D, levels, format, w, h);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, levels > 1 ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  return t;
}

}  // namespace

MetaballRenderer::MetaballRenderer(const GlContext& ctx, int width, int height,
                                   const MetaballSettings& settings)
    : MetaballBase(ctx, width, height, settings, "metaball") {
  if (settings.anisotropic) throw std::logic_error("MetaballRenderer: anisotropic smoothing is grid-only");
  allocateTargets(width, height);
  gl_.GenFramebuffers(1, &fbo_);
  gl_.GenVertexArrays(1, &vao_);
  gl_.GenQueries(1, &query_);

  // Every pass's shaders start with metaball_common.glsl, but the pyramid's reduction.
  const ShaderSource billboard =
      ShaderSource().add(glsl::metaball_common).add(glsl::metaball_billboard_vert);
  const ShaderSource fullscreen = ShaderSource().add(glsl::fullscreen_vert);
  auto link = [&](const ShaderSource& vertex, const GlslFile& fragment) {
    return GlProgram(
        gl_, linkProgram(gl_, vertex, ShaderSource().add(glsl::metaball_common).add(fragment)));
  };
  advance_ = link(billboard, glsl::metaball_advance_frag);
  potential_ = link(billboard, glsl::metaball_potential_frag);
  init_ = link(fullscreen, glsl::metaball_init_frag);
  window_ = link(fullscreen, glsl::metaball_window_frag);
  step_ = link(fullscreen, glsl::metaball_step_frag);
  secant_ = link(fullscreen, glsl::metaball_secant_frag);
  bracket_ = link(fullscreen, glsl::metaball_bracket_frag);
  bracket_base_ = link(fullscreen, glsl::metaball_bracket_base_frag);
  shade_ = link(fullscreen, glsl::metaball_shade_frag);
  reduce_ =
      GlProgram(gl_, linkProgram(gl_, fullscreen, ShaderSource().add(glsl::metaball_reduce_frag)));
  for (const GlProgram* p : {&advance_, &potential_, &init_, &window_, &step_, &secant_, &bracket_,
                             &bracket_base_, &shade_}) {
    gl_.UseProgram(*p);
    p->set("u_state", int(kStateUnit));
    p->set("u_hit", int(kHitUnit));
    p->set("u_next", int(kNextUnit));
    p->set("u_pot", int(kPotUnit));
    p->set("u_pyramid", int(kPyramidUnit));
    p->set("u_pot2", int(kPot2Unit));
  }
  gl_.check("metaball renderer setup");
}

void MetaballRenderer::allocateTargets(int width, int height) {
  width_ = width;
  height_ = height;
  levels_ = 1;
  while ((1 << levels_) <= std::max(width, height)) ++levels_;
  state_ = makeTexture(gl_, GL_RGBA32F, width, height);
  hit_ = makeTexture(gl_, GL_RGBA32F, width, height);
  next_ = makeTexture(gl_, GL_R32F, width, height);
  pot_ = makeTexture(gl_, GL_RGBA32F, width, height);
  pot2_ = makeTexture(gl_, GL_RGBA32F, width, height);
  pyramid_ = makeTexture(gl_, GL_RG32F, width, height, levels_);
}

void MetaballRenderer::freeTargets() {
  for (unsigned t : {state_, hit_, next_, pot_, pot2_, pyramid_}) gl_.DeleteTextures(1, &t);
}

void MetaballRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  // Immutable storage (TexStorage2D): new textures of the new size.
  freeTargets();
  allocateTargets(width, height);
  MetaballBase::resize(width, height);
}

void MetaballRenderer::setSettings(const MetaballSettings& settings) {
  if (settings.h != s_.h) throw std::logic_error("MetaballRenderer::setSettings: h changed");
  // The scene refuses particles.smoothing: anisotropic with the billboards (scene/scene.cpp).
  if (settings.anisotropic) throw std::logic_error("MetaballRenderer: anisotropic smoothing is grid-only");
  s_ = settings;
}

MetaballRenderer::~MetaballRenderer() {
  for (auto& b : bricks_) gl_.DeleteBuffers(1, &b.vbo);
  freeTargets();
  gl_.DeleteQueries(1, &query_);
  gl_.DeleteVertexArrays(1, &vao_);
  gl_.DeleteFramebuffers(1, &fbo_);
}

int MetaballRenderer::addBrick(const Box3& clip, const std::vector<glm::vec3>& particles) {
  GpuBrick g;
  g.clip = clip;
  g.count = int(particles.size());
  if (!particles.empty()) {
    g.bound = fieldBoundInside(clip, particles, s_.h);
    if (glm::any(glm::greaterThanEqual(g.bound.lo, g.bound.hi))) g.count = 0;
  }
  if (g.count > 0) {
    gl_.GenBuffers(1, &g.vbo);
    gl_.BindBuffer(GL_ARRAY_BUFFER, g.vbo);
    gl_.BufferData(GL_ARRAY_BUFFER, GLsizeiptr(particles.size() * sizeof(glm::vec3)), particles.data(),
                   GL_STATIC_DRAW);
    gl_.check("particle upload");
  }
  bricks_.push_back(g);
  return int(bricks_.size()) - 1;
}

void MetaballRenderer::attach(unsigned texture, int level) {
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, texture, level);
}

void MetaballRenderer::setCommonUniforms(const GlProgram& p, const Camera& cam,
                                         const GpuBrick& b) const {
  setRayUniforms(gl_, p, cam, width_, height_, s_, b.clip);
  p.set("u_window", s_.samples_per_pass);
  // 4 h: on the 65,536-particle layers at 512^2 the advance pass then skips the particles behind
  // the front (1.9 s/frame against 2.0 s looking all the way; 2 h: 1.8 s, 8 h: 2.3 s, noisy).
  p.set("u_lookahead", float(4.0 * s_.h));
}

void MetaballRenderer::fullscreen(unsigned program) {
  gl_.UseProgram(program);
  gl_.BindVertexArray(empty_vao_);
  gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
}

void MetaballRenderer::buildPyramid(const Rect& r) {
  if (!s_.cull) return;
  attach(target_.colour());
  gl_.UseProgram(reduce_);
  reduce_.set("u_rect", glm::ivec4(r.x, r.y, r.w, r.h));
  gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
  for (int level = 1; level < levels_; ++level) {
    int x0 = r.x >> level, y0 = r.y >> level;
    int x1 = (r.x + r.w - 1) >> level, y1 = (r.y + r.h - 1) >> level;
    gl_.Viewport(0, 0, std::max(1, width_ >> level), std::max(1, height_ >> level));
    gl_.Scissor(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
    reduce_.set("u_level", level);
    gl_.BindImageTexture(kBelowImage, pyramid_, level - 1, GL_FALSE, 0, GL_READ_ONLY, GL_RG32F);
    gl_.BindImageTexture(kLevelImage, pyramid_, level, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
    fullscreen(reduce_);
  }
  gl_.Viewport(0, 0, width_, height_);
  gl_.Scissor(r.x, r.y, r.w, r.h);
}

void MetaballRenderer::drawBillboards(const GlProgram& program, const GpuBrick& b,
                                      const glm::mat4& vp, const Rect& r, float cull_pad) {
  gl_.UseProgram(program);
  program.set("u_view_proj", vp);
  program.set("u_levels", s_.cull ? levels_ : 0);
  program.set("u_cull_pad", cull_pad);
  program.set("u_rect", glm::ivec4(r.x, r.y, r.w, r.h));
  gl_.BindVertexArray(vao_);
  gl_.BindBuffer(GL_ARRAY_BUFFER, b.vbo);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
  gl_.EnableVertexAttribArray(0);
  gl_.VertexAttribDivisor(0, 1);
  gl_.DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, b.count);
}

SurfaceBrick MetaballRenderer::render(int handle, const Camera& cam, double near_plane,
                                      double far_plane, bool want_surface) {
  const GpuBrick& b = bricks_.at(size_t(handle));
  SurfaceBrick out;
  if (b.count == 0) return out;
  Rect r = screenRectOf(cam, b.bound);
  if (r.empty()) return out;

  const glm::mat4 vp = cam.viewProjection(near_plane, far_plane);
  for (const GlProgram* p : {&advance_, &potential_, &init_, &window_, &step_, &secant_, &bracket_,
                             &bracket_base_, &shade_})
    setCommonUniforms(*p, cam, b);

  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.Viewport(0, 0, width_, height_);
  gl_.Enable(GL_SCISSOR_TEST);
  gl_.Scissor(r.x, r.y, r.w, r.h);
  gl_.Disable(GL_BLEND);
  const std::pair<Unit, unsigned> samplers[] = {
      {kStateUnit, state_}, {kHitUnit, hit_}, {kNextUnit, next_}, {kPotUnit, pot_}, {kPyramidUnit, pyramid_},
      {kPot2Unit, pot2_}};
  for (auto [unit, tex] : samplers) {
    gl_.ActiveTexture(GL_TEXTURE0 + unit);
    gl_.BindTexture(GL_TEXTURE_2D, tex);
  }
  gl_.BindImageTexture(kStateImage, state_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  gl_.BindImageTexture(kHitImage, hit_, 0, GL_FALSE, 0, GL_READ_WRITE, GL_RGBA32F);
  gl_.BindImageTexture(kBaseImage, pyramid_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RG32F);
  gl_.BindImageTexture(kNextImage, next_, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_R32F);
  gl_.BindImageTexture(kSurfaceImage, target_.surface(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
  // The framebuffer always has a colour attachment (passes that only write images mask it off).
  attach(next_);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("OpenGL: metaball framebuffer is not complete");

  // Passes that write only images keep the colour target attached (masked off): no texture they
  // sample may be the framebuffer's attachment.
  auto imagePass = [&](unsigned program) {
    attach(target_.colour());
    gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    fullscreen(program);
  };
  // The potential passes write two RGBA targets (samples 0-3 and 4-7 of a window); every other
  // pass draws into attachment 0 only.
  auto blendPass = [&](unsigned target, float clear, GLenum equation, const GlProgram& program,
                       float pad) {
    attach(target);
    const bool two = target == pot_;
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, two ? pot2_ : 0, 0);
    const GLenum both[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    gl_.DrawBuffers(two ? 2 : 1, both);
    gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    gl_.ClearColor(clear, clear, clear, clear);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
    gl_.Enable(GL_BLEND);
    gl_.BlendEquation(equation);
    gl_.BlendFunc(GL_ONE, GL_ONE);
    drawBillboards(program, b, vp, r, pad);
    gl_.Disable(GL_BLEND);
    gl_.BlendEquation(GL_FUNC_ADD);
    if (two) {
      gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, 0, 0);
      gl_.DrawBuffers(1, both);
    }
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
  };

  // 1-2: march windows of samples until no pixel is searching, or every pixel hit the cap.
  imagePass(init_);
  buildPyramid(r);
  const int max_rounds = s_.max_samples + 1;
  int rounds = 0;
  for (; rounds < max_rounds; ++rounds) {
    blendPass(next_, kInf, GL_MIN, advance_, 0.0f);
    imagePass(window_);
    buildPyramid(r);
    gl_.UseProgram(potential_);
    potential_.set("u_mode", 0);
    blendPass(pot_, 0.0f, GL_FUNC_ADD, potential_, float(s_.h));
    attach(target_.colour());
    gl_.ColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    gl_.BeginQuery(GL_ANY_SAMPLES_PASSED, query_);
    fullscreen(step_);
    gl_.EndQuery(GL_ANY_SAMPLES_PASSED);
    unsigned searching = 0;
    gl_.GetQueryObjectuiv(query_, GL_QUERY_RESULT, &searching);
    if (!searching) {
      ++rounds;
      break;
    }
    buildPyramid(r);
  }
  out.rounds = rounds;

  // 3: refinement passes (4 probes each) inside each bracket, then the secant estimate.
  for (int i = 0; i < s_.refine_iterations; ++i) {
    imagePass(bracket_base_);
    buildPyramid(r);
    gl_.UseProgram(potential_);
    potential_.set("u_mode", 1);
    blendPass(pot_, 0.0f, GL_FUNC_ADD, potential_, float(s_.h));
    imagePass(bracket_);
  }
  imagePass(secant_);
  buildPyramid(r);
  // 4: gradient at the surface, then shading.
  gl_.UseProgram(potential_);
  potential_.set("u_mode", 2);
  blendPass(pot_, 0.0f, GL_FUNC_ADD, potential_, float(s_.h));
  attach(target_.colour());
  gl_.ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  fullscreen(shade_);

  target_.readBack(r, want_surface, out);
  gl_.check("metaball render");
  return out;
}

}  // namespace sortlast
