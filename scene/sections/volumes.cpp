// The volumes section's key: several fields in one frame (scene/fields_scene.h). Each entry is
// read through the volume and transfer sections' own rows (a scene of its own, holding just the
// entry's keys under `volume` and `transfer`), so an entry takes exactly what `volume` and
// `transfer` take, with their defaults and checks; messages name `volumes[i].key`.
#include "scene/key_rows.h"
#include "scene/scene_reader.h"

std::vector<sortlast::SceneKey> sortlast::volumesKeys() {
  return {
    {"volumes", "[]",
     "Several scalar fields in one frame (docs/volumes.md, \"Several fields\"): a list of maps, "
     "each a field: the `volume.*` keys without the `volume.` (`file` or `procedural`, `dims`, "
     "`spacing`, `type`, `format`, ...; not `files`) and a `transfer` map of the `transfer.*` "
     "keys without the `transfer.` (`points` or `preset`, `colormap`, `range`, `unit_length`, "
     "`table_size`), the same defaults. A scene that sets `volume.*` too has that volume (with "
     "`transfer.*`) as its first field, the entries after it; otherwise the entries are all "
     "(and `transfer.*` at the top is refused). An entry's `visible: false` hides that field "
     "(drawn at zero opacity: it adds nothing; with two or more fields). `--set` and service "
     "requests name one entry's key as `volumes[i].key` (`volumes[1].transfer.points`, "
     "`volumes[1].visible`; i counts the list's entries from 0); a request may set an entry's "
     "`transfer.*` keys and `visible`, nothing else of `volumes`. Fields may have different dims and spacing; each "
     "is centred on the origin, as `volume` is. They are rendered as one medium: per sample "
     "each field is classified by its own transfer function, the extinctions add and the "
     "colour is their extinction-weighted mean. At most 4 fields; with 2 or more only the ray "
     "caster's composite blend renders them, and adaptive sampling, `render.adaptive_step`, "
     "`render.shading`, pre-integration, particles, surfaces, glow and legacy `.vtk` files are "
     "refused. Every field is checked when the scene is read; a bad key is an error naming "
     "`volumes[i].key`.",
     Structured{"list of fields"}},
  };
}

