// Shading (shade(), transfer/metaball_shading.h). Also stores (t, N) for depth tests and the
// surface output; misses get t = INF.
layout(rgba32f, binding = 1) uniform readonly image2D i_hit;
layout(rgba32f, binding = 4) uniform writeonly image2D i_surface;
uniform sampler2D u_next;
uniform sampler2D u_pot;
uniform vec3 u_colour;
out vec4 o_colour;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (imageLoad(i_hit, p).z <= 0.0) {
    imageStore(i_surface, p, vec4(INF, 0.0, 0.0, 0.0));
    o_colour = vec4(0.0);
    return;
  }
  vec3 d = pixelRay(gl_FragCoord.xy);
  vec3 n;
  o_colour = shade(u_colour, texelFetch(u_pot, p, 0).xyz, d, n);
  imageStore(i_surface, p, vec4(texelFetch(u_next, p, 0).x, n));
}
