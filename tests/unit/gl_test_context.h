#pragma once
// The OSMesa (llvmpipe) context of the GL unit tests (gl_program_tests): null, with the test
// failed and the reason given, where none can be made.
#include <gtest/gtest.h>

#include <exception>
#include <memory>

#include "render/gl/gl_context.h"

namespace sortlast {

inline std::unique_ptr<GlContext> testGlContext() {
  try {
    return createGlContext("osmesa");
  } catch (const std::exception& e) {
    ADD_FAILURE() << "no GL context: " << e.what();
    return nullptr;
  }
}

}  // namespace sortlast
