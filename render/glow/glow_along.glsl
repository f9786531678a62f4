// glowAlong(o, u, s0, s1): the colour-weighted sum of every emitter's integral over [s0, s1] of
// the ray o + s u (unit u). After glow_segment.glsl and glow_emitters.glsl. (The ray caster sums
// glowSegment itself, with the field's slope: glowFlushDue, render/volume/raycast_glow.frag.glsl.)
vec3 glowAlong(vec3 o, vec3 u, float s0, float s1) {
  vec3 sum = vec3(0.0);
  if (!(s1 > s0)) return sum;
  for (int i = 0; i < u_glow_count; ++i) {
    vec4 e0 = texelFetch(u_glow_emitters, ivec2(0, i), 0), e1 = texelFetch(u_glow_emitters, ivec2(1, i), 0);
    vec3 colour = texelFetch(u_glow_emitters, ivec2(2, i), 0).rgb;
    sum += colour * glowSegment(e0.xyz, e1.xyz, e0.w, e1.w, u_glow_eps, o, u, s0, s1);
  }
  return sum;
}
