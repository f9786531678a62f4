// tests/unit/glow_glsl_test.cpp's pass: one case per pixel (x), its inputs in a 5-texel row of
// u_cases, glowSegment (render/glow/glow_segment.glsl, the chunk before this one) evaluated as the
// ray caster and the glow pass evaluate it.
uniform sampler2D u_cases;
out vec4 frag;
void main() {
  int i = int(gl_FragCoord.x);
  vec4 t0 = texelFetch(u_cases, ivec2(0, i), 0), t1 = texelFetch(u_cases, ivec2(1, i), 0);
  vec4 t2 = texelFetch(u_cases, ivec2(2, i), 0), t3 = texelFetch(u_cases, ivec2(3, i), 0);
  float s1 = texelFetch(u_cases, ivec2(4, i), 0).x;
  frag = vec4(glowSegment(t0.xyz, t1.xyz, t0.w, t1.w, t2.w, t2.xyz, t3.xyz, t3.w, s1), 0.0, 0.0, 1.0);
}
