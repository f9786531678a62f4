#pragma once
// The CPU reference of subdivision surfaces, independent of the GL path (render/surfaces/subdiv_renderer.h):
// per pixel, the first point where the pixel's ray meets the exact limit surface, in double.
//
// Each control face is tessellated into an n x n grid of exact limit points (Stam's evaluation,
// subdiv/subdiv_eval.h); each triangle is intersected with the rays of the pixels its projection
// covers (Moller-Trumbore), the nearest hit kept with its interpolated (face, u, v); then Newton's
// method on the exact surface, in the unknowns (u, v, t) of S(u, v) = eye + t d (central-difference
// Jacobian), moves the hit onto the limit surface. The limit point and its exact normal are shaded
// with subdiv/subdiv_shading.h, the model the GL shader mirrors.
//
// Error: the distance from the final limit point to the pixel's ray (`residual`), reported per
// render; where a step would leave the control face it stops at the edge, so near face edges the
// tessellated hit's error (the tessellation's deviation from the limit surface, shrinking as 1/n^2)
// can remain. Coverage is the limit surface's as tessellated: at silhouettes (within the
// tessellation's deviation) it may differ from the true limit surface by a pixel.
#include <vector>

#include "common/camera.h"
#include "io/image.h"
#include "subdiv/subdiv_eval.h"
#include "io/surface_image.h"
#include "scene/surface_scene.h"

namespace sortlast {

struct SurfaceReferenceStats {
  long long hits = 0;
  double worst_residual = 0;  // max over hits: distance of the limit point from its ray, world units
  long long stopped_at_edge = 0;  // hits whose Newton steps ended clamped at a face edge
};

class SurfaceReference {
 public:
  // Builds every surface's evaluator and tessellation (`tessellation` x `tessellation` cells per
  // control face).
  explicit SurfaceReference(const std::vector<SurfaceSpec>& surfaces, int tessellation = 12);

  // The surfaces' image: (t, normal) per pixel (t: unit-ray distance; misses +inf) and the colour
  // (premultiplied, opaque where hit). `threads` rows at a time.
  void render(const Camera& cam, int threads, SurfaceImage& surface, ImageF& colour,
              SurfaceReferenceStats* stats = nullptr) const;

 private:
  struct Entry {
    SubdivSurface surface;
    SubdivShading shading;
    glm::dvec3 centre{0.0};
    double size = 1.0;
    std::vector<glm::dvec3> grid;  // per control face, (n + 1)^2 limit points, u fastest
  };
  std::vector<Entry> entries_;
  int n_ = 12;
};

// Per pixel the nearer of two opaque layers (surface images with their colours): `into` takes
// `other` where `other` is hit and nearer. Throws std::logic_error on different sizes.
void mergeNearest(SurfaceImage& into, ImageF& into_colour, const SurfaceImage& other, const ImageF& other_colour);

}  // namespace sortlast
