// The table of every scene key. Scripts outside the project use these names: keep them.
#include <sstream>

#include "common/scene.h"

namespace sortlast {

const std::vector<SceneKey>& sceneKeys() {
  static const std::vector<SceneKey> keys = {
      {"volume.file", "\"\"",
       "Data file. Empty: a procedural volume (`volume.procedural`). `.vti`/`.vtk`: a VTK image "
       "file (dims and spacing come from the file). Anything else: raw samples, x fastest, no "
       "header unless `volume.header_bytes`. Relative paths are relative to the scene file."},
      {"volume.procedural", "blobs",
       "Procedural field when there is no file: `blobs` (shells, blobs and a torus), "
       "`marschner_lobb` (the Marschner-Lobb test signal), `sphere` (1 - r), or `none`: no "
       "volume (the scene must then have particles)."},
      {"volume.files", "\"\"",
       "A time series: one data file per step, as a list of names or one glob pattern "
       "(`step_*.raw`; matches sorted by name). Each file is read like `volume.file` (same dims, "
       "type and layout for every step); `time.step` picks the step. Excludes `volume.file`."},
      {"volume.dims", "[128, 128, 128]", "Samples per axis [x, y, z] (raw and procedural volumes)."},
      {"volume.type", "uint8", "Raw sample type: `uint8`, `uint16`, `int16` or `float32`."},
      {"volume.spacing", "[1, 1, 1]", "Distance between samples along x, y, z (world units)."},
      {"volume.byte_order", "little", "Byte order of raw samples: `little` or `big`."},
      {"volume.header_bytes", "0", "Bytes to skip at the start of a raw file."},
      {"particles.file", "\"\"",
       "Particle centres, rendered as metaballs. `.vtk` (legacy polydata or unstructured grid), "
       "`.vtp`/`.vtu` (VTK XML): the points; `.csv`: x,y,z per line (optional header line, `#` "
       "comments, extra columns ignored); anything else: raw little-endian float32 x,y,z "
       "triples. Empty: `particles.procedural`. Relative paths are relative to the scene file."},
      {"particles.procedural", "none",
       "Procedural particles when there is no file: `none` (no particles), `layers` (the "
       "metaball paper's test scene: layers of 24 x 24 particles stacked up), `splash` (a "
       "shallow pool, a crown of spikes rising from it and droplets flying off). Setting both "
       "this and `particles.file` is an error."},
      {"particles.files", "\"\"",
       "A time series of particle files (a list, or one glob pattern, sorted), read like "
       "`particles.file`; `time.step` picks the step. The brick grid and the automatic camera "
       "frame the union of every step's particles (rank 0 reads each step once at start)."},
      {"particles.format", "auto",
       "Format of `particles.file`: `vtk`, `raw`, `csv`, or `auto` (by extension: "
       "`.vtk`/`.vtp`/`.vtu` vtk, `.csv` csv, anything else raw)."},
      {"particles.count", "auto",
       "Procedural sets: number of particles (`auto`: 4096). Files: the number the file must "
       "hold (`auto`: whatever it holds; a raw file's size must be a multiple of 12 bytes)."},
      {"particles.spacing", "0.3",
       "Procedural sets: distance between neighbouring particles (world units)."},
      {"particles.radius", "0.143",
       "Radius of the surface around a lone particle, h (1 - T) (the paper: 0.61 x 0.234375)."},
      {"particles.influence", "auto",
       "h, the radius beyond which a particle adds nothing to the field P(r) = (1 - r/h)^2. "
       "`auto`: particles.radius / (1 - particles.threshold)."},
      {"particles.threshold", "0.765625",
       "T: the surface is where sqrt(sum of P) = T (the paper's value); in (0, 1)."},
      {"particles.color", "[0.85, 0.9, 1]", "Surface colour [r, g, b], each in [0, 1]."},
      {"particles.method", "grid",
       "Metaball ray caster: `billboards` (the paper's: rounds of passes that draw every particle "
       "as a billboard) or `grid` (each brick's particles binned into cells of edge h/2, one pass "
       "marching every ray through the cells). Both sum the same particles in the same order at the "
       "same lattice points, refine and shade alike: the surfaces agree but for a few silhouette "
       "pixels (the grid also samples the rear halves of spheres, which the billboards skip). "
       "`grid` is 11-81x faster on llvmpipe (results/README.md). `slices` (the third paper's "
       "dynamic slices): the field summed once per brick and time step on a global lattice of "
       "spacing `particles.slice_spacing`, only in the coarse voxels a particle reaches, and each "
       "ray cast through its trilinear interpolation; a sampled field, so its surface is less "
       "exact (bounds in tests/mpi/particles_slices.sh)."},
      {"particles.slice_spacing", "0.25",
       "`particles.method: slices`: the field's lattice spacing, in units of h, in [0.05, 1]. "
       "Depth error grows with it and memory and splat time shrink as its cube "
       "(results/metaballs/)."},
      {"particles.step", "0.125",
       "Distance between field samples along a ray, in units of h (the paper: below 1/8 avoids "
       "holes)."},
      {"particles.max_samples", "96",
       "Cap on field samples per pixel in each brick (samples inside some particle's reach "
       "count); too few leave holes (the paper's Fig. 12). The paper found about 64 enough with "
       "windows of 4; windows of 8 spend more samples in gaps (64 left 1 hole on the dam break "
       "at 512^2, 96 none, for 2% more time). The grid method also samples the rear halves of "
       "spheres, so its samples run out sooner: raise the cap with finer steps (h/12: 144, h/16: 192 "
       "leave no holes on the dam break). With `particles.smoothing: anisotropic` the cap is "
       "multiplied by the larger of `particles.anisotropic.splash_scale` and `surface_scale` (the "
       "field reaches that much further)."},
      {"particles.refine_iterations", "3",
       "Refinement passes between the last sample outside and the first inside: each evaluates "
       "the secant estimate (the paper's eq. 5), two points close around it and the midpoint, "
       "and keeps the sign change (eq. 6). 0: the secant estimate of the samples alone (the "
       "paper's one linear interpolation)."},
      {"particles.samples_per_pass", "8",
       "Field samples per ray in one pass: 4 (the paper: one RGBA target) or 8 (two targets). "
       "8 needs half the passes (measured 1.4-1.5x faster on llvmpipe) and samples the same "
       "lattice, but runs on through gaps a window of 4 would jump, so a few pixels can differ."},
      {"particles.cull", "true",
       "Cull particles per screen tile with a min/max pyramid of the rays' sample distances "
       "(the paper's); false: no culling (slower; for checking)."},
      {"particles.smoothing", "none",
       "`none`: round metaballs. `anisotropic`: smoothed anisotropic metaballs (Kanamori and "
       "Nishita's, in 3D; ../shared/PAPERS.md §3): each particle's radius grows with its density "
       "from `particles.anisotropic.splash_scale` h (splash) to `surface_scale` h (surface and "
       "inside), and surface particles become ellipsoids along their neighbours' weighted "
       "covariance, normalised to the same mass (common/anisotropic_kernels.h). Only with "
       "`particles.method: grid` (the billboard method refuses it)."},
      {"particles.anisotropic.splash_scale", "1",
       "R_splash / h: radius factor of splash particles (density at most `rho_splash`); a lone "
       "particle is the round metaball of radius h x this. In [1/64, 8]."},
      {"particles.anisotropic.surface_scale", "1.5",
       "R_surface / h: radius factor of surface and inside particles (density at least "
       "`rho_surface`); smoothstep in between. Larger: smoother, slower (longer cell lists). "
       "In [1/64, 8]."},
      {"particles.anisotropic.rho_splash", "1.5",
       "Density at or below which a particle is splash. Density: the sum over the neighbours "
       "within `neighbourhood` h (itself included) of (1 - r^2/h_n^2)^3, so a lone particle has 1."},
      {"particles.anisotropic.rho_surface", "3",
       "Density at or above which a particle is surface or inside (fully smoothed); above "
       "`rho_splash`."},
      {"particles.anisotropic.neighbourhood", "1",
       "h_n / h: radius of the neighbourhood the density, mean and covariance are taken over. "
       "In [1e-6, 8]; bricks and ranks hold ghosts this much further out."},
      {"particles.anisotropic.max_axis_ratio", "3",
       "Longest over shortest ellipsoid axis, at most (eigenvalues clamped to sigma_1 / k^2): a "
       "plane of particles gives a disc of this ratio, a line a cigar. In [1, 100]; 1: spheres."},
      {"transfer.preset", "default",
       "Control points to use when `transfer.points` is not given: `default`, `ramp` (the "
       "paper's opacity = value, grey) or `sharp` (a narrow opaque band)."},
      {"transfer.points", "null",
       "List of control points `[value, r, g, b, a]`, all in [0, 1], values increasing; value "
       "is normalised over `transfer.range`. Colour and opacity are linear between points."},
      {"transfer.colormap", "\"\"",
       "Colour map for the volume: its colours replace those of `transfer.points` / "
       "`transfer.preset`, whose opacity stays as it is. Empty: none. A built-in by ParaView's "
       "name or its alias: `Cool to Warm` (`cool_to_warm`), `Viridis (matplotlib)` (`Viridis`, "
       "`viridis`), `Inferno (matplotlib)` (`inferno`), `Plasma (matplotlib)` (`plasma`), "
       "`Grayscale` (`grayscale`), `Black-Body Radiation` (`black_body`), `Jet` (`jet`). Or a "
       "colour-map file as ParaView exports it (`FILE.json`: an array of presets, or one, each "
       "with `RGBPoints` [x, r, g, b, ...] and `ColorSpace`: `RGB`, `Lab`/`CIELAB`, `Diverging` "
       "(Moreland's Msh interpolation, as ParaView's Cool to Warm uses) or `HSV`; the first "
       "preset, or `FILE.json#Name` for the one with that `Name`). The preset's x range is "
       "stretched onto `transfer.range` (first point at its low end, last at its high end); "
       "`Points` (ParaView's opacity), `NanColor` and other fields are ignored. The map is "
       "resampled at 256 evenly spaced values, its own points, and more where a Lab or "
       "Diverging path bends (to 0.1/255), and interpolated linearly in RGB between them. A relative FILE is relative to the scene file (with `--set`: to the "
       "working directory); the file is read whenever the scene is (a resident session: with "
       "each request). A request to `sortlast serve` may name a built-in only."},
      {"transfer.range", "auto",
       "Data values `[lo, hi]` that map to 0 and 1. `auto`: the volume's minimum and maximum."},
      {"transfer.unit_length", "auto",
       "World length over which a sample has the opacity `a` of the transfer function; other "
       "sample spacings are corrected with 1 - (1 - a)^(ds / unit_length). `auto`: the "
       "smallest voxel spacing."},
      {"transfer.table_size", "4096", "Entries in the transfer-function lookup table used by GL."},
      {"transfer.preintegrated", "auto",
       "`auto`: true where the opacity changes steeply (by 0.5 or more within 10 % of the range "
       "between two control points), where it pays; false on smooth functions, where it does not, "
       "and where it is not supported (`adaptive.tolerance` above 0, `render.sample_spacing` above "
       "2). Pre-integrated transfer function (Engel, Kraus and Ertl 2001) in both GL volume renderers: "
       "each ray segment between two samples takes the exact emission-absorption integral of a "
       "value going linearly from its front to its back value, from a 256 x 256 table rebuilt when "
       "the transfer function or the sample spacing changes (about 30 ms). Coarse steps stay "
       "accurate on sharp transfer functions. Needs `render.sample_spacing` <= 2 (so segment ends "
       "stay within the bricks' ghost layer) and `adaptive.tolerance` 0."},
      {"image.width", "512", "Image width in pixels."},
      {"image.height", "512", "Image height in pixels."},
      {"image.background", "[0, 0, 0]",
       "Colour the frame is composited over when written (premultiplied images stay exact)."},
      {"camera.position", "auto",
       "Eye position. `auto`: along (0.55, 0.35, 1) from `camera.look_at`, just far enough that "
       "the bounding sphere of the scene's bounds (the volume box, grown to hold the particles' "
       "domain) fits the vertical and the horizontal field of view. Must lie outside the volume."},
      {"camera.look_at", "auto",
       "Point the camera looks at. `auto`: the centre of the scene's bounds (the volume box, "
       "grown to hold the particles' domain; for a volume alone, the origin)."},
      {"camera.up", "[0, 1, 0]", "Up direction; also the axis of the orbit."},
      {"camera.fov", "35", "Vertical field of view in degrees."},
      {"camera.orbit.frames", "0",
       "0: a single view. N > 0: the paper's orbit, N frames 360/N degrees apart on a circle "
       "around `camera.look_at`, written as a numbered series (out_0000.png, ...)."},
      {"camera.orbit.elevation", "0", "Tilt of the orbit circle in degrees (-90 ... 90)."},
      {"camera.orbit.radius", "auto",
       "Orbit radius. `auto`: 2 x the largest extent of the scene's bounds (the volume box, "
       "grown to hold the particles' domain; the paper's R, kept for the benchmark protocol: it "
       "may crop a wide scene, which `camera.position: auto` does not)."},
      {"bricks.per_axis", "auto",
       "d: the scene is cut into d x d x d bricks. `auto`: 2, but 1 for a scene of glow emitters "
       "alone (their integral splits anywhere, so one brick draws them in one pass; docs/glow.md)."},
      {"render.backend", "osmesa",
       "OpenGL backend: `osmesa` (software) or `egl` (surfaceless platform, or the device "
       "platform on an NVIDIA GPU)."},
      {"render.sample_spacing", "0.5",
       "Distance between slices (ray casting: between samples along each ray), in units of "
       "the smallest voxel spacing (the paper: 1). The default 0.5, with ray casting and "
       "`transfer.preintegrated: auto`, reaches 45 dB against the reference on the benchmark's "
       "four data sets (results/accuracy)."},
      {"render.block_cells", "64",
       "Slicing: empty-space skipping; bricks are cut into blocks of this many cells per axis, and "
       "blocks whose values all map to zero opacity are not drawn (ray casting: "
       "`render.ray_block_cells`)."},
      {"render.ray_block_cells", "8",
       "Ray casting: cells per axis of the blocks rays walk, on one grid aligned to the volume (the "
       "same in every decomposition; a brick's outer blocks are cut by its faces). A block whose "
       "values all map to zero opacity is jumped, and with its neighbours at once: each block knows "
       "its distance to the nearest block that is not empty. Also the blocks whose range picks the "
       "step of `render.adaptive_step`. (`render.block_cells` is the slicing renderer's.)"},
      {"render.method", "raycast",
       "Volume renderer: `slicing` (3D-texture slicing, the paper's) or `raycast` (a GL ray caster "
       "per brick, front to back on samples `render.sample_spacing` apart along each ray, with "
       "early ray termination and empty blocks jumped along the ray)."},
      {"render.ert_threshold", "0.99",
       "Ray casting: a ray stops once its opacity reaches this, in (0, 1]; 1: never early. It "
       "stops only inside a brick (bricks behind still render), and changes a pixel by at most "
       "1 - threshold."},
      {"render.shading", "false",
       "Gradient shading of the volume (both renderers and the reference): Blinn-Phong with a "
       "headlight, two-sided. A sample of transfer-function colour c emits c' = clamp(c (ka + kd "
       "cos) + ks cos^p, 0, 1), cos = |n . l|, n the unit gradient and l the direction to the eye "
       "(the light, and the half vector); opacity is unchanged. The gradient is the central "
       "difference of the trilinear field one voxel either side along each axis (one-sided at the "
       "data set's faces); a sample whose gradient is at most 0.001 of `transfer.range` per "
       "smallest voxel spacing is unshaded (flat regions keep their colour), fully shaded from "
       "twice that, mixed linearly between. Not with `adaptive.tolerance` above 0. Six more "
       "texture reads per sample: measured 2.2-3.6x the render time on llvmpipe."},
      {"render.shading_ambient", "0.3", "Gradient shading: ka, the ambient term (>= 0)."},
      {"render.shading_diffuse", "0.7", "Gradient shading: kd, the diffuse term (>= 0)."},
      {"render.shading_specular", "0.2",
       "Gradient shading: ks, the specular term (>= 0), a white highlight added to the colour."},
      {"render.shading_shininess", "20",
       "Gradient shading: p, the specular exponent, in [1, 1000]."},
      {"render.adaptive_step", "false",
       "Ray casting: adaptive steps. Each block (`render.ray_block_cells`) takes every m-th sample "
       "of the rays' lattice (m = 1, 2, 4 or 8; each sample standing for the m steps around it, "
       "opacity corrected for their length), the largest m with m x spacing x (the most the "
       "transfer function's opacity or emission varies over the block's values) <= "
       "`render.adaptive_tolerance`, and m x spacing <= 2 voxels. Blocks over steep parts of the "
       "transfer function keep every sample; the lattice stays shared, so ranks and brick faces "
       "agree as without it."},
      {"render.adaptive_tolerance", "0.02",
       "Ray casting with `render.adaptive_step`: the most one coarse sample's optical depth (and "
       "emission) may be off, by the bound above; in (0, 1]."},
      {"adaptive.tolerance", "0",
       "Adaptive sampling (the paper's section 4.2), in percent: each block of the volume is stored at the "
       "coarsest resolution (halved step by step, a coarse sample the mean of the fine cells "
       "around it) whose error stays within this: the block's squared error against the original "
       "(the paper's eq. 3) at most (tolerance/100)^2 x its sum of squared values, i.e. an RMS "
       "error of at most this percent of its RMS value. 0: off (the original samples; the "
       "preprocessing at 0 is lossless). In [0, 100]. See `sortlast adaptive-stats`. Above 0 "
       "the volume is rendered from the blocks, each sampled at its own resolution along the rays "
       "(needs `render.method: raycast`; its blocks replace `render.block_cells`), and every rank "
       "reads the whole volume to build them."},
      {"adaptive.blocks", "8",
       "Adaptive sampling: b, the blocks per axis of the whole volume (the paper: 4, 8, 16); a "
       "power of two in [1, 256]. Blocks have the smallest power-of-two size s with b x s >= the "
       "cells per axis, so there may be fewer than b per axis; they do not depend on "
       "`bricks.per_axis`."},
      {"adaptive.steps", "own",
       "Adaptive sampling, along the rays: `own` (a block at level L, whose samples are 2^L cells "
       "apart, is rendered at its own resolution: every 2^L-th sample of the ray lattice, each "
       "standing for 2^L steps) or `fine` (every block at every step: the adaptive field's "
       "accuracy at the full sampling cost, to tell what the data reduction costs from what the "
       "fewer samples cost)."},
      {"compositing.strategy", "direct",
       "How brick images reach rank 0: `direct` (every brick image to rank 0, which blends them "
       "all), `binary-swap` (each rank blends its own bricks, then pairs of ranks swap halves of "
       "their image for log2 P rounds and rank 0 gathers the pieces) or `radix-k` (the same with "
       "`compositing.radix` partners per round). Any rank count: ranks beyond the largest count "
       "the rounds can take first fold their image into a neighbour's."},
      {"compositing.radix", "4",
       "k of `radix-k`: the most partners per round (>= 2; 2 is binary-swap; a round uses fewer "
       "where the rank count has no factor that large)."},
      {"compositing.precision", "float",
       "`float`: blend in float and round to 8 bits once per frame (swap strategies send partial "
       "composites at 16 bits), so every strategy and rank count gives the same frame within "
       "1/255; an `.exr` output then holds the unrounded frame. `rgba8`: the paper's 8-bit "
       "intermediate images (direct send rounds after every blend, swap strategies send 8-bit "
       "partials): fewer bytes, up to half a step of error per blend or round."},
      {"compositing.overlap", "true",
       "Direct send: each brick image is sent as soon as it is rendered, while the next brick "
       "renders, and rank 0 blends images as their visibility order allows. false: all images are "
       "sent after the last brick (to measure what overlap gains). The swap strategies need all "
       "of a rank's bricks first and ignore it."},
      {"compositing.rle", "true",
       "Run-length code transparent runs in every image message (the paper's Fig. 7). false: every "
       "pixel travels (to measure what RLE saves)."},
      {"time.step", "0",
       "The time step to render, 0 ... steps - 1 (a scene with `volume.files` or "
       "`particles.files`; otherwise only 0)."},
      {"time.cache_mib", "1024",
       "A resident session (`sortlast serve`) keeps the samples and particles of recent time steps "
       "in memory, up to this many MiB per rank, so going back to a step needs no reading."},
      {"limits.memory_mib", "auto",
       "Memory a rank may use, MiB; scenes estimated to need more are refused before loading. "
       "`auto`: 90% of MemAvailable (/proc/meminfo), shared by the ranks on the node."},
      {"glow.emitters", "[]",
       "Energy-wave glow emitters (docs/glow.md): a list of maps `{center: [x, y, z], direction: "
       "[x, y, z], a, b, color: [r, g, b]}`. Each adds the field b / sqrt(dist(P, axis)^2 + eps^2) on "
       "the side of the plane through `center` that `direction` points to (the axis: the line "
       "through `center` along `direction`) and a / sqrt(|P - center|^2 + eps^2) on the other side, "
       "eps = `glow.core_radius`; a = b makes it continuous. `direction` (default [1, 0, 0]) must "
       "not be zero; a and b (default 1) must be >= 0; color entries (default [1, 1, 1]) in [0, 1]. "
       "Per frame of an orbit and per step of a series (`time.step` s with an orbit of N frames "
       "starts at frame s N; without an orbit at frame s), optional linear rates: `velocity` [x, y, z] "
       "added to the centre, `turn` [x, y, z] added to the direction (then normalised), `a_rate`, "
       "`b_rate` added to a and b (refused if a, b would turn negative or the direction zero by the "
       "last frame of the last step). Glow "
       "is emission without opacity, integrated exactly along each ray inside `glow.box`, dimmed "
       "by the volume in front of it and stopped at opaque surfaces. Drawn by `sortlast render`, "
       "`serve` and `reference`; refused with `render.method: slicing`, `adaptive.tolerance` > 0, "
       "`compositing.precision: rgba8` and in situ (docs/glow.md)."},
      {"glow.core_radius", "0.01",
       "eps, the emitters' core radius (world units), > 0: it keeps the field finite at the "
       "centre and on the axis, where with eps = 0 the integral along a ray through them diverges."},
      {"glow.intensity", "1", "Glow radiance per unit of integrated field (times each emitter's color), >= 0."},
      {"glow.tone_map", "none",
       "`none` (radiance clamped to [0, 1] when written) or `exponential`: 1 - exp(-glow.exposure "
       "x radiance) per channel. Applied once to the final composited frame (volume included: "
       "after compositing, glow and volume light are one sum), never per brick: the map is not "
       "additive, so per-brick mapping would change with the decomposition."},
      {"glow.exposure", "1", "k of the exponential tone map, > 0."},
      {"glow.box", "auto",
       "`[[x0, y0, z0], [x1, y1, z1]]`: the box the glow is integrated in (the field's integral "
       "along an unbounded ray diverges like log length). `auto`: the scene's bounds (volume and "
       "particles); a scene of emitters alone must set it."},
      {"surfaces", "[]",
       "Catmull-Clark subdivision surfaces drawn exactly (docs/subdivision.md), opaque, composited "
       "with the volume and particles: a list of maps. Each has exactly one of `file` (an OBJ "
       "file, relative to the scene file; faces of any size; manifold meshes, closed or with "
       "boundaries (OpenSubdiv's edge-and-corner boundary rules; open surfaces are one-sided); "
       "creases and corner tags are refused) and `procedural` (`cube`, `torus`, `pole<N>` for N = "
       "3 ... 32, `prism<N>`, `octahedron`, and open ones: `open_grid`, `fan<N>` for N = 1 ... 12), "
       "and optionally: `color` [r, g, b] in "
       "[0, 1] (default [0.8, 0.8, 0.85]); `transform`, either `{scale: s | [sx, sy, sz], rotate: "
       "[x, y, z] (degrees, about x then y then z), translate: [x, y, z]}` applied scale, rotate, "
       "translate, or a 4 x 4 matrix (4 rows, last 0 0 0 1); `level` 1 ... 3 (default 2): how often "
       "the control mesh is subdivided for the rasterised coarse mesh, which decides coverage at "
       "silhouettes; `shading` `headlight` (default) or `reflection_lines` with `stripes` (default "
       "12), `stripe_width` in (0, 1) (default 0.3) and `stripe_direction` [x, y, z] (the striped "
       "light's normal, default [0, 1, 0]); `newton_steps` 0 ... 8 (default 3) per fragment onto "
       "its pixel's ray. Every mesh is read and checked when the scene is read: a bad one is an "
       "error naming `surfaces[i]`."},
      {"reference.step", "0.0625",
       "Step of the CPU reference integrator, in units of the smallest voxel spacing."},
      {"reference.field", "original",
       "The field the CPU reference integrates (`sortlast reference`, `render --psnr`): "
       "`original` (the volume's samples, trilinear) or `adaptive` (the adaptive-sampling field "
       "of `adaptive.tolerance` and `adaptive.blocks`, exactly as the ray caster's adaptive blocks "
       "hold it: to measure the renderer apart from what adaptive sampling itself costs)."},
  };
  return keys;
}

std::string sceneKeysMarkdown() {
  std::ostringstream md;
  md << "# Scene keys\n\n"
        "A scene is a YAML file of nested maps; `a.b.c` below means `a: {b: {c: ...}}`. Every key "
        "may be omitted (its default applies) and overridden on the command line with "
        "`--set a.b.c=VALUE` (VALUE is YAML: `--set volume.dims=[64,64,64]`). Unknown keys are "
        "errors. This page is generated by `sortlast keys`; a test checks it is current.\n\n"
        "| key | default | meaning |\n| --- | --- | --- |\n";
  for (const SceneKey& k : sceneKeys())
    md << "| `" << k.path << "` | `" << k.default_yaml << "` | " << k.doc << " |\n";
  return md.str();
}

}  // namespace sortlast
