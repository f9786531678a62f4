// The render section's keys: how bricks are drawn: GL backend and device, volume renderer,
// sampling, shading.
#include "common/build_features.h"
#include "scene/key_rows.h"
#include "scene/scene_reader.h"

std::vector<sortlast::SceneKey> sortlast::renderKeys() {
  return {
    // A build without OSMesa (SORTLAST_WITH_OSMESA=OFF) has EGL, and draws there by default.
    {"render.backend", build::kOsmesa ? "osmesa" : "egl",
     "OpenGL backend: `osmesa` (software) or `egl` (surfaceless platform, or the device "
     "platform on an NVIDIA GPU).",
     Choice{member<&Scene::render, &RenderSection::backend>}},
    {"render.device", "auto",
     "EGL on a node with GPUs: which hardware EGL device a rank renders on (Mesa's software "
     "device is not counted). `auto`: (the rank's index on its node) mod (the node's devices), "
     "so a node's ranks spread over its GPUs; N: device N. A device that cannot be opened ends "
     "the job with its number and the rank; with no hardware device, `auto` falls back to the "
     "surfaceless platform (llvmpipe). Only with `render.backend: egl` (docs/cluster.md).",
     Int{member<&Scene::render, &RenderSection::device>, {{"integers in [0, 63]", "must be auto or a device number {allowed}, got {value}"}}},
     AutoValue{}},
    {"render.sample_spacing", "auto",
     "Distance between slices (ray casting: between samples along each ray), in units of "
     "the smallest voxel spacing (the paper: 1). `auto`: the coarsest of 2, 1, 0.5 and 0.25 whose "
     "error meets `render.target_db` and at most 0.1 % of pixels more than 4/255 off, both at "
     "their 95 % bounds, as estimated against the exact model (`render.estimate`'s method) on small "
     "probe frames of the scene's automatic view and of the frame's own camera where it sets one "
     "(before any orbit; the finer step wins), coarsest first (0.25 when none does; `--stats` "
     "says `target_met`). Scenes the estimate does not model (projections, several fields, "
     "particles, surfaces, glow, adaptive sampling) take the largest of 0.5, 1 and 2 whose "
     "difference to the next finer step stays within 52 dB (session/auto_spacing.h). Probed again "
     "when the transfer function, the renderer's settings, the time step, the image size or a "
     "camera the frame sets change (not an orbit's frame); `--stats` gives the choice and each "
     "step's estimate. A still image (`sortlast render` of one frame, with `render.estimate` on "
     "or auto) does not probe: the frame is drawn at 0.5, checked by its own estimate, and "
     "again at 0.25 and 0.125 only where that misses the target (`by: still image`).",
     Real{member<&Scene::render, &RenderSection::sample_spacing>, {{"in [0.01, 100]", "must be {allowed} voxels"}}},
     AutoValue{member<&Scene::render, &RenderSection::sample_spacing_auto>}},
    {"render.block_cells", "64",
     "Slicing: empty-space skipping; bricks are cut into blocks of this many cells per axis, and "
     "blocks whose values all map to zero opacity are not drawn (ray casting: "
     "`render.ray_block_cells`).",
     Int{member<&Scene::render, &RenderSection::block_cells>, {{">= 1"}}}},
    {"render.ray_block_cells", "8",
     "Ray casting: cells per axis of the blocks rays walk, on one grid aligned to the volume (the "
     "same in every decomposition; a brick's outer blocks are cut by its faces). A block whose "
     "values all map to zero opacity is jumped, and with its neighbours at once: each block knows "
     "its distance to the nearest block that is not empty. Also the blocks whose range picks the "
     "step of `render.adaptive_step`. (`render.block_cells` is the slicing renderer's.)",
     Int{member<&Scene::render, &RenderSection::ray_block_cells>, {{">= 1"}}}},
    {"render.method", "raycast",
     "Volume renderer: `slicing` (3D-texture slicing, the paper's) or `raycast` (a GL ray caster "
     "per brick, front to back on samples `render.sample_spacing` apart along each ray, with "
     "early ray termination and empty blocks jumped along the ray).",
     Choice{member<&Scene::render, &RenderSection::method>}},
    {"render.blend", "composite",
     "How a volume's samples along each ray make its pixel: `composite` (emission and "
     "absorption, front to back), `mip` / `minip` (the largest / smallest trilinear value among "
     "the lattice samples a ray takes inside the volume; missing (NaN) samples ignored), "
     "`average` (the mean of those samples: their sum over their count), `additive` (the sum "
     "over the samples of the transfer function's premultiplied emission c(v) a, a = 1 - "
     "exp(-tau(v) spacing) the opacity corrected for the step, without absorption; alpha the sum "
     "of the a, both clamped to 1 in the frame), `isosurface` (the first crossings of "
     "`render.isovalues`). mip, minip and average colour the projected value v once, on the "
     "final value, through the transfer function: the pixel is (c(v) a(v), a(v)), c the table's "
     "colour and a(v) its opacity (`transfer.opacity` at v, per `transfer.unit_length`); a pixel "
     "no sample reached stays transparent. Projections never stop early (no early ray "
     "termination) and combine bricks with max / min / sum (docs/volumes.md). With "
     "`render.method: slicing` the samples are where the ray crosses the slice planes. With "
     "particles or surfaces (every projection, ray casting and slicing) a ray counts the samples in front of "
     "the first opaque hit, the surface's colour behind the projection's. "
     "compositing.precision float, without glow, shading, adaptive sampling or adaptive steps; "
     "transfer.preintegrated does not apply.",
     Choice{member<&Scene::render, &RenderSection::blend>}},
    {"render.mip_exact", "false",
     "`render.blend: mip` / `minip`: the exact largest / smallest value of the trilinear field "
     "along each ray inside the volume, instead of the largest / smallest sample's: the ray "
     "walks the volume's cells, and in each the field on the ray is a cubic in t whose extremum "
     "is at an end or at a root of its quadratic derivative (closed form). Thin features between "
     "samples keep their peak; it costs more per ray than sampling (docs/volumes.md). Ray "
     "casting only.",
     Flag{member<&Scene::render, &RenderSection::mip_exact>}},
    {"render.isovalues", "[]",
     "With `render.blend: isosurface` (ray casting only): the isosurfaces, a list of up to 8 maps "
     "`{value, color: [r, g, b], opacity}` (value in data units; color entries in [0, 1], default "
     "[1, 1, 1]; opacity in [0, 1], default 1). Every crossing of a value along a ray is a surface, "
     "shaded with the trilinear field's exact gradient (headlight Blinn-Phong, two-sided, with "
     "`render.shading_*`'s coefficients) and composited front to back; an opaque one ends the ray. "
     "A value outside the data's range is warned about (its surface never appears). Clipped by "
     "`clip.planes` / `clip.box` (the search starts at the cut: no surface on the cut face). Needs "
     "`render.sample_spacing` <= 1 (`auto`: 0.5) and no adaptive sampling, glow or "
     "pre-integration (docs/volumes.md).",
     Structured{"list of {value, color, opacity}"}},
    {"render.pipeline", "overlapped",
     "How each brick's pixels travel from GL to the compositor. `overlapped`: converted to RGBA8 "
     "on the GPU (rounded as the CPU rounds, bit for bit), read through a ring of pixel-buffer "
     "objects with fences, and the next brick drawn before this one's pixels are waited for. "
     "`serial`: each brick drawn, read back as floats and converted on the CPU before the next "
     "(the pipeline before; for measuring what overlap gains, as `compositing.overlap: false`). "
     "The images are the same; `--stats` gives each stage's time (`stages`).",
     Choice{member<&Scene::render, &RenderSection::pipeline>}},
    {"render.estimate", "auto",
     "The frame's accuracy, estimated as it renders (session/frame_estimate.h): about "
     "`render.estimate_pixels` of the frame's pixels, a stratified sample with more where the "
     "colour changes fastest, are integrated with the reference's exact model (double precision, "
     "not pre-integrated), each rank its own bricks' part of each ray, and compared with the frame "
     "as written: `--stats` gives `accuracy_estimate` (estimated PSNR, the share of pixels more than "
     "4/255 off, 95 % bounds of each, the time it took). `on`: every frame; `auto`: the first frame "
     "and whenever what the spacing probe depends on changes (not the camera; later frames repeat "
     "the last estimate, marked `fresh: false`); `off`: never (a batch render then drops its host "
     "copy of the samples once they are on the GPU). Volumes with `render.blend: composite` and one "
     "field, without particles, surfaces, glow or adaptive sampling; other scenes say why not.",
     Choice{member<&Scene::render, &RenderSection::estimate>}},
    {"render.estimate_pixels", "4096",
     "How many pixels `render.estimate` samples (more: tighter bounds, more time).",
     Int{member<&Scene::render, &RenderSection::estimate_pixels>, {{"in [64, 1000000]"}}}},
    {"render.target_db", "50",
     "`render.sample_spacing: auto`: the PSNR (against the exact model) the chosen step's "
     "estimated error must reach at its 95 % lower bound, with at most 0.1 % of the pixels more "
     "than 4/255 off at the share's upper bound.",
     Real{member<&Scene::render, &RenderSection::target_db>, {{"in [20, 100]"}}}},
    {"render.ert_threshold", "0.999",
     "Ray casting: a ray stops once its opacity reaches this; 1: never early. It "
     "stops only inside a brick (bricks behind still render), and changes a pixel by at most "
     "1 - threshold (0.999: 0.26/255, within the accuracy goal's 4/255 with room for the step's "
     "error; 0.99's 2.55/255 cost the head CT 5.8 dB against it at 0.5 voxel, "
     "results/accuracy/causes.md).",
     Real{member<&Scene::render, &RenderSection::ert_threshold>,
          {{"in (0, 1]", "must be {allowed} (1: no early termination)"}}}},
    {"render.shading", "false",
     "Gradient shading of the volume (both renderers and the reference): Blinn-Phong with a "
     "headlight, two-sided. A sample of transfer-function colour c emits c' = clamp(c (ka + kd "
     "cos) + ks cos^p, 0, 1), cos = |n . l|, n the unit gradient and l the direction to the eye "
     "(the light, and the half vector); opacity is unchanged. The gradient is the central "
     "difference of the trilinear field one voxel either side along each axis (one-sided at the "
     "data set's faces); a sample whose gradient is at most 0.001 of `transfer.range` per "
     "smallest voxel spacing is unshaded (flat regions keep their colour), fully shaded from "
     "twice that, mixed linearly between. Not with `adaptive.tolerance` above 0. Six more "
     "texture reads per sample: measured 2.2-3.6x the render time on llvmpipe.",
     Flag{member<&Scene::render, &RenderSection::shading, &Shading::enabled>}},
    {"render.shading_ambient", "0.3", "Gradient shading: ka, the ambient term.",
     Real{member<&Scene::render, &RenderSection::shading, &Shading::ambient>, {{"in [0, 100]"}}}},
    {"render.shading_diffuse", "0.7", "Gradient shading: kd, the diffuse term.",
     Real{member<&Scene::render, &RenderSection::shading, &Shading::diffuse>, {{"in [0, 100]"}}}},
    {"render.shading_specular", "0.2",
     "Gradient shading: ks, the specular term, a white highlight added to the colour.",
     Real{member<&Scene::render, &RenderSection::shading, &Shading::specular>, {{"in [0, 100]"}}}},
    {"render.shading_shininess", "20",
     "Gradient shading: p, the specular exponent.",
     Real{member<&Scene::render, &RenderSection::shading, &Shading::shininess>, {{"in [1, 1000]"}}}},
    {"render.adaptive_step", "false",
     "Ray casting: adaptive steps. Each block (`render.ray_block_cells`) takes every m-th sample "
     "of the rays' lattice (m = 1, 2, 4 or 8; each sample standing for the m steps around it, "
     "opacity corrected for their length), the largest m with m x spacing x (the most the "
     "transfer function's opacity or emission varies over the block's values) <= "
     "`render.adaptive_tolerance`, and m x spacing <= 2 voxels. Blocks over steep parts of the "
     "transfer function keep every sample; the lattice stays shared, so ranks and brick faces "
     "agree as without it.",
     Flag{member<&Scene::render, &RenderSection::adaptive_step>}},
    {"render.adaptive_tolerance", "0.02",
     "Ray casting with `render.adaptive_step`: the most one coarse sample's optical depth (and "
     "emission) may be off, by the bound above.",
     Real{member<&Scene::render, &RenderSection::adaptive_step_tolerance>, {{"in (0, 1]"}}}},
  };
}

namespace sortlast {

// A device index names an EGL device: with OSMesa it would be ignored without a word.
void checkRenderKeys(const Scene& s) {
  checkProjectionKeys(s);
  if (s.render.device >= 0 && s.render.backend != GlBackend::kEgl)
    throw InputError("scene key 'render.device': device " + std::to_string(s.render.device) +
                     " names an EGL device, but render.backend is " + std::string(nameOf(s.render.backend)) +
                     " (set render.backend: egl, or render.device: auto)");
}

}  // namespace sortlast
