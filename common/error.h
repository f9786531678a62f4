#pragma once
// The one exception type for bad input (scene files, data files, command lines).
// Its message names the problem in words a user can act on; main() prints it and exits non-zero.
#include <stdexcept>
#include <string>

namespace sortlast {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace sortlast
