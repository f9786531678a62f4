// The vertex shader of every fullscreen pass (the ray caster, the glow pass, the metaball passes,
// the subdivision surfaces' per-pixel pass): one triangle (gl_VertexID 0..2, no attributes) whose
// corners (-1, -1), (3, -1), (-1, 3) cover the viewport; the scissor picks the pixels.
void main() {
  vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1);
  gl_Position = vec4(p, 0.0, 1.0);
}
