// libFuzzer target: the NRRD header parser (io/nrrd_header.h) on a header's text, attached
// data or not. Bad input must end in InputError naming the field; any other exception escapes
// and libFuzzer reports it.
#include <cstdint>
#include <string>

#include "common/error.h"
#include "io/nrrd_header.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    NrrdHeader h = parseNrrdHeader(text, "fuzz.nrrd");
    (void)h;
  } catch (const InputError&) {
  }
  return 0;
}
