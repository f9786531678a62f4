#pragma once
// Several scalar fields in one frame (the `volumes` key, docs/volumes.md "Several fields"): each a
// volume (the `volume.*` keys: file or procedural, dims, spacing, type, ...) with its own transfer
// function (its `transfer` map: the `transfer.*` keys). Every field is centred on the world origin
// as the one volume is (io/volume_source.h has no origin), on a grid of its own. The frame renders
// their mixture: per sample the extinctions add and the colours are averaged weighted by them.
//
// The scene's layout cuts one grid that covers every field (fieldsGrid): its per-axis spacing the
// finest of the fields', its box the smallest centred one holding every field's box.
#include <optional>
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
  // An entry's `visible` (a request's `volumes[i].visible`): a hidden field is drawn with its
  // transfer function at zero opacity everywhere, so it adds nothing to any sample and every block
  // is empty under it (skipping stays exact).
  bool visible = true;

  // The transfer function the field is drawn with: its own, or (hidden) every point's opacity 0.
  TransferSpec shownTransfer() const;
};

// The fields the ray caster mixes at once: four volume textures and four tables on top of the
// program's own seven texture units, within the 16 every GL 4.5 driver has.
inline constexpr int kMaxFields = 4;

// The grid the layout cuts and the lattice steps from: spacing per axis the smallest of the
// fields', dims the fewest whose (centred) box holds every field's box.
GridGeometry fieldsGrid(const std::vector<FieldSpec>& fields);

// A key of one entry of `volumes` as `--set` and service requests name it (the way messages name
// it): "volumes[2].transfer.points" is entry 2's `transfer: {points: ...}`, "volumes[2].dims" its
// `dims`. Entries count from 0 in the list as written (a scene that also sets `volume` has that
// field first, edited through `transfer.*`).
struct FieldEntryKey {
  size_t entry = 0;
  std::string key;  // what follows "volumes[i].": "transfer.points", "visible", "dims", ...
  std::vector<std::string> path() const;  // its parts: {"transfer", "points"}
};
// Empty unless `path` has the form volumes[<digits>].<key> (the key is not checked here).
std::optional<FieldEntryKey> parseFieldEntryKey(const std::string& path);
// Whether an entry takes `key`: `visible`, the volume.* keys without `volume.` (not `files`) and
// `transfer.` with a transfer.* key.
bool isFieldEntryKey(const std::string& key);
// Whether a running session may change it per frame: the entry's transfer map (the transfer.*
// keys a frame may set) and `visible`; everything else of `volumes` fixes the data.
bool isFieldFrameKey(const std::string& key);

}  // namespace sortlast

namespace sortlast {

// A message about the keys `volume.x` and `transfer.x` said of field `name` ("volumes[2]"):
// "volumes[2].x" and "volumes[2].transfer.x" (the first field given as `volume`: unchanged).
std::string fieldMessage(const std::string& message, const std::string& name);

}  // namespace sortlast
