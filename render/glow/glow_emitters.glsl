// The emitters' uniforms (their texture, render/glow/glow_gl.h: u_glow_emitters, u_glow_count rows;
// core radius u_glow_eps; bound by bindGlowEmitters) and glowSpan(), which every glow program
// needs (the glow pass and the ray caster's GLOW variant).
uniform sampler2D u_glow_emitters;
uniform int u_glow_count;
uniform float u_glow_eps;

// The ray's span inside [lo, hi], t >= 0; false: it misses. An axis the ray does not move along
// is tested by position (no 0 * inf): a ray lying in a face plane between two bricks belongs to
// the brick above it only (hi_open 1 on that axis: [lo, hi)), so it is neither lost nor counted
// twice; the glow box's own upper faces are closed, as the reference's box is. Straight-line
// (selects, no loop with early returns): llvmpipe runs a per-pixel loop's control flow masked.
bool glowSpan(vec3 o, vec3 u, vec3 lo, vec3 hi, vec3 hi_open, out float t0, out float t1) {
  bvec3 still = equal(u, vec3(0.0));
  vec3 a = (lo - o) / u, b = (hi - o) / u;  // not used on a still axis (inf or NaN there)
  vec3 near = mix(min(a, b), vec3(0.0), still), far = mix(max(a, b), vec3(3.0e38), still);
  t0 = max(max(0.0, near.x), max(near.y, near.z));
  t1 = min(min(3.0e38, far.x), min(far.y, far.z));
  bvec3 outside = bvec3(lessThan(o, lo).x || greaterThan(o, hi).x || (hi_open.x > 0.5 && o.x == hi.x),
                        lessThan(o, lo).y || greaterThan(o, hi).y || (hi_open.y > 0.5 && o.y == hi.y),
                        lessThan(o, lo).z || greaterThan(o, hi).z || (hi_open.z > 0.5 && o.z == hi.z));
  return !any(bvec3(still.x && outside.x, still.y && outside.y, still.z && outside.z)) && t1 > t0;
}
