#pragma once
// The scene: everything a frame needs, read from a YAML file plus `--set key.path=value`
// overrides. Every key, its type, default, allowed values and meaning live in one table
// (scene/scene_keys.h), which the parser reads keys through and which generates docs/scene.md,
// so the documentation cannot drift from the parser.
#include <optional>
#include <string>
#include <vector>

#include "common/camera.h"
#include "scene/glow_scene.h"
#include "io/particles.h"
#include "scene/scene_keys.h"
#include "transfer/shading.h"
#include "scene/surface_scene.h"
#include "transfer/transfer_function.h"
#include "io/volume_source.h"

namespace sortlast {

struct TransferSpec {
  std::vector<TfPoint> points;  // with transfer.colormap's colours applied, if it is set
  std::string colormap;         // transfer.colormap as given (empty: none)
  std::optional<std::pair<double, double>> range;  // unset: the data's global min and max
  std::optional<double> unit_length;               // unset: the smallest voxel spacing
  int table_size = 4096;
  bool preintegrated = false;  // segments from a pre-integrated 2D table (transfer/preintegration.h)

  // Resolves the automatic parts against the data.
  TransferFunction build(double data_min, double data_max, double min_spacing) const;
};

// transfer.preintegrated `auto` turns pre-integration on where the opacity changes steeply: some
// stretch between control points changes it by kSteepOpacitySlope x the stretch's width (in the
// normalised range), i.e. by 0.5 or more within 10 % of the range. Measured (results/accuracy, 0.5
// voxel): on neghip's narrow band it gains 13 dB (34.8 -> 48.0) for 10 % more time; on smooth
// functions (the engine's ramp, slope 1; the head CT's, 3.5; the default preset's, 1.5) it gains
// nothing or loses (engine 53.2 -> 48.0 dB) and costs 50-70 % more time.
inline constexpr double kSteepOpacitySlope = 5.0;
bool hasSteepOpacity(const std::vector<TfPoint>& points);

struct Scene {
  VolumeDesc volume;           // none when volume.procedural is `none` and there is no file
  ParticleDesc particles;
  GlowSpec glow;               // glow.* (emitters: none unless given)
  std::vector<SurfaceSpec> surfaces;  // surfaces (subdivision surfaces; none unless given)
  TransferSpec transfer;
  Camera camera;               // with image width and height
  bool camera_auto = true;     // position derived from the bounds (camera.position: auto)
  bool look_at_auto = true;    // camera.look_at: auto, the bounds' centre (camera.look_at holds 0)
  int orbit_frames = 0;        // 0: a single view
  double orbit_elevation = 0;  // degrees
  std::optional<double> orbit_radius;
  glm::dvec3 background{0.0};
  int bricks_per_axis = 2;
  std::string backend = "osmesa";
  int device = -1;  // render.device: -1 auto, else a hardware EGL device index
  double sample_spacing = 0.5;  // in units of the smallest voxel spacing
  // render.sample_spacing: auto: the session picks the step per view and transfer function
  // (session/auto_spacing.h); sample_spacing then holds 0.5 until it does.
  bool sample_spacing_auto = true;
  int block_cells = 64;         // empty-space skipping granularity (slicing)
  int ray_block_cells = 8;      // the ray caster's skipping and step blocks
  std::string volume_method = "raycast";  // slicing | raycast
  double ert_threshold = 0.99;            // ray casting: early ray termination opacity
  Shading shading;                        // gradient shading of the volume (render.shading*)
  bool adaptive_step = false;             // ray casting: a block takes every m-th lattice sample
  double adaptive_step_tolerance = 0.02;  // the step rule's bound (render/volume/step_rule.h)
  double adaptive_tolerance = 0.0;  // adaptive sampling: relative L2 error per block, fraction; 0: off
  int adaptive_blocks = 8;          // adaptive sampling: b, blocks per axis of the whole volume
  std::string adaptive_steps = "own";  // own: a block's samples along rays at its resolution | fine
  std::string strategy = "direct";  // direct | binary-swap | radix-k | auto
  int radix = 4;                    // radix-k: partners per round
  double network_latency_us = 40;   // auto: the network its cost model assumes
  double network_gbps = 10;
  std::string precision = "float";  // float | rgba8: how partial composites are held
  bool overlap = true;              // direct send: send while the next brick renders
  bool rle = true;                  // run-length code image messages
  double reference_step = 0.0625;  // reference integrator step, in voxel units
  std::string reference_field = "original";  // original | adaptive: what the reference integrates
  // Time series (volume.files, particles.files): one file per step, sorted; volume.file and
  // particles.file then hold the file of `time_step`. Empty: no series (one step).
  std::vector<std::string> volume_files, particle_files;
  int time_step = 0;
  int time_steps = 1;          // steps of the series (1 without one)
  double time_cache_mib = 1024;  // host memory per rank for cached steps (resident sessions)
  std::optional<double> memory_limit_mib;  // limits.memory_mib; unset: from MemAvailable

  bool hasVolume() const { return !volume.file.empty() || volume.procedural != "none"; }

  // Cameras of every frame (one, or the orbit's), with the automatic parts resolved against the
  // scene's bounds: the volume box, grown to hold the particles' domain. An empty box (lo > hi)
  // counts as the origin with extent 1, a box of zero size as its centre with extent 1.
  std::vector<Camera> frameCameras(const Box3& bounds) const;
  double sampleSpacingWorld() const { return sample_spacing * volume.grid.minSpacing(); }
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
