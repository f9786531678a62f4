// The reference section's keys: the CPU reference integrator.
#include "scene/key_rows.h"

std::vector<sortlast::SceneKey> sortlast::referenceKeys() {
  return {
    {"reference.step", "0.0625",
     "Step of the CPU reference integrator, in units of the smallest voxel spacing.",
     Real{member<&Scene::reference, &ReferenceSection::step>, {{"in (0, 1]", "must be {allowed} voxels"}}}},
    {"reference.field", "original",
     "The field the CPU reference integrates (`sortlast reference`, `render --psnr`): "
     "`original` (the volume's samples, trilinear) or `adaptive` (the adaptive-sampling field "
     "of `adaptive.tolerance` and `adaptive.blocks`, exactly as the ray caster's adaptive blocks "
     "hold it: to measure the renderer apart from what adaptive sampling itself costs).",
     Choice{member<&Scene::reference, &ReferenceSection::field>}},
    {"reference.integrator", "cells",
     "How the CPU reference integrates a composited volume: `cells` (the frame estimate's "
     "integrator, reference/ray_segment.h: each cell's crossing cut where the field turns and "
     "meets a kink of opacity, each piece by adaptive Simpson to 1e-5 per voxel, stopping at "
     "transmittance 1e-15) or `steps` (equal steps of `reference.step`, each cut at the transfer "
     "function's kinks, Simpson's optical depth; the integrator before, kept as an independent "
     "check). 256², against `steps` at 1/256 voxel: `cells` 83-93 dB in 0.2-0.9 s, `steps` at 1/16 "
     "60-81 dB in 1.4-3.2 s (neghip's sharp function the 60). Glow, the adaptive field, "
     "projections, isosurfaces and several fields keep their own integrators.",
     Choice{member<&Scene::reference, &ReferenceSection::integrator>}},
  };
}
