#pragma once
// Particles rendered as metaballs (Mishima, Tanaka and Sagawa; ../shared/PAPERS.md §2): where the
// centres come from (a file or a procedural set), the field's constants and the renderer's
// settings. Rank 0 loads the set and sends each rank the particles near its region
// (session/particle_loading.h); bricks keep those near them (particlesNear), in global order, so the
// field a rank sums at a point is the same, in the same order, as on any other rank.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "io/anisotropic_kernels.h"
#include "common/box.h"
#include "common/enum_names.h"

namespace sortlast {

// particles.method: billboards (the paper's multi-pass method) | grid (one pass over a grid of
// cells of edge h) | slices (the field sampled on a lattice, render/particles/metaball_slices_renderer.h).
enum class ParticleMethod { kBillboards, kGrid, kSlices };
template <>
inline constexpr std::array kEnumNames<ParticleMethod>{"billboards", "grid", "slices"};

// particles.smoothing: none (round metaballs) | anisotropic (smoothed ellipsoids,
// io/anisotropic_kernels.h) | auto (either, from the loaded particles: resolveAutoSmoothing).
enum class Smoothing { kNone, kAnisotropic, kAuto };
template <>
inline constexpr std::array kEnumNames<Smoothing>{"none", "anisotropic", "auto"};

struct ParticleDesc {
  std::string file;                 // empty: procedural (or none)
  std::string procedural = "none";  // none | layers | splash
  // auto | vtk | raw | csv | hdf5 (auto: by extension, .vtk/.vtp/.vtu -> vtk, .csv -> csv,
  // .h5/.hdf5 -> hdf5, else raw)
  std::string format = "auto";
  std::string dataset = "/PartType0/Coordinates";  // hdf5: the N x 3 positions
  std::string radius_dataset;  // hdf5: per-particle radii (refused: not supported)
  // Procedural: number of particles (-1: 4096). File: the count it must hold (-1: whatever it
  // holds; a raw file's size must then be a multiple of 12 bytes).
  long long count = -1;
  double spacing = 0.3;    // layers / splash: distance between neighbouring particles
  double radius = 0.1430;  // radius of the surface around a lone particle = h (1 - T)
  // h, the field's influence radius; unset: radius / (1 - threshold)
  std::optional<double> influence;
  double threshold = 0.765625;  // T (the paper's)
  glm::dvec3 colour{0.85, 0.9, 1.0};
  // Metaball renderer settings.
  ParticleMethod method = ParticleMethod::kGrid;
  double slice_spacing = 0.25;  // slices: lattice spacing, in units of h
  double step = 0.125;        // sample step along rays, in units of h
  int max_samples = 96;       // cap on field samples per pixel (per brick)
  int refine_iterations = 3;  // refinement passes (4 probes around the secant of eq. 5)
  bool cull = true;           // min/max distance pyramid culling
  int samples_per_pass = 8;   // window of samples per pass: 4 (the paper) or 8 (half the passes)
  Smoothing smoothing = Smoothing::kNone;
  // Why `smoothing` is what it is, once resolveAutoSmoothing has run (for --stats); empty before.
  std::string smoothing_reason;
  AnisotropicParams anisotropic;

