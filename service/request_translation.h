#pragma once
// A client's frame request (JSON: scene keys, dotted or nested, plus the image format) turned into
// what a session takes: `key.path=value` overrides, as `--set` gives them. No MPI, no sockets.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortlast {

struct TranslatedRequest {
  std::vector<std::string> overrides;  // key.path=VALUE, VALUE as JSON (which YAML reads)
  std::string format = "png";          // png | jpeg
  int quality = 85;                    // JPEG quality, 1-100
};

// Throws InputError naming the key: not an object, a value that is not finite (JSON text cannot
// hold NaN or infinity, but a json value built in code can), a bad format or quality. Unknown keys pass here; the
// session names them.
TranslatedRequest translateRequest(const nlohmann::json& body);

// The overrides as one string for the broadcast to the other ranks, and back.
std::string packOverrides(const std::vector<std::string>& overrides);
std::vector<std::string> unpackOverrides(const std::string& packed);

}  // namespace sortlast
