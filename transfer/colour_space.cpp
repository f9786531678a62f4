#include "transfer/colour_space.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "common/error.h"

namespace sortlast {

namespace {

constexpr double kPi = std::numbers::pi;
// D65 white of the sRGB matrix below (its rows' sums), so grey has a = b = 0.
constexpr double kWhiteX = 0.9505, kWhiteY = 1.0, kWhiteZ = 1.089;

double srgbToLinear(double c) {
  return c > 0.04045 ? std::pow((c + 0.055) / 1.055, 2.4) : c / 12.92;
}
double linearToSrgb(double c) {
  return c > 0.0031308 ? 1.055 * std::pow(c, 1.0 / 2.4) - 0.055 : 12.92 * c;
}

// CIE's f(t) and its inverse: a cube root with a linear piece near 0.
double labF(double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; }
double labFInverse(double f) {
  double t = f * f * f;
  return t > 0.008856 ? t : (f - 16.0 / 116.0) / 7.787;
}

double angleDiff(double a, double b) {
  double d = std::fmod(std::abs(a - b), 2.0 * kPi);
  return d > kPi ? 2.0 * kPi - d : d;
}

// The hue an unsaturated colour of magnitude m_unsat should take when interpolated towards the
// saturated `sat`: spun away from sat's hue so the perceived change stays even along the way
// (Moreland 2009, section 4.2). VTK's constants: hold the hue when M differs by under 0.1, spin
// the other way below -0.3 pi (the purples).
double adjustHue(const std::array<double, 3>& sat, double m_unsat) {
  if (sat[0] >= m_unsat - 0.1) return sat[2];
  double spin =
      sat[1] * std::sqrt(m_unsat * m_unsat - sat[0] * sat[0]) / (sat[0] * std::sin(sat[1]));
  return sat[2] > -0.3 * kPi ? sat[2] + spin : sat[2] - spin;
}

Rgb interpolateDiverging(const Rgb& a, const Rgb& b, double t) {
  std::array<double, 3> m1 = rgbToMsh(a), m2 = rgbToMsh(b);
  // Two distinct saturated colours: interpolate through an unsaturated midpoint (white-ish, M at
  // least 88: L = 88 is sRGB grey 0.865) on the half of the segment that holds t.
  if (m1[1] > 0.05 && m2[1] > 0.05 && angleDiff(m1[2], m2[2]) > 0.33 * kPi) {
    double m_mid = std::max({88.0, m1[0], m2[0]});
    if (t < 0.5) {
      m2 = {m_mid, 0.0, 0.0};
      t = 2.0 * t;
    } else {
      m1 = {m_mid, 0.0, 0.0};
      t = 2.0 * t - 1.0;
    }
  }
  // An unsaturated end has no meaningful hue: give it one that makes the path sensible.
  if (m1[1] < 0.05 && m2[1] > 0.05)
    m1[2] = adjustHue(m2, m1[0]);
  else if (m2[1] < 0.05 && m1[1] > 0.05)
    m2[2] = adjustHue(m1, m2[0]);
  std::array<double, 3> m;
  for (int i = 0; i < 3; ++i) m[i] = (1.0 - t) * m1[i] + t * m2[i];
  return mshToRgb(m);
}

}  // namespace

ColourSpace parseColourSpace(const std::string& name) {
  if (name == "RGB") return ColourSpace::Rgb;
  if (name == "Lab" || name == "CIELAB") return ColourSpace::Lab;
  if (name == "Diverging") return ColourSpace::Diverging;
  if (name == "HSV") return ColourSpace::Hsv;
  throw InputError("unknown ColorSpace \"" + name + "\" (known: RGB, Lab, CIELAB, Diverging, HSV)");
}

std::array<double, 3> rgbToLab(const Rgb& rgb) {
  double r = srgbToLinear(rgb[0]), g = srgbToLinear(rgb[1]), b = srgbToLinear(rgb[2]);
  double x = 0.4124 * r + 0.3576 * g + 0.1805 * b;
  double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  double z = 0.0193 * r + 0.1192 * g + 0.9505 * b;
  double fx = labF(x / kWhiteX), fy = labF(y / kWhiteY), fz = labF(z / kWhiteZ);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Rgb labToRgb(const std::array<double, 3>& lab) {
  double fy = (lab[0] + 16.0) / 116.0;
  double fx = fy + lab[1] / 500.0, fz = fy - lab[2] / 200.0;
  double x = kWhiteX * labFInverse(fx), y = kWhiteY * labFInverse(fy),
         z = kWhiteZ * labFInverse(fz);
  Rgb c = {linearToSrgb(3.2406 * x - 1.5372 * y - 0.4986 * z),
           linearToSrgb(-0.9689 * x + 1.8758 * y + 0.0415 * z),
           linearToSrgb(0.0557 * x - 0.2040 * y + 1.0570 * z)};
  double top = std::max({c[0], c[1], c[2]});
  for (double& v : c) v = std::max(0.0, top > 1.0 ? v / top : v);
  return c;
}

std::array<double, 3> rgbToMsh(const Rgb& rgb) {
  auto lab = rgbToLab(rgb);
  double m = std::sqrt(lab[0] * lab[0] + lab[1] * lab[1] + lab[2] * lab[2]);
  double s = m > 0.001 ? std::acos(std::clamp(lab[0] / m, -1.0, 1.0)) : 0.0;
  double h = s > 0.001 ? std::atan2(lab[2], lab[1]) : 0.0;
  return {m, s, h};
}

Rgb mshToRgb(const std::array<double, 3>& msh) {
  return labToRgb({msh[0] * std::cos(msh[1]), msh[0] * std::sin(msh[1]) * std::cos(msh[2]),
                   msh[0] * std::sin(msh[1]) * std::sin(msh[2])});
}

std::array<double, 3> rgbToHsv(const Rgb& rgb) {
  double hi = std::max({rgb[0], rgb[1], rgb[2]}), lo = std::min({rgb[0], rgb[1], rgb[2]});
  double d = hi - lo;
  double h = 0.0;
  if (d > 0.0) {
    if (hi == rgb[0])
      h = (rgb[1] - rgb[2]) / d;
    else if (hi == rgb[1])
      h = 2.0 + (rgb[2] - rgb[0]) / d;
    else
      h = 4.0 + (rgb[0] - rgb[1]) / d;
    h /= 6.0;
    if (h < 0.0) h += 1.0;
  }
  return {h, hi > 0.0 ? d / hi : 0.0, hi};
}

Rgb hsvToRgb(const std::array<double, 3>& hsv) {
  double h = hsv[0] - std::floor(hsv[0]), s = hsv[1], v = hsv[2];
  double sector = h * 6.0;
  int i = std::min(5, int(sector));
  double f = sector - i;
  double p = v * (1.0 - s), q = v * (1.0 - s * f), u = v * (1.0 - s * (1.0 - f));
  switch (i) {
    case 0:
      return {v, u, p};
    case 1:
      return {q, v, p};
    case 2:
      return {p, v, u};
    case 3:
      return {p, q, v};
    case 4:
      return {u, p, v};
    default:
      return {v, p, q};
  }
}

Rgb interpolateColour(ColourSpace space, const Rgb& a, const Rgb& b, double t) {
  auto lerp = [t](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return std::array<double, 3>{x[0] + t * (y[0] - x[0]), x[1] + t * (y[1] - x[1]),
                                 x[2] + t * (y[2] - x[2])};
  };
  if (t <= 0.0) return a;  // the knots themselves, exactly (no round trip through a space)
  if (t >= 1.0) return b;
  Rgb c;
  switch (space) {
    case ColourSpace::Rgb:
      c = lerp(a, b);
      break;
    case ColourSpace::Lab:
      c = labToRgb(lerp(rgbToLab(a), rgbToLab(b)));
      break;
    case ColourSpace::Diverging:
      c = interpolateDiverging(a, b, t);
      break;
    case ColourSpace::Hsv:
      c = hsvToRgb(lerp(rgbToHsv(a), rgbToHsv(b)));
      break;
  }
  // Round-off in the conversions may step a hair outside [0, 1]; the transfer function may not.
  for (double& v : c) v = std::clamp(v, 0.0, 1.0);
  return c;
}

}  // namespace sortlast
