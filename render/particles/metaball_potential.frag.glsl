// Field contributions (eq. 7) added up by blending. Mode 0: the window's samples (§4.2);
// mode 1: the 4 refinement probes of the pixel's bracket; mode 2: gradient and field at `next`.
flat in vec3 v_centre;
uniform sampler2D u_state;
uniform sampler2D u_hit;
uniform sampler2D u_next;
uniform int u_mode;
out vec4 o_sum;
layout(location = 1) out vec4 o_sum2;  // samples 4-7 of an 8-sample window
float field(float s, float tb, float perp2) {
  float ds = s - tb;
  float q = max(1.0 - sqrt(perp2 + ds * ds) / u_h, 0.0);
  return q * q;
}
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (u_mode == 0) {
    float t_next = texelFetch(u_state, p, 0).x;
    if (t_next >= 0.5 * INF || t_next < 0.0) discard;
  } else if (texelFetch(u_hit, p, 0).z <= 0.0) {
    discard;
  }
  vec3 d = pixelRay(gl_FragCoord.xy);
  vec3 oc = v_centre - u_eye;
  float tb = dot(d, oc);
  vec3 perp = oc - tb * d;
  float perp2 = dot(perp, perp);
  if (perp2 >= u_h * u_h) discard;
  float s0 = texelFetch(u_next, p, 0).x;
  if (u_mode == 0) {
    float s[8];
    windowSamples(s0, clipInterval(d).y, s);
    o_sum = vec4(field(s[0], tb, perp2), field(s[1], tb, perp2), field(s[2], tb, perp2),
                 field(s[3], tb, perp2));
    o_sum2 = u_window > 4 ? vec4(field(s[4], tb, perp2), field(s[5], tb, perp2),
                                 field(s[6], tb, perp2), field(s[7], tb, perp2))
                          : vec4(0.0);
  } else if (u_mode == 1) {
    float q[4];
    refineProbes(texelFetch(u_hit, p, 0), q);
    o_sum = vec4(field(q[0], tb, perp2), field(q[1], tb, perp2), field(q[2], tb, perp2),
                 field(q[3], tb, perp2));
    o_sum2 = vec4(0.0);
  } else {
    // r = x - c = (s - tb) d - perp; dP/dx = -2 (1 - |r|/h) / h * r / |r| (0 at the centre).
    vec3 r = (s0 - tb) * d - perp;
    float len = length(r);
    float q = max(1.0 - len / u_h, 0.0);
    vec3 g = len > 0.0 ? (-2.0 * q / (u_h * len)) * r : vec3(0.0);
    o_sum = vec4(g, q * q);
    o_sum2 = vec4(0.0);
  }
}
