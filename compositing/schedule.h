#pragma once
// The partner schedule of radix-k compositing (binary-swap is k = 2), apart from any image or
// message: who folds into whom, who meets whom in each round, and which part of the frame each
// one keeps (the pattern of DIY's partners, after Peterka et al.'s radix-k). Pure arithmetic,
// tested without MPI or pixels.
//
// Participants are numbered by their position in the visibility order (0: the farthest), so any
// run of neighbouring positions may be composited on its own ("over" is associative). n
// participants become N <= n units: N is the largest count whose prime factors are all <= k (for
// k = 2 the largest power of two), and the first n - N pairs of neighbours (2i, 2i + 1) fold, the
// nearer sending its whole image to the farther, which carries the unit. N is the product of the
// rounds' radices k_0 k_1 ... (each in [2, k], largest first). In round t a unit's digit is
// (u / stride_t) % k_t, stride_t = k_0 ... k_{t-1}; its group is the k_t units that differ from it
// in that digit only, and between them they hold a run of neighbouring units, so the group
// composites its images in digit order, back to front. Member `digit` keeps part `digit` of the
// region the group shares, split k_t ways along its longer side. After the last round the units'
// regions tile the frame.
#include <utility>
#include <vector>

#include "common/camera.h"

namespace sortlast {

struct RadixKSchedule {
  int participants = 0;
  int folds = 0;             // pairs (2i, 2i + 1), i < folds: 2i + 1 folds into 2i
  std::vector<int> radices;  // k per round; their product is units()

  int units() const { return participants - folds; }
  int rounds() const { return int(radices.size()); }
  // Positions [firstPosition, lastPosition] make up the unit; the first carries it.
  int firstPosition(int unit) const { return unit < folds ? 2 * unit : unit + folds; }
  int lastPosition(int unit) const { return unit < folds ? 2 * unit + 1 : unit + folds; }
  int stride(int round) const;  // product of the radices before `round`
  int digit(int round, int unit) const { return (unit / stride(round)) % radices[size_t(round)]; }
  // The units of `unit`'s group in `round`, back to front (entry digit(round, unit) is `unit`).
  std::vector<int> group(int round, int unit) const;
  // The run of units whose images `unit` holds, composited, before `round` (rounds(): at the end).
  std::pair<int, int> mergedUnits(int round, int unit) const;
  // The part of `whole` that `unit` holds before `round` (rounds(): at the end).
  Rect region(int round, int unit, const Rect& whole) const;
};

// k >= 2; participants >= 0.
RadixKSchedule makeRadixKSchedule(int participants, int k);

// `parts` pieces of `r` cut across its longer side (width on a tie), in increasing x or y, sizes
// differing by at most one (some are empty when the side is shorter than `parts`).
std::vector<Rect> splitRect(const Rect& r, int parts);

}  // namespace sortlast
