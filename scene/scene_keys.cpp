// The table of every scene key (scene/scene_keys.h). Scripts outside the project use these
// names: keep them.
#include "scene/scene_keys.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "scene/scene.h"

namespace sortlast {

namespace {

[[noreturn]] void unreadable(const std::string& phrase) {
  throw std::logic_error("scene key table: cannot read the allowed values '" + phrase + "'");
}

bool consume(std::string_view& s, std::string_view prefix) {
  if (!s.starts_with(prefix)) return false;
  s.remove_prefix(prefix.size());
  return true;
}

// A bound as written: a number, a/b or a^b.
double readBound(std::string_view& s, std::string& text, const std::string& phrase) {
  const std::string rest(s);
  char* end = nullptr;
  double v = std::strtod(rest.c_str(), &end);
  size_t n = size_t(end - rest.c_str());
  if (n == 0 || std::isnan(v)) unreadable(phrase);
  if (n < rest.size() && (rest[n] == '/' || rest[n] == '^')) {
    char* end2 = nullptr;
    const double w = std::strtod(rest.c_str() + n + 1, &end2);
    if (end2 == rest.c_str() + n + 1) unreadable(phrase);
    v = rest[n] == '/' ? v / w : std::pow(v, w);
    n = size_t(end2 - rest.c_str());
  }
  text = rest.substr(0, n);
  s.remove_prefix(n);
  return v;
}

std::string joined(const std::vector<std::string>& items, const char* last) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? last : ", ") + items[i];
  return out;
}

}  // namespace

Allowed::Allowed(const char* phrase) : phrase_(phrase) {
  std::string_view s = phrase_;
  if (consume(s, "a finite number "))
    finite_ = true;
  else if (consume(s, "integers "))
    integer_ = true;
  else if (consume(s, "a power of two "))
    integer_ = power_of_two_ = true;
  const bool interval = consume(s, "in ");
  range_ = std::string(s);
  if (interval) {
    if (s.empty() || (s[0] != '[' && s[0] != '(')) unreadable(phrase_);
    lo_open_ = s[0] == '(';
    s.remove_prefix(1);
    lo_ = readBound(s, lo_text_, phrase_);
    if (!consume(s, ", ")) unreadable(phrase_);
    hi_ = readBound(s, hi_text_, phrase_);
    if (s.size() != 1 || (s[0] != ']' && s[0] != ')') || !(lo_ < hi_)) unreadable(phrase_);
    hi_open_ = s[0] == ')';
    s.remove_prefix(1);
  } else if (consume(s, ">= ")) {
    lo_ = readBound(s, lo_text_, phrase_);
  } else if (consume(s, "> ")) {
    lo_open_ = true;
    lo_ = readBound(s, lo_text_, phrase_);
  } else {  // a list: "4 or 8"
    std::string text;
    do list_.push_back(readBound(s, text, phrase_));
    while (consume(s, " or "));
    if (list_.size() < 2) unreadable(phrase_);
  }
  if (!s.empty()) unreadable(phrase_);
}

bool Allowed::admits(double v) const {
  if (std::isnan(v) || (finite_ && !std::isfinite(v)) || (integer_ && v != std::floor(v)))
    return false;
  if (!list_.empty()) return std::find(list_.begin(), list_.end(), v) != list_.end();
  if (lo_open_ ? !(v > lo_) : !(v >= lo_)) return false;
  if (hi_open_ ? !(v < hi_) : !(v <= hi_)) return false;
  if (power_of_two_) {
    const auto n = static_cast<unsigned long long>(v);  // in range, so finite and >= 1
    return (n & (n - 1)) == 0;
  }
  return true;
}

Allowed Allowed::within(const Allowed& other) const {
  if (isList()) return *this;
  if (other.isList()) return other;
  Allowed r = *this;
  if (other.lo_ > r.lo_ || (other.lo_ == r.lo_ && other.lo_open_))
    r.lo_ = other.lo_, r.lo_open_ = other.lo_open_, r.lo_text_ = other.lo_text_;
  if (other.hi_ < r.hi_ || (other.hi_ == r.hi_ && other.hi_open_))
    r.hi_ = other.hi_, r.hi_open_ = other.hi_open_, r.hi_text_ = other.hi_text_;
  r.finite_ = r.finite_ || other.finite_;
  r.integer_ = r.integer_ || other.integer_;
  r.power_of_two_ = r.power_of_two_ || other.power_of_two_;
  return r;
}

std::string Allowed::describe() const {
  if (isList()) return range_;
  const bool low = std::isfinite(lo_), high = std::isfinite(hi_);
  std::string bounds;
  if (low && high)
    bounds = "in " + std::string(lo_open_ ? "(" : "[") + lo_text_ + ", " + hi_text_ +
             (hi_open_ ? ")" : "]");
  else if (low)
    bounds = (lo_open_ ? "> " : ">= ") + lo_text_;
  else if (high)
    bounds = (hi_open_ ? "< " : "<= ") + hi_text_;
  return power_of_two_ ? "power of two " + bounds : bounds;
}

