#pragma once
// GLSL of the glow emitters' segment integral: glowSegment() below is common/glow_integral.h's
// glowSegment<float>, line by line (the derivation and the float bound: docs/glow.md), so the C++
// float instantiation that tests/unit/glow_test.cpp checks is the arithmetic the shader does, and
// tests/unit/glow_glsl_test.cpp checks this text itself on the GL driver. A shader that draws glow
// includes the string before its main().
namespace sortlast::shaders {

inline constexpr const char* kGlowSegment = R"(
// log1p(y) / y, y >= 0: below 0.5 the series of 2 atanh(w) / y, w = y / (2 + y) (GLSL has no
// log1p; log(1 + y) would lose everything to the rounding of 1 + y).
float glowLog1pOverX(float y) {
  if (y < 0.5) {
    float w = y / (2.0 + y), w2 = w * w;
    float series = 1.0 + w2 * (1.0 / 3.0 + w2 * (1.0 / 5.0 + w2 * (1.0 / 7.0 + w2 * (1.0 / 9.0))));
    return 2.0 / (2.0 + y) * series;
  }
  return log(1.0 + y) / y;
}

// One stretch moving away from the closest point: xi1 >= xi0 >= 0, r = R at its ends.
float glowStretch(float len, float xi0, float xi1, float r0, float r1, float speed) {
  float z = len * (1.0 + (xi0 + xi1) / (r0 + r1)) / (xi0 + r0);
  return z * glowLog1pOverX(speed * z);
}

// int_0^len ds / sqrt(|p0 + s q|^2 + eps^2); len >= 0, eps > 0.
float glowInverseDistance(vec3 p0, vec3 q, float len, float eps) {
  float e2 = eps * eps;
  float speed = length(q);
  vec3 qh = vec3(0.0);
  if (speed > 1e-30) qh = q / speed;
  else speed = 0.0;
  vec3 p1 = p0 + len * q;
  float r0 = sqrt(dot(p0, p0) + e2), r1 = sqrt(dot(p1, p1) + e2);
  float xi0 = dot(qh, p0), xi1 = xi0 + speed * len;
  if (xi0 >= 0.0) return glowStretch(len, xi0, xi1, r0, r1, speed);
  if (xi1 <= 0.0) return glowStretch(len, -xi1, -xi0, r1, r0, speed);
  vec3 c = p0 - xi0 * qh;
  float h = sqrt(dot(c, c) + e2);
  float before = min(-xi0 / speed, len), after = len - before;
  float xa = speed * before, xb = speed * after;
  return glowStretch(before, 0.0, xa, h, sqrt(h * h + xa * xa), speed) +
         glowStretch(after, 0.0, xb, h, sqrt(h * h + xb * xb), speed);
}

// int_{s0}^{s1} E(o + s u) ds for one emitter (centre, unit dir, a, b), unit u, eps > 0; cut where
// the segment crosses the plane through the centre with normal dir.
float glowSegment(vec3 centre, vec3 dir, float a, float b, float eps, vec3 o, vec3 u, float s0, float s1) {
  if (!(s1 > s0)) return 0.0;
  float len = s1 - s0;
  vec3 p0 = (o - centre) + s0 * u;
  float ud = dot(u, dir);
  vec3 qc = u - ud * dir;
  float g0 = dot(p0, dir), g1 = g0 + len * ud;
  if (g0 >= 0.0 && g1 >= 0.0) return b * glowInverseDistance(p0 - dot(p0, dir) * dir, qc, len, eps);
  if (g0 < 0.0 && g1 < 0.0) return a * glowInverseDistance(p0, u, len, eps);
  float lc = len * clamp(g0 / (g0 - g1), 0.0, 1.0);
  vec3 pc = p0 + lc * u;
  if (g0 >= 0.0)
    return b * glowInverseDistance(p0 - dot(p0, dir) * dir, qc, lc, eps) +
           a * glowInverseDistance(pc, u, len - lc, eps);
  return a * glowInverseDistance(p0, u, lc, eps) +
         b * glowInverseDistance(pc - dot(pc, dir) * dir, qc, len - lc, eps);
}
)";

}  // namespace sortlast::shaders
