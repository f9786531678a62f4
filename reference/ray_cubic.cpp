#include "reference/ray_cubic.h"

#include <algorithm>
#include <cmath>

namespace sortlast {

Turns turnsOf(const double* k, double sa, double sb) {
  Turns c;
  const double qa = 3.0 * k[3], qb = 2.0 * k[2], qc = k[1];  // v' = qa s^2 + qb s + qc
  auto take = [&](double s) {
    if (s > sa && s < sb) c.at[c.count++] = s;
  };
  if (qa != 0.0) {
    const double disc = qb * qb - 4.0 * qa * qc;
    if (disc > 0.0) {
      // The roots as q / qa and qc / q, q = -(qb + sign(qb) sqrt(disc)) / 2: no difference of
      // nearly equal terms. (-qb +- sqrt(disc)) / (2 qa) lost the root where the cubic term is
      // rounding noise (k3 ~ 1e-16 on a parabola-shaped crossing): the turn was dropped, the
      // crossing taken as monotone between its ends, and a peak of opacity inside it skipped --
      // one pixel of the head CT's sharp reference 118/255 off.
      const double q = -0.5 * (qb + std::copysign(std::sqrt(disc), qb));
      const double r1 = q / qa, r2 = q != 0.0 ? qc / q : r1;
      take(std::min(r1, r2));
      if (r2 != r1) take(std::max(r1, r2));
    }
  } else if (qb != 0.0) {
    take(-qc / qb);
  }
  return c;
}

double cubicRoot(const double* k, double sa, double sb, double va, double value) {
  double lo = sa, hi = sb;
  const bool rising = va < value;  // v(lo) < value < v(hi) when rising
  double s = 0.5 * (sa + sb);
  for (int i = 0; i < 60 && hi - lo > 1e-14 * (1.0 + std::abs(sa) + std::abs(sb)); ++i) {
    const double f = cubicAt(k, s) - value;
    if ((f < 0.0) == rising) lo = s; else hi = s;
    if (f == 0.0) return s;
    const double df = (3.0 * k[3] * s + 2.0 * k[2]) * s + k[1];
    const double next = df != 0.0 ? s - f / df : 0.5 * (lo + hi);
    s = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return s;
}

}  // namespace sortlast