std::string fillMessage(std::string_view key, std::string_view says,
                        const std::vector<std::pair<std::string_view, std::string>>& values) {
  std::string out;
  bool names_key = false;
  for (size_t i = 0; i < says.size();) {
    const size_t open = says.find('{', i);
    out += says.substr(i, open - i);
    if (open == std::string_view::npos) break;
    const size_t close = says.find('}', open);
    const std::string_view name = says.substr(open + 1, close - open - 1);
    if (name == "key") {
      out += key;
      names_key = true;
    } else {
      auto it = std::find_if(values.begin(), values.end(),
                             [&](const auto& v) { return v.first == name; });
      if (close == std::string_view::npos || it == values.end())
        throw std::logic_error("scene key table: message '" + std::string(says) + "' has no {" +
                               std::string(name) + "}");
      out += it->second;
    }
    i = close + 1;
  }
  return names_key ? out : "scene key '" + std::string(key) + "': " + out;
}

std::string Check::error(std::string_view key, const std::string& value,
                         const std::string& text) const {
  return fillMessage(key, says ? says : "must be {allowed}",
                     {{"allowed", allowed.phrase()},
                      {"range", allowed.range()},
                      {"value", value},
                      {"text", text}});
}

std::string choiceError(std::string_view key, std::string_view says,
                        const std::vector<std::string>& names, const std::string& text) {
  return fillMessage(
      key, says, {{"names", joined(names, " or ")}, {"list", joined(names, ", ")}, {"text", text}});
}

