// libFuzzer target: the service's request target (service/http_common.h): split at '?', the path
// percent-decoded, query parameters looked up and decoded. Malformed escapes give nullopt, never
// an exception or a read past the end.
#include <cstdint>
#include <string_view>

#include "service/http_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast::front;
  std::string_view target(reinterpret_cast<const char*>(data), size);
  Target t = splitTarget(target);
  for (std::string_view key : {"token", "scene", "", "a"}) (void)queryParam(t.query, key);
  return 0;
}
