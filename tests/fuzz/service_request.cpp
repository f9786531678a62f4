// libFuzzer target: a frame request as the service receives it (an HTTP body or a WebSocket text
// message): parsed as JSON the way service/http_session.cpp and ws_session.cpp do, translated to
// overrides (service/request_translation.h), packed for the broadcast to the other ranks and
// unpacked, then applied to the default scene as the session does (scene/scene.h). A bad request
// must end in a JSON parse error or InputError (both answered 400 with the message).
#include <cstdint>
#include <cstdlib>
#include <string>

#include <nlohmann/json.hpp>

#include "common/error.h"
#include "scene/scene.h"
#include "service/request_translation.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace sortlast;
  nlohmann::json body;
  try {
    body = nlohmann::json::parse(data, data + size);
  } catch (const nlohmann::json::exception&) {  // what the front end answers with 400
    return 0;
  }
  try {
    TranslatedRequest t = translateRequest(body);
    if (unpackOverrides(packOverrides(t.overrides)) != t.overrides) std::abort();
    Scene s = parseScene(SceneText{}, t.overrides);
    (void)s;
  } catch (const InputError&) {
  }
  return 0;
}
