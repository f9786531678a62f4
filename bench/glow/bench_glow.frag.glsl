// bench/glow/main.cpp's pass: render/glow/glow_pass.frag.glsl without the surface layer,
// tone-mapped here because this benchmark has no compositing (one brick, the final frame). After
// glow_segment, glow_emitters, glow_along and glow_pixel_ray (render/glow/).
uniform vec3 u_box_lo, u_box_hi;
uniform float u_intensity, u_exposure;
out vec4 frag;
void main() {
  vec3 o;
  vec3 dir = glowPixelRay(o);
  float t0, t1;
  vec3 sum = vec3(0.0);
  if (glowSpan(o, dir, u_box_lo, u_box_hi, vec3(0.0), t0, t1)) sum = glowAlong(o, dir, t0, t1);
  // Tone-mapped here only because this benchmark has no compositing: one brick, the final frame.
  frag = vec4(1.0 - exp(-u_exposure * u_intensity * sum), 1.0);
}
