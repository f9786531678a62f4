// The glow emitters' segment integral: glowSegment() below is glow/glow_integral.h's
// glowSegment<float>, line by line (the derivation and the float bound: docs/glow.md), so the C++
// float instantiation that tests/unit/glow_test.cpp checks is the arithmetic the shader does, and
// tests/unit/glow_glsl_test.cpp checks this text itself on the GL driver. Every program that draws
// glow (the glow pass, the ray caster's GLOW variant) puts this chunk before its own.
// z log1p(y) / y, y = speed z >= 0, inv = 1 / speed (0 when speed = 0): below y = 0.5 the series
// of 2 atanh(w) / y, w = y / (2 + y) (GLSL has no log1p; log(1 + y) would lose everything to the
// rounding of 1 + y), above log(1 + y) inv. Both forms are computed and one selected: llvmpipe
// runs both sides of a branch anyway (per SIMD lane mask), so straight-line code is no slower and
// keeps the program small.
float glowLogTerm(float z, float speed, float inv) {
  float y = speed * z;
  float inv2 = 1.0 / (2.0 + y), w = y * inv2, w2 = w * w;
  float series = 1.0 + w2 * (1.0 / 3.0 + w2 * (1.0 / 5.0 + w2 * (1.0 / 7.0 + w2 * (1.0 / 9.0))));
  float small = z * (2.0 * inv2 * series);
  float large = log(1.0 + y) * inv;
  return y < 0.5 ? small : large;
}

// z of one stretch moving away from the closest point (xi1 >= xi0 >= 0, r = R at its ends): its
// integral is z log1p(speed z) / (speed z).
float glowStretchZ(float len, float xi0, float xi1, float r0, float r1) {
  return len * (r0 + r1 + xi0 + xi1) / ((r0 + r1) * (xi0 + r0));
}

// speed = |q|, inv = 1 / speed, both 0 below 1e-30 (standing still).
void glowSpeed(vec3 q, out float speed, out float inv) {
  speed = length(q);
  bool moving = speed > 1e-30;
  inv = moving ? 1.0 / max(speed, 1e-30) : 0.0;
  speed = moving ? speed : 0.0;
}

// int_0^len ds / sqrt(|p0 + s q|^2 + eps^2); len >= 0, eps > 0; speed and inv from glowSpeed(q).
// The three cases of glow/glow_integral.h (moving away from the closest point, towards it
// (mirrored), or passing it (split in two)) select the inputs of two stretches (the second of
// length 0, so z = 0, unless split; its r0 is then any positive value) before the square roots,
// so three of them serve every case; the two z combine into one (z = za exactly when zb = 0), so
// one log per call.
float glowInverseDistance(vec3 p0, vec3 q, float speed, float inv, float len, float eps) {
  float e2 = eps * eps;
  vec3 qh = q * inv;
  vec3 p1 = p0 + len * q;
  float d0 = dot(p0, p0) + e2, d1 = dot(p1, p1) + e2;
  float xi0 = dot(qh, p0), xi1 = xi0 + speed * len;
  vec3 c = p0 - xi0 * qh;
  float h2 = dot(c, c) + e2;
  float before = clamp(-xi0 * inv, 0.0, len), after = len - before;  // [0, len] in every case
  float xa = speed * before, xb = speed * after;
  bool away = xi0 >= 0.0, towards = !away && xi1 <= 0.0, split = !away && !towards;
  float la = split ? before : len;
  float xa0 = split ? 0.0 : (away ? xi0 : -xi1);
  float xa1 = split ? xa : (away ? xi1 : -xi0);
  float ra0 = sqrt(split ? h2 : (away ? d0 : d1));  // h when split
  float ra1 = sqrt(split ? h2 + xa * xa : (away ? d1 : d0));
  float lb = split ? after : 0.0;
  float za = glowStretchZ(la, xa0, xa1, ra0, ra1);
  float zb = glowStretchZ(lb, 0.0, xb, ra0, sqrt(h2 + xb * xb));
  float z = za + zb + speed * za * zb;
  return glowLogTerm(z, speed, inv);
}

// int_{s0}^{s1} E(o + s u) ds for one emitter (centre, unit dir, a, b), unit u, eps > 0; cut where
// the segment crosses the plane through the centre with normal dir. The two parts (the second of
// length 0 when the segment does not cross) go through one call site in a loop: each part picks
// its term (cylinder where its side's height g >= 0, sphere below), so the closed form is inlined
// once per glowSegment, which keeps the ray caster's GLOW variant quick to compile.
float glowSegment(vec3 centre, vec3 dir, float a, float b, float eps, vec3 o, vec3 u, float s0, float s1) {
  if (!(s1 > s0)) return 0.0;
  float len = s1 - s0;
  vec3 p0 = (o - centre) + s0 * u;
  float ud = dot(u, dir);
  vec3 qc = u - ud * dir;
  float g0 = dot(p0, dir), g1 = g0 + len * ud;
  bool up0 = g0 >= 0.0, up1 = g1 >= 0.0;
  float lc = up0 == up1 ? len : len * clamp(g0 / (g0 - g1), 0.0, 1.0);
  float speed_c, inv_c, speed_u, inv_u;  // the sphere's is the same for every emitter: hoisted
  glowSpeed(qc, speed_c, inv_c);
  glowSpeed(u, speed_u, inv_u);
  float sum = 0.0;
  for (int k = 0; k < 2; ++k) {
    bool up = k == 0 ? up0 : up1;
    vec3 p = k == 0 ? p0 : p0 + lc * u;
    float l = k == 0 ? lc : len - lc;
    sum += (up ? b : a) * glowInverseDistance(up ? p - dot(p, dir) * dir : p, up ? qc : u,
                                              up ? speed_c : speed_u, up ? inv_c : inv_u, l, eps);
  }
  return sum;
}
