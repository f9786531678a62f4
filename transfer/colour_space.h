#pragma once
// Colour spaces of colour-map interpolation, as ParaView's presets name them ("ColorSpace"), and
// the conversions they need: sRGB <-> CIELAB (D65), Moreland's Msh (polar Lab) and HSV. ParaView
// interpolates with VTK's vtkColorTransferFunction; interpolateColour() follows its rules (the
// constants are noted where they matter), so a preset looks here as it does there.
#include <array>
#include <string>

namespace sortlast {

using Rgb = std::array<double, 3>;  // each in [0, 1]

enum class ColourSpace { Rgb, Lab, Diverging, Hsv };

// "RGB", "Lab" or "CIELAB", "Diverging", "HSV"; throws InputError naming the known spaces.
ColourSpace parseColourSpace(const std::string& name);

// sRGB (gamma-encoded, [0, 1]) <-> CIELAB with the D65 white of the sRGB matrix. labToRgb clips
// colours outside the sRGB gamut as VTK does: scaled down by the largest component if it
// exceeds 1, then negative components set to 0.
std::array<double, 3> rgbToLab(const Rgb& rgb);
Rgb labToRgb(const std::array<double, 3>& lab);

// Msh (Moreland 2009): M = |Lab|, s = angle from the L axis, h = hue angle in the a-b plane.
std::array<double, 3> rgbToMsh(const Rgb& rgb);
Rgb mshToRgb(const std::array<double, 3>& msh);

// HSV with h, s, v in [0, 1].
std::array<double, 3> rgbToHsv(const Rgb& rgb);
Rgb hsvToRgb(const std::array<double, 3>& hsv);

// The colour a fraction t in [0, 1] of the way from a to b, in the given space:
// - Rgb: componentwise linear.
// - Lab: linear in CIELAB.
// - Diverging: linear in Msh; two saturated colours whose hues differ by more than 60 degrees
//   get an unsaturated midpoint (M = max(88, M_a, M_b)) between them, and an unsaturated end
//   takes the hue that keeps the perceived change even (Moreland's "adjust hue").
// - Hsv: linear in h, s and v, hue not wrapped (ParaView's default: blue to red passes through
//   green, the rainbow, not through magenta).
Rgb interpolateColour(ColourSpace space, const Rgb& a, const Rgb& b, double t);

}  // namespace sortlast
