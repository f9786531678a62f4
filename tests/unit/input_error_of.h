#pragma once
// Shared by the unit tests that check bad input: runs `f`, which must throw InputError, and
// returns its message (a test failure, and "", if it throws anything else or nothing).
#include <gtest/gtest.h>

#include <exception>
#include <string>

#include "common/error.h"

namespace sortlast {

template <class F>
std::string inputErrorOf(F f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "threw something other than InputError: " << e.what();
    return "";
  }
  ADD_FAILURE() << "did not throw";
  return "";
}

}  // namespace sortlast
