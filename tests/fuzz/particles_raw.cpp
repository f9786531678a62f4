// libFuzzer target: the raw particle reader (io/particles.h, parseRawParticles) on any bytes,
// with and without a declared count. Bad input must end in InputError.
#include <cstdint>
#include <string_view>

#include "common/error.h"
#include "io/particles.h"
#include "io/particle_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  std::string_view bytes(reinterpret_cast<const char*>(data), size);
  for (long long declared : {-1LL, (long long)size / 12}) {
    try {
      parseRawParticles(bytes, "fuzz.raw", declared);
    } catch (const InputError&) {
    }
  }
  return 0;
}
