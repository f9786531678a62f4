#include "reference/glow_quadrature.h"

#include <algorithm>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <cmath>
#include <vector>

namespace sortlast {

QuadratureResult glowQuadrature(const GlowEmitter& e, double eps, const glm::dvec3& o,
                                const glm::dvec3& u, double s0, double s1) {
  QuadratureResult r;
  if (!(s1 > s0)) return r;
  const glm::dvec3 w = o - e.centre;
  std::vector<double> cuts{s0, s1};
  auto cut = [&](double s) {
    if (std::isfinite(s) && s > s0 && s < s1) cuts.push_back(s);
  };
  const double ud = glm::dot(u, e.direction);
  if (ud != 0.0) cut(-glm::dot(w, e.direction) / ud);  // the plane
  cut(-glm::dot(w, u));                                // closest to M
  const glm::dvec3 qc = u - ud * e.direction, wc = w - glm::dot(w, e.direction) * e.direction;
  if (glm::dot(qc, qc) > 0.0) cut(-glm::dot(wc, qc) / glm::dot(qc, qc));  // closest to the axis
  std::sort(cuts.begin(), cuts.end());
  // Cuts closer than 1e-12 of the segment merge: Boost's error estimate on a piece a few ulps long
  // is noise (measured: 1.7 on a piece of 4e-16), and a peak that close to a cut is at its end.
  std::vector<double> kept{s0};
  for (double c : cuts)
    if (c - kept.back() > 1e-12 * (s1 - s0)) kept.push_back(c);
  kept.back() = s1;
  cuts = kept;
  // One integrator per thread: it holds its abscissae, computed once and extended as levels are
  // needed (Boost 1.74's integrate() cannot be called on a const one).
  thread_local boost::math::quadrature::tanh_sinh<double> integrator(15);
  for (size_t i = 0; i + 1 < cuts.size(); ++i) {
    // Points near a piece's ends are placed from that end by Boost's complement xc (the offset from
    // the nearer end, negative near the left one), not as o + s u: offsets far below the ulp of s
    // stay distinct, so a peak at the end is resolved however narrow.
    const glm::dvec3 left = o + cuts[i] * u, right = o + cuts[i + 1] * u;
    auto f = [&](double, double xc) {
      return glowField(e, eps, xc <= 0.0 ? left - xc * u : right - xc * u);
    };
    double err = 0.0;
    r.value += integrator.integrate(f, cuts[i], cuts[i + 1], 1e-13, &err);
    r.error += err;
  }
  return r;
}

}  // namespace sortlast
