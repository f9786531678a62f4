#pragma once
// An offscreen OpenGL 4.5 core context, made current on creation, with its entry points loaded.
// Backends: OSMesa (software) and EGL (device platform on a GPU, else surfaceless). Each backend
// lives in its own file and is the only code that includes its headers.
#include <memory>
#include <string>

#include "render/gl/gl_api.h"

namespace sortlast {

// Which EGL device a rank asks for (render.device). Devices are counted among the hardware EGL
// devices only: Mesa's software device is skipped, so on a node with 4 GPUs they are 0-3.
struct DeviceRequest {
  static constexpr int kAuto = -1;
  int device = kAuto;  // kAuto: (local_rank) mod (hardware devices); else that device
  int local_rank = 0;  // this rank's index among its node's ranks (MPI_COMM_TYPE_SHARED)
  int rank = 0;        // for messages
};

// What a context runs on: for --stats, /api/scene, the in-situ report and the GPU memory check.
struct GlDeviceInfo {
  std::string backend;  // "osmesa", "egl device" or "egl surfaceless"
  int device = -1;      // index among the hardware EGL devices; -1: none (software rendering)
  int devices = 0;      // hardware EGL devices this process sees
  std::string vendor, renderer, version;  // GL_VENDOR, GL_RENDERER, GL_VERSION
  std::string host;                       // gethostname()
  // What the driver reports (GL_NVX_gpu_memory_info, GL_ATI_meminfo); -1: it does not say.
  double gpu_total_mib = -1, gpu_free_mib = -1;
  std::string gpu_memory_source;  // the extension that said, empty when none did
};

class GlContext {
 public:
  virtual ~GlContext() = default;
  const GlApi& gl() const { return gl_; }
  // "osmesa: llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 ..." — for logs and stats.
  std::string description() const { return description_; }
  const GlDeviceInfo& info() const { return info_; }

 protected:
  // Fills info_ (GL strings, host, GPU memory) and description_; the backend has set
  // info_.backend, .device and .devices.
  void finishSetup();
  GlApi gl_;
  std::string description_;
  GlDeviceInfo info_;
};

// backend: "osmesa" or "egl". Throws std::runtime_error with the backend's reason on failure
// (an EGL device that cannot be opened is named, with the rank and host).
std::unique_ptr<GlContext> createGlContext(const std::string& backend, const DeviceRequest& request = {});
std::unique_ptr<GlContext> createOsMesaContext();
std::unique_ptr<GlContext> createEglContext(const DeviceRequest& request);

// The device `auto` picks: (local rank) mod (hardware devices); -1 when there are none
// (surfaceless then).
int autoDevice(int local_rank, int hardware_devices);

}  // namespace sortlast
