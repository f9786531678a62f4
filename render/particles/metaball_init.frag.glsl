// Start of a brick: the clip interval, and "next window starts at the box entry".
layout(rgba32f, binding = 0) uniform writeonly image2D i_state;
layout(rgba32f, binding = 1) uniform writeonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec2 iv = clipInterval(pixelRay(gl_FragCoord.xy));
  bool inside = iv.x < iv.y;
  // Before the first sample the field is taken as 0 (I = -T): if the box entry lies inside a
  // sphere of influence, the first window starts exactly there and measures it.
  imageStore(i_state, p, inside ? vec4(iv.x, -u_T, iv.x, 0.0) : vec4(INF, -u_T, 0.0, 0.0));
  imageStore(i_hit, p, vec4(0.0));
  imageStore(i_base, p, inside ? vec4(iv.x, lookaheadEnd(iv.x, iv.y), 0.0, 0.0) : vec4(INF, -INF, 0.0, 0.0));
}
