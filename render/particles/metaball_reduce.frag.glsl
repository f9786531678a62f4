// One level of the min/max pyramid from the level below; children wholly outside the brick's
// rectangle hold stale values from earlier bricks and are ignored.
layout(rg32f, binding = 5) uniform readonly image2D i_below;
layout(rg32f, binding = 6) uniform writeonly image2D i_level;
uniform int u_level;
uniform ivec4 u_rect;
void main() {
  ivec2 q = ivec2(gl_FragCoord.xy);
  int cs = 1 << (u_level - 1);
  ivec2 size = imageSize(i_below);
  vec2 m = vec2(1e30, -1e30);
  for (int dy = 0; dy < 2; ++dy)
    for (int dx = 0; dx < 2; ++dx) {
      ivec2 c = 2 * q + ivec2(dx, dy);
      ivec2 lo = c * cs, hi = lo + cs - 1;
      if (any(greaterThanEqual(c, size)) || hi.x < u_rect.x || hi.y < u_rect.y ||
          lo.x >= u_rect.x + u_rect.z || lo.y >= u_rect.y + u_rect.w)
        continue;
      vec2 t = imageLoad(i_below, c).rg;
      m = vec2(min(m.x, t.x), max(m.y, t.y));
    }
  imageStore(i_level, q, vec4(m, 0.0, 0.0));
}
