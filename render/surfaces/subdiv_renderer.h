#pragma once
// Exact Catmull-Clark limit surfaces per fragment (../shared/PAPERS.md §5, Kanai and Yasui), in
// OpenGL 4.5 core, in the paper's two passes, per surface: pass 1 rasterises the coarse mesh
// (subdiv/subdiv_coarse.h), whose vertices carry (control face, u, v), with an ordinary depth
// test into (u, v, face) per pixel and a stencil mark; pass 2, one fragment per marked pixel,
// evaluates the exact limit position and normal from the precomputed control points
// (subdiv/subdiv_tables.h, in SSBOs; the GLSL mirrors evaluateTables), drops itself if that
// limit point lies outside the brick's box or behind what the pixel already holds (the layer
// underneath, the surfaces drawn before), and shades.
//
// Optionally (SubdivShading::newton_steps) pass 2 first moves (u, v) by Newton steps until the
// limit point lies on the pixel's ray, so the image does not depend on the coarse level.
//
// Every brick rasterises the whole coarse mesh, so every brick finds the same nearest coarse
// fragment per pixel and the same limit point, which exactly one brick holds: brick images
// composite to the one-brick image exactly (a brick leaves a pixel empty where another brick's
// surface hides its own). Within one surface the nearest coarse fragment, not the nearest limit
// point, decides a pixel: they differ only within the coarse mesh's deviation of a silhouette.
// Coverage is the coarse mesh's: at silhouettes the surface is drawn out to the coarse mesh's
// outline, not the limit surface's (the distance is coarseDeviation, e.g. 1e-2 of the size at
// level 1, 2e-3 at level 3 for pole5).
#include <string>
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "io/image.h"
#include "subdiv/subdiv_coarse.h"
#include "subdiv/subdiv_shading.h"
#include "subdiv/subdiv_tables.h"
#include "render/gl/brick_output.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"

namespace sortlast {

struct SubdivFrame {
  ImageRGBA8 pixels;             // whole image, premultiplied, alpha 1 on the surface
  std::vector<float> surface;    // per pixel (t, nx, ny, nz); t = 1e30 on a miss
  std::vector<float> parameters; // if asked for: per pixel (face, u, v, 1); face -1 on a miss
};

class SubdivRenderer {
 public:
  SubdivRenderer(const GlContext& ctx, int width, int height);
  ~SubdivRenderer();
  SubdivRenderer(const SubdivRenderer&) = delete;
  SubdivRenderer& operator=(const SubdivRenderer&) = delete;

  // Uploads a surface's tables and its coarse mesh at `level` (see buildCoarseMesh); every surface
  // added is drawn by each draw(), all into one depth buffer.
  void addSurface(const SubdivSurface& surface, int level, const SubdivShading& shading);
  void clearSurfaces();
  // clearSurfaces() and addSurface().
  void setSurface(const SubdivSurface& surface, int level, const SubdivShading& shading);
  bool empty() const { return surfaces_.empty(); }
  void resize(int width, int height);

  // Draws, per pixel, the limit point of the nearest coarse fragment if it lies in
  // [clip.lo, clip.hi) (half-open, so a point on a face shared by two bricks belongs to one) into
  // colourTexture() and surfaceTexture(). With
  // `under` (another opaque layer of the same brick: the metaballs'), the targets start as that
  // layer and a fragment replaces it only where it is nearer (smaller t): the two layers merged
  // by depth. [near_plane, far_plane] must hold the surface. With `region`, only that rectangle
  // of the targets is cleared and drawn (it must hold under->rect; outside it they are stale).
  void draw(const Camera& cam, const Box3& clip, double near_plane, double far_plane,
            const SurfaceLayer* under = nullptr, const Rect* region = nullptr);
  // After draw(): the shaded colour (RGBA32F, premultiplied, alpha 1 on the surface) and (t, normal)
  // per pixel (t = 1e30 on a miss), full-image textures with window row y = image row y.
  unsigned colourTexture() const { return colour_; }
  unsigned surfaceTexture() const { return surface_; }
  // Reads `r` of the targets back (rows top first); null pointers: not wanted. The (face, u, v)
  // target is written by render(..., want_parameters = true) only.
  void read(const Rect& r, ImageRGBA8* pixels, std::vector<float>* surface, std::vector<float>* parameters = nullptr);
  // draw() without a layer underneath and the whole image read back.
  SubdivFrame render(const Camera& cam, const Box3& clip, double near_plane, double far_plane,
                     bool want_parameters = false);

 private:
  struct GpuSurface {
    unsigned vao = 0, vbo = 0, ssbo[4] = {0, 0, 0, 0};
    int vertex_count = 0;
    glm::dvec3 centre{0.0};
    glm::dvec3 lo{0.0}, hi{0.0};  // bounds of its limit surface
    double size = 1.0;
    bool two_sided = false;  // an open mesh: its back faces are drawn too
    SubdivShading shading;
  };
  void makeTargets();
  void dropTargets();
  const GlApi& gl_;
  int width_, height_;
  unsigned fbo_ = 0, colour_ = 0, surface_ = 0, params_ = 0;
  unsigned coarse_fbo_ = 0, coarse_ = 0, depth_ = 0, screen_vao_ = 0;
  GlProgram program_, coarse_program_;
  bool write_parameters_ = false;
  std::vector<GpuSurface> surfaces_;
};

}  // namespace sortlast
