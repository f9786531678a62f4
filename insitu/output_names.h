#pragma once
// File names of in-situ images: an output pattern with {step}, and the orbit's frame numbers.
#include <string>

namespace sortlast {

// The one placeholder an output pattern knows; replaced by the step, zero-padded to 6 digits.
inline constexpr const char* kStepPlaceholder = "{step}";

// The file of one frame: every {step} in `pattern` replaced by the step ("images/v_{step}.png",
// step 20 -> "images/v_000020.png"); with frames > 1 (an orbit), _0000 ... before the extension,
// as `sortlast render` names an orbit's frames.
std::string outputName(const std::string& pattern, long long step, int frame, int frames);

// The step as it appears in file names and the Cinema index: zero-padded to 6 digits.
std::string stepLabel(long long step);

// Creates the folders that will hold `file` (nothing if it has none); throws InputError naming the
// folder if that fails, so a bad output path is reported like any other bad output.
void createParentDirectories(const std::string& file);

}  // namespace sortlast
