#pragma once
// `sortlast reference`: renders a scene's frames with the CPU references. One process; it holds
// the whole volume and every particle (it is a measuring instrument, not the product).
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "common/box.h"
#include "common/camera.h"
#include "app/render_job.h"

namespace sortlast {

// Volume only: the emission-absorption integral. Particles only: the metaball surface, rays
// clipped to the particles' bounds grown by h. Both: the volume integrated up to the surface, the
// surface composited behind it. The automatic camera frames the scene's domain (the volume box
// grown to hold the particles' reach). `surface_out`: also write each frame's
// surface image (t, nx, ny, nz) there as EXR, numbered like the frames (scenes with particles).
int runReferenceJob(const RenderOptions& opts, int threads, const std::string& surface_out = "");

// The metaball reference for one view: particles at `positions` with influence radius h and
// threshold T, rays clipped to `clip`, shaded with `colour` (transfer/metaball_shading.h) over
// `background` into `output` (PNG or EXR); with `surface_out` non-empty also the surface image
// (t, nx, ny, nz) as EXR. Returns the exit code: 0, or 1 after printing an InputError.
struct SurfaceReferenceJob {
  std::vector<glm::dvec3> positions;
  double h = 0.0, threshold = 0.0;
  glm::dvec3 colour{1.0}, background{0.0};
  Camera camera;
  Box3 clip;
  std::string output = "reference.png";
  std::string surface_out;  // empty: none
  int threads = 0;          // <= 0: all cores
};
int runSurfaceReference(const SurfaceReferenceJob& job);

}  // namespace sortlast
