// libFuzzer target: the CSV particle reader (io/particles.h, parseCsvParticles) on any text.
// Bad input must end in InputError naming the line.
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "io/particles.h"
#include "io/particle_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    parseCsvParticles(text, "fuzz.csv", -1);
  } catch (const InputError&) {
  }
  return 0;
}
