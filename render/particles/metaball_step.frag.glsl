// After the potential pass: walk the window's samples in order, looking for the first I >= 0.
// Pixels still searching pass the fragment test, so an occlusion query tells the host whether
// another window is needed.
layout(rgba32f, binding = 0) uniform image2D i_state;
layout(rgba32f, binding = 1) uniform writeonly image2D i_hit;
layout(rg32f, binding = 2) uniform writeonly image2D i_base;
uniform sampler2D u_next;
uniform sampler2D u_pot;
uniform sampler2D u_pot2;
uniform float u_cap;  // samples allowed per pixel
out vec4 o_unused;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 st = imageLoad(i_state, p);
  if (st.x >= 0.5 * INF) discard;
  vec2 iv = clipInterval(pixelRay(gl_FragCoord.xy));
  if (st.x < 0.0) {
    // Skipped ahead this round (see the window pass): still searching, nothing sampled.
    float t_next = -st.x;
    if (t_next >= iv.y) {
      imageStore(i_state, p, vec4(INF, st.yzw));
      imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
      discard;
    }
    imageStore(i_state, p, vec4(t_next, st.yzw));
    imageStore(i_base, p, vec4(t_next, lookaheadEnd(t_next, iv.y), 0.0, 0.0));
    o_unused = vec4(1.0);
    return;
  }
  vec4 f = texelFetch(u_pot, p, 0), f2 = texelFetch(u_pot2, p, 0);
  float s[8];
  windowSamples(texelFetch(u_next, p, 0).x, iv.y, s);
  float t_last = st.z, i_last = st.y, n = st.w;
  bool done = false;
  for (int k = 0; k < u_window; ++k) {
    if (k > 0 && s[k] == s[k - 1]) break;
    if (n >= u_cap) { done = true; break; }  // out of samples: a hole, the paper's Fig. 12
    float field = k < 4 ? f[k] : f2[k - 4];
    float value = sqrt(field) - u_T;
    // Only samples inside some particle's reach count against the cap: a window of 8 runs on
    // through gaps a window of 4 would jump, and those samples must not use up the budget.
    if (field > 0.0) n += 1.0;
    if (value >= 0.0) {
      // A sample exactly at the box entry that is already inside: the surface lies in front of
      // this brick (its owner draws it), so this brick shows nothing here.
      if (s[k] > iv.x) imageStore(i_hit, p, vec4(t_last, i_last, s[k], value));
      done = true;
      break;
    }
    t_last = s[k];
    i_last = value;
    if (s[k] >= iv.y) { done = true; break; }
  }
  if (done) {
    imageStore(i_state, p, vec4(INF, i_last, t_last, n));
    imageStore(i_base, p, vec4(INF, -INF, 0.0, 0.0));
    discard;
  }
  // The next lattice point, or the box exit if that comes first: the exit is always sampled, so
  // a surface between the last lattice point and the face is found in this brick.
  float t_next = min(latticeNext(s[u_window - 1]), iv.y);
  imageStore(i_state, p, vec4(t_next, i_last, t_last, n));
  imageStore(i_base, p, vec4(t_next, lookaheadEnd(t_next, iv.y), 0.0, 0.0));
  o_unused = vec4(1.0);
}
