// glowPixelRay(): the unit direction of this fragment's ray from u_eye, as the ray caster makes it
// (render/volume/raycast_march.frag.glsl), so t along it is the surface layer's t. Row y of the
// target is image row y from the top: s.y = 1 - 2 (y + 0.5) / height. Its uniforms are set by
// setPixelRayUniforms (render/glow/glow_gl.h).
uniform vec3 u_eye, u_forward, u_right, u_up;
uniform vec2 u_pixel_scale;
vec3 glowPixelRay() {
  vec2 s = vec2(gl_FragCoord.x * u_pixel_scale.x - 1.0, 1.0 - gl_FragCoord.y * u_pixel_scale.y);
  return normalize(u_forward + s.x * u_right + s.y * u_up);
}
