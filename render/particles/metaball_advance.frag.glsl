// Where may this pixel's next window start (eqs. 2-4)? MIN-blended over all particles into
// `next`. The paper bounds each particle by a cube; the exact sphere entry is used here instead,
// which skips strictly more empty space and samples the same lattice points.
flat in vec3 v_centre;
uniform sampler2D u_state;
out float o_next;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  float t_next = texelFetch(u_state, p, 0).x;
  if (t_next >= 0.5 * INF) discard;
  vec3 d = pixelRay(gl_FragCoord.xy);
  vec3 oc = v_centre - u_eye;
  float tb = dot(d, oc);
  if (tb < t_next) discard;  // eq. 3: its candidate region ends before the next sample
  vec3 perp = oc - tb * d;
  float perp2 = dot(perp, perp);
  if (perp2 >= u_h * u_h) discard;  // the ray misses its sphere of influence
  float tf = tb - sqrt(u_h * u_h - perp2);
  o_next = tf <= t_next ? t_next : latticeCeil(tf);  // eq. 4
}
