// Before a refinement pass: each hit pixel's bracket as [lo, hi] for culling.
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 b = imageLoad(i_hit, p);
  imageStore(i_base, p, b.z > 0.0 ? vec4(b.x, b.z, 0.0, 0.0) : vec4(INF, -INF, 0.0, 0.0));
}
