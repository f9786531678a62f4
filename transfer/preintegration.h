#pragma once
// Pre-integrated transfer functions (Engel, Kraus and Ertl 2001): for a ray segment of length L
// over which the data value goes linearly from vf (front, nearer the eye) to vb (back), the
// exact emission-absorption integral of the transfer function's model (transfer/transfer_function.h)
//   colour  C = int_0^L c(v(s)) tau(v(s)) exp(-int_0^s tau) ds     (premultiplied)
//   opacity A = 1 - exp(-D),  D = int_0^L tau(v(s)) ds              (the optical depth)
// with self-attenuation inside the segment. The table holds (C_r, C_g, C_b, D) for every pair
// (front, back) of n x n normalised values i / (n - 1), at one base length L0 (the renderers'
// sample step), in double; the GL renderers upload it as a linearly filtered RGBA32F texture.
// "Linearly" is in the domain of transfer.scale (transfer/value_scale.h): under log the segment's
// log10 v goes linearly from front to back (its v geometrically), as the table's axes are.
//
// How an entry is integrated: the value axis is cut into (n - 1) * kSubsteps fine cells; each
// cell gets its exact mean extinction (integral of tau over the cell, Gauss-Legendre on each
// smooth piece between control points) and its tau-weighted mean colour. A segment from entry i
// to entry j crosses kSubsteps * |j - i| whole cells, each for the same share of L0, and is
// composited cell by cell front to back: D is then exact (the cells' integrals add up), the
// colour has the error of treating colour and tau as constant inside one cell (bounded in
// tests/unit/preintegration_test.cpp). A constant segment (i == j) is the midpoint formula
// exactly: D = tau(v) L0, C = c(v) (1 - exp(-D)). exp() is taken once per cell and segment
// length, shared by every entry of that length: the build costs O(n^3 kSubsteps / 3)
// multiply-adds (256 entries: 26-75 ms on this shared 2-core machine; the unit test times it).
//
// Other lengths L (slicing: ds = spacing / cos): the optical depth of a linear segment is
// proportional to L, so A_L = 1 - exp(-D L / L0) is exact; the colour is scaled by A_L / A_L0
// (exact for a constant colour; otherwise it keeps the shape of the attenuation along the
// segment at L0, an error of order (L / L0 - 1) * D * (colour change along the segment)).
#include <array>
#include <vector>

#include "transfer/transfer_function.h"

namespace sortlast {

struct PreintegrationTable {
  static constexpr int kDefaultSize = 256;
  static constexpr int kSubsteps = 4;  // fine cells per table interval

  int n = 0;                 // entries per axis
  double base_length = 0.0;  // L0, world units
  // (C_r, C_g, C_b, D) of entry (front i, back j) at 4 * (i + n * j): front along x (fastest).
  std::vector<double> entries;

  // Builds the table of `tf` for segments of length `base_length` (> 0), n >= 2 entries per axis.
  static PreintegrationTable build(const TransferFunction& tf, int n, double base_length);

  // What the GL renderers compute for a segment from normalised value xf to xb (clamped to
  // [0, 1]) of length `length`: the bilinear filter of the texture at texel centres, then the
  // length correction. Premultiplied (r, g, b, alpha).
  std::array<double, 4> lookup(double xf, double xb, double length) const;

  // The table as RGBA32F texels, in the order of `entries`.
  std::vector<float> texels() const;
};

// The same transfer function (points, range, unit length): whether a table built for one serves
// the other.
bool sameTransferFunction(const TransferFunction& a, const TransferFunction& b);

}  // namespace sortlast
