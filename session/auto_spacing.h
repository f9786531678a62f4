#pragma once
// render.sample_spacing: auto.
//
// Against the exact model (issue 43; where the accuracy estimate applies, session/
// frame_estimate.h): small probe frames of the scene's automatic view (and of the frame's own
// camera where it sets one, before any orbit: the finer step of the two wins) at 2, 1, 0.5 and
// 0.25 voxel, coarsest first; a stratified sample of the first probe's pixels is integrated once with the
// reference's exact model, and each probe is compared with it. The first step whose estimate
// meets the target at its 95 % bound (PSNR >= render.target_db, default 50, and at most 0.1 % of
// pixels over 4/255: meetsTarget) is taken; 0.25 when none does (`target_met: false`). Unlike the
// difference of successive steps below, this sees the error the step does not change (GL's
// tables, early termination, 8-bit rounding against the exact integral). Measured at 512^2 on
// llvmpipe (frame figures against `sortlast reference`): the default scene takes 1 voxel (2 had
// 0.16 % of pixels over 4/255), 59.96 dB, largest 4/255; the head CT 0.5 voxel, 52.9 dB, 0.03 %
// over; neghip 0.25 voxel and still 0.29 % over (target not met: not the step).
//
// Otherwise (projections, several fields, particles, surfaces, glow, adaptive sampling), the
// difference of successive steps. The default step of 0.5 voxel was chosen so sharp
// transfer functions reach 45 dB; on smooth data and smooth functions a coarser step gives the
// same image for less time. Which step a scene can take depends on its data and its transfer
// function, so the session measures it: it renders the scene small from its automatic camera
// (`camera.position: auto`, whatever the frame's camera) at steps of 0.5, 1 and 2 voxels, and
// estimates each step's own error by its difference to the next finer one:
//   e(d) ~ |I(d) - I(d/2)|,
// the RMS over the composited RGB values (over the background, in [0, 1]). Not Richardson's
// 2 |I(d) - I(d/2)| for a smooth first-order bias: a coarse step's error is mostly aliasing
// that changes with the samples' phase, so the two frames' errors add like noise (measured on the
// head CT at 512^2: I(1) - I(0.5) 47.4 dB, I(1) against the reference 46.1 dB, I(0.5) 50.3 dB).
// The choice is the largest step whose estimate stays within kTargetDb = 52 dB, every finer step
// passing too; never finer than 0.5 voxel (the fixed default) nor coarser than 2
// (pre-integration's ghost layer). 52, not 45: the step's error can add in phase to the error the
// step does not change (the renderer's against the reference model), and the probe cannot see
// that part. Measured: neghip with missing samples and a fog transfer function (tests/mpi/
// hdf5_netcdf.sh) has 49.7 dB at 0.5 voxel and a 1-voxel difference of 50.0 dB, yet 43.8 dB at
// 1 voxel; at 47 or 50 dB auto took 1 voxel there and fell below 45. The head CT's difference is
// also 50.0 dB but its 1-voxel frame 47.8 dB: the probe cannot tell the two apart, so both keep
// 0.5, and 52 leaves 2 dB to the highest difference seen to fail.
//
// Probe size: the longer side a quarter of the frame's, at most kProbeSide pixels: the three
// probes then cost at most 11 % of a frame at 0.5 voxel, which matters to a service whose client
// edits the transfer function frame by frame (tests/soak's 2,000 requests, most with a new
// transfer function: 47 s with probes of the frame's own size, 22.7 s with a quarter's, 13.6 s
// with the step fixed). The probe runs again when what it depends on changes: the transfer
// function, the renderer's settings, the data's time step, the frame's size; not the camera,
// which the probes do not use: so a frame's step, and its image, follow from its request alone
// (an orbit's frame k rendered alone, or by the service after other frames, is frame k of the
// whole orbit), and an orbit probes once. (Probing each view instead cost neghip 0.03 s a frame,
// 28 %, since three small frames still pay a frame's fixed costs.)
#include <string>
#include <vector>

#include "io/image.h"
#include "session/frame_estimate.h"

#include <glm/glm.hpp>

