// After the advance pass: the window this pixel samples next, as [lo, hi] for culling.
layout(rgba32f, binding = 0) uniform image2D i_state;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
uniform sampler2D u_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 st = imageLoad(i_state, p);
  vec2 base = vec2(INF, -INF);
  if (st.x < 0.5 * INF) {
    float t_out = clipInterval(pixelRay(gl_FragCoord.xy)).y;
    float s0 = texelFetch(u_next, p, 0).x;
    float ahead = lookaheadEnd(st.x, t_out);
    if (s0 > ahead && ahead >= t_out) {
      // No candidate region before the box exit: nothing more to find in this brick.
      imageStore(i_state, p, vec4(INF, st.yzw));
    } else if (s0 > ahead) {
      // No candidate within the lookahead (the particles beyond it were not drawn): skip to its
      // end without sampling. A negative t marks the skip for the potential and step passes.
      imageStore(i_state, p, vec4(-latticeCeil(ahead), st.yzw));
    } else {
      float s[8];
      windowSamples(s0, t_out, s);
      base = vec2(s[0], s[u_window - 1]);
    }
  }
  imageStore(i_base, p, vec4(base, 0.0, 0.0));
}
