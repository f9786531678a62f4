#pragma once
// The scene's glow emitters (the `glow.*` keys, docs/scene.md; the field: glow/glow_field.h):
// what each emitter is at frame 0, how it moves per frame, and how the glow is scaled and
// tone-mapped. Parsed and validated here, apart from scene.cpp, as one list-valued key.
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <vector>

#include "common/box.h"
#include "common/enum_names.h"
#include "glow/glow_field.h"

namespace YAML {
class Node;
}

namespace sortlast {

struct GlowEmitterSpec {
  GlowEmitter at0;                    // frame 0; direction as given (not zero)
  glm::dvec3 velocity{0.0};           // added to the centre per frame
  glm::dvec3 turn{0.0};               // added to the direction as given per frame, then normalised
  double a_rate = 0.0, b_rate = 0.0;  // added to a and b per frame
};

// glow.tone_map: none (radiance clamped when written) | exponential (1 - exp(-exposure x radiance)).
enum class ToneMap { kNone, kExponential };
template <>
inline constexpr std::array kEnumNames<ToneMap>{"none", "exponential"};

struct GlowSpec {
  std::vector<GlowEmitterSpec> emitters;
  double core_radius = 0.01;      // eps, world units
  double intensity = 1.0;         // radiance = intensity * colour * integral of E
  ToneMap tone_map = ToneMap::kNone;
  double exposure = 1.0;          // exponential: 1 - exp(-exposure * radiance)
  std::optional<Box3> box;        // glow.box; unset: the scene's bounds
  // Frames before the first of this time step: the rates run on through a series (time.step s
  // of a scene whose orbit has N frames starts at frame s N; without an orbit at frame s).
  int first_frame = 0;

  bool enabled() const { return !emitters.empty(); }
  // The emitters at frame `frame` of this time step (an orbit's frame index, 0 without one):
  // first_frame + frame steps of each rate from the emitters as given.
  std::vector<GlowEmitter> emittersAt(int frame) const;
};

// Reads `glow.emitters` (a list of maps) and checks every entry; `frames` is the number of frames
// the scene renders (its time steps times its orbit's frames, each at least 1), so a rate that
// would make a or b negative or the direction zero in a later frame is refused now. Throws InputError naming the key and entry.
std::vector<GlowEmitterSpec> parseGlowEmitters(const YAML::Node& list, int frames);
// The rates' part of that check alone, for a frame count learnt later (the time steps inside one
// data file: scene/file_steps.h).
void checkGlowRates(const std::vector<GlowEmitterSpec>& emitters, int frames);

// The tone map, applied once to the final composited radiance (premultiplied rgb; alpha kept).
double toneMap(const GlowSpec& g, double radiance);

}  // namespace sortlast
