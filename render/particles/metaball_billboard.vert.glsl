// Billboards: for each particle the square facing the eye in front of its sphere of influence
// (the front face of the paper's bounding cube), drawn as an instanced 4-vertex strip. With
// culling on, a particle whose distance range [d - h, d + h] cannot meet any pixel's [lo, hi]
// in the tile it covers is moved off screen before rasterisation (§4.3).
// Orthographic: the square faces the view direction and d is the centre's depth in front of the
// eye plane (every parallel ray meets the sphere within [d - h, d + h] of its origin); its
// projection does not depend on its depth, so its vertices are put at depth 0 of the clip volume,
// drawn whatever the near and far planes.
layout(location = 0) in vec3 a_centre;
uniform mat4 u_view_proj;
uniform sampler2D u_pyramid;
uniform int u_levels;        // 0: no culling
uniform float u_cull_pad;    // cull when d + pad < tile lo, or d - h > tile hi
uniform ivec4 u_rect;        // x, y, w, h of the brick's screen rectangle
flat out vec3 v_centre;
void main() {
  vec3 c = a_centre;
  vec3 n = c - cameraEye();
  float dist = u_orthographic != 0 ? dot(n, u_fwd) : length(n);
  n = u_orthographic != 0 ? u_fwd : n / dist;
  vec3 a = abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0);
  vec3 u = normalize(cross(n, a)), v = cross(n, u);
  vec3 f = c - u_h * n;
  vec2 lo = vec2(INF), hi = vec2(-INF);
  bool behind = false;
  vec4 mine = vec4(0.0);
  for (int i = 0; i < 4; ++i) {
    vec2 k = vec2(float(i & 1), float(i >> 1)) * 2.0 - 1.0;
    vec4 q = u_view_proj * vec4(f + u_h * (k.x * u + k.y * v), 1.0);
    if (i == gl_VertexID) mine = q;
    if (q.w <= 0.0) behind = true;
    vec2 s = (q.xy / q.w * 0.5 + 0.5) * u_size;
    lo = min(lo, s);
    hi = max(hi, s);
  }
  if (u_orthographic != 0) mine.z = 0.0;  // w = 1: inside the clip volume's depth range
  gl_Position = mine;
  v_centre = c;
  if (u_levels > 0 && !behind) {
    vec2 rlo = vec2(u_rect.xy), rhi = vec2(u_rect.xy + u_rect.zw) - 1.0;
    bool culled = any(lessThan(hi, rlo)) || any(greaterThan(lo, rhi + 1.0));
    if (!culled) {
      ivec2 p0 = ivec2(clamp(lo, rlo, rhi)), p1 = ivec2(clamp(hi, rlo, rhi));
      int span = max(p1.x - p0.x, p1.y - p0.y);
      // Tiles a quarter of the billboard's size (up to 5 x 5 fetches): coarser tiles mix
      // distances from too far away to cull much (measured: 2.6x slower frames on the 4,096-
      // particle slab at 512^2 than this level; an eighth was no better).
      int level = max(0, (span <= 0 ? 0 : int(ceil(log2(float(span + 1))))) - 2);
      if (level < u_levels) {
        ivec2 q0 = p0 >> level, q1 = p1 >> level, last = textureSize(u_pyramid, level) - 1;
        vec2 m = vec2(INF, -INF);
        for (int y = q0.y; y <= q1.y; ++y)
          for (int x = q0.x; x <= q1.x; ++x) {
            vec2 t = texelFetch(u_pyramid, min(ivec2(x, y), last), level).rg;
            m = vec2(min(m.x, t.x), max(m.y, t.y));
          }
        culled = dist + u_cull_pad < m.x || dist - u_h > m.y;
      }
    }
    if (culled) gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
  }
}