namespace sortlast {

namespace {

// One entry: its keys moved under `volume` and `transfer` and read through their rows.
FieldSpec readEntry(const YAML::Node& e, const std::string& name, const Origin& o, bool& preint_auto) {
  if (!e.IsMap())
    throw InputError("scene key '" + name + "': expected a map of volume keys (file or procedural, "
                     "dims, spacing, ...) and a transfer map" + where(e));
  YAML::Node root(YAML::NodeType::Map), volume(YAML::NodeType::Map);
  bool visible = true;
  for (auto it = e.begin(); it != e.end(); ++it) {
    if (!it->first.IsScalar())
      throw InputError("scene key '" + name + "': a key is a list or map, not a name" + where(it->first));
    const std::string key = it->first.as<std::string>();
    if (key == "transfer") {
      if (!it->second.IsMap())
        throw InputError("scene key '" + name + ".transfer' must be a map" + where(it->second));
      for (auto t = it->second.begin(); t != it->second.end(); ++t) {
        const std::string sub = t->first.IsScalar() ? t->first.as<std::string>() : "?";
        if (!findSceneKey("transfer." + sub))
          throw InputError("unknown scene key '" + name + ".transfer." + sub + "'" + where(t->first) +
                           " (a field's transfer map takes the transfer.* keys: docs/scene.md)");
      }
      root["transfer"] = it->second;
      continue;
    }
    if (key == "visible") {
      if (!YAML::convert<bool>::decode(it->second, visible))
        throw InputError("scene key '" + name + ".visible': expected true or false" + where(it->second));
      continue;
    }
    if (key == "files")
      throw InputError("scene key '" + name + ".files': a time series is not available in volumes; "
                       "give each field one file" + where(it->first));
    if (!findSceneKey("volume." + key))
      throw InputError("unknown scene key '" + name + "." + key + "'" + where(it->first) +
                       " (an entry of volumes takes the volume.* keys and a transfer map: docs/scene.md)");
    volume[key] = it->second;
  }
  root["volume"] = volume;
  const Reader r(root);
  Scene entry;
  try {
    readTypedKeys(r, o, entry, {"volume.", "transfer."});
    checkVolumeKeys(entry);
    readTransferKeys(r, o, entry.transfer);
  } catch (const InputError& err) {
    throw InputError(fieldMessage(err.what(), name));
  }
  if (!entry.hasVolume())
    throw InputError("scene key '" + name + ".procedural': none is no field; give a file or a "
                     "procedural field" + where(e));
  preint_auto = r.isAuto("transfer.preintegrated");
  return {name, entry.volume, entry.transfer, visible};
}

// What renders several fields: the ray caster's composite blend, nothing it cannot mix per sample.
void checkFieldsScene(const Scene& s) {
  auto refuse = [](const std::string& keys, const std::string& why) {
    throw InputError("scene keys 'volumes' and '" + keys + "' cannot go together: " + why);
  };
  const std::string several = "a scene of " + std::to_string(s.fields.size()) + " fields";
  if (!s.render.raycast())
    refuse("render.method: slicing", several + " is mixed per sample by the ray caster only; use render.method: raycast");
  if (s.render.blend != VolumeBlend::kComposite)
    refuse("render.blend", several + " is rendered with the composite blend only");
  if (s.adaptive.tolerance > 0.0)
    refuse("adaptive.tolerance", "adaptive sampling holds one field; set adaptive.tolerance: 0");
  if (s.render.adaptive_step)
    refuse("render.adaptive_step", "the step rule reads one transfer function; set render.adaptive_step: false");
  if (s.render.shading.enabled)
    refuse("render.shading", "the mixture has no one gradient to shade with; set render.shading: false");
  if (s.particles.enabled()) refuse("particles", several + " is rendered without particles");
  if (!s.surfaces.empty()) refuse("surfaces", several + " is rendered without surfaces");
  if (s.glow.enabled()) refuse("glow.emitters", several + " is rendered without glow");
  for (const FieldSpec& f : s.fields) {
    if (f.transfer.preintegrated)
      throw InputError("scene key '" + fieldMessage("transfer.preintegrated", f.name) +
                       "': pre-integration is not available with several fields (the mixture of "
                       "two tables is not one table); set it false or auto");
    if (f.volume.readsWhole())
      throw InputError("scene key '" + fieldMessage("volume.file", f.name) + "': " + f.volume.file +
                       " is a legacy .vtk file, read whole by one rank, which several fields do not "
                       "do; convert it to .vti (VTK XML), read per brick");
  }
}

}  // namespace

std::optional<bool> readVolumesKey(const Reader& r, const Origin& o, const YAML::Node& root, Scene& s) {
  // The node as given (Reader::get clones it, and the clone's nodes have no line numbers).
  const YAML::Node list = root["volumes"] ? root["volumes"] : r.get("volumes");
  if (list.IsNull() || (list.IsSequence() && list.size() == 0)) return std::nullopt;
  if (!list.IsSequence())
    throw InputError("scene key 'volumes': expected a list of fields ({file | procedural, dims, "
                     "spacing, ..., transfer: {...}})" + where(list));
  // Relative files start at the scene file, or where the user runs for `--set volumes=...`.
  Origin entries{o.fromOverride("volumes") ? std::filesystem::current_path() : o.base_dir, {}};
  std::vector<FieldSpec> fields;
  bool first_auto = true;
  if (root["volume"].IsDefined() && s.hasVolume()) {
    if (!s.time.volume_files.empty())
      throw InputError("scene keys 'volume.files' and 'volumes' cannot go together: a time series "
                       "is not mixed with other fields");
    fields.push_back({"volume", s.volume, s.transfer});
    first_auto = r.isAuto("transfer.preintegrated");
  } else if (root["transfer"].IsDefined()) {
    throw InputError("scene key 'transfer': the scene's fields are all in volumes, each with its "
                     "own transfer map; move these keys there (or give the first field as volume)");
  }
  for (size_t i = 0; i < list.size(); ++i) {
    bool preint_auto = true;
    fields.push_back(readEntry(list[i], "volumes[" + std::to_string(i) + "]", entries, preint_auto));
    if (fields.size() == 1) first_auto = preint_auto;
  }
  if (fields.size() > size_t(kMaxFields))
    throw InputError("scene key 'volumes': " + std::to_string(fields.size()) + " fields; the ray "
                     "caster mixes at most " + std::to_string(kMaxFields));
  if (fields.size() == 1 && !fields[0].visible)
    throw InputError("scene key 'volumes[0].visible': false hides the scene's only field; a scene "
                     "of one field shows it (hide one of several)");
  s.volume = fields[0].volume;
  s.transfer = fields[0].transfer;
  if (fields.size() > 1) {
    s.fields = std::move(fields);
    checkFieldsScene(s);
  }
  return first_auto;
}

}  // namespace sortlast
