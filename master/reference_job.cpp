#include "master/reference_job.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>
#include <thread>

#include "common/error.h"
#include "common/scene.h"
#include "master/metaball_reference.h"
#include "master/progress.h"
#include "master/reference.h"

namespace sortlast {

namespace {

// Everything the volume integrator needs, for the whole volume.
struct VolumeInput {
  WholeVolume vol;
  TransferFunction tf;
  double step = 0.0;  // world units
};

VolumeInput loadWholeVolume(Scene& scene) {
  validateVolume(scene.volume);
  VolumeInput in{{scene.volume.grid, {}}, {}, 0.0};
  IndexBox all{{0, 0, 0}, scene.volume.grid.dims - 1};
  in.vol.samples =
      scene.volume.isVtk() ? readWholeVtk(scene.volume) : readSamples(scene.volume, all);
  auto [lo, hi] = std::minmax_element(in.vol.samples.begin(), in.vol.samples.end());
  in.tf = scene.transfer.build(*lo, *hi, scene.volume.grid.minSpacing());
  in.step = scene.reference_step * scene.volume.grid.minSpacing();
  return in;
}

MetaballModel loadMetaballs(const Scene& scene) {
  MetaballModel m;
  for (const glm::vec3& p : loadParticles(scene.particles).positions) m.positions.emplace_back(p);
  m.h = scene.particles.influenceRadius();
  m.threshold = scene.particles.threshold;
  return m;
}

// Where the particles' field can be non-zero: their bounds grown by h (empty: lo > hi).
Box3 reachOf(const MetaballModel& m) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b{glm::dvec3(inf), glm::dvec3(-inf)};
  for (const glm::dvec3& p : m.positions)
    b.lo = glm::min(b.lo, p - m.h), b.hi = glm::max(b.hi, p + m.h);
  return b;
}

// The scene's domain: the volume box grown to hold the particles' reach. It places the automatic
// camera and clips the surface rays (the GL renderer's bricks tile the same box).
Box3 sceneBounds(const std::optional<VolumeInput>& volume,
                 const std::optional<MetaballModel>& balls) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  Box3 b = balls ? reachOf(*balls) : Box3{glm::dvec3(inf), glm::dvec3(-inf)};
  if (volume) {
    Box3 v = volume->vol.grid.worldBox();
    b = {glm::min(b.lo, v.lo), glm::max(b.hi, v.hi)};
  }
  return b;
}

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
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    std::optional<VolumeInput> volume;
    std::optional<MetaballModel> balls;
    if (scene.hasVolume()) volume = loadWholeVolume(scene);
    if (scene.particles.enabled()) balls = loadMetaballs(scene);
    if (!surface_out.empty() && !balls)
      throw InputError(
          "--surface-out: the scene has no particles, so there is no surface to write");
    Box3 bounds = sceneBounds(volume, balls);
    auto cams = scene.frameCameras(bounds);
    int n = int(cams.size());
    Progress progress(n, opts.quiet);
    for (int f = 0; f < n; ++f) {
      const Camera& cam = cams[f];
      if (volume && volume->vol.grid.worldBox().contains(cam.position))
        throw InputError("camera.position is inside the volume; move the camera outside it");
      std::optional<SurfaceImage> surface;
      if (balls) {
        surface = referenceSurface(*balls, cam, bounds, threads);
        if (!surface_out.empty()) writeSurfaceImage(frameFileName(surface_out, f, n), *surface);
      }
      std::string out = frameFileName(opts.output, f, n);
      if (!volume) {
        writeSurfaceFrame(*surface, cam, scene.particles.colour, scene.background, out);
      } else if (surface) {  // the volume integrated up to the surface, the surface behind it
        ImageF colour = shadeSurfaceFloat(*surface, cam, scene.particles.colour);
        writeImage(
            out,
            renderReference(volume->vol, volume->tf, cam, volume->step, threads, *surface, colour),
            scene.background);
      } else {
        writeImage(out, renderReference(volume->vol, volume->tf, cam, volume->step, threads),
                   scene.background);
      }
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
