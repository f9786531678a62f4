#include "master/reference_job.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "common/error.h"
#include "common/scene.h"
#include "master/progress.h"
#include "master/reference.h"

namespace sortlast {

int runReferenceJob(const RenderOptions& opts, int threads) {
  try {
    Scene scene = loadScene(opts.scene, opts.overrides);
    validateVolume(scene.volume);
    WholeVolume vol{scene.volume.grid, {}};
    IndexBox all{{0, 0, 0}, scene.volume.grid.dims - 1};
    vol.samples = scene.volume.isVtk() ? readWholeVtk(scene.volume) : readSamples(scene.volume, all);
    auto [lo, hi] = std::minmax_element(vol.samples.begin(), vol.samples.end());
    TransferFunction tf = scene.transfer.build(*lo, *hi, scene.volume.grid.minSpacing());
    auto cams = scene.frameCameras();
    if (threads <= 0) threads = int(std::max(1u, std::thread::hardware_concurrency()));
    Progress progress(int(cams.size()), opts.quiet);
    for (int f = 0; f < int(cams.size()); ++f) {
      if (scene.volume.grid.worldBox().contains(cams[f].position))
        throw InputError("camera.position is inside the volume; move the camera outside it");
      ImageF img = renderReference(vol, tf, cams[f], scene.reference_step * scene.volume.grid.minSpacing(), threads);
      writeImage(frameFileName(opts.output, f, int(cams.size())), img, scene.background);
      progress.frameDone(f);
    }
  } catch (const InputError& e) {
    std::fprintf(stderr, "sortlast: error: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace sortlast
