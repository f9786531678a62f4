// After refinement: the surface is the secant estimate in the final bracket (eq. 5).
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
layout(r32f, binding = 3) uniform writeonly image2D i_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  if (b.z <= 0.0) {
    imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
    return;
  }
  float t = secantEstimate(b);
  imageStore(i_next, p, vec4(t));
  imageStore(i_base, p, vec4(t, t, 0.0, 0.0));
}