namespace sortlast {

constexpr int kProbeSide = 96;
constexpr int kProbeFraction = 4;  // the probe's longer side: the frame's over this, or less
constexpr double kTargetDb = 52.0;
// The steps probed, finest first; the choice is one of them.
inline const std::vector<double>& probeSpacings() {
  static const std::vector<double> s{0.5, 1.0, 2.0};
  return s;
}

// The steps tried against the exact model (session/frame_estimate.h), coarsest first: the first
// whose estimate meets the target is taken, 0.25 when none does.
inline const std::vector<double>& estimatedSpacings() {
  static const std::vector<double> s{2.0, 1.0, 0.5, 0.25, 0.125};
  return s;
}
// A still image (a job of one frame: FrameRequest::job_frames 1) does not probe: a probe pays for
// itself only over the frames it serves. The frame itself is drawn at 0.5 voxel and checked by the
// estimate it computes anyway (the exact values integrated once serve every try); 0.25 and 0.125
// only where that misses the target. Why 0.5 first, from measured costs (README's command: the
// default scene, 512^2, 4 ranks, llvmpipe, 7 interleaved runs on a loaded 2-core machine, medians):
// probes 0.90 s, the frame at 1 voxel 0.58 s, at 0.5 0.99 s, the estimate 0.37 s; so probing (to
// find that 1 voxel suffices) costs more than the finer frame, 1.85 s against 1.41 s. Starting at 1
// instead pays only where 1 voxel meets the target in more than F(1) / F(0.5) = 59 % of scenes;
// in the defaults matrix (63 cells, results/accuracy) about one in five does.
inline const std::vector<double>& stillSpacings() {
  static const std::vector<double> s{0.5, 0.25, 0.125};
  return s;
}

// transfer.preintegrated `auto` (TransferSpec::preintegrated_auto) decides by the steepness rule
// (scene/sections.h hasSteepOpacity), which the estimate may overturn: the rule is a proxy, and a
// function just under its slope can need pre-integration (neghip, ray cast, 256^2, opacity 0 ->
// 0.24 -> 0 over 0.05 of the range each way, slope 4.8: unintegrated the estimate cannot certify
// the target even at 0.125 voxel, pre-integrated it does at 0.25; tests/mpi/auto_spacing.sh). A
// pre-integrated sample costs about kPreintegratedCost plain ones (results/accuracy: 50-70 % more
// time).
constexpr double kPreintegratedCost = 1.5;
inline double sampleCost(double step, bool preintegrated) {
  return (preintegrated ? kPreintegratedCost : 1.0) / step;
}
// A still frame's tries, in order (step, pre-integrated), the first that meets the target taken:
// stillSpacings with the rule's choice; where the choice may change, after unintegrated 0.25
// missed, pre-integrated at 0.25 (it costs less than unintegrated 0.125), and last the other
// choice at 0.125. (Unintegrated is
// not tried between pre-integrated steps: where the rule takes pre-integration the opacity is
// steep, and unintegrated steps missed by 10-15 dB on every sharp cell of the matrix.)
std::vector<std::pair<double, bool>> stillTries(bool preintegrated, bool may_change);
// The probes' steps of the other choice, coarsest first, after the rule's choice met the target
// at `step` (`met`) or missed at every step: pre-integrated after unintegrated met it only at the
// finest step, where it costs less (sampleCost); either after a miss. At most kOtherChoiceCoarsest.
constexpr double kOtherChoiceCoarsest = 0.5;
std::vector<double> otherChoiceSteps(bool preintegrated, bool met, double step);
constexpr double kTargetOver4Share = 0.001;  // IceT's image tests: at most 0.1 % over 4/255
// Whether an estimate meets the target at its 95 % bound: PSNR >= target_db and at most
// kTargetOver4Share of the pixels over 4/255.
inline bool meetsTarget(const AccuracyEstimate& e, double target_db) {
  return e.psnrLo() >= target_db && e.over4Hi() <= kTargetOver4Share;
}
// Whether only the bound on the share over 4/255 stands between an estimate and the target: its
// PSNR bound and its share itself meet it, the share's 95 % bound does not. From 4,096 pixels one
// or two seen over 4/255 put the bound above 0.1 % whatever the true share (the rule of three
// alone is 0.073 %): the engine, head CT and ironProt sharp at 0.25 voxel, 0.03-0.1 % over 4/255
// against the reference, took 0.125 voxel for that (results/accuracy/defaults_speed_512.md).
inline bool shareUndecided(const AccuracyEstimate& e, double target_db) {
  return e.psnrLo() >= target_db && e.over4_share <= kTargetOver4Share && e.over4Hi() > kTargetOver4Share;
}
// A still frame whose estimate is undecided so draws kStillTopUp times the sampled pixels again
// (once) before it draws a finer step: at 512² the exact integrals of 16,384 pixels cost about
// 0.1-0.3 s, a frame at half the step 0.3-0.8 s.
constexpr int kStillTopUp = 4;

// The probe's size against the exact model: the frame's own up to kEstimateProbeSide pixels on
// its longer side (a 32^2 probe of a 128^2 frame has too few pixels to tell 0.1 % from 0.5 %).
constexpr int kEstimateProbeSide = 128;
std::pair<int, int> estimateProbeSize(int width, int height);

struct EstimatedStep {
  double step = 0.0;
  AccuracyEstimate estimate;
  std::string view;  // "auto": the automatic view; "scene": the scene's own camera
  bool preintegrated = false;
};

struct SpacingChoice {
  double spacing = 0.5;
  // Per probed step but the finest: its estimated error as a PSNR in dB (inf: no difference).
  std::vector<std::pair<double, double>> estimated_db;
  // Chosen against the exact model instead: each step tried and its estimate.
  std::vector<EstimatedStep> against_exact;
  bool preintegrated = false;  // with it (where TransferSpec::preintegrated_auto let it choose)
  bool preintegration_chosen = false;  // by the estimate (every rank): else the scene's stays
};

// probes[i]: the premultiplied float frame at probeSpacings()[i], all the same size; background:
// what the frame is composited over. Throws std::logic_error on mismatched images.
SpacingChoice chooseSpacing(const std::vector<ImageF>& probes, const glm::dvec3& background);

// The probe's image size for a frame of width x height: the longer side the frame's over
// kProbeFraction, at most kProbeSide, the aspect kept (each side at least 8).
std::pair<int, int> probeSize(int width, int height);

}  // namespace sortlast
