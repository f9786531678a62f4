#pragma once
// The exact line integral of the glow field (glow/glow_field.h) along a segment of a ray, in
// closed forms that stay accurate for every ray (derivation and checks: docs/glow.md).
//
// Both terms reduce to one integral: with p(s) = p0 + s q (the offset from M for the sphere, its
// part perpendicular to D for the cylinder) and R(s) = sqrt(|p(s)|^2 + eps^2),
//   I = int_0^len ds / R(s) = (1/|q|) [asinh(xi/h)] = (1/|q|) ln((xi1 + R1) / (xi0 + R0))
// where xi = q^.p(s) is the progress along the projected ray and h the softened closest distance.
// The ratio minus one is rewritten as |q| z with z a sum and quotient of positive terms only,
//   z = len (1 + (xi0 + xi1) / (R0 + R1)) / (xi0 + R0)        (both xi >= 0),
// so I = z log1p(|q| z) / (|q| z): no difference of two asinh values, no division by |q| (the ray
// parallel to the axis gives |q| = 0 and I = len / R exactly), nothing divided by a value that can
// be 0 (R >= eps > 0). Stretches with xi <= 0 are mirrored; a stretch that passes the closest point
// is split there, and its two halves' logarithms combined into one. The template is instantiated
// for double (the reference path, log1p from libm) and for float with the expressions of the GLSL
// in render/glow/glow_segment.glsl, so its float error can be tested on the CPU.
#include <cmath>
#include <glm/glm.hpp>
#include <type_traits>

#include "glow/glow_field.h"

