// glowPixelRay(): this fragment's ray as the ray caster makes it (render/volume/raycast_march.frag.glsl
// pixelRay, Camera::pixelRay), so t along it is the surface layer's t: its origin, the eye or,
// orthographic, the pixel's point on the eye plane (o), and its unit direction (returned). Row y
// of the target is image row y from the top: s.y = 1 - 2 (y + 0.5) / height. Its uniforms are set
// by setPixelRayUniforms (render/glow/glow_gl.h).
uniform vec3 u_eye, u_forward, u_right, u_up;
uniform int u_orthographic;  // 1: parallel rays along u_forward
uniform vec2 u_pixel_scale;
vec3 glowPixelRay(out vec3 o) {
  vec2 s = vec2(gl_FragCoord.x * u_pixel_scale.x - 1.0, 1.0 - gl_FragCoord.y * u_pixel_scale.y);
  o = u_eye;
  if (u_orthographic != 0) {
    o += s.x * u_right + s.y * u_up;
    return u_forward;
  }
  return normalize(u_forward + s.x * u_right + s.y * u_up);
}
