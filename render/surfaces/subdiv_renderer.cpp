#include "render/surfaces/subdiv_renderer.h"

#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "render/gl/glsl_files.h"  // generated from render/gl/*.glsl (cmake/embed_shaders.cmake)
#include "render/surfaces/glsl_files.h"

namespace sortlast {

SubdivRenderer::SubdivRenderer(const GlContext& ctx, int width, int height)
    : gl_(ctx.gl()), width_(width), height_(height) {
  // Pass 1: the coarse mesh; pass 2: one fragment per pixel (render/surfaces/subdiv_*.glsl).
  coarse_program_ = GlProgram(gl_, linkProgram(gl_, ShaderSource().add(glsl::subdiv_coarse_vert),
                                               ShaderSource().add(glsl::subdiv_coarse_frag)));
  program_ = GlProgram(gl_, linkProgram(gl_, ShaderSource().add(glsl::fullscreen_vert),
                                        ShaderSource().add(glsl::subdiv_limit_frag)));
  gl_.GenFramebuffers(1, &fbo_);
  gl_.GenFramebuffers(1, &coarse_fbo_);
  gl_.GenVertexArrays(1, &screen_vao_);
  makeTargets();
}

void SubdivRenderer::makeTargets() {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  unsigned* targets[3] = {&colour_, &surface_, &params_};
  for (int i = 0; i < 3; ++i) {
    gl_.GenTextures(1, targets[i]);
    gl_.BindTexture(GL_TEXTURE_2D, *targets[i]);
    gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width_, height_, 0, GL_RGBA, GL_FLOAT, nullptr);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_TEXTURE_2D, *targets[i],
                             0);
  }
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("SubdivRenderer: framebuffer incomplete");
  // Pass 1's target: the nearest coarse fragment's (u, v, face, surface) and its depth.
  gl_.BindFramebuffer(GL_FRAMEBUFFER, coarse_fbo_);
  gl_.GenTextures(1, &coarse_);
  gl_.BindTexture(GL_TEXTURE_2D, coarse_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA32F, width_, height_, 0, GL_RGBA, GL_FLOAT, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, coarse_, 0);
  gl_.GenTextures(1, &depth_);
  gl_.BindTexture(GL_TEXTURE_2D, depth_);
  gl_.TexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH32F_STENCIL8, width_, height_, 0, GL_DEPTH_STENCIL,
                 GL_FLOAT_32_UNSIGNED_INT_24_8_REV, nullptr);
  gl_.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depth_, 0);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("SubdivRenderer: coarse framebuffer incomplete");
  // Pass 2 tests the same stencil (the surface pass 1 found per pixel), without depth.
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.FramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_TEXTURE_2D, depth_, 0);
  if (gl_.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("SubdivRenderer: framebuffer incomplete");
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void SubdivRenderer::dropTargets() {
  unsigned textures[5] = {colour_, surface_, params_, coarse_, depth_};
  gl_.DeleteTextures(5, textures);
}

void SubdivRenderer::resize(int width, int height) {
  if (width == width_ && height == height_) return;
  dropTargets();
  width_ = width;
  height_ = height;
  makeTargets();
}

SubdivRenderer::~SubdivRenderer() {
  clearSurfaces();
  dropTargets();
  gl_.DeleteFramebuffers(1, &fbo_);
  gl_.DeleteFramebuffers(1, &coarse_fbo_);
  gl_.DeleteVertexArrays(1, &screen_vao_);
}

void SubdivRenderer::clearSurfaces() {
  for (GpuSurface& g : surfaces_) {
    gl_.DeleteBuffers(4, g.ssbo);
    gl_.DeleteBuffers(1, &g.vbo);
    gl_.DeleteVertexArrays(1, &g.vao);
  }
  surfaces_.clear();
}

void SubdivRenderer::setSurface(const SubdivSurface& surface, int level,
                                const SubdivShading& shading) {
  clearSurfaces();
  addSurface(surface, level, shading);
}

void SubdivRenderer::addSurface(const SubdivSurface& surface, int level,
                                const SubdivShading& shading) {
  const SubdivTables tables = buildTables(surface);
  const CoarseMesh coarse = buildCoarseMesh(surface, level);
  GpuSurface g;
  g.shading = shading;
  g.size = surface.control().mesh.size();
  g.two_sided = surface.twoSided();
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& p : surface.control().mesh.points) lo = glm::min(lo, p), hi = glm::max(hi, p);
  g.centre = 0.5 * (lo + hi);
  // The limit surface lies in the control points' bounds (convex combinations of them); grown by
  // far more than the float tables' rounding, so no float limit point can lie outside.
  g.lo = lo - 1e-5 * g.size;
  g.hi = hi + 1e-5 * g.size;
  // Triangles unrolled (no index buffer): position, then (u, v, face); face ids are exact floats
  // below 2^24.
  std::vector<float> vertices;
  vertices.reserve(coarse.triangles.size() * 6);
  for (unsigned i : coarse.triangles) {
    const CoarseVertex& c = coarse.vertices[i];
    vertices.insert(vertices.end(),
                    {c.position.x, c.position.y, c.position.z, c.u, c.v, float(c.face)});
  }
  g.vertex_count = int(coarse.triangles.size());
  gl_.GenVertexArrays(1, &g.vao);
  gl_.GenBuffers(1, &g.vbo);
  gl_.GenBuffers(4, g.ssbo);
  gl_.BindVertexArray(g.vao);
  gl_.BindBuffer(GL_ARRAY_BUFFER, g.vbo);
  gl_.BufferData(GL_ARRAY_BUFFER, vertices.size() * sizeof(float), vertices.data(), GL_STATIC_DRAW);
  gl_.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
  gl_.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float),
                          reinterpret_cast<void*>(3 * sizeof(float)));
  gl_.EnableVertexAttribArray(0);
  gl_.EnableVertexAttribArray(1);
  gl_.BindVertexArray(0);
  auto upload = [&](unsigned buffer, const void* data, size_t bytes) {
    gl_.BindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
    gl_.BufferData(GL_SHADER_STORAGE_BUFFER, bytes, data, GL_STATIC_DRAW);
  };
  upload(g.ssbo[0], tables.faces.data(), tables.faces.size() * sizeof(SubdivTables::FaceEntry));
  upload(g.ssbo[1], tables.positions.data(), tables.positions.size() * sizeof(glm::vec4));
  upload(g.ssbo[2], tables.tangents.data(), tables.tangents.size() * sizeof(glm::vec4));
  // Per face and edge c (corner c -> c+1): the face across it and that face's edge, as face * 4 +
  // edge.
  const ControlMesh& cm = surface.control();
  std::vector<int> neighbours(size_t(cm.mesh.faceCount()) * 4);
  for (int f = 0; f < cm.mesh.faceCount(); ++f)
    for (int c = 0; c < 4; ++c) {
      // Across a boundary edge or into a hole: no face (-1), the Newton steps stay on this one.
      const auto& t = cm.topology.twin[cm.mesh.face_offsets[f] + c];
      neighbours[size_t(f) * 4 + c] = t.face < 0 || surface.hole(t.face) ? -1 : t.face * 4 + t.corner;
    }
  upload(g.ssbo[3], neighbours.data(), neighbours.size() * sizeof(int));
  surfaces_.push_back(g);
}

