#pragma once
// Compiling and linking GLSL programs; errors carry the driver's log.
#include "worker/gl/gl_api.h"

namespace sortlast {

// Throws std::runtime_error with the compile or link log.
unsigned linkProgram(const GlApi& gl, const char* vertex_src, const char* fragment_src);
unsigned linkComputeProgram(const GlApi& gl, const char* compute_src);

}  // namespace sortlast
