// The resident session (render_session.h). Construction reads the scene, lays out the bricks and
// loads the first step; render() resolves a request against the base scene, brings the GPU to it
// (only what changed), and runs one frame: render each brick, encode, composite in visibility
// order.
#include "session/render_session.h"
#include "session/projection_frame.h"

#include "scene/file_steps.h"
#include "scene/isosurface_scene.h"
#include "scene/surface_output.h"

#include "session/auto_spacing.h"
#include "session/brick_stages.h"
#include "session/fault_injection.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <thread>

#include "common/error.h"
#include "common/pixel_threads.h"
#include "compositing/compositor.h"
#include "compositing/rect_image.h"
#include "compositing/rle.h"
#include "common/visibility.h"
#include "session/adaptive_loading.h"
#include "render/brick_renderer.h"
#include "session/collective.h"
#include "session/frame_footprint.h"
#include "session/frame_estimate.h"
#include "session/frame_stats.h"
#include "session/device_report.h"
#include "session/memory_budget.h"
#include "session/particle_loading.h"
#include "session/session_layout.h"
#include "session/step_data.h"
#include "session/volume_loading.h"
#include "io/image.h"
#include "io/volume_source.h"
#include "session/surface_gather.h"

namespace sortlast {

namespace {

// Ray casting: the block value ranges adaptive steps choose from are the whole grid's, which no
// rank holds alone: each rank's part, reduced over ranks (every rank calls it; slicing has none,
// alike on every rank).
void shareBlockRanges(BrickRenderer& renderer, const GridGeometry& grid, MPI_Comm comm) {
  auto part = renderer.blockRangesPart(grid);
  if (!part) return;
  auto& [vmin, vmax] = *part;
  MPI_Allreduce(MPI_IN_PLACE, vmin.data(), int(vmin.size()), MPI_FLOAT, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, vmax.data(), int(vmax.size()), MPI_FLOAT, MPI_MAX, comm);
  renderer.setBlockRanges(std::move(*part));
}

// bench_compositing --layers input: the frame size and brick order (order.txt) and each brick's
// packed image (brick_ID.bin).
void dumpOrder(const std::string& dir, const Camera& cam, const VisibilityOrder& order) {
  std::filesystem::create_directories(dir);
  std::ofstream out(dir + "/order.txt");
  out << cam.width << " " << cam.height << "\n";
  for (int id : order.bricks) out << id << "\n";
  if (!out) throw InputError("cannot write " + dir + "/order.txt");
}

// What the GL path draws with glow emitters (docs/glow.md), checked at start and per request.
// In situ (external) none: the simulation's bricks have no glow boxes, so glow is refused rather
// than drawn without them.
void checkGlowScene(const Scene& sc, bool external) {
  if (!sc.glow.enabled()) return;
  if (external)
    throw InputError("scene key 'glow.emitters': in situ sessions do not draw glow emitters; "
                     "remove them (`sortlast render` and `serve` draw them)");
  if (sc.compositing.precision == Precision::kRgba8)
    throw InputError("scene keys 'glow.emitters' and 'compositing.precision: rgba8' cannot go "
                     "together: glow is light above 1 until the final tone map, which 8-bit "
                     "partial images would clamp; use compositing.precision: float");
  if (sc.hasVolume() && !sc.render.raycast())
    throw InputError("scene keys 'glow.emitters' and 'render.method: slicing' cannot go together: "
                     "the glow inside a volume is integrated per ray step (render.method: raycast)");
  if (sc.hasVolume() && sc.adaptive.tolerance > 0.0)
    throw InputError("scene keys 'glow.emitters' and 'adaptive.tolerance' above 0 cannot go "
                     "together: the ray caster's adaptive blocks do not integrate glow");
}

// The composited glow frame (rank 0, float, premultiplied): the tone map once, then an opaque
// RGBA8 frame over the background, since premultiplied RGBA8 cannot hold colour above alpha. One
// pass over the frame, in float: 1 - expf(-e x) is within 1e-7 of the double toneMap (4.5e-8 for
// expf and the subtraction, 2.2e-8 for e x rounded to float, whose relative error moves the result
// by at most that times y e^-y <= 1/e), far under 1/255; expm1f would keep relative precision near
// 0, which 8 bits do not need, at three times the cost. The 8-bit rounding is x * 255 + 0.5
// truncated (toRGBA8's lround without the call; they differ only within a float ulp below
// k + 1/2), so a level can differ from the double path only where a value lies within about 1e-7
// of a rounding boundary. `f` keeps the tone-mapped colour (the float frame, an .exr).
void finishGlowFrame(const GlowSpec& g, const glm::dvec3& background, ImageF& f, ImageRGBA8& out) {
  const bool exponential = g.tone_map == ToneMap::kExponential;
  const float exposure = float(g.exposure);
  const float bg[3] = {float(background.x), float(background.y), float(background.z)};
  if (out.width != f.width || out.height != f.height) out = ImageRGBA8(f.width, f.height);  // every pixel written
  float* px = f.px.data();
  uint8_t* o = out.px.data();
  const size_t n = size_t(f.width) * f.height;
  for (size_t p = 0; p < n; ++p, px += 4, o += 4) {
    const float k = 1.0f - px[3];
    for (int c = 0; c < 3; ++c) {
      const float t = exponential ? 1.0f - std::exp(-exposure * px[c]) : px[c];
      px[c] = t;
      o[c] = uint8_t(std::clamp(t + k * bg[c], 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    o[3] = 255;
  }
}

nlohmann::json vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// describe()'s histogram: counts even in `scale` over `range` (null: none counted).
nlohmann::json histogramJson(const ValueHistogram& h) {
  if (h.counts.empty()) return nullptr;
  return {{"range", {h.lo, h.hi}}, {"scale", std::string(nameOf(h.scale.kind))},
          {"linear_width", h.scale.linear_width}, {"counts", h.counts}};
}

// The transfer.* settings a viewer edits, as the scene gives them.
nlohmann::json transferSettings(const TransferSpec& t) {
  nlohmann::json points = nlohmann::json::array();
  for (const TfPoint& p : t.points) points.push_back({p.value, p.r, p.g, p.b, p.a});
  return {{"transfer.points", points},
          {"transfer.colormap", t.colormap},
          {"transfer.range", t.range ? nlohmann::json{t.range->first, t.range->second} : nlohmann::json("auto")},
          {"transfer.scale", std::string(nameOf(t.scale))},
          {"transfer.linear_width", t.linear_width}};
}

nlohmann::json cameraJson(const Camera& c) {
  nlohmann::json j = {{"position", vec3Json(c.position)}, {"look_at", vec3Json(c.look_at)}, {"up", vec3Json(c.up)},
                      {"fov", c.fov_deg}, {"width", c.width}, {"height", c.height}};
  if (c.orthographic()) j["parallel_scale"] = c.parallel_scale;  // absent: perspective
  return j;
}

// The compositor's settings: a new compositor only when they change.
struct CompositorKey {
  Strategy strategy = Strategy::kDirect;
  int radix = 0;
  Precision precision = Precision::kFloat;
  bool overlap = true, rle = true, float_frame = false, emission = false;
  double latency_us = 0, gbps = 0;  // auto's network
  VolumeBlend blend = VolumeBlend::kComposite;  // a projection's partial images and colouring
  bool bounded = false;                         // ... bounded by particles or surfaces
  bool operator==(const CompositorKey&) const = default;
};

// What the GPU holds: the bricks of one step, for one volume renderer and one influence radius.
struct GpuKey {
  int step = -1;
  RenderMethod method = RenderMethod::kRaycast;
  double h = -1;  // the particles' ghost margin (ParticleDesc::ghostMargin)
  // Kernels are per brick: new smoothing settings need the bricks again.
  Smoothing smoothing = Smoothing::kNone;
  AnisotropicParams anisotropic;
  bool operator==(const GpuKey&) const = default;
};

}  // namespace

std::vector<std::string> frameKeys() {
  std::vector<std::string> keys;
  for (const SceneKey& k : sceneKeys())
    if (isFrameKey(k.path)) keys.push_back(k.path);
  return keys;
}

struct RenderSession::State {
  SessionOptions opts;
  // The transfer function a projection's final values are coloured with (kept current per request).
  std::shared_ptr<TransferFunction> projection_tf = std::make_shared<TransferFunction>();
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  Scene base;
  bool adaptive = false;
  SessionLayout layout;
  std::unique_ptr<StepCache> cache;
  StepData* current = nullptr;  // the step on the GPU (owned by the cache)
  long long current_id = 0;      // a new number each time `current` is set (EmptyBlocksCache::data)
  EmptyBlocksCache estimate_blocks;
  std::unique_ptr<BrickRenderer> renderer;
  GpuKey gpu;
  std::vector<int> handles;
  double particles_held = 0;
  std::unique_ptr<Compositor> compositor;
  CompositorKey compositor_key;
  double ranks_per_core = 1;  // on the busiest node (auto's cost model)
  // Rank 0's float frame of a glow scene whose caller wants no float frame, kept from frame to
  // frame: the compositor copies into its memory instead of a fresh 16 bytes a pixel.
  ImageF glow_frame;
  int frames_rendered = 0;
  // render.sample_spacing: auto: the last probe's inputs and choice (auto_spacing.h).
  struct {
    std::vector<double> key;
    SpacingChoice choice;
    bool valid = false;
  } spacing;
  MemoryBudget budget;            // what this rank may use (memory_budget.h)
  MemoryBudget gpu_budget;        // what it may put in its GPU's memory (infinite: not reported)
  std::vector<GlDeviceInfo> devices;  // rank 0: every rank's GL identity (device_report.h)
  long long particles_total = 0;  // of the first step, for the memory estimates of requests
  // In situ: the step's bricks come from the caller.
  bool external = false;
  std::optional<ExternalStep> ext;
  // In situ: the step's samples as the accuracy estimate reads them (ExternalStep::samples_of),
  // copied on the step's first estimate; ext_id numbers the steps (the block maps' cache).
  StepData ext_samples;
  bool ext_samples_read = false;
  long long ext_id = 0;
  // setAutoRange: what transfer.range: auto stands for instead of the current step's range.
  std::optional<std::pair<double, double>> auto_range;

  std::pair<double, double> dataRange() const {
    if (auto_range) return *auto_range;
    if (ext) return {ext->data_min, ext->data_max};
    return current ? std::make_pair(current->data_min, current->data_max) : std::make_pair(0.0, 1.0);
  }
  // What the accuracy estimate reads: the step on the GPU, or in situ the simulation's samples
  // (null where it cannot read them).
  const StepData* estimateSource() const {
    if (!external) return current;
    return ext && ext->has_volume && ext->samples_of ? &ext_samples : nullptr;
  }
  // Why this scene's frames get no estimate ("" where they can: frame_estimate.h).
  std::string estimateWhyNot(const Scene& sc) const {
    return estimateUnavailable(sc, adaptive, external && !estimateSource(), estimateSource());
  }
  // The estimate's samples, copied from the simulation on a step's first call in situ. Collective.
  const StepData& estimateSamples();
  long long estimateDataId() const { return external ? ext_id : current_id; }
  VisibilityOrder orderFor(const glm::dvec3& eye) const {
    if (ext && ext->order) return ext->order(eye);
    return visibilityOrder(layout.assignment, layout.planes, eye);
  }
  Scene resolve(const FrameRequest& request) const;
  // After the renderer is made on every rank: the GPU budget and every rank's identity on rank 0.
  void meetDevices();
  void bringGpuTo(const Scene& scene);
  void uploadBricks(const Scene& scene, StepData& d);
  // The frame's stages (RenderSession::render).
  void applyFrameSettings(const Scene& sc, const FrameRequest& request, const Camera& cam);
  void drawBricks(const Scene& sc, const FrameRequest& request, const Camera& cam, bool want_surface,
                  RankFrameStats& st, std::vector<SurfacePiece>& surfaces);
  nlohmann::json frameStats(const Scene& sc, const FrameRequest& request, const Camera& cam,
                            RankFrameStats& st, const CompositeStats& cs, double total_s,
                            const nlohmann::json& spacing_info);
  FrameFaults faults;  // the robustness tests' (fault_injection.h); inert unless asked for
  // This frame's visibility order and auto's footprint: the compositor holds pointers to them
  // from begin() to finish().
  VisibilityOrder frame_order;
  FrameFootprint frame_footprint;
  std::vector<double> spacingKey(const Scene& sc, std::pair<int, int> probe) const;
  // preintegrated: -1 the scene's, else pinned (0, 1).
  FrameRequest probeRequest(const FrameRequest& request, double step, std::pair<int, int> size,
                            const Scene* scene_view = nullptr, int preintegrated = -1) const;
  // render.estimate (session/frame_estimate.h): the last estimate and what it depended on.
  struct {
    std::vector<double> key;
    nlohmann::json last;
    bool valid = false;
  } estimate;
  nlohmann::json estimateAccuracy(const Scene& sc, const Camera& cam, const FrameResult& out, int frame);
};

RenderSession::RenderSession(SessionOptions options, MPI_Comm comm) : s_(std::make_unique<State>()) {
  State& S = *s_;
  S.opts = std::move(options);
  S.comm = comm;
  MPI_Comm_rank(comm, &S.rank);
  MPI_Comm_size(comm, &S.size);
  S.faults = FrameFaults::fromEnvironment(S.rank);
  // Scene and volume geometry: every rank parses the same input, so they agree.
  collectively(comm, [&] {
    S.base = parseScene(S.opts.scene, S.opts.overrides);
    resolveFileSteps(S.base);
    S.adaptive = usesAdaptiveBlocks(S.base);
    if (S.base.hasVolume()) validateVolume(S.base.volume);
    if (S.base.hasFields()) validateFields(S.base.fields);  // the layout's grid covers their grids
    checkGlowScene(S.base, false);
  });
  const Scene& scene = S.base;
  S.budget = memoryBudget(scene, comm);
  const DeviceRequest device{scene.render.device, nodeLocalRank(comm), S.rank};
  // Rank 0 reads the whole particle set first (or every rank its share): bounded before it is read.
  collectively(comm, [&] {
    if (S.rank == 0 || readsInShares(scene.particles))
      checkMemory(particleSetNeed(scene, S.size), S.budget, S.rank, "the scene's particle set");
  });
  // Particles: rank 0 loads the current step; the brick grid and the camera frame the centres of
  // every step of a series (read once here, then dropped).
  LoadedParticles first;
  Box3 centres = noBox();
  if (scene.particles.enabled()) {
    first = loadParticleSet(scene.particles, comm);
    if (first.total > 0) centres = first.bounds;
    for (int step = 0; step < int(scene.time.particle_files.size()); ++step) {
      if (step == scene.time.step) continue;
      ParticleDesc other = scene.particles;
      other.file = scene.time.particle_files[size_t(step)];
      LoadedParticles r = loadParticleSet(other, comm);
      if (r.total > 0) centres = isEmpty(centres) ? r.bounds : unite(centres, r.bounds);
    }
  }
  S.particles_total = first.total;
  // particles.smoothing: auto, from the first step's set, before anything sized by the ghost
  // margin: each rank counts over what it holds (rank 0 the whole set, or every rank its share),
  // the sums make one mean and so one choice on every rank.
  if (S.base.particles.enabled()) {
    NeighbourCount count;
    if (S.base.particles.smoothing == Smoothing::kAuto) {
      count = countNeighbours(first.set.positions, S.base.particles.influenceRadius());
      double sums[2] = {count.neighbours, count.sampled};
      MPI_Allreduce(MPI_IN_PLACE, sums, 2, MPI_DOUBLE, MPI_SUM, comm);
      count = {sums[0], sums[1]};
    }
    resolveAutoSmoothing(S.base.particles, count);
  }
  collectively(comm, [&] {
    PhaseScope phase("laying out the bricks");
    S.layout = makeLayout(scene, centres, S.rank, S.size);
    // Before the first large allocation (image targets, samples, particles): on every rank.
    checkMemory(sessionNeed(scene, S.layout, S.particles_total, S.rank, S.opts.resident), S.budget,
                S.rank, "the scene");
    std::vector<Camera> cams = scene.frameCameras(S.layout.bounds);
    const Box3 keep_out = keepOutBox(S.layout);
    for (size_t i = 0; i < cams.size(); ++i)
      checkCameraOutside(cams[i], S.layout.bounds,
                         cams.size() > 1 ? " of orbit frame " + std::to_string(i) : "", &keep_out);
    S.renderer = std::make_unique<BrickRenderer>(std::string(nameOf(scene.render.backend)), scene.camera.width, scene.camera.height, device);
  });
  S.meetDevices();
  collectively(comm, [&] {
    checkMemory(sessionNeed(scene, S.layout, S.particles_total, S.rank, S.opts.resident).onGpu(),
                S.gpu_budget, S.rank, "the scene's GPU textures and render targets");
  });
  // A batch session never changes step: its cache holds the one step, and only until upload.
  S.cache = std::make_unique<StepCache>(S.opts.resident ? scene.time.cache_mib : 0.0);
  if (scene.particles.enabled()) {
    // The first step's particle set is loaded already: hand it to the cache's loader.
    S.cache->preload(std::move(first));
  }
  S.bringGpuTo(scene);
  if (S.rank == 0 && !S.opts.quiet)
    std::fprintf(stderr, "sortlast: %d rank(s), %d^3 bricks, %dx%d%s%s, %s\n", S.size,
                 scene.bricks.per_axis, scene.camera.width, scene.camera.height,
                 scene.particles.enabled() ? (", " + std::to_string(particleCount()) + " particles").c_str() : "",
                 scene.time.steps > 1 ? (", " + std::to_string(scene.time.steps) + " time steps").c_str() : "",
                 S.renderer->description().c_str());
}

RenderSession::RenderSession(std::unique_ptr<State> state) : s_(std::move(state)) {}

std::unique_ptr<RenderSession> RenderSession::external(SessionOptions options, MPI_Comm comm) {
  auto S = std::make_unique<State>();
  S->opts = std::move(options);
  S->comm = comm;
  S->external = true;
  MPI_Comm_rank(comm, &S->rank);
  MPI_Comm_size(comm, &S->size);
  S->faults = FrameFaults::fromEnvironment(S->rank);
  const int local_rank = nodeLocalRank(comm);
  collectively(comm, [&] {
    S->base = parseScene(S->opts.scene, S->opts.overrides);
    resolveAutoSmoothing(S->base.particles, {}, true);  // in situ: round metaballs
    // The simulation's layout frames and bricks its own data only: a surface outside it would be
    // cut off or lie beyond the depth range, so surfaces are refused rather than drawn in part.
    if (!S->base.surfaces.empty())
      throw InputError("scene key 'surfaces': subdivision surfaces are not drawn in situ (the "
                       "simulation's bricks need not hold them); use `sortlast render` or `serve`");
    checkGlowScene(S->base, true);
    S->renderer = std::make_unique<BrickRenderer>(std::string(nameOf(S->base.render.backend)), S->base.camera.width, S->base.camera.height,
                                                  DeviceRequest{S->base.render.device, local_rank, S->rank});
  });
  S->meetDevices();
  S->budget = memoryBudget(S->base, comm);  // requests' image sizes are checked against it
  S->cache = std::make_unique<StepCache>(0.0);
  return std::unique_ptr<RenderSession>(new RenderSession(std::move(S)));
}

void RenderSession::setExternalStep(ExternalStep step) {
  State& S = *s_;
  S.layout = step.layout;
  S.ext = std::move(step);
  S.gpu = GpuKey{};  // upload on the next render
  S.ext_samples = StepData{};
  S.ext_samples_read = false;
  ++S.ext_id;
}

double RenderSession::estimateBytesHeld() const {
  double bytes = 0.0;
  for (const auto& b : s_->ext_samples.samples) bytes += double(b.size()) * sizeof(float);
  return bytes;
}

const StepData& RenderSession::State::estimateSamples() {
  if (!external) return *current;
  collectively(comm, [&] {
    if (ext_samples_read) return;
    ext_samples = StepData{};
    ext_samples.step = ext->step;
    ext_samples.has_volume = true;
    ext_samples.data_min = ext->data_min, ext_samples.data_max = ext->data_max;
    for (int id : layout.mine) ext_samples.samples.push_back(ext->samples_of(id));
    ext_samples_read = true;
  });
  return ext_samples;
}

RenderSession::~RenderSession() = default;

const Scene& RenderSession::baseScene() const { return s_->base; }
TransferFunction RenderSession::transferFunction() const {
  const auto [lo, hi] = s_->dataRange();
  return s_->base.transfer.build(lo, hi, s_->layout.grid.minSpacing());
}
MPI_Comm RenderSession::comm() const { return s_->comm; }
void RenderSession::setAutoRange(std::pair<double, double> range) { s_->auto_range = range; }

std::pair<double, double> RenderSession::seriesRange(const std::vector<int>& steps) {
  State& S = *s_;
  PhaseScope phase("scanning the data range of the series");
  collectively(S.comm, [&] {
    if (S.external || !S.base.hasVolume() || S.base.hasFields())
      throw std::logic_error("RenderSession::seriesRange needs the session's own one-field volume");
  });
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  std::string files;  // named in the error when every sample is missing
  for (int step : steps) {
    if (S.current && S.current->has_volume && S.current->step == step) {
      lo = std::min(lo, float(S.current->data_min));  // over every rank already; exact in float
      hi = std::max(hi, float(S.current->data_max));
      continue;
    }
    VolumeDesc desc;
    collectively(S.comm, [&] {
      FrameRequest r;
      r.overrides = {"time.step=" + std::to_string(step)};
      desc = S.resolve(r).volume;
      validateVolume(desc);
      if (desc.grid.dims != S.layout.grid.dims || desc.grid.spacing != S.layout.grid.spacing)
        throw InputError("volume file " + desc.file + " (time step " + std::to_string(step) +
                         ") has another grid than the session's first step: every step of "
                         "volume.files needs the same dims and spacing");
    });
    if (files.size() < 200) files += (files.empty() ? "" : ", ") + desc.file;
    const auto samples = loadOwnBricks(desc, S.layout.volume_bricks, S.layout.mine, S.layout.assignment, S.comm);
    for (const auto& s : samples) widenRange(s.data(), s.size(), lo, hi);  // missing samples left out
  }
  double in[2] = {lo, -double(hi)}, out[2];
  MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_MIN, S.comm);
  collectively(S.comm, [&] {  // the same answer on every rank: every rank throws or none
    if (!(out[0] <= -out[1]))
      throw InputError("every sample of the series' steps is missing (NaN): " + files);
  });
  return {out[0], -out[1]};
}
std::string RenderSession::rendererDescription() const { return s_->renderer->description(); }
const GlDeviceInfo& RenderSession::deviceInfo() const { return s_->renderer->deviceInfo(); }

void RenderSession::State::meetDevices() {
  const GlDeviceInfo& mine = renderer->deviceInfo();
  gpu_budget = gpuMemoryBudget(mine, ranksSharingDevice(mine, comm));
  ranks_per_core = ranksPerCore(comm);
  devices = gatherDeviceInfo(mine, comm);
  // The CPU pixel work's threads (common/pixel_threads.h): this rank's share of the cores in its
  // affinity mask, which the node's ranks share.
  setPixelThreads(pixelThreadsFor(nodePlace(comm).size));
}
long long RenderSession::particleCount() const { return s_->current ? s_->current->loaded.total : 0; }
int RenderSession::currentStep() const {
  if (s_->ext) return s_->ext->step;
  return s_->current ? s_->current->step : s_->base.time.step;
}
int RenderSession::orbitFrames() const { return int(s_->base.frameCameras(s_->layout.bounds).size()); }

Scene RenderSession::State::resolve(const FrameRequest& request) const {
  for (const std::string& o : request.overrides) {
    auto eq = o.find('=');
    std::string key = o.substr(0, eq);
    // volumes[i].key: one entry's key (scene/fields_scene.h; whether entry i exists is parseScene's)
    const std::optional<FieldEntryKey> field = parseFieldEntryKey(key);
    bool known = field && isFieldEntryKey(field->key);
    for (const SceneKey& k : sceneKeys()) known = known || key == k.path;
    if (eq == std::string::npos || eq == 0 || !known)
      throw InputError("unknown key '" + key + "' (the keys a request may set: " +
                       [] { std::string s; for (auto& k : frameKeys()) s += (s.empty() ? "" : ", ") + k; return s; }() + ")");
    if (!isFrameKey(key))
      throw InputError("scene key '" + key + "' fixes the data layout and cannot change in a running "
                       "session; start the session with it instead" +
                       (field ? std::string(" (a request may set an entry's transfer.* keys and visible)") : ""));
  }
  std::vector<std::string> all = opts.overrides;
  all.insert(all.end(), request.overrides.begin(), request.overrides.end());
  Scene sc = parseScene(opts.scene, all);
  // particles.smoothing: auto is the session's choice, made from its particles at start.
  if (sc.particles.smoothing == Smoothing::kAuto) sc.particles.smoothing = base.particles.smoothing;
  sc.particles.smoothing_reason = base.particles.smoothing == sc.particles.smoothing
                                      ? base.particles.smoothing_reason
                                      : "set: particles.smoothing: " + std::string(nameOf(sc.particles.smoothing));
  resolveFileSteps(sc);
  if (external) {
    if (!ext) throw std::logic_error("RenderSession: no step published yet");
    // The data is the simulation's: the scene's own volume and particle sources do not apply.
    sc.volume.file.clear();
    sc.volume.procedural = ext->has_volume ? "external" : "none";
    sc.particles.file.clear();
    sc.particles.procedural = ext->has_particles ? "external" : "none";
    sc.time.volume_files.clear();
    sc.time.particle_files.clear();
    sc.time.step = ext->step;
    sc.adaptive.tolerance = 0.0;
  }
  usesAdaptiveBlocks(sc);  // adaptive blocks need the ray caster: refuse slicing
  checkGlowScene(sc, external);
  // The layout and the renderers were made with or without glow (the bricks reach out to
  // glow.box, the images travel in float): a request may change the emitters, not their presence.
  if (sc.glow.enabled() != base.glow.enabled())
    throw InputError(base.glow.enabled()
                         ? "scene key 'glow.emitters': this session draws glow and a request cannot remove "
                           "every emitter; set glow.intensity: 0 to hide the glow"
                         : "scene key 'glow.emitters': this session was started without glow emitters, so "
                           "its bricks do not cover a glow box; start it with glow.emitters");
  sc.volume.grid = layout.grid;  // a VTK file's grid, read at start
  for (size_t f = 0; f < sc.fields.size() && f < base.fields.size(); ++f)
    sc.fields[f].volume.grid = base.fields[f].volume.grid;  // (`volumes` is no frame key: the same fields)
  if (sc.camera.width > opts.max_image_side || sc.camera.height > opts.max_image_side)
    throw InputError("image size " + std::to_string(sc.camera.width) + " x " + std::to_string(sc.camera.height) +
                     " is larger than this session allows (" + std::to_string(opts.max_image_side) +
                     " pixels per side)");
  if (sc.particles.enabled() && sc.particles.reach() > layout.particle_h * (1 + 1e-12))
    throw InputError("the particles' reach " + std::to_string(sc.particles.reach()) +
                     " (h = particles.radius / (1 - particles.threshold), or particles.influence, times "
                     "the anisotropic reach bound with particles.smoothing: anisotropic) is larger "
                     "than the session's " + std::to_string(layout.particle_h) +
                     ", which its brick grid was made for; start the session with the larger radius");
  std::vector<Camera> cams = sc.frameCameras(layout.bounds);
  if (request.orbit_frame >= int(cams.size()))
    throw InputError("orbit frame " + std::to_string(request.orbit_frame) + " of " + std::to_string(cams.size()));
  const Box3 keep_out = keepOutBox(layout);
  checkCameraOutside(cams[size_t(std::max(0, request.orbit_frame))], layout.bounds, "", &keep_out);
  // A request's image size must fit beside the data the session holds.
  const int d = sc.bricks.per_axis;
  checkMemory(external ? imageNeed(sc, sc.camera.width, sc.camera.height, rank,
                                   int(layout.mine.size()), d * d * d)
                       : sessionNeed(sc, layout, particles_total, rank, opts.resident),
              budget, rank, "the request");
  const MemoryNeed gpu_need = external ? imageNeed(sc, sc.camera.width, sc.camera.height, rank,
                                                   int(layout.mine.size()), d * d * d).onGpu()
                                       : sessionNeed(sc, layout, particles_total, rank, opts.resident).onGpu();
  checkMemory(gpu_need, gpu_budget, rank, "the request's GPU textures and render targets");
  return sc;
}

Scene RenderSession::check(const FrameRequest& request) const { return s_->resolve(request); }

Camera RenderSession::camera(const FrameRequest& request) const {
  Scene sc = s_->resolve(request);
  return sc.frameCameras(s_->layout.bounds)[size_t(std::max(0, request.orbit_frame))];
}

void RenderSession::State::uploadBricks(const Scene& scene, StepData& d) {
  const int d_axis = scene.bricks.per_axis;
  auto cellOf = [&](int id) { return glm::ivec3(id % d_axis, (id / d_axis) % d_axis, id / (d_axis * d_axis)); };
  const bool has_particles = scene.particles.enabled();
  const double margin = has_particles ? scene.particles.ghostMargin() : 0.0;
  handles.clear();
  particles_held = 0;
  renderer->reset();
  if (scene.hasVolume())
    renderer->enableVolume(scene.transfer.build(d.data_min, d.data_max, layout.grid.minSpacing()),
                           scene.transfer.table_size, scene.render.block_cells, volumeMethod(scene));
  if (scene.hasVolume() && rank == 0 && scene.render.blend == VolumeBlend::kIsosurface)
    for (const std::string& w : isovalueRangeWarnings(scene.render.isovalues, d.data_min, d.data_max))
      std::fprintf(stderr, "%s\n", w.c_str());
  if (scene.hasFields()) renderer->setFieldTransfers(fieldTransfers(scene.fields, d.fields), fieldTableSizes(scene.fields));
  if (has_particles) renderer->enableParticles(metaballSettings(scene.particles));
  renderer->enableSurfaces(scene.surfaces);
  if (scene.glow.enabled()) renderer->enableGlow();
  for (size_t i = 0; i < layout.mine.size(); ++i) {
    const int id = layout.mine[i];
    Box3 clip = brickBox(layout.planes, cellOf(id));
    std::vector<glm::vec3> near = has_particles ? particlesNear(d.particles, clip, margin) : std::vector<glm::vec3>();
    particles_held += double(near.size());
    if (scene.hasFields()) {  // several fields: the scene refuses particles and glow with them
      handles.push_back(renderer->addFieldsBrick(layout.volume_bricks[size_t(id)], layout.grid,
                                                 fieldParts(scene.fields, d.fields, i), clip));
      continue;
    }
    const Brick* vb = scene.hasVolume() ? &layout.volume_bricks[size_t(id)] : nullptr;
    handles.push_back(renderer->addBrick(vb, &layout.grid, vb && !adaptive ? &d.samples[i] : nullptr, clip,
                                         has_particles ? &near : nullptr,
                                         vb && adaptive ? &d.adaptive.bricks[i] : nullptr));
    // The brick's share of the glow box: brick boxes tile it, so the shares add up to the whole.
    if (scene.glow.enabled()) {
      const Box3 g = intersect(clip, layout.glow_box);
      if (hasVolume(g)) renderer->setBrickGlow(handles.back(), g, layout.glow_box);
    }
  }
}

void RenderSession::State::bringGpuTo(const Scene& scene) {
  const bool has_particles = scene.particles.enabled();
  GpuKey want{scene.time.step, scene.render.method, has_particles ? scene.particles.ghostMargin() : 0.0,
              scene.particles.smoothing, scene.particles.anisotropic};
  if (want == gpu) return;
  if (external) {
    collectively(comm, [&] {
      handles.clear();
      particles_held = 0;
      renderer->reset();
      auto [lo, hi] = dataRange();
      if (scene.hasVolume())
        renderer->enableVolume(scene.transfer.build(lo, hi, layout.grid.minSpacing()), scene.transfer.table_size,
                               scene.render.block_cells, volumeMethod(scene));
      if (has_particles) renderer->enableParticles(metaballSettings(scene.particles));
      renderer->enableSurfaces(scene.surfaces);
      ext->add_bricks(*renderer, scene, handles, particles_held);
      renderer->dropSpareTextures();
    });
    if (scene.hasVolume()) shareBlockRanges(*renderer, layout.grid, comm);
    gpu = want;
    return;
  }
  PhaseScope phase("loading time step " + std::to_string(scene.time.step));
  StepData& d = cache->get(scene, layout, adaptive, comm);
  current = &d;
  ++current_id;
  collectively(comm, [&] {
    if (d.dropped && want.step == gpu.step)
      throw std::logic_error("a batch session cannot change its volume renderer or h");
  });
  const double margin = has_particles ? scene.particles.ghostMargin() : 0.0;
  if (has_particles && d.scattered_h != margin) scatterStepParticles(d, layout, margin, comm);
  collectively(comm, [&] {
    PhaseScope upload("uploading the bricks to the GPU");
    uploadBricks(scene, d);
    renderer->dropSpareTextures();
  });
  // Adaptive steps choose per block from the whole block's range, which no rank holds alone.
  if (scene.hasVolume()) shareBlockRanges(*renderer, layout.grid, comm);
  gpu = want;
  // The textures hold the data now; a batch session keeps no second copy, unless the accuracy
  // estimate or auto's probes read the samples (session/frame_estimate.h; so a batch frame with
  // render.estimate: off takes the step a service frame with the same keys takes).
  const bool reads_samples = scene.render.estimate != EstimateMode::kOff || scene.render.sample_spacing_auto;
  if (!opts.resident && (!reads_samples || !estimateUnavailable(scene, adaptive, external, &d).empty()))
    d.dropHostCopies();
}

// What a probe's choice depends on (auto_spacing.h): the transfer function as built, the renderer's
// settings, the time step and the probe's size. Not the camera: the probes look from the scene's
// automatic camera, so a frame's step (and image) follows from its request alone, whatever came
// before, and an orbit probes once. The same on every rank (resolved from the same request).
std::vector<double> RenderSession::State::spacingKey(const Scene& sc, std::pair<int, int> probe) const {
  const auto [lo, hi] = dataRange();
  std::vector<double> key{double(sc.time.step), lo, hi, sc.render.ert_threshold, double(sc.transfer.preintegrated),
                          double(sc.render.shading.enabled), double(sc.render.adaptive_step), sc.render.adaptive_step_tolerance,
                          sc.adaptive.tolerance, double(!sc.render.raycast()),
                          double(sc.transfer.table_size), sc.image.background.x, sc.image.background.y, sc.image.background.z};
  const TransferFunction tf = sc.transfer.build(lo, hi, layout.grid.minSpacing());
  tf.appendKey(key);
  // Several fields: each one's transfer function as drawn (a request may change or hide one).
  if (sc.hasFields() && current)
    for (const TransferFunction& f : fieldTransfers(sc.fields, current->fields)) f.appendKey(key);
  // The blend mode, the projection and the clip region change what the probes see.
  key.insert(key.end(), {double(sc.render.blend), double(sc.render.mip_exact), double(sc.camera.projection),
                         sc.camera.parallel_scale});
  for (const ClipPlane& c : sc.clip.halfSpaces()) key.insert(key.end(), {c.normal.x, c.normal.y, c.normal.z, c.offset});
  key.insert(key.end(), {double(probe.first), double(probe.second)});
  return key;
}

// A probe frame of the scene's automatic view (the default camera), whatever this frame's camera.
// `scene_view`: the frame's own camera (the resolved request's, before any orbit) instead.
FrameRequest RenderSession::State::probeRequest(const FrameRequest& request, double step, std::pair<int, int> size,
                                                const Scene* scene_view, int preintegrated) const {
  FrameRequest p;
  p.overrides = request.overrides;
  p.overrides.push_back("render.sample_spacing=" + std::to_string(step));
  if (preintegrated >= 0) p.overrides.push_back(std::string("transfer.preintegrated=") + (preintegrated ? "true" : "false"));
  p.overrides.push_back("image.width=" + std::to_string(size.first));
  p.overrides.push_back("image.height=" + std::to_string(size.second));
  auto vec = [](const glm::dvec3& v) {
    return "[" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) + "]";
  };
  if (scene_view) {
    const Camera& c = scene_view->camera;
    p.overrides.push_back("camera.position=" + vec(c.position));
    p.overrides.push_back(scene_view->look_at_auto ? std::string("camera.look_at=auto") : "camera.look_at=" + vec(c.look_at));
    p.overrides.push_back("camera.up=" + vec(c.up));
    p.overrides.push_back("camera.fov=" + std::to_string(c.fov_deg));
    p.overrides.push_back("camera.orbit.frames=0");
  } else {
    for (const char* k : {"camera.position=auto", "camera.look_at=auto", "camera.up=[0, 1, 0]",
                          "camera.fov=35", "camera.orbit.frames=0"})
      p.overrides.push_back(k);
  }
  p.orbit_frame = -1;
  p.float_frame = true;
  p.probe = true;
  return p;
}

double RenderSession::autoSpacing(const Scene& sc, const FrameRequest& request, nlohmann::json& info) {
  State& S = *s_;
  const bool exact = S.estimateWhyNot(sc).empty();
  // Plain ints, not a structured binding: the probes' lambda below captures them (clang before 16
  // refuses to capture a binding).
  const std::pair<int, int> probe_size = exact ? estimateProbeSize(sc.camera.width, sc.camera.height)
                                               : probeSize(sc.camera.width, sc.camera.height);
  const int w = probe_size.first, h = probe_size.second;
  std::vector<double> key = S.spacingKey(sc, {w, h});
  key.insert(key.end(), {sc.render.target_db, double(sc.render.estimate_pixels)});
  if (exact && !sc.camera_auto) {  // the frame's own view is probed too
    const Camera& c = sc.camera;
    key.insert(key.end(), {c.position.x, c.position.y, c.position.z, c.look_at.x, c.look_at.y, c.look_at.z,
                           c.up.x, c.up.y, c.up.z, c.fov_deg, double(sc.look_at_auto)});
  }
  bool probed = false;
  double t0 = MPI_Wtime();
  if (!S.spacing.valid || key != S.spacing.key) {
    double chosen = 0.5;
    bool preint = sc.transfer.preintegrated;  // the same on every rank (each probe's pass is broadcast)
    if (exact) {
      // Against the exact model (session/frame_estimate.h): coarsest first, the first step whose
      // estimate meets the target at its 95 % bound is taken; the exact values of the sampled
      // pixels are integrated once, for the first probe, and serve every step.
      // Two views where the frame sets its camera: the automatic one and the frame's own (before
      // any orbit: an orbit probes once); the finer step wins. The second view starts at the
      // first's choice. (So a request that moves the camera probes again: the viewer asks for
      // `auto` on its full frames only.)
      // transfer.preintegrated `auto`: the rule's choice first; the other one's probes where it
      // could do better (otherChoiceSteps), taken where it meets the target at less cost.
      const EstimateVolume mine = estimateVolumeOf(sc, S.layout, S.estimateSamples(), S.dataRange(), &S.estimate_blocks, S.estimateDataId());
      std::vector<EstimatedStep> tried;
      EstimateSample samples[2];
      std::vector<double> exacts[2];  // rank 0's, per view: they serve every probe of that view
      bool integrated[2] = {false, false};
      // The probes of one choice over `steps` (coarsest first), from both views: the step taken
      // (the finer of the views' choices) and whether it met the target.
      auto probeSteps = [&](const std::vector<double>& steps, bool pre) {
        size_t first = 0;  // the coarsest step still to try
        bool met = true;
        for (const bool scene_view : {false, true}) {
          if (scene_view && sc.camera_auto) break;
          EstimateSample& sample = samples[scene_view];
          std::vector<double>& exact = exacts[scene_view];
          int pass = 0;
          for (size_t i = first; i < steps.size(); ++i) {
            FrameResult probe = render(S.probeRequest(request, steps[i], {w, h}, scene_view ? &sc : nullptr,
                                                      sc.transfer.preintegrated_auto ? int(pre) : -1));
            const Camera cam = probe.scene.frameCameras(S.layout.bounds)[0];
            if (!integrated[scene_view]) {
              if (S.rank == 0) {
                sample = chooseEstimatePixels(toRGBA8(probe.image_f), sc.image.background, screenRectOf(cam, S.layout.grid.worldBox()),
                                              std::min(sc.render.estimate_pixels, w * h / 2));
              }
              broadcastSample(sample, S.comm);
              exact = exactSampledPixels(sample, cam, mine, sc.image.background, pixelThreads(), S.comm);
              integrated[scene_view] = true;
            }
            if (S.rank == 0) {
              const AccuracyEstimate e = compareWithExact(sample, exact, nullptr, &probe.image_f, sc.image.background);
              tried.push_back({steps[i], e, scene_view ? "scene" : "auto", pre});
              pass = meetsTarget(e, sc.render.target_db);
            }
            MPI_Bcast(&pass, 1, MPI_INT, 0, S.comm);
            first = i;
            if (pass) break;
          }
          met = met && pass;
        }
        return std::pair<double, bool>{steps[first], met};
      };
      const bool rule = sc.transfer.preintegrated;
      auto [step, met] = probeSteps(estimatedSpacings(), rule);
      if (sc.transfer.preintegrated_auto) {
        const std::vector<double> other = otherChoiceSteps(rule, met, step);
        if (!other.empty()) {
          const auto [o_step, o_met] = probeSteps(other, !rule);
          if (o_met && (!met || sampleCost(o_step, !rule) < sampleCost(step, rule))) step = o_step, preint = !rule;
        }
      }
      chosen = step;
      if (S.rank == 0) S.spacing.choice = {chosen, {}, std::move(tried), preint};
    } else {
      // What the estimate does not model (its `why`): the steps' differences to each other.
      std::vector<ImageF> probes;
      for (double step : probeSpacings()) probes.push_back(std::move(render(S.probeRequest(request, step, {w, h})).image_f));
      if (S.rank == 0) S.spacing.choice = chooseSpacing(probes, sc.image.background);
      chosen = S.spacing.choice.spacing;
    }
    // Rank 0 decides; every rank takes its step (so all ranks agree whatever the rounding).
    MPI_Bcast(&chosen, 1, MPI_DOUBLE, 0, S.comm);
    S.spacing.choice.spacing = chosen;
    S.spacing.choice.preintegrated = preint;
    S.spacing.choice.preintegration_chosen = exact;
    S.spacing.key = std::move(key);
    S.spacing.valid = true;
    probed = true;
  }
  if (S.rank == 0) {
    const SpacingChoice& c = S.spacing.choice;
    if (!c.against_exact.empty()) {
      nlohmann::json steps = nlohmann::json::array();
      bool met = false;
      for (const EstimatedStep& e : c.against_exact) {
        nlohmann::json j = e.estimate.json();
        j["step"] = e.step;
        j["preintegrated"] = e.preintegrated;
        j["view"] = e.view;
        steps.push_back(j);
        met = met || meetsTarget(e.estimate, sc.render.target_db);
      }
      info = {{"chosen", c.spacing}, {"preintegrated", c.preintegrated}, {"by", "estimate against the exact model"}, {"steps", steps},
              {"target_db", sc.render.target_db}, {"target_over4_share", kTargetOver4Share},
              {"target_met", met}, {"probed", probed}, {"probe_s", probed ? MPI_Wtime() - t0 : 0.0}};
    } else {
      nlohmann::json est = nlohmann::json::object();
      for (auto [step, db] : c.estimated_db)
        est[std::to_string(step).substr(0, 3)] = std::isfinite(db) ? nlohmann::json(db) : nlohmann::json("inf");
      info = {{"chosen", c.spacing}, {"by", "difference of successive steps"}, {"estimated_db", est},
              {"target_db", kTargetDb}, {"probed", probed}, {"probe_s", probed ? MPI_Wtime() - t0 : 0.0}};
    }
  }
  return S.spacing.choice.spacing;
}

// Settings: what changes in place for a request (image size, transfer function, renderer
// settings, glow emitters) and the compositor (a new one only when its settings change).
void RenderSession::State::applyFrameSettings(const Scene& sc, const FrameRequest& request, const Camera& cam) {
  const auto [data_min, data_max] = dataRange();
  renderer->setImageSize(cam.width, cam.height);
  if (sc.hasVolume()) {
    renderer->setTransferFunction(sc.transfer.build(data_min, data_max, layout.grid.minSpacing()),
                                  sc.transfer.table_size, sc.transfer.preintegrated);
    renderer->setVolumeMethodSettings(volumeMethod(sc));
    renderer->setClip(sc.clip);
    if (sc.hasFields() && current) renderer->setFieldTransfers(fieldTransfers(sc.fields, current->fields), fieldTableSizes(sc.fields));
  }
  if (sc.particles.enabled()) renderer->setMetaballSettings(metaballSettings(sc.particles));
  const bool glow = sc.glow.enabled();
  // An orbit moves the emitters: this frame's (the renderer uploads them when they change).
  if (glow)
    renderer->setGlowEmitters(sc.glow.emittersAt(std::max(0, request.orbit_frame)), sc.glow.core_radius,
                              sc.glow.intensity);
  // Glow: the frame comes back in float for the tone map.
  const bool float_frame = request.float_frame || glow;
  const CompositingSection& c = sc.compositing;
  // A projection's colouring reads the current transfer function (session/projection_frame.h).
  const bool projection = sc.hasVolume() && sc.render.projection();
  if (projection)
    *projection_tf = sc.transfer.build(data_min, data_max, layout.grid.minSpacing());
  const bool bounded = projection && projectionBounded(sc);
  CompositorKey key{c.strategy, c.radix, c.precision, c.overlap, c.rle, float_frame, glow, c.latency_us, c.bandwidth_gbps,
                    projection ? sc.render.blend : VolumeBlend::kComposite, bounded};
  if (compositor && key == compositor_key) return;
  CompositeOptions copts;
  copts.precision = c.precision;
  copts.overlap = c.overlap;
  copts.rle = c.rle;
  copts.float_frame = float_frame;
  copts.emission = glow;
  if (projection) {
    copts.projection = projectionFormat(sc.render.blend, bounded);
    copts.colour_projection = projectionColouring(sc.render.blend, projection_tf, bounded);
  }
  copts.network_latency_s = c.latency_us * 1e-6;
  copts.network_bandwidth_Bps = c.bandwidth_gbps * 1e9 / 8;
  copts.ranks_per_core = ranks_per_core;
  compositor = makeCompositor(c.strategy, c.radix, copts);
  compositor_key = key;
}

// Bricks: every brick of this rank drawn, read back, encoded and handed to the compositor, which
// was told the frame first (visibility order; auto's footprint). On any rank's error the frame is
// abandoned on every rank (no send left unmatched) and JobFailed thrown.
void RenderSession::State::drawBricks(const Scene& sc, const FrameRequest& request, const Camera& cam,
                                      bool want_surface, RankFrameStats& st,
                                      std::vector<SurfacePiece>& surfaces) {
  const bool has_particles = sc.particles.enabled();
  const double h = has_particles ? sc.particles.reach() : 0.0;
  // Billboards reach sqrt(3) h beyond a particle: the depth range holds them too.
  const auto [near_plane, far_plane] = depthRange(cam, has_particles ? grow(layout.bounds, h) : layout.bounds);
  // The compositor reads the order and footprint until finish(): kept in the state.
  frame_order = orderFor(orderEye(cam, layout.bounds));  // orthographic: the eye at infinity
  const VisibilityOrder& order = frame_order;
  // auto chooses from every rank's bricks on the screen: the same numbers on every rank.
  const bool choose = sc.compositing.strategy == Strategy::kAuto;
  frame_footprint = choose ? forecastFootprint(layout, cam, size) : FrameFootprint{};
  compositor->begin(FrameSetup{&order, int(layout.mine.size()), cam.width, cam.height, comm,
                               choose ? &frame_footprint : nullptr});
  if (!request.dump_layers.empty())  // rank 0 makes the directory first
    collectively(comm, [&] { if (rank == 0) dumpOrder(request.dump_layers, cam, order); });
  const BrickStages stages{*renderer, *compositor, faults, layout.mine, handles, cam,
                           sc.sampleSpacingWorld(), near_plane, far_plane, want_surface,
                           sc.glow.enabled(), sc.compositing.rle,
                           sc.render.pipeline == Pipeline::kOverlapped, request.dump_layers,
                           sc.hasVolume() && sc.render.projection()
                               ? projectionFormat(sc.render.blend, projectionBounded(sc))
                               : WireFormat::RGBA8};
  try {
    collectively(comm, [&] {
      faults.beforeBricks();
      runBrickStages(stages, st, surfaces);
    }, [&] { compositor->progress(); });
  } catch (const JobFailed&) {
    compositor->abandon();  // so no rank is left with a send nobody receives
    throw;
  }
}

// Stats: every rank's stages and counts gathered to rank 0, as the frame's --stats object.
nlohmann::json RenderSession::State::frameStats(const Scene& sc, const FrameRequest& request, const Camera& cam,
                                                RankFrameStats& st, const CompositeStats& cs, double total_s,
                                                const nlohmann::json& spacing_info) {
  const StrategyChoice* choice = compositor->choice();
  if (choice) st.strategy_code = choice->radix ? choice->radix : 1;
  st.peak_rss_mb = peakRssMiB();
  st.rss_mb = currentRssMiB();
  st.heap_mb = heapInUseMiB();
  auto all = gatherStats(st, comm);
  if (rank != 0) return nullptr;
  nlohmann::json j = frameJson(request.orbit_frame >= 0 ? request.orbit_frame : frames_rendered, all,
                               cs.composite_s, total_s);
  j["stages"] = stagesJson(all, total_s);
  j["camera"] = cameraJson(cam);
  j["width"] = cam.width;
  j["height"] = cam.height;
  j["step"] = sc.time.step;
  j["ranks"] = size;
  if (sc.hasVolume()) j["sample_spacing"] = sc.render.sample_spacing;
  if (!spacing_info.is_null()) j["sample_spacing_auto"] = spacing_info;
  if (choice) {
    // Every rank forecast the same footprint; a rank that chose otherwise is a bug to see.
    bool same = true;
    for (const RankFrameStats& r : all) same = same && r.strategy_code == all[0].strategy_code;
    j["compositing"] = {{"strategy", "auto"},
                        {"chose", choice->label},
                        {"forecast_s", choice->forecast_s},
                        {"why", choice->why},
                        {"same_on_every_rank", same}};
  }
  return j;
}

// A frame, top-down as its stages: settings (the request resolved, the GPU and the compositor
// brought to it), bricks (draw, read-back, encode, exchange: session/brick_stages.h), composite
// (blend and gather: the compositor), stats.
FrameResult RenderSession::render(const FrameRequest& request) {
  State& S = *s_;
  PhaseScope phase("rendering a frame");
  Scene sc;
  collectively(S.comm, [&] { sc = S.resolve(request); });
  S.bringGpuTo(sc);
  // render.sample_spacing: auto: the step from probe frames of the scene's automatic view
  // (auto_spacing.h). Its probe frames count in this frame's total_s (they are what auto costs).
  nlohmann::json spacing_info;
  double probe_s = 0.0;
  if (sc.render.sample_spacing_auto && sc.hasVolume() && !request.probe && request.job_frames == 1 &&
      sc.render.estimate != EstimateMode::kOff && S.estimateWhyNot(sc).empty())
    return renderStill(request, sc);
  if (sc.render.sample_spacing_auto && sc.hasVolume() && !request.probe) {
    const double t0 = MPI_Wtime();
    sc.render.sample_spacing = autoSpacing(sc, request, spacing_info);
    // transfer.preintegrated `auto`: the probes' choice (the rule's where they did not choose).
    if (sc.transfer.preintegrated_auto && S.spacing.choice.preintegration_chosen)
      sc.transfer.preintegrated = S.spacing.choice.preintegrated;
    probe_s = MPI_Wtime() - t0;
  }
  const Camera cam = sc.frameCameras(S.layout.bounds)[size_t(std::max(0, request.orbit_frame))];
  collectively(S.comm, [&] { S.applyFrameSettings(sc, request, cam); });

  const double t_frame = MPI_Wtime();
  RankFrameStats st;
  st.particles_held = S.particles_held;
  std::vector<SurfacePiece> surfaces;
  const bool want_surface = hasSurfaceImage(sc) && request.surface;
  S.drawBricks(sc, request, cam, want_surface, st, surfaces);

  FrameResult out;
  CompositeStats cs;
  const bool glow = sc.glow.enabled();
  collectively(S.comm, [&] {
    ImageF* float_frame = request.float_frame ? &out.image_f : glow ? &S.glow_frame : nullptr;
    out.image = S.compositor->finish(cs, float_frame);
    if (glow && S.rank == 0) finishGlowFrame(sc.glow, sc.image.background, *float_frame, out.image);
  });
  if (want_surface) out.surface = gatherSurface(surfaces, cam.width, cam.height, S.comm);
  st.transfer_s = cs.transfer_s;
  st.composite_s = cs.composite_s;
  st.bytes_sent = cs.bytes_sent;
  st.wall_s = MPI_Wtime() - t_frame;
  out.stats = S.frameStats(sc, request, cam, st, cs, MPI_Wtime() - t_frame + probe_s, spacing_info);
  // The accuracy estimate, after the frame's time is taken (its own time is in it).
  if (sc.render.estimate != EstimateMode::kOff && !request.probe) {
    nlohmann::json est;
    const int frame = request.orbit_frame >= 0 ? request.orbit_frame : S.frames_rendered;
    collectively(S.comm, [&] { est = S.estimateAccuracy(sc, cam, out, frame); });
    if (S.rank == 0) out.stats["accuracy_estimate"] = std::move(est);
  }
  out.scene = std::move(sc);
  if (!request.probe) ++S.frames_rendered;
  return out;
}

// A still image's step (auto_spacing.h, stillSpacings): the frame at each step, safest first, until
// its own estimate meets the target. The sampled pixels are chosen from the first try and their
// exact values integrated once: every later try is compared with the same values. The frame
// returned is the one taken; its total_s holds every try, its accuracy_estimate is the check.
FrameResult RenderSession::renderStill(const FrameRequest& request, const Scene& sc) {
  State& S = *s_;
  const Camera cam = sc.frameCameras(S.layout.bounds)[size_t(std::max(0, request.orbit_frame))];
  // (step, pre-integrated): the steps, and where transfer.preintegrated is `auto` the other choice
  // too (stillTries); the exact values serve every try (they do not depend on either).
  const bool may_change = sc.transfer.preintegrated_auto;
  const std::vector<std::pair<double, bool>> tries = stillTries(sc.transfer.preintegrated, may_change);
  EstimateSample sample;
  std::vector<double> exact;  // rank 0's
  double estimate_s = 0.0, tries_s = 0.0;
  nlohmann::json tried = nlohmann::json::array();
  AccuracyEstimate e;
  FrameResult out;
  bool met = false, topped_up = false;
  // Where no try meets the target, the one estimated closest to it (the highest estimated PSNR)
  // is the frame, not merely the last: the last may be the other pre-integration choice.
  FrameResult best;
  AccuracyEstimate best_e;
  double best_db = -HUGE_VAL;  // rank 0's
  for (size_t i = 0; i < tries.size(); ++i) {
    FrameRequest r = request;
    r.overrides.push_back("render.sample_spacing=" + std::to_string(tries[i].first));
    if (may_change) r.overrides.push_back(std::string("transfer.preintegrated=") + (tries[i].second ? "true" : "false"));
    r.probe = true;  // no probe, no estimate, not counted: this function does those
    r.job_frames = 0;
    if (i > 0 && S.rank == 0) tries_s += out.stats["total_s"].get<double>();
    out = render(r);
    const double te = MPI_Wtime();
    // The sampled pixels of this frame (budget of them) integrated exactly; they serve every step.
    auto drawSample = [&](int budget) {
      if (S.rank == 0)
        sample = chooseEstimatePixels(out.image, sc.image.background, screenRectOf(cam, S.layout.grid.worldBox()),
                                      budget);
      broadcastSample(sample, S.comm);
      const EstimateVolume mine = estimateVolumeOf(sc, S.layout, S.estimateSamples(), S.dataRange(), &S.estimate_blocks, S.estimateDataId());
      exact = exactSampledPixels(sample, cam, mine, sc.image.background, pixelThreads(), S.comm);
    };
    if (i == 0) drawSample(sc.render.estimate_pixels);
    int pass = 0, undecided = 0;
    auto judge = [&] {
      if (S.rank == 0) {
        e = compareWithExact(sample, exact, &out.image, nullptr, sc.image.background);
        nlohmann::json j = e.json();
        j["step"] = tries[i].first;
        j["preintegrated"] = tries[i].second;
        j["view"] = "frame";
        tried.push_back(j);
        pass = meetsTarget(e, sc.render.target_db);
        undecided = !pass && shareUndecided(e, sc.render.target_db);
      }
      int both[2] = {pass, undecided};
      MPI_Bcast(both, 2, MPI_INT, 0, S.comm);
      pass = both[0], undecided = both[1];
    };
    judge();
    // Undecided (shareUndecided): a sample kStillTopUp times larger, once per frame, before a
    // finer step is drawn; kept for the steps after.
    if (undecided && !topped_up) {
      drawSample(kStillTopUp * sc.render.estimate_pixels);
      topped_up = true;
      judge();
    }
    estimate_s += MPI_Wtime() - te;
    met = pass;
    if (pass) break;
    int better = 0;
    if (S.rank == 0) better = e.psnr_db() > best_db;
    MPI_Bcast(&better, 1, MPI_INT, 0, S.comm);
    if (better) best = out, best_e = e, best_db = e.psnr_db();
  }
  double last_s = 0.0;  // the last try's own time (the others are in tries_s)
  if (S.rank == 0) last_s = out.stats["total_s"].get<double>();
  if (!met) out = std::move(best), e = best_e;
  const int frame = request.orbit_frame >= 0 ? request.orbit_frame : S.frames_rendered;
  if (S.rank == 0) {
    out.stats["total_s"] = last_s + tries_s;
    out.stats["sample_spacing_auto"] = {{"chosen", out.scene.render.sample_spacing},
                                        {"preintegrated", out.scene.transfer.preintegrated},
                                        {"by", "still image: the frame checked by its estimate"},
                                        {"steps", tried},
                                        {"target_db", sc.render.target_db},
                                        {"target_over4_share", kTargetOver4Share},
                                        {"target_met", met},
                                        {"probed", false},
                                        {"probe_s", tries_s}};
    nlohmann::json j = e.json();
    j["seconds"] = estimate_s;
    j["available"] = true;
    j["fresh"] = true;
    j["frame"] = frame;
    out.stats["accuracy_estimate"] = j;
  }
  // What a later frame with these settings would reuse (render.estimate: auto).
  std::vector<double> key = S.spacingKey(out.scene, {cam.width, cam.height});
  key.insert(key.end(), {out.scene.render.sample_spacing, double(sc.render.estimate_pixels), double(S.external ? S.ext_id : 0)});
  S.estimate = {std::move(key), S.rank == 0 ? out.stats["accuracy_estimate"] : nlohmann::json(), true};
  ++S.frames_rendered;
  return out;
}

// render.estimate: on every frame, or (auto) when what the frame's accuracy depends on, other
// than the camera, changed since the last estimate; the same decision on every rank.
nlohmann::json RenderSession::State::estimateAccuracy(const Scene& sc, const Camera& cam, const FrameResult& out,
                                                     int frame) {
  const std::string why = estimateWhyNot(sc);
  if (!why.empty()) return rank == 0 ? nlohmann::json{{"available", false}, {"why", why}} : nlohmann::json();
  std::vector<double> key = spacingKey(sc, {cam.width, cam.height});
  // In situ every step is new data (time.step stays).
  key.insert(key.end(), {sc.render.sample_spacing, double(sc.render.estimate_pixels), double(external ? ext_id : 0)});
  if (sc.render.estimate == EstimateMode::kAuto && estimate.valid && key == estimate.key) {
    nlohmann::json j = estimate.last;
    if (rank == 0) j["fresh"] = false;
    return j;
  }
  const double t0 = MPI_Wtime();
  const EstimateVolume mine = estimateVolumeOf(sc, layout, estimateSamples(), dataRange(), &estimate_blocks, estimateDataId());
  const double t_volume = MPI_Wtime() - t0;
  nlohmann::json j = estimateFrame(mine, cam, layout.grid.worldBox(), sc.image.background,
                                   rank == 0 ? &out.image : nullptr, nullptr, sc.render.estimate_pixels, comm);
  if (rank == 0) {
    j["seconds"] = MPI_Wtime() - t0;  // with the blocks' emptiness (rank 0's) below
    j["empty_blocks_s"] = t_volume;
    j["available"] = true;
    j["fresh"] = true;
    j["frame"] = frame;  // the frame it was taken on
  }
  estimate = {std::move(key), j, true};
  return j;
}

nlohmann::json RenderSession::describe(const std::vector<std::string>& base) const {
  const State& S = *s_;
  Scene with_base;
  if (!base.empty()) {
    FrameRequest r;
    r.overrides = base;
    with_base = S.resolve(r);
  }
  const Scene& b = base.empty() ? S.base : with_base;
  nlohmann::json j;
  const Box3& box = S.layout.bounds;
  j["bounds"] = {{"lo", vec3Json(box.lo)}, {"hi", vec3Json(box.hi)}};
  Camera cam = b.frameCameras(box)[0];
  j["camera"] = cameraJson(cam);
  j["image"] = {{"width", b.camera.width}, {"height", b.camera.height}};
  j["has_volume"] = b.hasVolume();
  j["has_particles"] = b.particles.enabled();
  j["particles"] = particleCount();
  j["steps"] = b.time.steps;
  j["step"] = S.current ? S.current->step : b.time.step;
  j["ranks"] = S.size;
  j["bricks_per_axis"] = b.bricks.per_axis;
  j["renderer"] = S.renderer->description();
  j["ranks_gl"] = deviceJson(S.devices);  // each rank's GL_VENDOR, GL_RENDERER, device, host
  j["data_range"] = nullptr;
  j["histogram"] = nullptr;
  if (S.ext) {
    j["has_volume"] = S.ext->has_volume;
    j["has_particles"] = S.ext->has_particles;
    if (S.ext->has_volume) j["data_range"] = {S.ext->data_min, S.ext->data_max};
  } else if (b.hasVolume() && S.current) {
    j["data_range"] = {S.current->data_min, S.current->data_max};
    if (!S.current->histogram.empty())
      j["histogram"] = histogramJson({S.current->histogram, S.current->histogram_scale, S.current->histogram_lo,
                                      S.current->histogram_hi});
  }
  j["settings"] = transferSettings(b.transfer);
  j["settings"].update(nlohmann::json{
                   {"image.legend", {{"position", std::string(nameOf(b.image.legend.position))},
                                     {"title", b.image.legend.title}, {"ticks", b.image.legend.ticks},
                                     {"units", b.image.legend.units}}},
                   {"image.width", b.camera.width},
                   {"image.height", b.camera.height},
                   {"image.background", vec3Json(b.image.background)},
                   {"render.method", std::string(nameOf(b.render.method))},
                   {"render.sample_spacing", b.render.sample_spacing_auto ? nlohmann::json("auto")
                                                                   : nlohmann::json(b.render.sample_spacing)},
                   {"render.ert_threshold", b.render.ert_threshold},
                   {"render.shading", b.render.shading.enabled},
                   {"transfer.preintegrated", b.transfer.preintegrated},  // as resolved (auto: on or off)
                   {"render.adaptive_step", b.render.adaptive_step},
                   {"render.adaptive_tolerance", b.render.adaptive_step_tolerance},
                   {"compositing.strategy", std::string(nameOf(b.compositing.strategy))},
                   {"compositing.radix", b.compositing.radix},
                   {"compositing.precision", std::string(nameOf(b.compositing.precision))},
                   {"camera.fov", b.camera.fov_deg},
                   {"time.step", b.time.step}});
  if (b.particles.enabled()) {
    j["settings"]["particles.color"] = vec3Json(b.particles.colour);
    j["settings"]["particles.threshold"] = b.particles.threshold;
    j["settings"]["particles.step"] = b.particles.step;
  }
  j["request_keys"] = frameKeys();
  // Several fields: each one's range, histogram and transfer settings, and the keys that edit it.
  if (b.hasFields() && S.current && S.current->fields.size() == b.fields.size() && !S.ext) {
    nlohmann::json fields = nlohmann::json::array();
    for (size_t f = 0; f < b.fields.size(); ++f) {
      const FieldSpec& spec = b.fields[f];
      const FieldStep& d = S.current->fields[f];
      const std::optional<FieldEntryKey> entry = parseFieldEntryKey(spec.name + ".visible");
      const std::string prefix = entry ? spec.name + "." : "";  // the first field given as volume: none
      nlohmann::json field = {{"index", f},
                              {"name", spec.name},
                              // what the viewer labels it with: its procedural field or file name
                              {"source", spec.volume.file.empty() ? spec.volume.procedural
                                                                  : std::filesystem::path(spec.volume.file).filename().string()},
                              {"data_range", {d.data_min, d.data_max}},
                              {"histogram", histogramJson(d.histogram)},
                              {"visible", spec.visible},
                              {"visible_key", entry ? nlohmann::json(prefix + "visible") : nlohmann::json(nullptr)},
                              {"transfer_prefix", prefix + "transfer."},
                              {"settings", transferSettings(spec.transfer)}};
      fields.push_back(std::move(field));
      if (entry)
        for (const SceneKey& k : sceneKeys())
          if (std::string_view(k.path).starts_with("transfer.") && isFrameKey(k.path))
            j["request_keys"].push_back(prefix + k.path);
      if (entry) j["request_keys"].push_back(prefix + "visible");
    }
    j["fields"] = std::move(fields);
  }
  j["limits"] = {{"max_width", S.opts.max_image_side}, {"max_height", S.opts.max_image_side}};
  return j;
}

nlohmann::json RenderSession::jobStats() const {
  const State& S = *s_;
  nlohmann::json top = nlohmann::json::object();
  top["ranks_gl"] = deviceJson(S.devices);  // each rank's GL_VENDOR, GL_RENDERER, device, host
  top["pixel_threads"] = pixelThreads();     // rank 0's (common/pixel_threads.h)
  // Rank 0's host memory budget and the bound that set it (memory_budget.h).
  top["memory_budget"] = {{"mib", std::isfinite(S.budget.bytes) ? nlohmann::json(S.budget.bytes / (1024.0 * 1024.0))
                                                                : nlohmann::json(nullptr)},
                          {"bound", S.budget.bound},
                          {"source", S.budget.source}};
  // particles.smoothing as drawn, and why (auto: the neighbour count that chose it).
  if (S.base.particles.enabled())
    top["smoothing"] = {{"chosen", std::string(nameOf(S.base.particles.smoothing))},
                        {"reason", S.base.particles.smoothing_reason}};
  // The volume's data range (several fields: the first's) and, with several fields, each one's.
  if (S.current && S.current->has_volume) top["data_range"] = {S.current->data_min, S.current->data_max};
  if (S.current && !S.current->fields.empty()) {
    nlohmann::json ranges = nlohmann::json::array();
    for (size_t f = 0; f < S.current->fields.size(); ++f)
      ranges.push_back({{"name", f < S.base.fields.size() ? S.base.fields[f].name : std::to_string(f)},
                        {"data_range", {S.current->fields[f].data_min, S.current->fields[f].data_max}}});
    top["data_ranges"] = std::move(ranges);
  }
  if (S.current && !S.current->read_s.empty()) {
    top["volume_read_s"] = S.current->read_s;  // per rank: its bricks, from the file
    top["peak_rss_after_read_mb"] = S.current->read_peak_rss_mb;
    if (!S.current->hdf5_transfers.empty()) top["hdf5_transfers"] = S.current->hdf5_transfers;
  }
  if (S.adaptive && S.current) {
    // Once per step, before its first frame (not in any frame's total_s); slowest rank.
    const AdaptiveRankData& a = S.current->adaptive;
    top["adaptive_tolerance_percent"] = 100.0 * S.base.adaptive.tolerance;
    top["adaptive_blocks"] = S.base.adaptive.blocks;
    top["adaptive_data_left_percent"] = 100.0 * a.data_left;
    top["adaptive_read_s"] = a.read_s;
    top["adaptive_preprocess_s"] = a.preprocess_s;
    top["adaptive_bricks_s"] = a.bricks_s;
  }
  return top;
}

}  // namespace sortlast
