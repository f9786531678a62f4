// sortlast::InSitu (include/sortlast/insitu.h): the simulation's data drawn by the resident
// session. publish() only remembers where the arrays are; execute() decides which renders fire,
// lays the ranks' blocks out as bricks (insitu/grid_blocks.h), sends particles where they are
// needed (insitu/particle_exchange.h), hands the session an external step and asks it for each
// image the firing renders want.
#include "sortlast/insitu.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <fstream>
#include <optional>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "common/error.h"
#include "io/particles.h"
#include "compositing/box_order.h"
#include "insitu/actions.h"
#include "insitu/cinema.h"
#include "insitu/grid_blocks.h"
#include "insitu/output_names.h"
#include "insitu/particle_exchange.h"
#include "insitu/trigger.h"
#include "render/brick_renderer.h"
#include "session/collective.h"
#include "session/render_session.h"
#include "common/build_features.h"
#include "common/listen_address.h"
// The live view (actions' `serve:`) is the service's front end: only where the build has it
// (SORTLAST_WITH_SERVICE; parseActions refuses `serve:` elsewhere).
#if SORTLAST_HAVE_SERVICE
#include "service/frame_service.h"
#include "service/serve_job.h"
#endif
#include "session/session_layout.h"

namespace sortlast {

namespace {

std::string readText(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError("actions file " + file + ": cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string vec3Yaml(const glm::dvec3& v) {
  char t[128];
  std::snprintf(t, sizeof t, "[%.17g, %.17g, %.17g]", v.x, v.y, v.z);
  return t;
}

// The actions' camera points are the simulation's; sortlast centres the grid on its origin.
std::vector<std::string> shiftCamera(const std::vector<std::string>& overrides, const glm::dvec3& shift) {
  std::vector<std::string> out;
  for (const std::string& o : overrides) {
    auto eq = o.find('=');
    std::string key = o.substr(0, eq);
    if (key == "camera.position" || key == "camera.look_at") {
      YAML::Node v = YAML::Load(o.substr(eq + 1));
      if (v.IsSequence() && v.size() == 3) {
        glm::dvec3 p(v[0].as<double>(), v[1].as<double>(), v[2].as<double>());
        out.push_back(key + "=" + vec3Yaml(p - shift));
        continue;
      }
    }
    out.push_back(o);
  }
  return out;
}

double influenceOf(const std::vector<std::string>& overrides) {
  return parseScene(SceneText{}, overrides).particles.influenceRadius();
}

// How far beyond its region a rank needs particles (ParticleDesc::ghostMargin: h, more for slices).
double ghostMarginOf(const std::vector<std::string>& overrides) {
  return parseScene(SceneText{}, overrides).particles.ghostMargin();
}

}  // namespace

struct InSitu::Impl {
  MPI_Comm comm = MPI_COMM_NULL;
  int rank = 0, size = 1;
  Actions actions;
  TriggerState triggers;
  std::unique_ptr<RenderSession> session;
  std::vector<std::unique_ptr<CinemaIndex>> cinema;  // per render; null without a database
  bool published = false;
  long long step = 0;
  double time = 0;
  Published data;
  // This step's pieces (kept until the next execute(): the session's bricks read them).
  GridLayout grid;
  std::unique_ptr<SimulationSamples> samples;
  std::vector<glm::vec3> particles;
  glm::dvec3 shift{0.0};
  double texture_bytes = 0;
  bool prepared = false;               // prepareStep ran for the published step
  bool described = false;              // the live view's GET /api/scene has a step to show
#if SORTLAST_HAVE_SERVICE
  std::unique_ptr<LiveView> live;      // rank 0, with `serve:` in the actions
#endif

  ~Impl() {
    session.reset();
    if (comm != MPI_COMM_NULL) MPI_Comm_free(&comm);
  }

