#pragma once
// The resident session: loads a scene once (bricks, particles, GL context, textures, compositor) and
// then renders frames on demand. The batch `render` command, the service (`serve`) and the in-situ
// library all drive this one object; none of them has a frame loop of its own.
//
// A frame request names scene keys (the scene file's names) on top of the session's base scene;
// each request starts from the base scene again, so requests are independent of each other (two
// clients of one service do not see each other's settings). Only frame keys (isFrameKey: camera,
// image, transfer function, render and compositing options, particle shading, time step) may
// change; they are applied in place: a new image size reallocates the render targets, a new
// transfer function uploads its table and re-classifies empty blocks, a new time step reads that
// step's bricks (or takes them from the step cache), a new volume renderer or influence radius
// re-uploads the bricks from the cache. Everything else is kept.
//
// Collective calls (the constructor, render) must be made by every rank of the communicator with
// the same arguments: rank 0 decides and broadcasts (service/serve_job.cpp), the others follow.
#include <mpi.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/image.h"
#include "scene/scene.h"
#include "io/surface_image.h"
#include "common/visibility.h"
#include "session/session_layout.h"
#include "render/gl/gl_context.h"

namespace sortlast {

struct SessionOptions {
  SceneText scene;                     // the scene file's text (empty path: the built-in scene)
  std::vector<std::string> overrides;  // --set keys: part of the base scene
  // Keep each step's samples and particles in host memory (up to time.cache_mib) so a request
  // can change the step, the volume renderer or h without reading files. A batch render, which
  // never does, drops them once they are on the GPU.
  bool resident = false;
  int max_image_side = 32768;  // requests for larger images are refused
  bool quiet = false;
};

struct FrameRequest {
  std::vector<std::string> overrides;  // key.path=value (YAML values); frame keys only
  int orbit_frame = -1;        // >= 0: that frame of the scene's orbit; else its first camera
  bool float_frame = false;    // rank 0 also gets the frame before rounding (EXR output)
  bool surface = false;        // rank 0 also gets the particle surface (t, normal per pixel)
  std::string dump_layers;     // write this frame's brick images and order into this directory
  bool probe = false;          // a probe frame of render.sample_spacing: auto (not counted)
  // How many frames the job renders with these settings; 0: not known (the service, in situ).
  // 1: a still image, for which render.sample_spacing: auto does not probe (auto_spacing.h).
  int job_frames = 0;
};

struct FrameResult {  // on rank 0; other ranks get empty images and null stats
  ImageRGBA8 image;
  ImageF image_f;         // request.float_frame only
  SurfaceImage surface;   // request.surface only
  Scene scene;            // the resolved scene of the request
  nlohmann::json stats;   // the --stats fields of the frame, plus its camera, size and step
};

class BrickRenderer;

// In situ (insitu/): a step whose bricks are the simulation's, read where they lie, instead of
// the scene's files. The caller lays the bricks out; the session renders them like its own.
struct ExternalStep {
  int step = 0;
  SessionLayout layout;  // bricks, owners, bounds, grid, particle_h (the ghost margin used)
  bool has_volume = false, has_particles = false;
  double data_min = 0, data_max = 0;  // the volume's range over every rank
  // Far to near for an eye; empty: the layout's kd order.
  std::function<VisibilityOrder(const glm::dvec3& eye)> order;
  // Adds this rank's bricks (layout.mine, in order) to a renderer that has the scene's volume and
  // particle renderers enabled; runs again whenever the volume renderer or h changes.
  std::function<void(BrickRenderer& renderer, const Scene& scene, std::vector<int>& handles,
                     double& particles_held)>
      add_bricks;
  // The stored samples (ghosts included, x fastest) of brick `id` of layout.mine, for the frame's
  // accuracy estimate; unset: the frames get none (session/frame_estimate.h says why).
  std::function<std::vector<float>(int id)> samples_of;
};

class RenderSession {
 public:
  // In situ: a session with no data of its own (the base scene gives settings only); each step
  // comes through setExternalStep. Collective.
  static std::unique_ptr<RenderSession> external(SessionOptions options, MPI_Comm comm);
  // Collective. The next frames draw this step (uploaded on the next render).
  void setExternalStep(ExternalStep step);
  // In situ: the bytes of the step's samples copied for the accuracy estimate on this rank (0 until
  // a frame of the step is estimated).
  double estimateBytesHeld() const;

  // Collective. Throws JobFailed (after the failing rank printed why) on any rank's error.
  RenderSession(SessionOptions options, MPI_Comm comm);
  ~RenderSession();
  RenderSession(const RenderSession&) = delete;
  RenderSession& operator=(const RenderSession&) = delete;

  // The scene a request resolves to, checked as far as one rank can (keys, values, image size,
  // camera outside the scene). Not collective: rank 0 checks a request before broadcasting it.
  // Throws InputError naming the problem.
  Scene check(const FrameRequest& request) const;
  // The camera a request resolves to (automatic parts framed on the session's bounds).
  Camera camera(const FrameRequest& request) const;

  // Collective; every rank passes the same request. Throws JobFailed on an error (the frame is
  // abandoned on every rank and the session stays usable).
  FrameResult render(const FrameRequest& request);

  const Scene& baseScene() const;
  int orbitFrames() const;                // cameras of the base scene (1 without an orbit)
  // The base scene's transfer function against the current step's data range, or the range given
  // to setAutoRange (what the legend of a written frame shows).
  TransferFunction transferFunction() const;
  // Collective. The union of the data ranges of the given time steps (a series rendered as one
  // movie): each rank reads its own bricks of each step (the step on the GPU gives its range from
  // memory), takes their min/max, then one reduction over ranks. Needs a volume without `volumes`.
  // Throws JobFailed (a step's file that cannot be read, every sample missing).
  std::pair<double, double> seriesRange(const std::vector<int>& steps);
  // From now on `transfer.range: auto` stands for `range` (every rank passes the same) instead of
  // the current step's data range: the frames and transferFunction() (the legend) use it.
  void setAutoRange(std::pair<double, double> range);
  long long particleCount() const;        // of the current step
  int currentStep() const;                // the step on the GPU
  std::string rendererDescription() const;
  const GlDeviceInfo& deviceInfo() const;  // this rank's GL identity (device_report.h)
  // Rank 0: what a client needs to know (bounds, camera, data range, histogram, steps, the base
  // settings, the keys a request may set, limits).
  // `base`: keys applied first, as every request of this client will have them (the in-situ live
  // view: the first render's), so the settings and camera shown are the ones its frames use.
  nlohmann::json describe(const std::vector<std::string>& base = {}) const;
  // Per-job facts for --stats (adaptive sampling's preprocessing), rank 0.
  nlohmann::json jobStats() const;
  MPI_Comm comm() const;

 private:
  struct State;
  RenderSession(std::unique_ptr<State> state);
  // render.sample_spacing: auto: the step for `sc` (probing when its inputs changed); rank 0's
  // `info` gets the choice and estimates for --stats. Collective.
  double autoSpacing(const Scene& sc, const FrameRequest& request, nlohmann::json& info);
  // render.sample_spacing: auto for a still image (auto_spacing.h, stillSpacings): the frame itself
  // at each step until its estimate meets the target. Collective.
  FrameResult renderStill(const FrameRequest& request, const Scene& sc);
  std::unique_ptr<State> s_;
};

// Scene keys a request may set (isFrameKey over the key table), for describe() and the docs.
std::vector<std::string> frameKeys();

}  // namespace sortlast
