#include "app/reference_job.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>
#include <thread>

#include "common/error.h"
#include "io/image.h"
#include "scene/file_steps.h"
#include "scene/scene.h"
#include "scene/surface_output.h"
#include "reference/frame_reference.h"
#include "reference/metaball_reference.h"
#include "app/progress.h"
#include "reference/reference.h"

namespace sortlast {

namespace {

// One view of the particles alone: shade, quantise like the GL frame (toRGBA8) so both go through
// the same rounding, write.
void writeSurfaceFrame(const SurfaceImage& surface, const Camera& cam, const glm::dvec3& colour,
                       const glm::dvec3& background, const std::string& output) {
  writeImage(output, shadeSurface(surface, cam, colour), background);
}

}  // namespace

int runReferenceJob(const RenderOptions& opts, int threads, const std::string& surface_out) {
  try {
    Scene scene = loadScene(opts.scene, opts.overrides);
    resolveFileSteps(scene);
    FrameReference reference(scene, threads);
    if (!surface_out.empty() && !hasSurfaceImage(scene))
      throw InputError("--surface-out: the scene has neither particles, surfaces nor isosurfaces, so "
                       "there is no surface to write");
    auto cams = firstFrames(scene.frameCameras(reference.bounds()), opts.max_frames);
    int n = int(cams.size());
    Progress progress(n, opts.quiet);
    for (int f = 0; f < n; ++f) {
      SurfaceImage surface;
      SurfaceReferenceStats stats;
      ImageF frame = reference.render(cams[f], &surface, f, &stats);
      // The subdivision reference's own error: how far its limit points lie from their rays.
      if (reference.hasSurfaces() && !opts.quiet)
        std::fprintf(stderr,
                     "sortlast reference: frame %d: %lld surface pixels, limit points within %.3g of "
                     "their rays (world units), %lld stopped at a face edge\n",
                     f, stats.hits, stats.worst_residual, stats.stopped_at_edge);
      if (!surface_out.empty()) writeSurfaceImage(frameFileName(surface_out, f, n), surface);
      std::string out = frameFileName(opts.output, f, n);
      // Particles alone are rounded like the GL frame before they are written.
      if (reference.hasVolume() || reference.hasGlow())
        writeImage(out, frame, scene.image.background);
      else
        writeImage(out, toRGBA8(frame), scene.image.background);
      progress.frameDone(f);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

int runSurfaceReference(const SurfaceReferenceJob& job) {
  try {
    MetaballModel model{job.positions, job.h, job.threshold};
    SurfaceImage surface = referenceSurface(model, job.camera, job.clip, job.threads);
    writeSurfaceFrame(surface, job.camera, job.colour, job.background, job.output);
    if (!job.surface_out.empty()) writeSurfaceImage(job.surface_out, surface);
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace sortlast
