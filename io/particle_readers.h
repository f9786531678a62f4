#pragma once
// The raw and CSV particle readers on bytes already in memory: loadParticles (particles.h) reads
// the file, then calls these; tests/fuzz feeds them arbitrary bytes. `file` names the source in
// messages; `declared` is particles.count (-1: any number). The same checks and messages as
// loadParticles: InputError on a raw size that is no multiple of 12 bytes, a count other than the
// declared one, a malformed CSV line (naming it), a NaN, infinite or too large coordinate.
#include <string>
#include <string_view>
#include <vector>

#include <glm/glm.hpp>

namespace sortlast {

std::vector<glm::vec3> parseRawParticles(std::string_view bytes, const std::string& file,
                                         long long declared, const std::string& hint = "");
std::vector<glm::vec3> parseCsvParticles(std::string_view text, const std::string& file,
                                         long long declared);

}  // namespace sortlast
