// EGL backend. On a machine with a GPU, EGL's device platform (EGL_EXT_platform_device) gives a
// context on the GPU with no window system; elsewhere Mesa's surfaceless platform gives llvmpipe.
// Mesa also lists a software "device": it is skipped so that surfaceless is used instead.
// Which hardware device: render.device (DeviceRequest), `auto` spreading a node's ranks over its GPUs.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/gl/gl_context.h"

namespace sortlast {

namespace {

bool hasExtension(const char* list, const char* name) {
  if (!list) return false;
  std::string s = std::string(" ") + list + " ";
  return s.find(std::string(" ") + name + " ") != std::string::npos;
}

template <class F>
F eglProc(const char* name) {
  return reinterpret_cast<F>(eglGetProcAddress(name));
}

class EglContext final : public GlContext {
 public:
  explicit EglContext(const DeviceRequest& request) {
    const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    auto get_display = eglProc<PFNEGLGETPLATFORMDISPLAYEXTPROC>("eglGetPlatformDisplayEXT");
    if (!get_display) throw std::runtime_error("EGL: eglGetPlatformDisplayEXT is missing");
    // The hardware devices, in EGL's order (Mesa's software device left out).
    std::vector<EGLDeviceEXT> hardware;
    if (hasExtension(client, "EGL_EXT_platform_device")) {
      auto query_devices = eglProc<PFNEGLQUERYDEVICESEXTPROC>("eglQueryDevicesEXT");
      auto query_device_string = eglProc<PFNEGLQUERYDEVICESTRINGEXTPROC>("eglQueryDeviceStringEXT");
      EGLint n = 0;
      EGLDeviceEXT devices[64];
      if (query_devices && query_device_string && query_devices(64, devices, &n))
        for (EGLint i = 0; i < n; ++i)
          if (!hasExtension(query_device_string(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software"))
            hardware.push_back(devices[i]);
    }
    info_.devices = int(hardware.size());
    const int want = request.device == DeviceRequest::kAuto
                         ? autoDevice(request.local_rank, info_.devices)
                         : request.device;
    if (want >= 0) {
      // A device asked for (or auto's pick) that is missing or does not open ends the job: falling
      // back to another device, or to llvmpipe, would silently put two ranks on one GPU or run a
      // hundred times slower.
      const std::string which = "render.device " + std::to_string(want) +
                                (request.device == DeviceRequest::kAuto ? " (auto: node-local rank " + std::to_string(request.local_rank) + ")" : std::string()) +
                                " on rank " + std::to_string(request.rank) + " (host " + host() + ")";
      if (want >= info_.devices)
        throw std::runtime_error(which + ": this node has " + std::to_string(info_.devices) +
                                 " hardware EGL device(s)" +
                                 (info_.devices > 0 ? " (0 to " + std::to_string(info_.devices - 1) + ")" : std::string()));
      EGLDisplay d = get_display(EGL_PLATFORM_DEVICE_EXT, hardware[size_t(want)], nullptr);
      if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr))
        throw std::runtime_error(which + ": EGL device " + std::to_string(want) + " of " +
                                 std::to_string(info_.devices) + " cannot be opened (EGL error 0x" +
                                 hex(eglGetError()) + ")");
      display_ = d;
      info_.backend = "egl device";
      info_.device = want;
    }
    if (display_ == EGL_NO_DISPLAY && hasExtension(client, "EGL_MESA_platform_surfaceless")) {
      EGLDisplay d = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
      if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
        display_ = d;
        info_.backend = "egl surfaceless";
      }
    }
    if (display_ == EGL_NO_DISPLAY)
      throw std::runtime_error("EGL: no GPU device and no surfaceless platform could be initialised");
    if (!eglBindAPI(EGL_OPENGL_API)) throw std::runtime_error("EGL: cannot bind the OpenGL API");
    const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint n_configs = 0;
    eglChooseConfig(display_, config_attribs, &config, 1, &n_configs);
    const EGLint ctx_attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                                  EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                  EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    // Without a config, EGL_KHR_no_config_context lets us create one anyway.
    context_ = eglCreateContext(display_, n_configs > 0 ? config : EGL_NO_CONFIG_KHR,
                                EGL_NO_CONTEXT, ctx_attribs);
    if (context_ == EGL_NO_CONTEXT)
      throw std::runtime_error("EGL: cannot create an OpenGL 4.5 core context (error 0x" +
                               hex(eglGetError()) + ")");
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_))
      throw std::runtime_error("EGL: cannot make a surfaceless context current (error 0x" +
                               hex(eglGetError()) + ")");
    gl_.load([](const char* name) { return reinterpret_cast<void*>(eglGetProcAddress(name)); });
    finishSetup();
  }
  ~EglContext() override {
    if (display_ != EGL_NO_DISPLAY) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
      if (context_ != EGL_NO_CONTEXT) eglDestroyContext(display_, context_);
      eglTerminate(display_);
    }
  }

 private:
  static std::string host() {
    char b[256] = {};
    return gethostname(b, sizeof b - 1) == 0 ? std::string(b) : std::string("?");
  }
  static std::string hex(EGLint e) {
    char b[16];
    std::snprintf(b, sizeof b, "%x", unsigned(e));
    return b;
  }
  EGLDisplay display_ = EGL_NO_DISPLAY;
  EGLContext context_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> createEglContext(const DeviceRequest& request) {
  return std::make_unique<EglContext>(request);
}

}  // namespace sortlast
