// The glow pass alone (render/glow/glow_renderer.h): each pixel's ray through this brick's part of
// the glow box, up to the particle or surface layer's t, summing every emitter's exact integral.
// After glow_segment, glow_emitters, glow_along and glow_pixel_ray (glow_renderer.cpp composes it).
uniform vec3 u_box_lo, u_box_hi, u_box_hi_open;
uniform float u_intensity;
uniform sampler2D u_surface;
uniform int u_has_surface;
uniform ivec4 u_surface_rect;
out vec4 frag;
void main() {
  vec3 o;
  vec3 dir = glowPixelRay(o);
  float t0, t1;
  vec3 sum = vec3(0.0);
  if (glowSpan(o, dir, u_box_lo, u_box_hi, u_box_hi_open, t0, t1)) {
    ivec2 px = ivec2(gl_FragCoord.xy);
    if (u_has_surface != 0 && all(greaterThanEqual(px, u_surface_rect.xy)) &&
        all(lessThan(px, u_surface_rect.xy + u_surface_rect.zw)))
      t1 = min(t1, texelFetch(u_surface, px, 0).x);
    sum = glowAlong(o, dir, t0, t1);
  }
  frag = vec4(u_intensity * sum, 0.0);  // added to what the target holds: no opacity
}
