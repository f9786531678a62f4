#pragma once
// Exact Catmull-Clark limit surfaces per fragment (../shared/PAPERS.md §5, Kanai and Yasui), in
// OpenGL 4.5 core, as the paper's MRT variant: one pass rasterises the coarse mesh
// (common/subdiv_coarse.h), whose vertices carry (control face, u, v); each fragment evaluates the
// exact limit position and normal from the precomputed control points (common/subdiv_tables.h, in
// SSBOs; the GLSL mirrors evaluateTables), drops itself if that limit point lies outside the
// brick's box, writes the limit point's depth, and shades.
//
// Optionally (SubdivShading::newton_steps) each fragment first moves its (u, v) by Newton steps
// until the limit point lies on the pixel's ray, so the image does not depend on the coarse level.
//
// Because a fragment's depth and its brick are both decided by its exact limit point, every
// fragment belongs to exactly one brick and the nearest limit point wins per pixel in each: brick
// images composite to the one-brick image exactly. Coverage is the coarse mesh's: at silhouettes
// the surface is drawn out to the coarse mesh's outline, not the limit surface's (the distance is
// coarseDeviation, e.g. 1e-2 of the size at level 1, 2e-3 at level 3 for pole5).
#include <string>
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "common/image.h"
#include "common/subdiv_coarse.h"
#include "common/subdiv_tables.h"
#include "worker/gl_context.h"

namespace sortlast {

struct SubdivShading {
  std::string mode = "headlight";  // headlight | reflection_lines
  glm::dvec3 colour{0.8, 0.8, 0.85};
  // reflection_lines: a planar light perpendicular to `light_direction` (from the surface's centre,
  // at 2 sizes), striped `stripes` times across its size with bright bands of `stripe_width` (0..1)
  int stripes = 12;
  double stripe_width = 0.3;
  glm::dvec3 light_direction{0.0, 1.0, 0.0};
  // Newton steps per fragment moving its (u, v) onto the pixel's ray (0: the coarse fragment's
  // interpolated (u, v), as the paper does); a step that leaves the control face continues on
  // the face across that edge.
  int newton_steps = 2;
};

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

  // Uploads the surface's tables and its coarse mesh at `level` (see buildCoarseMesh).
  void setSurface(const SubdivSurface& surface, int level, const SubdivShading& shading);
  // Renders the fragments whose limit points lie in [clip.lo, clip.hi) (half-open, so a point on
  // a face shared by two bricks belongs to one). [near_plane, far_plane] must hold the surface.
  SubdivFrame render(const Camera& cam, const Box3& clip, double near_plane, double far_plane,
                     bool want_parameters = false);

 private:
  const GlApi& gl_;
  int width_, height_;
  unsigned fbo_ = 0, colour_ = 0, surface_ = 0, params_ = 0, depth_ = 0;
  unsigned program_ = 0, vao_ = 0, vbo_ = 0, ssbo_[4] = {0, 0, 0, 0};
  int vertex_count_ = 0;
  glm::dvec3 centre_{0.0};
  double size_ = 1.0;
  SubdivShading shading_;
};

}  // namespace sortlast
