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
  };
}
