#pragma once
// The scene's sections, one struct each (Scene, scene/scene.h, is made of them with the volume,
// particles, glow and surfaces, whose structs live beside their readers), and the enums their keys
// take, each with its names (kEnumNames, common/enum_names.h: the parser reads them, nameOf
// prints them). A section's rows of the key table, with their defaults, checks and docs, are in
// scene/sections/<section>.cpp.
#include <glm/glm.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scene/scene_keys.h"
#include "transfer/isosurface.h"
#include "transfer/shading.h"
#include "transfer/transfer_function.h"

namespace sortlast {

// render.method: the volume renderer.
enum class RenderMethod { kSlicing, kRaycast };
template <>
inline constexpr std::array kEnumNames<RenderMethod>{"slicing", "raycast"};

// render.backend: where the GL context comes from.
enum class GlBackend { kOsmesa, kEgl };
template <>
inline constexpr std::array kEnumNames<GlBackend>{"osmesa", "egl"};

// render.pipeline: how a frame's bricks go from GL to the compositor (session/brick_stages.h).
enum class Pipeline { kOverlapped, kSerial };
template <>
inline constexpr std::array kEnumNames<Pipeline>{"overlapped", "serial"};

// render.estimate: when the frame's accuracy is estimated (session/frame_estimate.h). kAuto:
// when what it depends on changes (the spacing probe's key), not every frame of an orbit.
enum class EstimateMode { kOff, kOn, kAuto };
template <>
inline constexpr std::array kEnumNames<EstimateMode>{"off", "on", "auto"};

// render.blend: how a volume's samples along a ray make the pixel. kComposite: emission-absorption
// (front to back "over"); the projections take the maximum, the minimum, the mean or the sum of
// what each ray meets (order-free: every brick's partial result combines with any other's);
// kIsosurface: the first crossings of render.isovalues.
enum class VolumeBlend { kComposite, kMip, kMinip, kAverage, kAdditive, kIsosurface };
template <>
inline constexpr std::array kEnumNames<VolumeBlend>{"composite", "mip", "minip", "average", "additive",
                                                    "isosurface"};

struct RenderSection {
  GlBackend backend = GlBackend::kOsmesa;
  int device = -1;              // a hardware EGL device index; -1: auto
  double sample_spacing = 0.5;  // in units of the smallest voxel spacing
  // render.sample_spacing: auto: the session picks the step per view and transfer function
  // (session/auto_spacing.h); sample_spacing then holds 0.5 until it does.
  bool sample_spacing_auto = true;
  int block_cells = 64;     // empty-space skipping granularity (slicing)
  int ray_block_cells = 8;  // the ray caster's skipping and step blocks
  RenderMethod method = RenderMethod::kRaycast;
  double ert_threshold = 0.999;           // ray casting: early ray termination opacity
  Shading shading;                        // gradient shading of the volume (render.shading*)
  bool adaptive_step = false;             // ray casting: a block takes every m-th lattice sample
  double adaptive_step_tolerance = 0.02;  // the step rule's bound (render/volume/step_rule.h)
  Pipeline pipeline = Pipeline::kOverlapped;
  VolumeBlend blend = VolumeBlend::kComposite;
  bool mip_exact = false;  // mip / minip: the exact extremum of the trilinear field along each ray
  std::vector<Isovalue> isovalues;  // render.isovalues (scene/isosurface_scene.h)
  EstimateMode estimate = EstimateMode::kAuto;  // render.estimate
  int estimate_pixels = 4096;                   // the estimate's sampled pixels
  double target_db = 50.0;  // render.sample_spacing auto: the PSNR its estimate must reach

  bool raycast() const { return method == RenderMethod::kRaycast; }
  // mip, minip, average, additive: order-free (docs/volumes.md, compositing/projection_pixels.h).
  bool projection() const {
    return blend == VolumeBlend::kMip || blend == VolumeBlend::kMinip || blend == VolumeBlend::kAverage ||
           blend == VolumeBlend::kAdditive;
  }
};

// compositing.strategy
enum class Strategy { kDirect, kBinarySwap, kRadixK, kAuto };
template <>
inline constexpr std::array kEnumNames<Strategy>{"direct", "binary-swap", "radix-k", "auto"};

// compositing.precision: how partial results are held. kFloat: blend in float, round to RGBA8
// once per frame (partial composites travel at 16 bits), so every strategy and rank count gives
// the same frame within 1/255. kRgba8: the paper's intermediate images; direct send rounds after
// every blend, the swap strategies send their partial composites as RGBA8 (fewer bytes, up to
// half a step of error per round).
enum class Precision { kFloat, kRgba8 };
template <>
inline constexpr std::array kEnumNames<Precision>{"float", "rgba8"};

struct CompositingSection {
  Strategy strategy = Strategy::kDirect;
  int radix = 4;                // radix-k: partners per round
  double latency_us = 40;       // auto: the network its cost model assumes
  double bandwidth_gbps = 10;
  Precision precision = Precision::kFloat;
  bool overlap = true;  // direct send: send while the next brick renders
  bool rle = true;      // run-length code image messages
};

// adaptive.steps: how a block's samples are taken along the rays.
enum class AdaptiveSteps { kOwn, kFine };
template <>
inline constexpr std::array kEnumNames<AdaptiveSteps>{"own", "fine"};

struct AdaptiveSection {
  double tolerance = 0.0;  // relative L2 error per block, a fraction (the key is in percent); 0: off
  int blocks = 8;          // b, blocks per axis of the whole volume
  AdaptiveSteps steps = AdaptiveSteps::kOwn;

