// The particles section's keys: the particles: their file or generator, and the metaball model and
// methods (io/particles.h holds ParticleDesc).
#include "scene/key_rows.h"
#include "scene/scene_reader.h"

std::vector<sortlast::SceneKey> sortlast::particleKeys() {
  const Check kLength = lengthCheck();
  const Check kPositive = positiveCheck();
  const Check kColour = colourCheck();
  // Radii beyond 8 h would make every particle's reach (and the bricks' ghost margins) huge;
  // below 1/64 h the field falls between the ray caster's samples (step h/8).
  const Check kScale{"in [1/64, 8]", "must be {allowed} (units of h), got {value}"};
  const Check kDensity{"in [0, 1e9]", "must be {allowed}, got {value}"};
  return {
    {"particles.file", "\"\"",
     "Particle centres, rendered as metaballs. `.vtk` (legacy polydata or unstructured grid), "
     "`.vtp`/`.vtu` (VTK XML): the points; `.csv`: x,y,z per line (optional header line, `#` "
     "comments, extra columns ignored); `.h5`/`.hdf5`: an HDF5 snapshot "
     "(`particles.dataset`); anything else: raw little-endian float32 x,y,z "
     "triples. Empty: `particles.procedural`. Relative paths are relative to the scene file.",
     Text{member<&Scene::particles, &ParticleDesc::file>, true}},
    {"particles.procedural", "none",
     "Procedural particles when there is no file: `none` (no particles), `layers` (the "
     "metaball paper's test scene: layers of 24 x 24 particles stacked up), `splash` (a "
     "shallow pool, a crown of spikes rising from it and droplets flying off). Setting both "
     "this and `particles.file` is an error.",
     Choice{member<&Scene::particles, &ParticleDesc::procedural>,
           names({"none", "layers", "splash"})}},
    {"particles.files", "\"\"",
     "A time series of particle files (a list, or one glob pattern, sorted), read like "
     "`particles.file`; `time.step` picks the step. The brick grid and the automatic camera "
     "frame the union of every step's particles (rank 0 reads each step once at start).",
     Structured{"list of file names, or a glob pattern"}},
    {"particles.format", "auto",
     "Format of `particles.file`: `vtk`, `raw`, `csv`, `hdf5`, or `auto` (by extension: "
     "`.vtk`/`.vtp`/`.vtu` vtk, `.csv` csv, `.h5`/`.hdf5` hdf5, anything else raw).",
     Choice{member<&Scene::particles, &ParticleDesc::format>,
           names({"auto", "vtk", "raw", "csv", "hdf5"})}},
    {"particles.dataset", "/PartType0/Coordinates",
     "HDF5 snapshots (Gadget/SWIFT/AREPO layout): the N x 3 float32 or float64 dataset of "
     "positions.",
     Text{member<&Scene::particles, &ParticleDesc::dataset>}},
    {"particles.radius_dataset", "\"\"",
     "Per-particle radii from an HDF5 dataset (`SmoothingLength`): not supported, setting it is "
     "an error (every particle has `particles.radius`).",
     Text{member<&Scene::particles, &ParticleDesc::radius_dataset>}},
    // At most 2^31: 24 GiB of centres is surely a typo.
    {"particles.count", "auto",
     "Procedural sets: number of particles (`auto`: 4096). Files: the number the file must "
     "hold (`auto`: whatever it holds; a raw file's size must be a multiple of 12 bytes).",
     Long{member<&Scene::particles, &ParticleDesc::count>,
          {{"in [0, 2147483648]", "must be auto or {allowed}, got {value}"}}},
     AutoValue{}},
    {"particles.spacing", "0.3",
     "Procedural sets: distance between neighbouring particles (world units).",
     Real{member<&Scene::particles, &ParticleDesc::spacing>, {kPositive, kLength}}},
    {"particles.radius", "0.143",
     "Radius of the surface around a lone particle, h (1 - T) (the paper: 0.61 x 0.234375).",
     Real{member<&Scene::particles, &ParticleDesc::radius>, {kPositive, kLength}}},
    {"particles.influence", "auto",
     "h, the radius beyond which a particle adds nothing to the field P(r) = (1 - r/h)^2. "
     "`auto`: particles.radius / (1 - particles.threshold).",
     OptionalReal{member<&Scene::particles, &ParticleDesc::influence>, {kPositive, kLength}},
     AutoValue{}},
    {"particles.threshold", "0.765625",
     "T: the surface is where sqrt(sum of P) = T (the paper's value).",
     Real{member<&Scene::particles, &ParticleDesc::threshold>, {{"in (0, 1)"}}}},
    {"particles.color", "[0.85, 0.9, 1]", "Surface colour [r, g, b].",
     Vector<glm::dvec3>{member<&Scene::particles, &ParticleDesc::colour>, {kColour}}},
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
     "exact (bounds in tests/mpi/particles_slices.sh).",
     Choice{member<&Scene::particles, &ParticleDesc::method>}},
    // Below 1/20 h the lattice needs 8000 points per h^3 (memory and splat time grow as the
    // inverse cube); above h the lattice cannot even hold a lone particle's surface (0.23 h).
    {"particles.slice_spacing", "0.25",
     "`particles.method: slices`: the field's lattice spacing, in units of h. "
     "Depth error grows with it and memory and splat time shrink as its cube "
     "(results/metaballs/).",
     Real{member<&Scene::particles, &ParticleDesc::slice_spacing>,
          {{"in [0.05, 1]", "must be {allowed} (units of h), got {text}"}}}},
    {"particles.step", "0.125",
     "Distance between field samples along a ray, in units of h (the paper: below 1/8 avoids "
     "holes).",
     Real{member<&Scene::particles, &ParticleDesc::step>, {kPositive}}},
    {"particles.max_samples", "96",
     "Cap on field samples per pixel in each brick (samples inside some particle's reach "
     "count); too few leave holes (the paper's Fig. 12). The paper found about 64 enough with "
     "windows of 4; windows of 8 spend more samples in gaps (64 left 1 hole on the dam break "
     "at 512^2, 96 none, for 2% more time). The grid method also samples the rear halves of "
     "spheres, so its samples run out sooner: raise the cap with finer steps (h/12: 144, h/16: 192 "
     "leave no holes on the dam break). With `particles.smoothing: anisotropic` the cap is "
     "multiplied by the larger of `particles.anisotropic.splash_scale` and `surface_scale` (the "
     "field reaches that much further).",
     Int{member<&Scene::particles, &ParticleDesc::max_samples>, {{">= 1"}}}},
    {"particles.refine_iterations", "3",
     "Refinement passes between the last sample outside and the first inside: each evaluates "
     "the secant estimate (the paper's eq. 5), two points close around it and the midpoint, "
     "and keeps the sign change (eq. 6). 0: the secant estimate of the samples alone (the "
     "paper's one linear interpolation).",
     Int{member<&Scene::particles, &ParticleDesc::refine_iterations>, {{">= 0"}}}},
    {"particles.samples_per_pass", "8",
     "Field samples per ray in one pass: 4 (the paper: one RGBA target) or 8 (two targets). "
     "8 needs half the passes (measured 1.4-1.5x faster on llvmpipe) and samples the same "
     "lattice, but runs on through gaps a window of 4 would jump, so a few pixels can differ.",
     Int{member<&Scene::particles, &ParticleDesc::samples_per_pass>, {{"4 or 8"}}}},
    {"particles.cull", "true",
     "Cull particles per screen tile with a min/max pyramid of the rays' sample distances "
     "(the paper's); false: no culling (slower; for checking).",
     Flag{member<&Scene::particles, &ParticleDesc::cull>}},
    {"particles.smoothing", "none",
     "`none`: round metaballs. `anisotropic`: smoothed anisotropic metaballs (Kanamori and "
     "Nishita's, in 3D; ../shared/PAPERS.md §3): each particle's radius grows with its density "
     "from `particles.anisotropic.splash_scale` h (splash) to `surface_scale` h (surface and "
     "inside), and surface particles become ellipsoids along their neighbours' weighted "
     "covariance, normalised to the same mass (io/anisotropic_kernels.h). With "
     "`particles.method: grid` or `slices` (the billboard method refuses it); `slices` draws "
     "them at about round `grid`'s frame time (the lattice's cost does not grow with the "
     "kernels; `grid` walks about 2.8x the list entries: 3x round's time on the dam break at "
     "512^2). `auto`: `anisotropic` when the loaded particles lie closer than the kernel radius "
     "h (at least 10 other particles within h on average, as SPH output: the dam break has "
     "41), else `none` (and `none` with billboards or in situ); --stats says which and "
     "why (`smoothing`).",
     Choice{member<&Scene::particles, &ParticleDesc::smoothing>}},
    {"particles.anisotropic.splash_scale", "1",
     "R_splash / h: radius factor of splash particles (density at most `rho_splash`); a lone "
     "particle is the round metaball of radius h x this.",
     Real{member<&Scene::particles, &ParticleDesc::anisotropic, &AnisotropicParams::splash_scale>,
          {kScale}}},
    {"particles.anisotropic.surface_scale", "1.5",
     "R_surface / h: radius factor of surface and inside particles (density at least "
     "`rho_surface`); smoothstep in between. Larger: smoother, slower (longer cell lists).",
     Real{
         member<&Scene::particles, &ParticleDesc::anisotropic, &AnisotropicParams::surface_scale>,
         {kScale}}},
    {"particles.anisotropic.rho_splash", "3",
     "Density at or below which a particle is splash. Density: the sum over the neighbours "
     "within `neighbourhood` h (itself included) of (1 - r^2/h_n^2)^3, so a lone particle has 1.",
     Real{member<&Scene::particles, &ParticleDesc::anisotropic, &AnisotropicParams::rho_splash>,
          {kDensity}}},
    {"particles.anisotropic.rho_surface", "6",
     "Density at or above which a particle is surface or inside (fully smoothed); above "
     "`rho_splash`.",
     Real{member<&Scene::particles, &ParticleDesc::anisotropic, &AnisotropicParams::rho_surface>,
          {kDensity}}},
    {"particles.anisotropic.neighbourhood", "2.5",
     "h_n / h: radius of the neighbourhood the density, mean and covariance are taken over. "
     "Bricks and ranks hold ghosts this much further out. The default 2.5 (with `rho_splash` 3 "
     "and `rho_surface` 6) makes a resting surface about half as rough as round metaballs' "
     "(dam break pool 8.19 -> 3.93 degrees at 512^2); 1 (with 1.5 and 3) only 0.87x, the "
     "covariance of so few neighbours being noisy (results/metaballs/README.md).",
     Real{
         member<&Scene::particles, &ParticleDesc::anisotropic, &AnisotropicParams::neighbourhood>,
         {{"in [1e-6, 8]", "must be {allowed} (units of h), got {value}"}}}},
    {"particles.anisotropic.max_axis_ratio", "3",
     "Longest over shortest ellipsoid axis, at most (eigenvalues clamped to sigma_1 / k^2): a "
     "plane of particles gives a disc of this ratio, a line a cigar. 1: spheres.",
     Real{member<&Scene::particles, &ParticleDesc::anisotropic,
                 &AnisotropicParams::max_axis_ratio>,
          {{"in [1, 100]", "must be {allowed}, got {value}"}}}},
    {"particles.anisotropic.position_smoothing", "0",
     "lambda: each kernel sits at (1 - lambda) c_i + lambda mu_i, between the particle and the "
     "weighted mean of its neighbours within h_n (Yu and Turk's smoothed centres; the paper's "
     "normalisation integrates around mu_i). Flattens the surface layer. 0: at the particle.",
     Real{member<&Scene::particles, &ParticleDesc::anisotropic,
                 &AnisotropicParams::position_smoothing>,
          {{"in [0, 1]", "must be {allowed}, got {value}"}}}},
  };
}

namespace sortlast {

constexpr long long kDefaultProceduralParticles = 4096;  // particles.count: auto, procedural

// The particles.* rules between keys (each key's own range is the table's).
void checkParticleKeys(const Reader& r, ParticleDesc& p) {
  if (!p.file.empty() && p.procedural != "none")
    throw InputError(
        "scene keys 'particles.file' and 'particles.procedural' are both set: use one "
        "(set particles.procedural to none to read the file)");
  if (r.isAuto("particles.count") && p.file.empty() && p.procedural != "none")
    p.count = kDefaultProceduralParticles;
  if (!p.radius_dataset.empty())
    throw InputError("scene key 'particles.radius_dataset': per-particle radii (" + p.radius_dataset +
                     ") are not supported: every particle has particles.radius; remove the key");
  validateAnisotropic(p.anisotropic);
  if (p.anisotropicOn() && p.method == ParticleMethod::kBillboards) {
    const std::string method(nameOf(p.method));
    throw InputError("scene key 'particles.smoothing': anisotropic needs particles.method: grid or slices (the " +
                     method + " method draws round particles only); got particles.method: " + method);
  }
}

}  // namespace sortlast