namespace sortlast {

// z log1p(y) / y with y = speed z >= 0 and inv = 1 / speed (0 when speed = 0): the integral of a
// stretch (or of two combined) whose z is z. Float: below y = 0.5 the series of 2 atanh(w) / y with
// w = y / (2 + y) (w <= 0.2, five terms: truncation below 1e-8), one reciprocal of 2 + y serving w
// and 2 / (2 + y); above, z log(1 + y) / y = log(1 + y) inv (y >= 0.5 means speed > 0: no
// division by y), whose argument is >= 1.5, so rounding 1 + y costs at most 1.5e-7 relative. GLSL
// has no log1p, and log(1 + y) for small y would lose everything to the rounding of 1 + y.
template <class T>
T glowLogTerm(T z, T speed, T inv) {
  const T y = speed * z;
  if constexpr (std::is_same_v<T, double>) {
    return y > 0.0 ? z * (std::log1p(y) / y) : z;
  } else {
    if (y < T(0.5)) {
      const T inv2 = T(1) / (T(2) + y), w = y * inv2, w2 = w * w;
      const T series = T(1) + w2 * (T(1) / 3 + w2 * (T(1) / 5 + w2 * (T(1) / 7 + w2 * (T(1) / 9))));
      return z * (T(2) * inv2 * series);
    }
    return std::log(T(1) + y) * inv;
  }
}

// One stretch moving away from the closest point (xi1 >= xi0 >= 0, r = R at its ends): its
// integral is z log1p(speed z) / (speed z) with
//   z = len (1 + (xi0 + xi1) / (r0 + r1)) / (xi0 + r0) = len (r0 + r1 + xi0 + xi1) / ((r0 + r1) (xi0 + r0)),
// the second form with one division (positive terms only; the product is >= 2 eps^2, so it
// underflows only where eps^2 itself does).
template <class T>
T glowStretchZ(T len, T xi0, T xi1, T r0, T r1) {
  return len * (r0 + r1 + xi0 + xi1) / ((r0 + r1) * (xi0 + r0));
}

// Smallest |q| taken as moving: below it the projected ray counts as standing still (|q| len is
// then far below eps for any segment the scene allows) and the direction q / |q| is not formed.
template <class T>
constexpr T kGlowStill = std::is_same_v<T, double> ? T(1e-300) : T(1e-30);

// speed = |q| and inv = 1 / speed, both 0 below kGlowStill.
template <class T>
void glowSpeed(glm::vec<3, T> q, T& speed, T& inv) {
  speed = glm::length(q);
  if (speed > kGlowStill<T>) {
    inv = T(1) / speed;
  } else {
    speed = T(0);
    inv = T(0);
  }
}

// int_0^len ds / sqrt(|p0 + s q|^2 + eps^2); len >= 0, eps > 0; speed and inv from glowSpeed(q)
// (glowSegment forms the sphere's once per ray and the cylinder's once per emitter).
template <class T>
T inverseDistanceIntegral(glm::vec<3, T> p0, glm::vec<3, T> q, T speed, T inv, T len, T eps) {
  const T e2 = eps * eps;
  const glm::vec<3, T> qh = q * inv;
  const glm::vec<3, T> p1 = p0 + len * q;
  const T d0 = glm::dot(p0, p0) + e2, d1 = glm::dot(p1, p1) + e2;  // R^2 at the ends
  const T xi0 = glm::dot(qh, p0), xi1 = xi0 + speed * len;
  T z;
  if (xi0 >= T(0)) {
    z = glowStretchZ(len, xi0, xi1, std::sqrt(d0), std::sqrt(d1));
  } else if (xi1 <= T(0)) {
    z = glowStretchZ(len, -xi1, -xi0, std::sqrt(d1), std::sqrt(d0));
  } else {
    // Passes the closest point (speed > 0 here, as xi1 > xi0): split there. The two lengths sum
    // to len exactly and each stretch is built from h and its own length, consistent with itself:
    // the split point's position carries the rounding of xi0 (absolute, ~ulp(|p0|)), which on a
    // short segment would otherwise change its length (measured: 10 % in float on a 1e-6 segment).
    const glm::vec<3, T> c = p0 - xi0 * qh;
    const T h2 = glm::dot(c, c) + e2, h = std::sqrt(h2);
    const T before = glm::min(-xi0 * inv, len), after = len - before;
    const T xa = speed * before, xb = speed * after;
    const T za = glowStretchZ(before, T(0), xa, h, std::sqrt(h2 + xa * xa));
    const T zb = glowStretchZ(after, T(0), xb, h, std::sqrt(h2 + xb * xb));
    // The two stretches' logs as one: log1p(speed za) + log1p(speed zb) = log1p(speed z) with
    // speed z = (1 + speed za)(1 + speed zb) - 1, all terms >= 0 (no cancellation).
    z = za + zb + speed * za * zb;
  }
  return glowLogTerm(z, speed, inv);
}

template <class T>
T inverseDistanceIntegral(glm::vec<3, T> p0, glm::vec<3, T> q, T len, T eps) {
  T speed, inv;
  glowSpeed(q, speed, inv);
  return inverseDistanceIntegral(p0, q, speed, inv, len, eps);
}

// int_{s0}^{s1} E(o + s u) ds for one emitter (without its colour); u of unit length, eps > 0.
// The segment is split where it crosses the plane through M with normal D; the crossing comes from
// the signed heights g0, g1 of the ends (opposite signs, so g0 - g1 is not 0): a ray along the
// plane has g0 = g1 and is never split, and nothing is divided by u.D.
template <class T>
T glowSegment(glm::vec<3, T> centre, glm::vec<3, T> dir, T a, T b, T eps, glm::vec<3, T> o,
              glm::vec<3, T> u, T s0, T s1) {
  if (!(s1 > s0)) return T(0);
  const T len = s1 - s0;
  const glm::vec<3, T> p0 = (o - centre) + s0 * u;
  const T ud = glm::dot(u, dir);
  const glm::vec<3, T> qc = u - ud * dir;  // the ray's velocity across the axis
  const T g0 = glm::dot(p0, dir), g1 = g0 + len * ud;
  T speed_c, inv_c, speed_u, inv_u;
  glowSpeed(qc, speed_c, inv_c);
  glowSpeed(u, speed_u, inv_u);
  auto cyl = [&](glm::vec<3, T> p, T l) {
    return b * inverseDistanceIntegral(p - glm::dot(p, dir) * dir, qc, speed_c, inv_c, l, eps);
  };
  auto sph = [&](glm::vec<3, T> p, T l) { return a * inverseDistanceIntegral(p, u, speed_u, inv_u, l, eps); };
  if (g0 >= T(0) && g1 >= T(0)) return cyl(p0, len);
  if (g0 < T(0) && g1 < T(0)) return sph(p0, len);
  const T lc = len * glm::clamp(g0 / (g0 - g1), T(0), T(1));
  const glm::vec<3, T> pc = p0 + lc * u;
  return g0 >= T(0) ? cyl(p0, lc) + sph(pc, len - lc) : sph(p0, lc) + cyl(pc, len - lc);
}

// Double-precision entry for the scene's emitters.
inline double glowSegment(const GlowEmitter& e, double eps, const glm::dvec3& o,
                          const glm::dvec3& u, double s0, double s1) {
  return glowSegment<double>(e.centre, e.direction, e.a, e.b, eps, o, u, s0, s1);
}

}  // namespace sortlast