  void prepareStep(const std::vector<size_t>& firing);
  void renderAction(const RenderAction& ra, size_t index, ExecuteReport& report);
  void answerLiveView();
};

// Between steps: a browser's pending requests are answered from the newest step (uploaded for it
// when no render fired on this step).
void InSitu::Impl::answerLiveView() {
#if SORTLAST_HAVE_SERVICE
  long long pending = live ? (long long)live->pending() : 0;
  MPI_Bcast(&pending, 1, MPI_LONG_LONG, 0, comm);
  // The first step is prepared even unasked, so a browser's first GET /api/scene finds a scene.
  if (pending == 0 && described) {
    if (live && prepared) live->describe(*session, shiftCamera(actions.renders[0].overrides, shift));
    return;
  }
  try {
    if (!prepared) {
      std::vector<size_t> all;
      for (size_t i = 0; i < actions.renders.size(); ++i) all.push_back(i);
      prepareStep(all);
      prepared = true;
    }
    if (live) live->describe(*session, shiftCamera(actions.renders[0].overrides, shift));
    described = true;
    LiveView::answerPending(live.get(), *session, comm, 0.5, shiftCamera(actions.renders[0].overrides, shift));
  } catch (const JobFailed& e) {
    if (rank == 0) std::fprintf(stderr, "sortlast in situ: live view: %s\n", e.message.c_str());
  }
#endif
}

void InSitu::Impl::prepareStep(const std::vector<size_t>& firing) {
  // Every render that fires may have its own radius: the ghost margin is the largest.
  double h = 0;
  double margin = 0;
  for (size_t i : firing) {
    h = std::max(h, influenceOf(actions.renders[i].overrides));
    margin = std::max(margin, ghostMarginOf(actions.renders[i].overrides));
  }
  int local_grid = data.grid.dims[0] > 0 || data.grid.dims[1] > 0 || data.grid.dims[2] > 0, has_grid = 0;
  MPI_Allreduce(&local_grid, &has_grid, 1, MPI_INT, MPI_MAX, comm);
  samples.reset();
  particles.clear();
  shift = glm::dvec3(0.0);
  double range[2] = {0, 0};
  if (has_grid) {
    collectively(comm, [&] { grid = gatherGridLayout(data.grid, comm); });
    shift = grid.shift;
    std::pair<double, double> mine;
    collectively(comm, [&] { mine = ownedRange(data.grid, grid, rank); });
    double in[2] = {mine.first, -mine.second}, out[2];
    MPI_Allreduce(in, out, 2, MPI_DOUBLE, MPI_MIN, comm);
    range[0] = out[0], range[1] = -out[1];
    samples = std::make_unique<SimulationSamples>(data.grid, grid, comm);
  }
  ParticleExtent pe;
  collectively(comm, [&] { pe = gatherParticleExtent(data.particles, shift, comm); });
  const bool has_particles = pe.total > 0;
  if (!has_grid && !has_particles)
    collectively(comm, [&] { throw InputError("nothing was published: no grid block and no particle on any rank"); });

  ExternalStep ext;
  ext.step = int(step);
  ext.has_volume = has_grid;
  ext.has_particles = has_particles;
  ext.data_min = range[0];
  ext.data_max = range[1];
  SessionLayout& L = ext.layout;
  L.particle_h = h;
  L.particle_domain = has_particles ? grow(pe.bounds, h) : noBox();
  std::vector<Box3> regions(size_t(size), noBox());
  if (has_grid) {
    // One brick per rank with cells; brick ids count those ranks (the compositors want 0 ... n-1).
    L.grid = grid.grid;
    std::vector<int> id_of(size_t(size), -1);
    for (int r = 0; r < size; ++r)
      if (grid.hasCells(r)) {
        id_of[size_t(r)] = int(L.volume_bricks.size());
        Brick b = grid.bricks[size_t(r)];
        b.id = id_of[size_t(r)];
        L.volume_bricks.push_back(b);
        L.assignment.owner.push_back(r);
        regions[size_t(r)] = b.world;
      }
    if (id_of[size_t(rank)] >= 0) L.mine = {id_of[size_t(rank)]};
    L.bounds = grid.grid.worldBox();
    // Particles are drawn inside the grid's bricks only (their clip boxes).
    ext.order = [regions, id_of](const glm::dvec3& eye) {
      VisibilityOrder o;
      o.ranks = backToFrontBoxes(regions, eye);
      for (int r : o.ranks)
        if (id_of[size_t(r)] >= 0) o.bricks.push_back(id_of[size_t(r)]);
      return o;
    };
  } else {
    // Particles alone: sortlast's own kd-split of their bounds, as for a particle file.
    Scene s = parseScene(SceneText{}, {"volume.procedural=none", "particles.procedural=layers",
                                       "particles.influence=" + std::to_string(h > 0 ? h : 1.0)});
    s.particles.influence = h;
    collectively(comm, [&] { L = makeLayout(s, pe.bounds, rank, size); });
    for (int r = 0; r < size; ++r)
      if (L.assignment.region[size_t(r)].count() > 0)
        regions[size_t(r)] = cellRangeBox(L.planes, L.assignment.region[size_t(r)]);
  }
  if (has_particles) particles = exchangeParticles(data.particles, shift, regions, margin, comm);
  const SessionLayout layout = L;
  ext.add_bricks = [this, layout, has_grid, has_particles](BrickRenderer& renderer, const Scene& scene,
                                                           std::vector<int>& handles, double& held) {
    const double rh = has_particles ? scene.particles.ghostMargin() : 0.0;
    // The simulation's ghost exchange covers h; smoothed kernels need their neighbourhoods too.
    if (has_particles && scene.particles.anisotropicOn())
      throw InputError("particles.smoothing: anisotropic is not supported in situ (the ghost "
                       "exchange reaches h only); use particles.smoothing: none");
    const int d = scene.bricks.per_axis;
    for (int id : layout.mine) {
      Box3 clip = has_grid ? layout.volume_bricks[size_t(id)].world
                           : brickBox(layout.planes, glm::ivec3(id % d, (id / d) % d, id / (d * d)));
      std::vector<glm::vec3> near = has_particles ? particlesNear(particles, clip, rh) : std::vector<glm::vec3>();
      held += double(near.size());
      if (has_grid) {
        if (!samples) throw InputError("the simulation's data of step " + std::to_string(step) + " is no longer published");
        const Brick& b = layout.volume_bricks[size_t(id)];
        handles.push_back(renderer.addBrick(b, layout.grid, *samples, clip, has_particles ? &near : nullptr));
        texture_bytes = double(b.stored.count()) * sizeof(float);
      } else {
        handles.push_back(renderer.addParticleBrick(clip, near));
      }
    }
  };
  if (has_grid)
    ext.samples_of = [this, layout](int id) {
      if (!samples) throw InputError("the simulation's data of step " + std::to_string(step) + " is no longer published");
      return samples->read(layout.volume_bricks[size_t(id)].stored);
    };
  session->setExternalStep(std::move(ext));
}

namespace {

// The frame's accuracy estimate (its --stats' accuracy_estimate) into the report (rank 0).
void takeAccuracy(const nlohmann::json& stats, ExecuteReport& report) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  report.estimated_psnr_db = report.psnr_db_lo = report.psnr_db_hi = report.over4_share = report.over4_share_hi = nan;
  report.accuracy_why.clear();
  const auto e = stats.find("accuracy_estimate");
  if (e == stats.end() || !e->is_object()) {
    report.accuracy_why = "render.estimate: off";
    return;
  }
  if (!e->value("available", false)) {
    report.accuracy_why = e->value("why", std::string("no estimate"));
    return;
  }
  auto db = [](const nlohmann::json& v) { return v.is_string() ? HUGE_VAL : v.get<double>(); };  // "inf"
  report.estimated_psnr_db = db(e->at("estimated_psnr_db"));
  report.psnr_db_lo = db(e->at("psnr_db_95")[0]);
  report.psnr_db_hi = db(e->at("psnr_db_95")[1]);
  report.over4_share = e->at("over4_share").get<double>();
  report.over4_share_hi = e->at("over4_share_95")[1].get<double>();
}

}  // namespace

void InSitu::Impl::renderAction(const RenderAction& ra, size_t index, ExecuteReport& report) {
  FrameRequest base;
  base.overrides = shiftCamera(ra.overrides, shift);
  // The render's scene is checked as a request's is: one it refuses (glow emitters, say) is this
  // step's error on every rank, reported or aborting as on_error says, not an exception that ends
  // the simulation.
  Scene sc;
  collectively(comm, [&] { sc = session->check(base); });
  // The images of this render: the output pattern's (one, or an orbit's), and the Cinema sweep's.
  std::vector<std::pair<FrameRequest, std::string>> views;
  if (!ra.output.empty()) {
    const int frames = std::max(1, sc.orbit.frames);
    for (int f = 0; f < frames; ++f) {
      FrameRequest r = base;
      r.orbit_frame = sc.orbit.frames > 0 ? f : -1;
      views.push_back({r, outputName(ra.output, step, f, frames)});
    }
  }
  std::vector<std::string> cinema_images;
  if (CinemaIndex* db = cinema[index].get()) {
    Camera cam = session->camera(base);
    for (double phi : db->spec().phi)
      for (double theta : db->spec().theta) {
        FrameRequest r = base;
        glm::dvec3 p = cinemaPosition(cam.look_at, cam.position, cam.up, phi, theta);
        r.overrides.push_back("camera.position=" + vec3Yaml(p));
        r.overrides.push_back("camera.look_at=" + vec3Yaml(cam.look_at));
        r.overrides.push_back("camera.orbit.frames=0");
        std::string rel = db->imagePath(step, phi, theta);
        cinema_images.push_back(rel);
        views.push_back({r, db->spec().directory + "/" + rel});
      }
  }
  for (auto& [request, file] : views) {
    FrameResult result = session->render(request);
    collectively(comm, [&] {
      if (rank != 0) return;
      createParentDirectories(file);
      writeImage(file, result.image, result.scene.image.background);
    });
    if (rank == 0) {
      report.images.push_back(file);
      takeAccuracy(result.stats, report);
    }
  }
  if (CinemaIndex* db = cinema[index].get())
    collectively(comm, [&] {
      db->addStep(step, time, cinema_images);
      if (rank == 0) db->write();
    });
}

InSitu::InSitu(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
InSitu::~InSitu() = default;
InSitu::InSitu(InSitu&&) noexcept = default;
InSitu& InSitu::operator=(InSitu&&) noexcept = default;

std::unique_ptr<InSitu::Impl> InSitu::open(MPI_Comm user_comm, const std::string& text,
                                           const std::string& source, bool from_file) {
  auto impl = std::make_unique<InSitu::Impl>();
  // Our own communicator: our messages never match the simulation's.
  MPI_Comm_dup(user_comm, &impl->comm);
  MPI_Comm_rank(impl->comm, &impl->rank);
  MPI_Comm_size(impl->comm, &impl->size);
  try {
    collectively(impl->comm, [&] {
      impl->actions = parseActions(from_file ? readText(source) : text, source);
      for (const RenderAction& ra : impl->actions.renders)
        impl->cinema.push_back(ra.cinema ? std::make_unique<CinemaIndex>(*ra.cinema) : nullptr);
    });
    SessionOptions so;
    so.quiet = true;
    so.overrides = impl->actions.session_overrides;
    impl->session = RenderSession::external(so, impl->comm);
#if SORTLAST_HAVE_SERVICE
    if (!impl->actions.serve.empty())
      collectively(impl->comm, [&] {
        if (impl->rank != 0) return;
        auto [address, port] = parseListen(impl->actions.serve);
        ServerOptions server;
        server.address = address;
        server.port = port;
        server.token = impl->actions.serve_token;
        server.static_dir = findViewerDir("");
        impl->live = std::make_unique<LiveView>(server);
        std::fprintf(stderr, "sortlast in situ: live view at http://%s:%d/ (answered between steps)\n",
                     address.c_str(), impl->live->port());
      });
#endif
  } catch (const JobFailed& e) {
    throw InSituError("sortlast in situ: " + e.message);
  }
  return impl;
}

InSitu::InSitu(MPI_Comm comm, const std::string& actions_file)
    : impl_(open(comm, "", actions_file, true)) {}

InSitu InSitu::fromText(MPI_Comm comm, const std::string& actions_yaml) {
  return InSitu(open(comm, actions_yaml, "actions", false));
}

void InSitu::publish(long long step, double time, const Published& data) {
  impl_->step = step;
  impl_->time = time;
  impl_->data = data;
  impl_->published = true;
}

ExecuteReport InSitu::execute() {
  Impl& I = *impl_;
  ExecuteReport report;
  const double t0 = MPI_Wtime();
  if (!I.published) throw InSituError("sortlast in situ: execute() before publish()");
  I.published = false;
  I.prepared = false;
  try {
    // Which renders fire: decided by every rank alone, without a message, since every rank
    // publishes the same step and quantities (docs/insitu.md); a step that renders nothing costs
    // no communication. A missing quantity is then missing on every rank: each throws the same.
    std::vector<size_t> firing;
    try {
      for (size_t i = 0; i < I.actions.renders.size(); ++i)
        if (I.triggers.fires(I.actions.renders[i], I.step, I.data.quantities)) firing.push_back(i);
    } catch (const InputError& e) {
      throw JobFailed{e.what()};
    }
    if (!firing.empty()) {
      I.prepareStep(firing);
      I.prepared = true;
      for (size_t i : firing) I.renderAction(I.actions.renders[i], i, report);
      report.rendered = true;
    }
  } catch (const JobFailed& e) {
    report.error = "step " + std::to_string(I.step) + ": " + e.message;
    report.images.clear();
    takeAccuracy(nlohmann::json{{"accuracy_estimate", {{"available", false}, {"why", "the step's images were skipped"}}}}, report);
    if (I.actions.abort_on_error) throw InSituError("sortlast in situ: " + report.error);
    if (I.rank == 0) std::fprintf(stderr, "sortlast in situ: %s; its images are skipped\n", report.error.c_str());
  }
  if (!I.actions.serve.empty()) I.answerLiveView();
  report.seconds = MPI_Wtime() - t0;
  double bytes = (I.samples ? I.samples->bytesHeld() : 0.0) + double(I.particles.size()) * sizeof(glm::vec3) +
                 I.session->estimateBytesHeld();
  report.memory_added_mib = bytes / (1024.0 * 1024.0);
  report.texture_mib = I.texture_bytes / (1024.0 * 1024.0);
  const GlDeviceInfo& gl = I.session->deviceInfo();
  report.gl_vendor = gl.vendor;
  report.gl_renderer = gl.renderer;
  report.host = gl.host;
  report.device = gl.device;
  return report;
}

}  // namespace sortlast