void SubdivRenderer::draw(const Camera& cam, const Box3& clip, double near_plane, double far_plane,
                          const SurfaceLayer* under, const Rect* region) {
  gl_.Viewport(0, 0, width_, height_);
  gl_.Disable(GL_BLEND);
  // Clears and fragments outside `region` are skipped: a brick's fragments elsewhere would all be
  // evaluated (Newton steps included) only to be discarded for lying outside its box.
  if (region) {
    gl_.Enable(GL_SCISSOR_TEST);
    gl_.Scissor(region->x, region->y, region->w, region->h);
  } else {
    gl_.Disable(GL_SCISSOR_TEST);
  }
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  // The (face, u, v) target is cleared and written only when asked for (tests): a frame needs
  // colour and (t, normal) alone.
  const unsigned buffers[3] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1,
                               unsigned(write_parameters_ ? GL_COLOR_ATTACHMENT2 : GL_NONE)};
  // Misses: colour transparent, t = 1e30, face -1. Clear each target to its own value.
  const float clears[3][4] = {{0, 0, 0, 0}, {1e30f, 0, 0, 0}, {-1, 0, 0, 0}};
  for (int i = 0; i < (write_parameters_ ? 3 : 2); ++i) {
    const unsigned one = buffers[i];
    gl_.DrawBuffers(1, &one);
    gl_.ClearColor(clears[i][0], clears[i][1], clears[i][2], clears[i][3]);
    gl_.Clear(GL_COLOR_BUFFER_BIT);
  }
  gl_.DrawBuffers(3, buffers);
  // The layer underneath starts in the targets; fragments nearer than it replace it (the shader
  // discards the others), so the targets end holding the nearer of the two per pixel.
  if (under && !under->rect.empty()) {
    const Rect& r = under->rect;
    gl_.CopyImageSubData(under->colour_texture, GL_TEXTURE_2D, 0, r.x, r.y, 0, colour_,
                         GL_TEXTURE_2D, 0, r.x, r.y, 0, r.w, r.h, 1);
    gl_.CopyImageSubData(under->surface_texture, GL_TEXTURE_2D, 0, r.x, r.y, 0, surface_,
                         GL_TEXTURE_2D, 0, r.x, r.y, 0, r.w, r.h, 1);
  }
  const glm::mat4 vp = cam.viewProjection(near_plane, far_plane);
  const glm::dvec2 scale = cam.screenScale();  // tan(fov / 2) (x aspect), or parallel_scale (x aspect)
  gl_.Enable(GL_STENCIL_TEST);
  for (const GpuSurface& g : surfaces_) {
    // A surface none of whose limit points the brick can hold draws nothing here: both passes
    // skipped (each surface's passes are its own, so the others are unchanged).
    if (glm::any(glm::lessThan(g.hi, clip.lo)) || glm::any(glm::greaterThanEqual(g.lo, clip.hi)))
      continue;
    // Pass 1 (the paper's first pass): this surface's nearest coarse fragment per pixel, by the
    // coarse mesh's depth, marked in the stencil. Its fragment shader is a copy, so llvmpipe's
    // early depth test and the 4 x 4 blocks it shades whole on small triangles' edges cost
    // little; the exact evaluation runs once per pixel in pass 2. Every brick rasterises the
    // whole coarse mesh, so every brick finds the same nearest coarse fragment and, in pass 2, the
    // same limit point, which exactly one brick holds. One surface at a time: which of two
    // surfaces is nearer is decided by their limit points, not by their coarse meshes.
    gl_.BindFramebuffer(GL_FRAMEBUFFER, coarse_fbo_);
    gl_.StencilMask(0xff);
    gl_.Clear(GL_DEPTH_BUFFER_BIT | GL_STENCIL_BUFFER_BIT);
    gl_.Enable(GL_DEPTH_TEST);
    gl_.StencilFunc(GL_ALWAYS, 1, 0xff);
    gl_.StencilOp(GL_KEEP, GL_KEEP, GL_REPLACE);
    // A closed coarse mesh is counter-clockwise from outside: its back faces are hidden except
    // within the coarse mesh's deviation of a silhouette, so they are culled (half the fragments).
    // Camera::viewProjection mirrors y (window row 0 = image row 0), which turns
    // counter-clockwise into clockwise on screen: the outside faces are the clockwise ones there.
    // An open mesh shows its back side where the camera looks at it from behind: both sides are
    // drawn (the shading does not depend on the normal's sign: |n . view| and a reflection).
    if (!g.two_sided) gl_.Enable(GL_CULL_FACE);
    gl_.FrontFace(GL_CW);
    gl_.UseProgram(coarse_program_);
    coarse_program_.set("view_projection", vp);
    gl_.BindVertexArray(g.vao);
    gl_.DrawArrays(GL_TRIANGLES, 0, g.vertex_count);
    gl_.Disable(GL_DEPTH_TEST);
    gl_.Disable(GL_CULL_FACE);
    gl_.FrontFace(GL_CCW);

    // Pass 2: the exact limit point per pixel of the nearest coarse fragment, only where pass 1
    // drew: llvmpipe tests the stencil before the fragment shader (which writes no depth or
    // stencil) and skips blocks that none of them passes, where a discard in the shader would
    // still run it for every pixel of the region.
    gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
    gl_.StencilMask(0);
    gl_.StencilFunc(GL_EQUAL, 1, 0xff);
    gl_.StencilOp(GL_KEEP, GL_KEEP, GL_KEEP);
    // The shader reads the (t, normal) target at its own pixel and writes it once: defined
    // after a texture barrier (what the surfaces before this one wrote).
    gl_.TextureBarrier();
    gl_.UseProgram(program_);
    program_.set("eye", glm::vec3(cam.position));
    program_.set("ray_forward", glm::vec3(cam.forward()));
    program_.set("ray_right", glm::vec3(cam.right() * scale.x));
    program_.set("ray_up", glm::vec3(cam.trueUp() * scale.y));
    program_.set("orthographic", cam.orthographic() ? 1 : 0);
    program_.set("image_size", glm::vec2(float(cam.width), float(cam.height)));
    program_.set("clip_lo", glm::vec3(clip.lo));
    program_.set("clip_hi", glm::vec3(clip.hi));
    program_.set("coarse", 0);
    program_.set("nearest", 1);
    gl_.ActiveTexture(GL_TEXTURE0);
    gl_.BindTexture(GL_TEXTURE_2D, coarse_);
    gl_.ActiveTexture(GL_TEXTURE1);
    gl_.BindTexture(GL_TEXTURE_2D, surface_);
    gl_.ActiveTexture(GL_TEXTURE0);
    const SubdivShading& sh = g.shading;
    program_.set("colour", glm::vec3(sh.colour));
    program_.set("centre", glm::vec3(g.centre));
    program_.set("light_dir", glm::vec3(glm::normalize(sh.light_direction)));
    program_.set("stripe_axis", glm::vec3(stripeAxis(sh.light_direction)));
    program_.set("size", float(g.size));
    program_.set("stripe_width", float(sh.stripe_width));
    program_.set("stripes", sh.stripes);
    program_.set("reflection_lines", sh.mode == "reflection_lines" ? 1 : 0);
    program_.set("newton_steps", sh.newton_steps);
    for (int b = 0; b < 4; ++b) gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b, g.ssbo[b]);
    gl_.BindVertexArray(screen_vao_);
    gl_.DrawArrays(GL_TRIANGLES, 0, 3);
  }
  gl_.BindVertexArray(0);
  gl_.Disable(GL_STENCIL_TEST);
  gl_.StencilMask(0xff);
  gl_.Disable(GL_SCISSOR_TEST);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

