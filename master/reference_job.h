#pragma once
// `sortlast reference`: renders a scene's frames with the CPU reference integrator. One process;
// it holds the whole volume (it is a measuring instrument, not the product).
#include "master/render_job.h"

namespace sortlast {

int runReferenceJob(const RenderOptions& opts, int threads);

}  // namespace sortlast