namespace {

std::vector<std::pair<const char*, std::string>> names(std::initializer_list<const char*> list) {
  std::vector<std::pair<const char*, std::string>> out;
  for (const char* n : list) out.emplace_back(n, n);
  return out;
}

using Real = Number<double>;
using OptionalReal = Number<std::optional<double>>;
using Int = Number<int>;
using Long = Number<long long>;
using Names = Choice<std::string>;

// One row per key: its path, its default (YAML), its help, its type (where the value goes and
// what it may be), and AutoValue where `auto` is one of its values.
std::vector<SceneKey> makeTable() {
  // Float math on the GPU (common/box.h): the lengths it can hold, the coordinates it can square.
  const Check kLength{"in [1e-12, 1e18]",
                      "{value} is outside {range}, the lengths float math on the GPU can hold"};
  const Check kCoordinate{
      "in [-1e18, 1e18]",
      "{value} is beyond +-1e18, which float math on the GPU cannot hold (it squares distances)"};
  const Check kPositive{"a finite number > 0"};
  const Check kColour{"in [0, 1]", "entries must be {allowed}"};
  // Checked by parseScene with both sizes in the message.
  const Check kImageSize{"in [1, 32768]", nullptr};
  // Radii beyond 8 h would make every particle's reach (and the bricks' ghost margins) huge;
  // below 1/64 h the field falls between the ray caster's samples (step h/8).
  const Check kScale{"in [1/64, 8]", "must be {allowed} (units of h), got {value}"};
  const Check kDensity{"in [0, 1e9]", "must be {allowed}, got {value}"};
  return {
      {"volume.file", "\"\"",
       "Data file. Empty: a procedural volume (`volume.procedural`). `.vti`: a VTK XML image, each "
       "rank reading its bricks' extent; `.vtk`: a legacy VTK image, read whole by rank 0 and "
       "scattered; `.nrrd`/`.nhdr`: NRRD (raw or gzip encoding, read per brick; docs/data.md); "
       "`.h5`/`.hdf5`: an HDF5 dataset (`volume.dataset`), each rank reading its bricks "
       "collectively through MPI-IO; `.nc`: a NetCDF variable (`volume.variable`), read per brick "
       "(docs/data_hdf5_netcdf.md). For these the file gives dims, spacing and type. Anything else: "
       "raw samples, x fastest, no header unless `volume.header_bytes`. Relative paths are relative "
       "to the scene file.",
       Text{member<&Scene::volume, &VolumeDesc::file>, true}},
      {"volume.format", "auto",
       "How `volume.file` is read: `raw`, `vtk` (.vti or legacy .vtk), `nrrd`, `hdf5`, `netcdf`, or "
       "`auto`: by its extension (`.vti`/`.vtk` vtk, `.nrrd`/`.nhdr` nrrd, `.h5`/`.hdf5` hdf5, `.nc` "
       "netcdf, anything else raw).",
       Names{member<&Scene::volume, &VolumeDesc::format>,
             names({"auto", "raw", "vtk", "nrrd", "hdf5", "netcdf"})}},
      {"volume.dataset", "\"\"",
       "HDF5: the path of the 3-D dataset to read (`/fields/density`). Empty: the file's only 3-D "
       "dataset (a file with several needs this key). Its type gives the samples' (uint8, uint16, "
       "int16, float32, float64; others are refused). With `{step}` (`/step_{step}/density`) the "
       "file is a time series: steps 0, 1, 2, ... (no padding) while their datasets exist, "
       "`time.step` picks one.",
       Text{member<&Scene::volume, &VolumeDesc::dataset>}},
      {"volume.variable", "\"\"",
       "NetCDF: the variable to read, 3-D, or 4-D with an unlimited (or `time`) first dimension: "
       "a time series, one step per record (`time.step` picks it). Empty: the file's only such variable. Coordinate variables (1-D, "
       "named like a dimension) give the spacing when uniform (within 1e-6 relative; non-uniform "
       "ones are refused); samples equal to `_FillValue` or `missing_value` are missing: a point "
       "whose trilinear stencil touches one is transparent (not with `adaptive.tolerance`).",
       Text{member<&Scene::volume, &VolumeDesc::variable>}},
      {"volume.axis_order", "zyx",
       "HDF5 and NetCDF: which axis each dimension of the array is, slowest (first) to fastest "
       "(last). Both store arrays in C order, so `zyx` (what NumPy's `a[z, y, x]` writes) makes "
       "the last dimension x (a Fortran `a(nx, ny, nz)` written through the Fortran API is stored "
       "so too); `xyz` makes the first dimension x (NumPy's `a[x, y, z]`).",
       Names{member<&Scene::volume, &VolumeDesc::axis_order>, names({"zyx", "xyz"})}},
      {"volume.spacing_attribute", "\"\"",
       "HDF5: the attribute (of the dataset, else of the root group) holding the spacing, three "
       "numbers in the dataset's dimension order (`zyx`: [dz, dy, dx]). Empty: `volume.spacing`.",
       Text{member<&Scene::volume, &VolumeDesc::spacing_attribute>}},
      {"volume.origin_attribute", "\"\"",
       "HDF5: the attribute holding the origin (three numbers, dimension order). It is read and "
       "checked (finite numbers) but does not move the volume: sortlast centres every volume on "
       "the world origin.",
       Text{member<&Scene::volume, &VolumeDesc::origin_attribute>}},
      {"volume.mpi_io", "auto",
       "HDF5: how the ranks read their bricks through MPI-IO: `collective` (one collective "
       "H5Dread per brick: MPI-IO may aggregate the ranks' requests, what a parallel file system "
       "wants at scale), `independent` (each rank reads alone: on one node or a local disk it "
       "was faster and held less memory, results/io) or `auto`: collective when the ranks span "
       "more than one node, independent on one.",
       Names{member<&Scene::volume, &VolumeDesc::mpi_io>, names({"auto", "collective", "independent"})}},
      {"volume.procedural", "blobs",
       "Procedural field when there is no file: `blobs` (shells, blobs and a torus), "
       "`marschner_lobb` (the Marschner-Lobb test signal), `sphere` (1 - r), or `none`: no "
       "volume (the scene must then have particles).",
       Text{member<&Scene::volume, &VolumeDesc::procedural>}},
      {"volume.files", "\"\"",
       "A time series: one data file per step, as a list of names or one glob pattern "
       "(`step_*.raw`; matches sorted by name). Each file is read like `volume.file` (same dims, "
       "type and layout for every step); `time.step` picks the step. Excludes `volume.file`.",
       Structured{"list of file names, or a glob pattern"}},
      {"volume.dims", "[128, 128, 128]", "Samples per axis [x, y, z] (raw and procedural volumes).",
       Vector<glm::ivec3>{member<&Scene::volume, &VolumeDesc::grid, &GridGeometry::dims>,
                          {{"integers in [2, 2^20]", "entries must be {allowed}"}}}},
      {"volume.type", "uint8", "Raw sample type.",
       Choice<SampleType>{member<&Scene::volume, &VolumeDesc::type>,
                          {{"uint8", SampleType::kUint8},
                           {"uint16", SampleType::kUint16},
                           {"int16", SampleType::kInt16},
                           {"float32", SampleType::kFloat32},
                           {"float64", SampleType::kFloat64}},
                          "{key}: unknown type '{text}' (known: {list})"}},
      {"volume.spacing", "[1, 1, 1]", "Distance between samples along x, y, z (world units).",
       Vector<glm::dvec3>{member<&Scene::volume, &VolumeDesc::grid, &GridGeometry::spacing>,
                          {kLength}}},
      {"volume.byte_order", "little", "Byte order of raw samples.",
       Choice<bool>{member<&Scene::volume, &VolumeDesc::big_endian>,
                    {{"little", false}, {"big", true}}}},
      {"volume.header_bytes", "0", "Bytes to skip at the start of a raw file.",
       Long{member<&Scene::volume, &VolumeDesc::header_bytes>, {{">= 0"}}}},
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
       Names{member<&Scene::particles, &ParticleDesc::procedural>,
             names({"none", "layers", "splash"})}},
      {"particles.files", "\"\"",
       "A time series of particle files (a list, or one glob pattern, sorted), read like "
       "`particles.file`; `time.step` picks the step. The brick grid and the automatic camera "
       "frame the union of every step's particles (rank 0 reads each step once at start).",
       Structured{"list of file names, or a glob pattern"}},
      {"particles.format", "auto",
       "Format of `particles.file`: `vtk`, `raw`, `csv`, `hdf5`, or `auto` (by extension: "
       "`.vtk`/`.vtp`/`.vtu` vtk, `.csv` csv, `.h5`/`.hdf5` hdf5, anything else raw).",
       Names{member<&Scene::particles, &ParticleDesc::format>,
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
       Names{member<&Scene::particles, &ParticleDesc::method>,
             names({"billboards", "grid", "slices"})}},
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
       "covariance, normalised to the same mass (io/anisotropic_kernels.h). Only with "
       "`particles.method: grid` (the billboard method refuses it).",
       Names{member<&Scene::particles, &ParticleDesc::smoothing>, names({"none", "anisotropic"})}},
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
      {"transfer.preset", "default",
       "Control points to use when `transfer.points` is not given: `default`, `ramp` (the "
       "paper's opacity = value, grey) or `sharp` (a narrow opaque band).",
       Structured{"preset name"}},
      {"transfer.points", "null",
       "List of control points `[value, r, g, b, a]`, all in [0, 1], values increasing; value "
       "is normalised over `transfer.range`. Colour and opacity are linear between points.",
       Structured{"list of [value, r, g, b, a]"}},
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
       "each request). A request to `sortlast serve` may name a built-in only.",
       Structured{"colour map name, or FILE.json[#Name]"}},
      {"transfer.range", "auto",
       "Data values `[lo, hi]` that map to 0 and 1. `auto`: the volume's minimum and maximum.",
       Structured{"`auto` or [lo, hi]",
                  {{"in [-1e38, 1e38]", "{value} is beyond float's range (+-3.4e38)"}}}},
      {"transfer.unit_length", "auto",
       "World length over which a sample has the opacity `a` of the transfer function; other "
       "sample spacings are corrected with 1 - (1 - a)^(ds / unit_length). `auto`: the "
       "smallest voxel spacing.",
       OptionalReal{member<&Scene::transfer, &TransferSpec::unit_length>, {kLength}}, AutoValue{}},
      {"transfer.table_size", "4096", "Entries in the transfer-function lookup table used by GL.",
       Int{member<&Scene::transfer, &TransferSpec::table_size>, {{"in [2, 65536]"}}}},
      {"transfer.preintegrated", "auto",
       "`auto`: true where the opacity changes steeply (by 0.5 or more within 10 % of the range "
       "between two control points), where it pays; false on smooth functions, where it does not, "
       "and where it is not supported (`adaptive.tolerance` above 0, `render.sample_spacing` above "
       "2). Pre-integrated transfer function (Engel, Kraus and Ertl 2001) in both GL volume renderers: "
       "each ray segment between two samples takes the exact emission-absorption integral of a "
       "value going linearly from its front to its back value, from a 256 x 256 table rebuilt when "
       "the transfer function or the sample spacing changes (about 30 ms). Coarse steps stay "
       "accurate on sharp transfer functions. Needs `render.sample_spacing` <= 2 (so segment ends "
       "stay within the bricks' ghost layer) and `adaptive.tolerance` 0.",
       Flag{member<&Scene::transfer, &TransferSpec::preintegrated>}, AutoValue{}},
      {"image.width", "512", "Image width in pixels.",
       Int{member<&Scene::camera, &Camera::width>, {kImageSize}}},
      {"image.height", "512", "Image height in pixels.",
       Int{member<&Scene::camera, &Camera::height>, {kImageSize}}},
      {"image.background", "[0, 0, 0]",
       "Colour the frame is composited over when written (premultiplied images stay exact).",
       Vector<glm::dvec3>{member<&Scene::background>}},
      {"camera.position", "auto",
       "Eye position. `auto`: along (0.55, 0.35, 1) from `camera.look_at`, just far enough that "
       "the bounding sphere of the scene's bounds (the volume box, grown to hold the particles' "
       "domain) fits the vertical and the horizontal field of view. Must lie outside the volume.",
       Vector<glm::dvec3>{member<&Scene::camera, &Camera::position>, {kCoordinate}},
       AutoValue{member<&Scene::camera_auto>}},
      {"camera.look_at", "auto",
       "Point the camera looks at. `auto`: the centre of the scene's bounds (the volume box, "
       "grown to hold the particles' domain; for a volume alone, the origin).",
       Vector<glm::dvec3>{member<&Scene::camera, &Camera::look_at>, {kCoordinate}},
       AutoValue{member<&Scene::look_at_auto>}},
      {"camera.up", "[0, 1, 0]", "Up direction; also the axis of the orbit.",
       Vector<glm::dvec3>{
           member<&Scene::camera, &Camera::up>,
           {kCoordinate,
            {">= 1e-12", "must not be zero (its length must be at least 1e-12)", true}}}},
      {"camera.fov", "35", "Vertical field of view in degrees.",
       Real{member<&Scene::camera, &Camera::fov_deg>,
            {{"in (0, 180)", "must be {allowed} degrees"}}}},
      {"camera.orbit.frames", "0",
       "0: a single view. N > 0: the paper's orbit, N frames 360/N degrees apart on a circle "
       "around `camera.look_at`, written as a numbered series (out_0000.png, ...).",
       Int{member<&Scene::orbit_frames>, {{">= 0"}}}},
      {"camera.orbit.elevation", "0", "Tilt of the orbit circle in degrees.",
       Real{member<&Scene::orbit_elevation>, {{"in [-90, 90]", "must be {allowed} degrees"}}}},
      {"camera.orbit.radius", "auto",
       "Orbit radius. `auto`: 2 x the largest extent of the scene's bounds (the volume box, "
       "grown to hold the particles' domain; the paper's R, kept for the benchmark protocol: it "
       "may crop a wide scene, which `camera.position: auto` does not).",
       OptionalReal{member<&Scene::orbit_radius>, {{"> 0"}, kLength}}, AutoValue{}},
      {"bricks.per_axis", "auto",
       "d: the scene is cut into d x d x d bricks. `auto`: 2, but 1 for a scene of glow emitters "
       "alone (their integral splits anywhere, so one brick draws them in one pass; docs/glow.md).",
       Int{member<&Scene::bricks_per_axis>, {{"in [1, 64]"}}}, AutoValue{}},
      {"render.backend", "osmesa",
       "OpenGL backend: `osmesa` (software) or `egl` (surfaceless platform, or the device "
       "platform on an NVIDIA GPU).",
       Names{member<&Scene::backend>, names({"osmesa", "egl"})}},
      {"render.device", "auto",
       "EGL on a node with GPUs: which hardware EGL device a rank renders on (Mesa's software "
       "device is not counted). `auto`: (the rank's index on its node) mod (the node's devices), "
       "so a node's ranks spread over its GPUs; N: device N. A device that cannot be opened ends "
       "the job with its number and the rank; with no hardware device, `auto` falls back to the "
       "surfaceless platform (llvmpipe). Only with `render.backend: egl` (docs/cluster.md).",
       Int{member<&Scene::device>, {{"integers in [0, 63]", "must be auto or a device number {allowed}, got {value}"}}},
       AutoValue{}},
      {"render.sample_spacing", "auto",
       "Distance between slices (ray casting: between samples along each ray), in units of "
       "the smallest voxel spacing (the paper: 1). `auto`: 0.5, 1 or 2, the largest whose own "
       "error, estimated from small probe frames of the scene's automatic view at all three steps, "
       "stays within 52 dB (session/auto_spacing.h); probed again when the transfer "
       "function, the renderer's settings, the time step or the image size change, not the camera; "
       "`--stats` gives "
       "the choice and the estimates. 0.5 (the fixed default before) with ray casting and "
       "`transfer.preintegrated: auto` reaches 45 dB on the benchmark's four data sets "
       "(results/accuracy).",
       Real{member<&Scene::sample_spacing>, {{"in [0.01, 100]", "must be {allowed} voxels"}}},
       AutoValue{member<&Scene::sample_spacing_auto>}},
      {"render.block_cells", "64",
       "Slicing: empty-space skipping; bricks are cut into blocks of this many cells per axis, and "
       "blocks whose values all map to zero opacity are not drawn (ray casting: "
       "`render.ray_block_cells`).",
       Int{member<&Scene::block_cells>, {{">= 1"}}}},
      {"render.ray_block_cells", "8",
       "Ray casting: cells per axis of the blocks rays walk, on one grid aligned to the volume (the "
       "same in every decomposition; a brick's outer blocks are cut by its faces). A block whose "
       "values all map to zero opacity is jumped, and with its neighbours at once: each block knows "
       "its distance to the nearest block that is not empty. Also the blocks whose range picks the "
       "step of `render.adaptive_step`. (`render.block_cells` is the slicing renderer's.)",
       Int{member<&Scene::ray_block_cells>, {{">= 1"}}}},
      {"render.method", "raycast",
       "Volume renderer: `slicing` (3D-texture slicing, the paper's) or `raycast` (a GL ray caster "
       "per brick, front to back on samples `render.sample_spacing` apart along each ray, with "
       "early ray termination and empty blocks jumped along the ray).",
       Names{member<&Scene::volume_method>, names({"slicing", "raycast"})}},
      {"render.ert_threshold", "0.99",
       "Ray casting: a ray stops once its opacity reaches this; 1: never early. It "
       "stops only inside a brick (bricks behind still render), and changes a pixel by at most "
       "1 - threshold.",
       Real{member<&Scene::ert_threshold>,
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
       Flag{member<&Scene::shading, &Shading::enabled>}},
      {"render.shading_ambient", "0.3", "Gradient shading: ka, the ambient term.",
       Real{member<&Scene::shading, &Shading::ambient>, {{"in [0, 100]"}}}},
      {"render.shading_diffuse", "0.7", "Gradient shading: kd, the diffuse term.",
       Real{member<&Scene::shading, &Shading::diffuse>, {{"in [0, 100]"}}}},
      {"render.shading_specular", "0.2",
       "Gradient shading: ks, the specular term, a white highlight added to the colour.",
       Real{member<&Scene::shading, &Shading::specular>, {{"in [0, 100]"}}}},
      {"render.shading_shininess", "20",
       "Gradient shading: p, the specular exponent.",
       Real{member<&Scene::shading, &Shading::shininess>, {{"in [1, 1000]"}}}},
      {"render.adaptive_step", "false",
       "Ray casting: adaptive steps. Each block (`render.ray_block_cells`) takes every m-th sample "
       "of the rays' lattice (m = 1, 2, 4 or 8; each sample standing for the m steps around it, "
       "opacity corrected for their length), the largest m with m x spacing x (the most the "
       "transfer function's opacity or emission varies over the block's values) <= "
       "`render.adaptive_tolerance`, and m x spacing <= 2 voxels. Blocks over steep parts of the "
       "transfer function keep every sample; the lattice stays shared, so ranks and brick faces "
       "agree as without it.",
       Flag{member<&Scene::adaptive_step>}},
      {"render.adaptive_tolerance", "0.02",
       "Ray casting with `render.adaptive_step`: the most one coarse sample's optical depth (and "
       "emission) may be off, by the bound above.",
       Real{member<&Scene::adaptive_step_tolerance>, {{"in (0, 1]"}}}},
      {"adaptive.tolerance", "0",
       "Adaptive sampling (the paper's section 4.2), in percent: each block of the volume is stored at the "
       "coarsest resolution (halved step by step, a coarse sample the mean of the fine cells "
       "around it) whose error stays within this: the block's squared error against the original "
       "(the paper's eq. 3) at most (tolerance/100)^2 x its sum of squared values, i.e. an RMS "
       "error of at most this percent of its RMS value. 0: off (the original samples; the "
       "preprocessing at 0 is lossless). See `sortlast adaptive-stats`. Above 0 "
       "the volume is rendered from the blocks, each sampled at its own resolution along the rays "
       "(needs `render.method: raycast`; its blocks replace `render.block_cells`), and every rank "
       "reads the whole volume to build them.",
       Real{member<&Scene::adaptive_tolerance>, {{"in [0, 100]", "must be {allowed} percent"}}}},
      {"adaptive.blocks", "8",
       "Adaptive sampling: b, the blocks per axis of the whole volume (the paper: 4, 8, 16). "
       "Blocks have the smallest power-of-two size s with b x s >= the "
       "cells per axis, so there may be fewer than b per axis; they do not depend on "
       "`bricks.per_axis`.",
       Int{member<&Scene::adaptive_blocks>,
           {{"a power of two in [1, 256]", "must be {allowed}, got {value}"}}}},
      {"adaptive.steps", "own",
       "Adaptive sampling, along the rays: `own` (a block at level L, whose samples are 2^L cells "
       "apart, is rendered at its own resolution: every 2^L-th sample of the ray lattice, each "
       "standing for 2^L steps) or `fine` (every block at every step: the adaptive field's "
       "accuracy at the full sampling cost, to tell what the data reduction costs from what the "
       "fewer samples cost).",
       Names{member<&Scene::adaptive_steps>, names({"own", "fine"})}},
      {"compositing.strategy", "direct",
       "How brick images reach rank 0: `direct` (every brick image to rank 0, which blends them "
       "all), `binary-swap` (each rank blends its own bricks, then pairs of ranks swap halves of "
       "their image for log2 P rounds and rank 0 gathers the pieces), `radix-k` (the same with "
       "`compositing.radix` partners per round) or `auto` (each frame, whichever of direct and "
       "radix-k with k = 2, 4, 8, 16, 32 a cost model forecasts fastest for the rank count, image "
       "size and the bricks' screen rectangles, with the network of `compositing.latency_us` and "
       "`compositing.bandwidth_gbps`; every rank makes the same choice, and --stats says which and "
       "why: docs/compositing.md). Any rank count: ranks beyond the largest count the rounds can "
       "take first fold their image into a neighbour's.",
       Names{member<&Scene::strategy>, names({"direct", "binary-swap", "radix-k", "auto"})}},
      {"compositing.latency_us", "40",
       "`auto`: one message's latency between two ranks, microseconds (40: 10 Gbit/s Ethernet "
       "through one switch; about 2-5 for InfiniBand or a fat tree, 1 between ranks of one node).",
       Real{member<&Scene::network_latency_us>, {{"in [0, 1e6]", "must be {allowed} us"}}}},
      {"compositing.bandwidth_gbps", "10",
       "`auto`: one rank's link bandwidth, each way, Gbit/s (10 GbE; 100 for EDR InfiniBand).",
       Real{member<&Scene::network_gbps>, {{"in [0.001, 1e5]", "must be {allowed} Gbit/s"}}}},
      {"compositing.radix", "4",
       "k of `radix-k`: the most partners per round (2 is binary-swap; a round uses fewer "
       "where the rank count has no factor that large).",
       Int{member<&Scene::radix>, {{">= 2"}}}},
      {"compositing.precision", "float",
       "`float`: blend in float and round to 8 bits once per frame (swap strategies send partial "
       "composites at 16 bits), so every strategy and rank count gives the same frame within "
       "1/255; an `.exr` output then holds the unrounded frame. `rgba8`: the paper's 8-bit "
       "intermediate images (direct send rounds after every blend, swap strategies send 8-bit "
       "partials): fewer bytes, up to half a step of error per blend or round.",
       Names{member<&Scene::precision>, names({"float", "rgba8"})}},
      {"compositing.overlap", "true",
       "Direct send: each brick image is sent as soon as it is rendered, while the next brick "
       "renders, and rank 0 blends images as their visibility order allows. false: all images are "
       "sent after the last brick (to measure what overlap gains). The swap strategies need all "
       "of a rank's bricks first and ignore it.",
       Flag{member<&Scene::overlap>}},
      {"compositing.rle", "true",
       "Run-length code transparent runs in every image message (the paper's Fig. 7). false: every "
       "pixel travels (to measure what RLE saves).",
       Flag{member<&Scene::rle>}},
      {"time.step", "0",
       "The time step to render, 0 ... steps - 1 (a scene with `volume.files`, "
       "`particles.files`, a 4-D NetCDF `volume.variable` or an HDF5 `volume.dataset` with "
       "`{step}`; otherwise only 0).",
       Int{member<&Scene::time_step>}},
      {"time.cache_mib", "1024",
       "A resident session (`sortlast serve`) keeps the samples and particles of recent time steps "
       "in memory, up to this many MiB per rank, so going back to a step needs no reading.",
       Real{member<&Scene::time_cache_mib>, {{"in [0, 1e9]", "must be {allowed} MiB"}}}},
      {"limits.memory_mib", "auto",
       "Memory a rank may use, MiB; scenes estimated to need more are refused before loading. "
       "`auto`: 90% of MemAvailable (/proc/meminfo), shared by the ranks on the node.",
       OptionalReal{member<&Scene::memory_limit_mib>,
                    {{"in (0, 1e12]", "must be auto or {allowed} MiB"}}},
       AutoValue{}},
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
       "`compositing.precision: rgba8` and in situ (docs/glow.md).",
       Structured{"list of emitters"}},
      {"glow.core_radius", "0.01",
       "eps, the emitters' core radius (world units): it keeps the field finite at the "
       "centre and on the axis, where with eps = 0 the integral along a ray through them diverges.",
       Real{member<&Scene::glow, &GlowSpec::core_radius>, {kLength}}},
      {"glow.intensity", "1",
       "Glow radiance per unit of integrated field (times each emitter's color).",
       Real{member<&Scene::glow, &GlowSpec::intensity>, {{"in [0, 1e30]"}}}},
      {"glow.tone_map", "none",
       "`none` (radiance clamped to [0, 1] when written) or `exponential`: 1 - exp(-glow.exposure "
       "x radiance) per channel. Applied once to the final composited frame (volume included: "
       "after compositing, glow and volume light are one sum), never per brick: the map is not "
       "additive, so per-brick mapping would change with the decomposition.",
       Names{member<&Scene::glow, &GlowSpec::tone_map>, names({"none", "exponential"})}},
      {"glow.exposure", "1", "k of the exponential tone map.",
       Real{member<&Scene::glow, &GlowSpec::exposure>, {{"in (0, 1e30]"}}}},
      {"glow.box", "auto",
       "`[[x0, y0, z0], [x1, y1, z1]]`: the box the glow is integrated in (the field's integral "
       "along an unbounded ray diverges like log length). `auto`: the scene's bounds (volume and "
       "particles); a scene of emitters alone must set it.",
       Structured{"`auto` or [[x0, y0, z0], [x1, y1, z1]]", {kCoordinate}}},
      {"surfaces", "[]",
       "Catmull-Clark subdivision surfaces drawn exactly (docs/subdivision.md), opaque, composited "
       "with the volume and particles: a list of maps. Each has exactly one of `file` (an OBJ "
       "file, relative to the scene file; faces of any size; manifold meshes, closed or with "
       "boundaries (OpenSubdiv's edge-and-corner boundary rules unless the file's `t "
       "interpolateboundary` says otherwise; open surfaces are two-sided), with OpenSubdiv's "
       "subdivision tags `t crease`, `t corner`, `t hole`, `t interpolateboundary`, `t creasemethod`) "
       "and `procedural` (`cube`, `torus`, `pole<N>` for N = "
       "3 ... 32, `prism<N>`, `octahedron`, open ones: `open_grid`, `fan<N>` for N = 1 ... 12, and "
       "tagged ones: `cube_crease<S>` and `cube_corner<S>` for a sharpness S (a number up to 10 or "
       "`inf`), `cube_chaikin`, `lathe`, `lathe<N>`, `open_grid_edge_only`, `open_grid_none`), "
       "and optionally: `color` [r, g, b] in "
       "[0, 1] (default [0.8, 0.8, 0.85]); `transform`, either `{scale: s | [sx, sy, sz], rotate: "
       "[x, y, z] (degrees, about x then y then z), translate: [x, y, z]}` applied scale, rotate, "
       "translate, or a 4 x 4 matrix (4 rows, last 0 0 0 1); `level` 1 ... 3 (default 2): how often "
       "the control mesh is subdivided for the rasterised coarse mesh, which decides coverage at "
       "silhouettes; `shading` `headlight` (default) or `reflection_lines` with `stripes` (default "
       "12), `stripe_width` in (0, 1) (default 0.3) and `stripe_direction` [x, y, z] (the striped "
       "light's normal, default [0, 1, 0]); `newton_steps` 0 ... 8 (default 3) per fragment onto "
       "its pixel's ray. Every mesh is read and checked when the scene is read: a bad one is an "
       "error naming `surfaces[i]`.",
       Structured{"list of surfaces"}},
      {"reference.step", "0.0625",
       "Step of the CPU reference integrator, in units of the smallest voxel spacing.",
       Real{member<&Scene::reference_step>, {{"in (0, 1]", "must be {allowed} voxels"}}}},
      {"reference.field", "original",
       "The field the CPU reference integrates (`sortlast reference`, `render --psnr`): "
       "`original` (the volume's samples, trilinear) or `adaptive` (the adaptive-sampling field "
       "of `adaptive.tolerance` and `adaptive.blocks`, exactly as the ray caster's adaptive blocks "
       "hold it: to measure the renderer apart from what adaptive sampling itself costs).",
       Names{member<&Scene::reference_field>, names({"original", "adaptive"})}},
  };
}

}  // namespace

