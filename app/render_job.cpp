// `sortlast render`: the simplest client of the resident session. Every rank opens the session on
// the scene, then asks it for each camera of the orbit in turn (or, with --steps, for each step
// of a time series, in one colour range found before the first frame); rank 0 writes the frames (on its
// writer thread, io/frame_writer.h, while the next frame renders), the stats and (--psnr) their
// distance from the CPU reference.
#include "app/render_job.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "app/frame_output.h"
#include "io/frame_writer.h"
#include "io/movie_writer.h"
#include "scene/scene.h"
#include "scene/surface_output.h"
#include "session/collective.h"
#include "app/compare.h"
#include "reference/frame_reference.h"
#include "app/progress.h"
#include "session/render_session.h"

namespace sortlast {

std::vector<int> parseSteps(const std::string& spec, int steps) {
  auto bad = [&](const std::string& why) -> InputError {
    return InputError("--steps " + spec + ": " + why);
  };
  std::vector<long long> v;
  if (spec == "all") {
    v = {0, steps > 0 ? steps - 1 : 0, 1};
  } else {
    size_t at = 0;
    while (at <= spec.size()) {
      const size_t colon = std::min(spec.find(':', at), spec.size());
      const std::string part = spec.substr(at, colon - at);
      size_t used = 0;
      long long n = -1;
      try {
        n = std::stoll(part, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (part.empty() || used != part.size())
        throw bad("expected all, A:B or A:B:S with whole numbers ('" + part + "' is not one)");
      v.push_back(n);
      at = colon + 1;
    }
    if (v.size() < 2 || v.size() > 3) throw bad("expected all, A:B or A:B:S");
    if (v.size() == 2) v.push_back(1);
  }
  if (v[0] < 0) throw bad("the first step is below 0");
  if (v[1] < v[0]) throw bad("the last step is before the first");
  if (v[2] < 1) throw bad("the stride must be >= 1");
  if (steps >= 0 && v[1] >= steps)
    throw bad("step " + std::to_string(v[1]) + " is out of range: the scene has " + std::to_string(steps) +
              " time step(s), 0 ... " + std::to_string(steps - 1));
  std::vector<int> out;
  for (long long k = v[0]; k <= v[1]; k += v[2]) out.push_back(int(k));
  return out;
}

std::vector<Camera> firstFrames(std::vector<Camera> cameras, int max_frames) {
  if (max_frames > 0 && cameras.size() > size_t(max_frames)) cameras.resize(size_t(max_frames));
  return cameras;
}

namespace {

// The frame's distance from the CPU reference, as `sortlast compare` reports it on the two images
// written over the background: PSNR over RGB and the largest channel difference.
void addAccuracy(nlohmann::json& j, const ImageRGBA8& frame, const FrameReference& reference,
                 const Camera& cam, const glm::dvec3& background) {
  double t0 = MPI_Wtime();
  const ImageRGBA8 a = opaqueOver(toFloat(frame), background), b = opaqueOver(reference.render(cam), background);
  ImageDifference d = compareImages(a, b);
  // IceT's image-test rule: the share of pixels with a channel more than 4/255 off.
  j["over4_share"] = double(countPixelsOver(a, b, 4)) / (double(a.width) * a.height);
  // JSON has no infinity: an image identical to the reference reports null.
  j["psnr_db"] = std::isfinite(d.psnr_db) ? nlohmann::json(d.psnr_db) : nlohmann::json();
  j["max_diff"] = d.max_diff;
  j["reference_s"] = MPI_Wtime() - t0;
}

Camera cameraOf(const nlohmann::json& stats, const Camera& fallback) {
  Camera c = fallback;
  auto v = [](const nlohmann::json& a) { return glm::dvec3(a[0].get<double>(), a[1].get<double>(), a[2].get<double>()); };
  const auto& j = stats.at("camera");
  c.position = v(j.at("position"));
  c.look_at = v(j.at("look_at"));
  c.up = v(j.at("up"));
  c.fov_deg = j.at("fov").get<double>();
  if (j.contains("parallel_scale")) {
    c.projection = Projection::kOrthographic;
    c.parallel_scale = j.at("parallel_scale").get<double>();
  } else {
    c.projection = Projection::kPerspective;
  }
  c.width = j.at("width").get<int>();
  c.height = j.at("height").get<int>();
  return c;
}

}  // namespace

int runRenderJob(const RenderOptions& opts, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  try {
    SessionOptions so;
    so.overrides = opts.overrides;
    so.quiet = opts.quiet;
    collectively(comm, [&] {
      if (!isMoviePath(opts.output)) checkOutputFormat(opts.output);
      so.scene = readSceneText(opts.scene);
      if (!opts.steps.empty()) {
        if (opts.psnr)
          throw InputError("--psnr and --steps cannot go together: the CPU reference holds one time step");
        // The session opens on the series' first step, so it is not read twice.
        const std::vector<int> syntax = parseSteps(opts.steps, -1);
        so.overrides.push_back("time.step=" + std::to_string(syntax.front()));
      }
    });
    RenderSession session(std::move(so), comm);
    const Scene& scene = session.baseScene();
    // A series (--steps): frame i is step steps[i] seen by orbit camera i (mod the orbit's
    // frames, so a single view stays put and an orbit advances one camera per step). Otherwise
    // the orbit's frames of time.step.
    std::vector<int> steps;
    collectively(comm, [&] {
      if (!opts.steps.empty()) steps = parseSteps(opts.steps, scene.time.steps);
    });
    const int orbit = session.orbitFrames();
    const int frames = std::min(steps.empty() ? orbit : int(steps.size()),
                                opts.max_frames > 0 ? opts.max_frames : 1 << 30);
    if (!steps.empty()) steps.resize(size_t(frames));
    // One colour range for the whole series, found once before the first frame, so a value has
    // the same colour in every frame whichever steps the series holds (a given range is kept).
    nlohmann::json series_stats;
    if (steps.size() > 1) {
      series_stats = {{"steps", steps}, {"range", nullptr}, {"range_s", 0.0}};
      if (scene.hasVolume() && !scene.transfer.range) {
        const double t0 = MPI_Wtime();
        const auto range = session.seriesRange(steps);
        session.setAutoRange(range);
        series_stats["range"] = {range.first, range.second};
        series_stats["range_s"] = MPI_Wtime() - t0;
        if (rank == 0 && !opts.quiet)
          std::fprintf(stderr, "sortlast: %zu steps, one colour range for all: [%g, %g] (%.3f s to scan)\n",
                       steps.size(), range.first, range.second, series_stats["range_s"].get<double>());
      } else if (scene.hasVolume()) {
        series_stats["range"] = {scene.transfer.range->first, scene.transfer.range->second};
      }
    }
    // An EXR output holds the frame before rounding; PNG is 8-bit.
    const bool float_output = std::filesystem::path(opts.output).extension() == ".exr";
    // --psnr: rank 0 holds the whole scene for the CPU reference of every frame.
    std::unique_ptr<FrameReference> reference;
    if (opts.psnr)
      collectively(comm, [&] { if (rank == 0) reference = std::make_unique<FrameReference>(scene, 0); });
    // --stats: each frame's object goes to the file as the frame ends, so rank 0 holds none of
    // them (a long orbit's stats would otherwise grow its memory by ~3 KiB a frame, which the soak
    // test would read as a leak). Written to FILE.partial, renamed when the job ends well.
    std::ofstream stats_out;
    const std::string stats_partial = opts.stats + ".partial";
    bool first_frame_stats = true;
    if (rank == 0 && !opts.stats.empty()) {
      stats_out.open(stats_partial);
      stats_out << "{\"frames\": [\n";
    }
    // Frame N is encoded and written while frame N+1 renders. Two frames may wait (the writer
    // holds a third): at 1024² that is 12 MiB of pixels at most, and one frame of slack for a
    // write that takes longer once (a slow disk) before the render waits for it.
    FrameWriter writer(opts.sync_output ? 0 : 2);
    // Image files or a movie (app/frame_output.h), with the legend drawn in on the writer thread.
    std::unique_ptr<FrameOutput> output;
    collectively(comm, [&] {
      if (rank == 0) output = std::make_unique<FrameOutput>(opts.output, scene, frames, writer);
    });
    Progress progress(frames, opts.quiet);
    for (int f = 0; f < frames; ++f) {
      FrameRequest request;
      request.orbit_frame = steps.empty() ? f : f % orbit;
      if (!steps.empty()) request.overrides.push_back("time.step=" + std::to_string(steps[size_t(f)]));
      request.float_frame = float_output;
      request.job_frames = frames;  // one: a still image, for which auto does not probe
      request.surface = !opts.surface_out.empty();
      if (f == 0) request.dump_layers = opts.dump_layers;
      FrameResult result = session.render(request);
      // After the frame's time is taken: the reference is a measuring instrument. Before the
      // hand-off, which takes the frame's pixels.
      if (rank == 0 && reference)
        addAccuracy(result.stats, result.image, *reference, cameraOf(result.stats, scene.camera),
                    scene.image.background);
      // Rank 0 hands the frame to its writer; a write that failed before (this frame's
      // predecessors) is thrown here and so stops every rank.
      collectively(comm, [&] {
        if (rank != 0) return;
        if (float_output)
          output->push(f, std::move(result.image_f));
        else
          output->push(f, std::move(result.image), scene.hasVolume() ? session.transferFunction() : TransferFunction());
        if (request.surface && hasSurfaceImage(scene)) {
          const std::string surface_file = frameFileName(opts.surface_out, f, frames);
          writer.push(surface_file, [surface_file, surface = std::move(result.surface)] {
            writeSurfaceImage(surface_file, surface);
          });
        }
      });
      if (rank == 0) {
        if (stats_out.is_open()) {
          stats_out << (first_frame_stats ? "" : ",\n") << result.stats.dump(1);
          first_frame_stats = false;
        }
        progress.frameDone(f);
      }
    }
    // The last frames are written before the job ends well, and before the stats, which say so.
    collectively(comm, [&] {
      if (rank == 0) {
        output->close();
        writer.finish();
      }
    });
    if (stats_out.is_open()) {
      nlohmann::json top{{"ranks", size},
                         {"bricks_per_axis", scene.bricks.per_axis},
                         {"width", scene.camera.width},
                         {"height", scene.camera.height},
                         {"renderer", session.rendererDescription()},
                         {"volume_method", scene.hasVolume() ? std::string(nameOf(scene.render.method)) : ""},
                         {"compositing", std::string(nameOf(scene.compositing.strategy))},
                         {"particles", session.particleCount()}};
      top.update(session.jobStats());
      // A series: its steps, the one colour range of its frames ([lo, hi]; null without a volume)
      // and the seconds spent scanning the steps for it (0 for a given transfer.range).
      if (!series_stats.is_null()) {
        top["series_steps"] = series_stats["steps"];
        top["series_range"] = series_stats["range"];
        top["series_range_s"] = series_stats["range_s"];
      }
      const FrameWriter::Stats written = writer.stats();
      top["output"] = {{"mode", opts.sync_output ? "sync" : "writer_thread"},
                       {"files", written.files},
                       {"write_s", written.write_s},
                       {"wait_s", written.wait_s}};
      // The rest of the top-level object after the frames: top's members without its '{'.
      stats_out << "\n],\n" << top.dump(1).substr(1) << "\n";
      stats_out.close();
      std::error_code ec;
      if (stats_out) std::filesystem::rename(stats_partial, opts.stats, ec);
      if (!stats_out || ec)
        std::fprintf(stderr, "sortlast: warning: could not write stats to %s\n", opts.stats.c_str());
    }
  } catch (const JobFailed&) {
    return 1;
  }
  return 0;
}

}  // namespace sortlast