  bool enabled() const { return !file.empty() || procedural != "none"; }
  double influenceRadius() const { return influence ? *influence : radius / (1.0 - threshold); }
  // (auto counts as off until resolveAutoSmoothing has chosen.)
  bool anisotropicOn() const { return smoothing == Smoothing::kAnisotropic; }
  // The furthest a particle's field reaches from its centre: h, or with anisotropic smoothing
  // the bound on the longest ellipsoid axis (anisotropicReachBound).
  double reach() const {
    return influenceRadius() * (anisotropicOn() ? anisotropicReachBound(anisotropic) : 1.0);
  }
  // How far beyond a brick (or rank) the particles it is given must reach. Round metaballs: h.
  // Anisotropic smoothing: the reach bound plus each particle's whole neighbourhood (radius h_n),
  // so its kernel comes out as on any other rank count. The slices method evaluates the field up
  // to one ray step w before its brick (where its rays' brackets start) and takes gradients one
  // spacing s further (per axis); interpolation there reads lattice points up to s further on
  // each axis: points within w + sqrt(6) s < w + 2.5 s of the brick, each the sum of every
  // particle whose field reaches it (round: within h; anisotropic: the reach bound, plus the
  // neighbourhood as above).
  double ghostMargin() const {
    const double h = influenceRadius();
    const double own = reach() + (anisotropicOn() ? anisotropic.neighbourhood * h : 0.0);
    if (method == ParticleMethod::kSlices) return own + h * (step + 2.5 * slice_spacing);
    return own;
  }
};

// particles.smoothing: auto. SPH output has its particles closer together than the kernel radius
// h (each particle's field overlaps dozens of others'), so its round metaballs show one bump per surface particle and anisotropic kernels
// flatten them (the dam break: 41 neighbours within h on average; the procedural layers at
// spacing 0.49 h: 27); a sparse set (droplets, point clouds with spacing near or above h) has few
// neighbours within h and keeps round metaballs. Auto picks anisotropic when the mean number of
// other particles within h is at least kAutoSmoothingNeighbours (a simple cubic lattice reaches
// 18 at spacing 0.7 h and has none below h at spacing h).
inline constexpr double kAutoSmoothingNeighbours = 10.0;
// Sum over up to `max_sampled` particles of `ps` (evenly strided) of how many others lie within h
// of each, and how many were sampled: summed over ranks' shares, their ratio is the mean.
struct NeighbourCount {
  double neighbours = 0.0;
  double sampled = 0.0;
};
NeighbourCount countNeighbours(const std::vector<glm::vec3>& ps, double h, size_t max_sampled = 65536);
// Resolves desc.smoothing == auto from the mean neighbour count (`count`, over the whole set), and
// sets desc.smoothing_reason (also for an explicit none or anisotropic). Anisotropic kernels need
// the grid or slices method: with billboards auto gives none. `in_situ`: auto gives none (in situ
// refuses anisotropic smoothing).
void resolveAutoSmoothing(ParticleDesc& desc, const NeighbourCount& count, bool in_situ = false);

struct ParticleSet {
  std::vector<glm::vec3> positions;
  Box3 bounds() const;  // of the centres; empty set: lo > hi (lo = +inf, hi = -inf)
};

// The set `desc` names: its file (format by desc.format) or its procedural set. Throws InputError:
// file missing or unreadable, raw size not a multiple of 12 bytes, a file whose particle count is
// not desc.count (when given), NaN or infinite position (naming its index), malformed CSV (naming
// the line), unknown format or procedural name. A file with no particles gives an empty set.
ParticleSet loadParticles(const ParticleDesc& desc);
// Formats read by every rank, a contiguous share each (HDF5 snapshots), rather than whole by one.
bool readsInShares(const ParticleDesc& desc);
// Share `part` of `parts` of such a file (the same checks as loadParticles, particles named by
// their index in the file); *total receives the file's particle count. Throws InputError.
ParticleSet loadParticleShare(const ParticleDesc& desc, int part, int parts, long long* total);

// Procedural sets, in units where neighbouring particles are `spacing` apart, centred at the
// origin (the centres' bounding box), bit-identical on every machine (an integer hash, no std::
// distributions, no trigonometry):
//  "layers": the metaball paper's test scene: layers of 24 x 24 particles stacked up (y up) until
//            `count` particles (the last layer partial).
//  "splash": a shallow pool, a crown of particles rising from it in spikes, and droplets flying
//            off the spikes.
ParticleSet proceduralParticles(const std::string& name, long long count, double spacing);

// Particles whose centre lies within `margin` of `box` (distance from point to box <= margin), in
// their original order: field sums must be bit-identical on every rank.
std::vector<glm::vec3> particlesNear(const std::vector<glm::vec3>& all, const Box3& box,
                                     double margin);

// The part of `clip` where the field of `particles` (influence radius h) can be non-zero: the box
// of their centres grown by h, cut to `clip`. No particle, or none reaching `clip`: lo >= hi on
// some axis. Both metaball renderers bound their bricks with it.
Box3 fieldBoundInside(const Box3& clip, const std::vector<glm::vec3>& particles, double h);

// Points of a VTK file (legacy .vtk polydata / unstructured grid, XML .vtp / .vtu); what
// loadParticles uses for format vtk. Only vtk_particles.cpp sees VTK's headers.
std::vector<glm::vec3> readVtkParticles(const std::string& file);
// Positions of an HDF5 snapshot: the N x 3 float32 or float64 `dataset` (particles.dataset);
// io/hdf5_particles.cpp, the only file of these that sees HDF5's headers.
// Share `part` of `parts` (rows n*part/parts up to n*(part+1)/parts, n the dataset's rows; 0 of 1:
// all of them); *total (if given) receives n.
std::vector<glm::vec3> readHdf5Particles(const std::string& file, const std::string& dataset, int part = 0,
                                         int parts = 1, long long* total = nullptr);

}  // namespace sortlast
