// sortlast: a distributed sort-last volume renderer. Parses the command line and hands over to
// the job for the subcommand.
#include <mpi.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/scene.h"
#include "master/compare.h"
#include "master/reference_job.h"
#include "master/render_job.h"

using namespace sortlast;

namespace {

void addSceneOptions(CLI::App* cmd, RenderOptions& o) {
  cmd->add_option("scene", o.scene, "Scene file (YAML); omitted: the built-in default scene");
  cmd->add_option("-o,--output", o.output, "Output image (.png or .exr); a series gets _0000 ...");
  cmd->add_option("--set", o.overrides, "Override a scene key: key.path=value (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("-q,--quiet", o.quiet, "No progress lines");
}

int runCompare(const std::string& a, const std::string& b, int max_diff, long long allow_pixels,
               double min_psnr, const std::string& diff_out) {
  try {
    ImageRGBA8 ia = readImageRGBA8(a), ib = readImageRGBA8(b);
    ImageDifference d = compareImages(ia, ib);
    std::printf("psnr_db=%.3f max_diff=%d worst_pixel=(%d,%d) mean_abs=%.4f\n", d.psnr_db,
                d.max_diff, d.worst_x, d.worst_y, d.mean_abs);
    if (!diff_out.empty()) writeImage(diff_out, differenceImage(ia, ib, 16), glm::dvec3(0.0));
    bool ok = true;
    if (max_diff >= 0) {
      long long over = countPixelsOver(ia, ib, max_diff);
      std::printf("pixels_over_%d=%lld\n", max_diff, over);
      if (over > allow_pixels) {
        std::printf("FAIL: %lld pixels differ by more than %d (allowed: %lld); worst %d at pixel (%d,%d)\n",
                    over, max_diff, allow_pixels, d.max_diff, d.worst_x, d.worst_y);
        ok = false;
      }
    }
    if (!std::isnan(min_psnr) && d.psnr_db < min_psnr) {
      std::printf("FAIL: psnr %.3f dB < required %.3f dB\n", d.psnr_db, min_psnr);
      ok = false;
    }
    return ok ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 2;
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"sortlast: distributed sort-last volume rendering"};
  app.require_subcommand(1);

  RenderOptions render_opts;
  auto* render = app.add_subcommand("render", "Render a scene (run under mpirun -np N)");
  addSceneOptions(render, render_opts);
  render->add_option("--stats", render_opts.stats, "Write per-frame timings and byte counts as JSON");

  RenderOptions ref_opts;
  ref_opts.output = "reference.png";
  int threads = 0;
  auto* reference = app.add_subcommand("reference", "Render a scene with the CPU reference integrator");
  addSceneOptions(reference, ref_opts);
  reference->add_option("--threads", threads, "Worker threads (default: all cores)");

  std::string img_a, img_b, diff_out;
  int max_diff = -1;
  long long allow_pixels = 0;
  double min_psnr = std::nan("");
  auto* compare = app.add_subcommand("compare", "Compare two images (PSNR, largest difference)");
  compare->add_option("a", img_a)->required();
  compare->add_option("b", img_b)->required();
  compare->add_option("--max-diff", max_diff, "Fail if any channel differs by more (1/255 units)");
  compare->add_option("--allow-pixels", allow_pixels, "How many pixels may exceed --max-diff (default 0)");
  compare->add_option("--min-psnr", min_psnr, "Fail if PSNR is lower (dB)");
  compare->add_option("--diff", diff_out, "Write a difference image (x16)");

  auto* keys = app.add_subcommand("keys", "Print every scene key with its default (Markdown)");

  CLI11_PARSE(app, argc, argv);

  if (*keys) {
    std::fputs(sceneKeysMarkdown().c_str(), stdout);
    return 0;
  }
  if (*compare) return runCompare(img_a, img_b, max_diff, allow_pixels, min_psnr, diff_out);
  if (*reference) return runReferenceJob(ref_opts, threads);

  MPI_Init(&argc, &argv);
  int code = runRenderJob(render_opts, MPI_COMM_WORLD);
  MPI_Finalize();
  return code;
}
