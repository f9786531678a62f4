// Refinement, eq. 6 over the probes (refineBracket).
layout(rgba32f, binding = 1) uniform image2D i_hit;
uniform sampler2D u_pot;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  if (b.z <= 0.0) return;
  float q[4];
  refineProbes(b, q);
  imageStore(i_hit, p, refineBracket(b, q, texelFetch(u_pot, p, 0)));
}
