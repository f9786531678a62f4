#pragma once
// Several scalar fields in one frame (the `volumes` key, docs/volumes.md "Several fields"): each a
// volume (the `volume.*` keys: file or procedural, dims, spacing, type, ...) with its own transfer
// function (its `transfer` map: the `transfer.*` keys). Every field is centred on the world origin
// as the one volume is (io/volume_source.h has no origin), on a grid of its own. The frame renders
// their mixture: per sample the extinctions add and the colours are averaged weighted by them.
//
// The scene's layout cuts one grid that covers every field (fieldsGrid): its per-axis spacing the
// finest of the fields', its box the smallest centred one holding every field's box.
#include <string>
#include <vector>

#include "common/grid.h"
#include "io/volume_source.h"
#include "scene/sections.h"

namespace sortlast {

struct FieldSpec {
  std::string name;  // "volume" or "volumes[i]": what messages call it
  VolumeDesc volume;
  TransferSpec transfer;
};

// The fields the ray caster mixes at once: four volume textures and four tables on top of the
// program's own seven texture units, within the 16 every GL 4.5 driver has.
inline constexpr int kMaxFields = 4;

// The grid the layout cuts and the lattice steps from: spacing per axis the smallest of the
// fields', dims the fewest whose (centred) box holds every field's box.
GridGeometry fieldsGrid(const std::vector<FieldSpec>& fields);

}  // namespace sortlast

namespace sortlast {

// A message about the keys `volume.x` and `transfer.x` said of field `name` ("volumes[2]"):
// "volumes[2].x" and "volumes[2].transfer.x" (the first field given as `volume`: unchanged).
std::string fieldMessage(const std::string& message, const std::string& name);

}  // namespace sortlast
