#pragma once
// The field along a ray inside one cell of a trilinear grid is a cubic in the ray parameter
// (reference/ray_segment.cpp's FieldCursor): its value, where it turns and where it meets a value.
// The cell integrator cuts each crossing there, so that every piece is monotone and opacity
// smooth on it.

namespace sortlast {

// k0 + k1 s + k2 s^2 + k3 s^3 by Horner's rule.
inline double cubicAt(const double* k, double s) { return ((k[3] * s + k[2]) * s + k[1]) * s + k[0]; }

// Where v(s) = k0 + k1 s + k2 s^2 + k3 s^3 turns inside (sa, sb): the roots of v' there, in order
// (none, one or two). Stable where k3 or k2 is rounding noise beside the others.
struct Turns {
  double at[2];
  int count = 0;
};
Turns turnsOf(const double* k, double sa, double sb);

// Where the cubic, monotone on [sa, sb] with va = v(sa) and v(sb) on either side of `value`,
// meets it: Newton's steps kept inside the bracket, bisection where one leaves it.
double cubicRoot(const double* k, double sa, double sb, double va, double value);

}  // namespace sortlast
