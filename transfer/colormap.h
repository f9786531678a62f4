#pragma once
// Colour maps in ParaView's preset format (the JSON that ParaView's presets dialog exports and
// imports): a JSON array of presets, or one preset object, each with "Name",
// "ColorSpace" and "RGBPoints" [x, r, g, b, x, r, g, b, ...]. Other fields ("NanColor", "Points"
// (opacity), "Creator", ...) are read past: a volume's opacity comes from the transfer
// function's own points, and its data has no NaN colour.
//
// A colour map only colours: applyColourMap() keeps a transfer function's opacity and replaces its
// colours, resampled densely so that everything downstream (TfPoint lists, GL tables, the CPU
// reference) stays piecewise linear in RGB.
#include <string>
#include <vector>

#include "transfer/colour_space.h"
#include "transfer/transfer_function.h"

namespace sortlast {

struct ColourKnot {
  double x;  // normalised value in [0, 1]
  Rgb rgb;
};

struct ColourMap {
  std::string name;  // the preset's "Name" (may be empty)
  ColourSpace space = ColourSpace::Rgb;
  std::vector<ColourKnot> knots;  // at least 2; x strictly increasing, first 0, last 1

  Rgb at(double x) const;  // interpolated in `space`; clamped to the ends outside [0, 1]

  // Knots for linear RGB interpolation: the map's own knots and n evenly spaced samples, exact
  // for an RGB map. In the other spaces a step whose midpoint lies further than kSampleTolerance
  // from the straight line is halved (up to 8 times), so that the chords follow the curve.
  std::vector<ColourKnot> sampled(int n = 256) const;
  static constexpr double kSampleTolerance = 0.1 / 255;
};

// Parses a preset file's text. `source` names it in messages ("colour-map file maps/x.json");
// `pick`, if not empty, is the "Name" of the preset to take from an array (else the first).
// The preset's x range is rescaled linearly onto [0, 1] (first point 0, last 1). Throws
// InputError starting with `source` for malformed JSON, an unknown ColorSpace, fewer than 2
// points, a non-number, x not increasing, a colour outside [0, 1], ... (the checks in
// colormap.cpp), naming the point at fault. No ColorSpace means RGB, as in VTK.
ColourMap parseColourMapJson(const std::string& text, const std::string& source,
                             const std::string& pick = "");

// The transfer function `points` with its colour channels taken from `colours` (piecewise linear,
// as from ColourMap::sampled) and its opacity unchanged: the result has a point at every x of
// either list (every opacity point kept, steps included), so both curves are reproduced exactly.
// `points` must be valid transfer-function points (as TransferFunction's constructor checks).
std::vector<TfPoint> applyColourMap(const std::vector<TfPoint>& points,
                                    const std::vector<ColourKnot>& colours);

}  // namespace sortlast
