#pragma once
// The scene: everything a frame needs, read from a YAML file plus `--set key.path=value`
// overrides, as typed sections (scene/sections/: each section's struct and enums in its header,
// its rows of the key table in its .cpp). Every key, its type, default, allowed values and meaning
// live in one table (scene/scene_keys.h), which the parser reads keys through and which generates
// docs/scene.md, so the documentation cannot drift from the parser.
#include <optional>
#include <string>
#include <vector>

#include "common/camera.h"
#include "common/clip.h"
#include "io/particles.h"
#include "io/volume_source.h"
#include "scene/fields_scene.h"
#include "scene/glow_scene.h"
#include "scene/scene_keys.h"
#include "scene/sections.h"
#include "scene/surface_scene.h"

namespace sortlast {

struct Scene {
  VolumeDesc volume;           // none when volume.procedural is `none` and there is no file
  ParticleDesc particles;
  GlowSpec glow;               // glow.* (emitters: none unless given)
  std::vector<SurfaceSpec> surfaces;  // surfaces (subdivision surfaces; none unless given)
  TransferSpec transfer;
  // Several fields (`volumes`, scene/fields_scene.h): all of them, the first also in volume and
  // transfer; empty with one field (then in volume and transfer alone, as without `volumes`).
  std::vector<FieldSpec> fields;
  ImageSection image;
  Camera camera;               // with image width and height
  bool camera_auto = true;     // position derived from the bounds (camera.position: auto)
  bool parallel_scale_auto = true;  // camera.parallel_scale: auto (from the distance and fov)
  bool look_at_auto = true;    // camera.look_at: auto, the bounds' centre (camera.look_at holds 0)
  OrbitSpec orbit;
  ClipRegion clip;             // clip.planes, clip.box (volumes only)
  BricksSection bricks;
  RenderSection render;
  AdaptiveSection adaptive;
  CompositingSection compositing;
  TimeSection time;
  LimitsSection limits;
  ReferenceSection reference;

  bool hasVolume() const { return !volume.file.empty() || volume.procedural != "none"; }
  bool hasFields() const { return fields.size() > 1; }

  // Cameras of every frame (one, or the orbit's), with the automatic parts resolved against the
  // scene's bounds: the volume box, grown to hold the particles' domain. An empty box (lo > hi)
  // counts as the origin with extent 1, a box of zero size as its centre with extent 1.
  std::vector<Camera> frameCameras(const Box3& bounds) const;
  // In units of the smallest voxel spacing of any field.
  double sampleSpacingWorld() const {
    return render.sample_spacing * (hasFields() ? fieldsGrid(fields).minSpacing() : volume.grid.minSpacing());
  }
};

// A scene file's text, read once: a resident session parses it again with each request's keys, so
// an edit of the file on disk cannot change a running session behind its back.
struct SceneText {
  std::string path;  // empty: the built-in default scene
  std::string yaml;
};
// Throws InputError if the file cannot be read.
SceneText readSceneText(const std::string& path);

// Parses and validates; throws InputError naming the key (and file line) at fault. An empty path
// means the built-in default scene.
Scene parseScene(const SceneText& text, const std::vector<std::string>& overrides);
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides);

// Whether a resident session can apply a change of this key without reloading its data layout
// (camera, image, transfer function, render and compositing options, particle shading, time step).
bool isFrameKey(const std::string& path);

}  // namespace sortlast