const std::vector<SceneKey>& sceneKeys() {
  static const std::vector<SceneKey> keys = makeTable();
  return keys;
}

const SceneKey* findSceneKey(std::string_view path) {
  for (const SceneKey& k : sceneKeys())
    if (path == k.path) return &k;
  return nullptr;
}

const SceneKey& sceneKey(std::string_view path) {
  if (const SceneKey* k = findSceneKey(path)) return *k;
  throw std::logic_error("no scene key '" + std::string(path) + "' in the table");
}

const std::vector<Check>& sceneKeyChecks(std::string_view path) {
  static const std::vector<Check> none;
  return std::visit(
      [](const auto& type) -> const std::vector<Check>& {
        if constexpr (requires { type.checks; })
          return type.checks;
        else
          return none;
      },
      sceneKey(path).type);
}

namespace {

// What the checks of a number (or of each entry of a list) allow together, for the docs.
std::string bounds(const std::vector<Check>& checks) {
  std::optional<Allowed> all;
  for (const Check& c : checks)
    if (!c.of_length) all = all ? all->within(c.allowed) : c.allowed;
  return all ? all->describe() : "";
}

std::string lengthBounds(const std::vector<Check>& checks) {
  for (const Check& c : checks)
    if (c.of_length) return "length " + c.allowed.describe();
  return "";
}

// The non-empty parts, joined.
std::string sentence(std::initializer_list<std::string> parts, const char* separator = " ") {
  std::string out;
  for (const std::string& p : parts)
    if (!p.empty()) out += (out.empty() ? "" : separator) + p;
  return out;
}

template <class T>
std::string values(const Number<T>& n) {
  const bool listed = std::any_of(n.checks.begin(), n.checks.end(),
                                  [](const Check& c) { return c.allowed.isList(); });
  const std::string b = bounds(n.checks);
  if (listed || b.starts_with("power of two")) return b;  // "4 or 8": integers anyway
  return sentence({std::is_integral_v<T> ? "integer" : "number", b});
}
std::string values(const Flag&) { return "`true` or `false`"; }
std::string values(const Text& t) { return t.file ? "file name" : "string"; }
template <class T>
std::string values(const Choice<T>& c) {
  std::vector<std::string> quoted;
  for (const auto& [name, value] : c.names) quoted.push_back("`" + std::string(name) + "`");
  return joined(quoted, " or ");
}
template <class T>
std::string values(const Vector<T>& v) {
  constexpr bool integer = std::is_same_v<T, glm::ivec3>;
  return sentence(
      {sentence({integer ? "3 integers" : "3 numbers", bounds(v.checks)}), lengthBounds(v.checks)},
      ", ");
}
std::string values(const Structured& s) { return s.values; }

}  // namespace

std::string sceneKeyValues(const SceneKey& key) {
  const std::string v = std::visit([](const auto& type) { return values(type); }, key.type);
  if (!key.auto_value) return v;
  return std::holds_alternative<Flag>(key.type) ? "`auto`, `true` or `false`" : "`auto` or " + v;
}

std::string sceneKeysMarkdown() {
  std::ostringstream md;
  md << "# Scene keys\n\n"
        "A scene is a YAML file of nested maps; `a.b.c` below means `a: {b: {c: ...}}`. Every key "
        "may be omitted (its default applies) and overridden on the command line with "
        "`--set a.b.c=VALUE` (VALUE is YAML: `--set volume.dims=[64,64,64]`). Unknown keys are "
        "errors, and so is a value outside what the key takes (the values column). This page is "
        "generated by `sortlast keys` from the table the parser reads the keys through; a test "
        "checks it is current.\n\n"
        "| key | default | values | meaning |\n| --- | --- | --- | --- |\n";
  for (const SceneKey& k : sceneKeys())
    md << "| `" << k.path << "` | `" << k.default_yaml << "` | " << sceneKeyValues(k) << " | "
       << k.doc << " |\n";
  return md.str();
}

}  // namespace sortlast