  bool enabled() const { return tolerance > 0.0; }
};

// reference.field: what the reference integrates.
enum class ReferenceField { kOriginal, kAdaptive };
template <>
inline constexpr std::array kEnumNames<ReferenceField>{"original", "adaptive"};

// reference.integrator: fixed steps of reference.step, or each cell's crossing to a tolerance
// (reference/ray_segment.h).
enum class ReferenceIntegrator { kSteps, kCells };
template <>
inline constexpr std::array kEnumNames<ReferenceIntegrator>{"steps", "cells"};

struct ReferenceSection {
  double step = 0.0625;  // in units of the smallest voxel spacing
  ReferenceField field = ReferenceField::kOriginal;
  ReferenceIntegrator integrator = ReferenceIntegrator::kCells;
};

// image.* (image.width and image.height are the camera's: Camera carries the image size).
// image.legend.position: where the colour legend is drawn into written frames (none: no legend;
// session/frame_legend.h).
enum class LegendPosition { kNone, kRight, kLeft, kBottom, kTop };
template <>
inline constexpr std::array kEnumNames<LegendPosition>{"none", "right", "left", "bottom", "top"};

struct LegendSpec {
  LegendPosition position = LegendPosition::kNone;
  std::string title;  // above the bar; empty: none
  int ticks = 5;      // about this many labelled ticks
  std::string units;  // after the title, in brackets; empty: none
  bool enabled() const { return position != LegendPosition::kNone; }
};

// movie.*: a movie output (-o NAME.mp4 / NAME.webm; io/movie_writer.h).
struct MovieSpec {
  int frame_rate = 30;                  // frames per second
  std::optional<double> quality;        // the codec's CRF; unset: its default (23 H.264, 31 VP9)
};

struct ImageSection {
  glm::dvec3 background{0.0};  // what the frame is composited over when written
  LegendSpec legend;
  MovieSpec movie;
};

// camera.orbit.*
struct OrbitSpec {
  int frames = 0;          // 0: a single view
  double elevation = 0;    // degrees
  double start = 0;        // degrees: the azimuth of the first frame
  std::optional<double> radius;
};

// bricks.*
struct BricksSection {
  int per_axis = 2;  // d: d x d x d bricks
};

// time.* and the series keys (volume.files, particles.files): one file per step, sorted;
// volume.file and particles.file then hold the file of `step`. Empty: no series (one step).
struct TimeSection {
  std::vector<std::string> volume_files, particle_files;
  int step = 0;
  int steps = 1;            // steps of the series (1 without one)
  double cache_mib = 1024;  // host memory per rank for cached steps (resident sessions)
};

// limits.*
struct LimitsSection {
  std::optional<double> memory_mib;  // unset: from MemAvailable
};

struct TransferSpec {
  std::vector<TfPoint> points;  // with transfer.colormap's colours applied, if it is set
  std::string colormap;         // transfer.colormap as given (empty: none)
  std::optional<std::pair<double, double>> range;  // unset: the data's global min and max
  std::optional<double> unit_length;               // unset: the smallest voxel spacing
  int table_size = 4096;
  bool preintegrated = false;  // segments from a pre-integrated 2D table (transfer/preintegration.h)
  // transfer.preintegrated was `auto` where either choice renders (a composite volume of one field,
  // no adaptive sampling): render.sample_spacing `auto` may then overturn the steepness rule's
  // choice from the frame's estimate (session/auto_spacing.h stillTries, otherChoiceSteps).
  bool preintegrated_auto = false;
  ValueScaleKind scale = ValueScaleKind::kLinear;  // transfer.scale (transfer/value_scale.h)
  double linear_width = 1.0;                       // transfer.linear_width: symlog's w

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

}  // namespace sortlast
