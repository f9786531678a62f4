#include "render/gl/gl_context.h"

#include <unistd.h>

#include <cstdio>
#include <stdexcept>

#include "common/build_features.h"
#include "common/missing_feature.h"

namespace sortlast {

namespace {

// GL_NVX_gpu_memory_info and GL_ATI_meminfo tokens (not in glcorearb.h).
constexpr GLenum kGpuMemoryTotalNvx = 0x9048;      // GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX, KiB
constexpr GLenum kGpuMemoryAvailableNvx = 0x9049;  // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX, KiB
constexpr GLenum kTextureFreeMemoryAti = 0x87FC;   // TEXTURE_FREE_MEMORY_ATI: 4 values, [0] = free KiB

std::string hostName() {
  char b[256] = {};
  if (gethostname(b, sizeof b - 1) != 0) return "?";
  return b;
}

}  // namespace

int autoDevice(int local_rank, int hardware_devices) {
  if (hardware_devices <= 0) return -1;
  return local_rank % hardware_devices;
}

void GlContext::finishSetup() {
  auto str = [&](GLenum e) {
    const GLubyte* s = gl_.GetString(e);
    return s ? std::string(reinterpret_cast<const char*>(s)) : std::string("?");
  };
  info_.vendor = str(GL_VENDOR);
  info_.renderer = str(GL_RENDERER);
  info_.version = str(GL_VERSION);
  info_.host = hostName();
  GLint n = 0;
  gl_.GetIntegerv(GL_NUM_EXTENSIONS, &n);
  bool nvx = false, ati = false;
  for (GLint i = 0; i < n; ++i) {
    const GLubyte* e = gl_.GetStringi(GL_EXTENSIONS, GLuint(i));
    if (!e) continue;
    const std::string name(reinterpret_cast<const char*>(e));
    nvx = nvx || name == "GL_NVX_gpu_memory_info";
    ati = ati || name == "GL_ATI_meminfo";
  }
  if (nvx) {
    GLint total = 0, avail = 0;
    gl_.GetIntegerv(kGpuMemoryTotalNvx, &total);
    gl_.GetIntegerv(kGpuMemoryAvailableNvx, &avail);
    info_.gpu_total_mib = total / 1024.0;
    info_.gpu_free_mib = avail / 1024.0;
    info_.gpu_memory_source = "GL_NVX_gpu_memory_info";
  } else if (ati) {
    GLint free[4] = {};
    gl_.GetIntegerv(kTextureFreeMemoryAti, free);
    info_.gpu_free_mib = free[0] / 1024.0;  // ATI reports no total
    info_.gpu_memory_source = "GL_ATI_meminfo";
  }
  gl_.GetError();  // an extension that lied about a token leaves an error: not ours to report
  std::string where = info_.backend;
  if (info_.device >= 0) where += " " + std::to_string(info_.device) + " of " + std::to_string(info_.devices);
  description_ = where + ": " + info_.renderer + ", OpenGL " + info_.version;
}

std::unique_ptr<GlContext> createGlContext(const std::string& backend, const DeviceRequest& request) {
  // Each backend is compiled only where the build has it (SORTLAST_WITH_OSMESA, _EGL). Every rank
  // opens its context, so every rank refuses the other here, by the option's name.
  if (backend == "osmesa") {
    if constexpr (build::kOsmesa) return createOsMesaContext();
    refuseMissingFeature(Feature::kOsmesa, "render.backend osmesa");
  }
  if (backend == "egl") {
    if constexpr (build::kEgl) return createEglContext(request);
    refuseMissingFeature(Feature::kEgl, "render.backend egl");
  }
  throw std::runtime_error("unknown render.backend '" + backend + "'");
}

}  // namespace sortlast
