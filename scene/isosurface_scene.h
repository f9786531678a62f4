#pragma once
// The scene's isosurfaces (render.blend: isosurface, render.isovalues; transfer/isosurface.h):
// the list's parser and the rules between it and the other sections' keys.
#include <string>
#include <vector>

#include "transfer/isosurface.h"

namespace YAML {
class Node;
}

namespace sortlast {

struct Scene;
class Reader;

// render.isovalues: a list of maps {value, color: [r, g, b], opacity}. Throws InputError naming
// the entry and the problem.
std::vector<Isovalue> parseIsovalues(const YAML::Node& list);

// With render.blend: isosurface, what the other keys must be (throws InputError naming the keys),
// and what `auto` means for them (the ray caster's fixed step, no pre-integration). Call once
// transfer.preintegrated and adaptive.tolerance are resolved.
void applyIsosurfaceRules(const Reader& r, Scene& s);

// Warnings (one line each, "warning: render.isovalues[i] ...") for isovalues outside the data's
// range [lo, hi]: such a surface never appears. Empty when all are inside.
std::vector<std::string> isovalueRangeWarnings(const std::vector<Isovalue>& isovalues, double lo, double hi);

}  // namespace sortlast