void SubdivRenderer::read(const Rect& r, ImageRGBA8* pixels, std::vector<float>* surface,
                          std::vector<float>* parameters) {
  gl_.BindFramebuffer(GL_FRAMEBUFFER, fbo_);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
  const size_t n = size_t(r.area());
  auto readTarget = [&](int attachment, std::vector<float>& into) {
    into.resize(n * 4);
    gl_.ReadBuffer(GL_COLOR_ATTACHMENT0 + attachment);
    // Window row y is image row y (Camera::viewProjection flips y), so rows come back top first.
    gl_.ReadPixels(r.x, r.y, r.w, r.h, GL_RGBA, GL_FLOAT, into.data());
  };
  if (pixels) {
    std::vector<float> rgba;
    readTarget(0, rgba);
    *pixels = ImageRGBA8(r.w, r.h);
    // std::lround's rounding (half away from zero; exact in double), without a libm call per value.
    for (size_t i = 0; i < n * 4; ++i)
      pixels->px[i] = uint8_t(double(std::clamp(rgba[i], 0.0f, 1.0f) * 255.0f) + 0.5);
  }
  if (surface) readTarget(1, *surface);
  if (parameters) readTarget(2, *parameters);
  gl_.BindFramebuffer(GL_FRAMEBUFFER, 0);
}

SubdivFrame SubdivRenderer::render(const Camera& cam, const Box3& clip, double near_plane,
                                   double far_plane, bool want_parameters) {
  write_parameters_ = want_parameters;
  draw(cam, clip, near_plane, far_plane, nullptr);
  write_parameters_ = false;
  SubdivFrame out;
  read({0, 0, width_, height_}, &out.pixels, &out.surface,
       want_parameters ? &out.parameters : nullptr);
  return out;
}

}  // namespace sortlast
