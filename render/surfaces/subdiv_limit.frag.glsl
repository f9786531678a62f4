// Subdivision surfaces, pass 2 (render/surfaces/subdiv_renderer.h): one fragment per pixel (the
// fullscreen triangle, render/gl/fullscreen.vert.glsl, scissored to the region) starts from pass
// 1's nearest coarse (u, v, face) and finds the exact limit point on its ray. The evaluation is
// subdiv/subdiv_tables.cpp's evaluateTables, line for line.
layout(std430, binding = 0) readonly buffer Faces { ivec2 faces[]; };      // first_set, type (0 irregular, 1 regular, 2 split)
layout(std430, binding = 1) readonly buffer Positions { vec4 positions[]; };
layout(std430, binding = 2) readonly buffer Tangents { vec4 tangents[]; };
layout(std430, binding = 3) readonly buffer Neighbours { ivec4 neighbours[]; };  // across edge c: face * 4 + its edge
uniform vec3 eye, clip_lo, clip_hi, colour, centre, light_dir, stripe_axis;
// The pixel's ray, as Camera::pixelRay: from `eye` along forward + sx * right + sy * up (right and
// up scaled by the half field of view) or, orthographic, along forward from eye + sx * right +
// sy * up (scaled by parallel_scale); independent of the near and far planes, so every brick sees
// one ray. Distances t and the view direction are measured from the ray's origin.
uniform vec3 ray_forward, ray_right, ray_up;
uniform int orthographic;
uniform vec2 image_size;
// Pass 1's nearest coarse fragment of this surface per pixel: (u, v, face, 1).
uniform sampler2D coarse;
// The (t, normal) target itself: the nearest of the layer underneath (metaballs) and the surfaces
// drawn before this one, read at this fragment's own pixel only (after a texture barrier).
uniform sampler2D nearest;
uniform float size, stripe_width;
uniform int stripes, reflection_lines, newton_steps;
layout(location = 0) out vec4 out_colour;
layout(location = 1) out vec4 out_surface;
layout(location = 2) out vec4 out_param;

void basis(float t, out vec4 b, out vec4 db) {
  float s = 1.0 - t, t2 = t * t, t3 = t2 * t;
  b = vec4(s * s * s, 3.0 * t3 - 6.0 * t2 + 4.0, -3.0 * t3 + 3.0 * t2 + 3.0 * t + 1.0, t3) / 6.0;
  db = vec4(-0.5 * s * s, 1.5 * t2 - 2.0 * t, -1.5 * t2 + t + 0.5, 0.5 * t2);
}

// Where (face, u, v) is in the tables: the first of its 16 control points, the sub-patch's own
// (s, t) and the scale of its parameters to the face's. A face's extraordinary corner is its
// corner 0 (buildControlMesh checks), so (u, v) is the patch's own frame: no rotation. A face
// split at semi-sharp tags is a tree: down it to the leaf whose square holds (u, v).
void locate(int face, float u, float v, out int set, out float s, out float t, out float scale) {
  ivec2 e = faces[face];
  scale = 1.0;
  while (e.y == 2) {
    int a = u >= 0.5 ? 1 : 0, b = v >= 0.5 ? 1 : 0;
    u = 2.0 * u - float(a);
    v = 2.0 * v - float(b);
    scale *= 2.0;
    e = faces[e.x + (b == 0 ? a : 3 - a)];
  }
  set = e.x;
  s = u; t = v;
  if (e.y == 0) {
    float m = max(u, v);
    int n = 15;
    if (m > 0.0) n = clamp(int(floor(-log2(m))) + 1, 1, 15);
    float su = ldexp(u, n), sv = ldexp(v, n);
    int k;
    if (su >= 1.0 && sv >= 1.0) k = 2;
    else if (su >= 1.0) k = 1;
    else if (sv >= 1.0) k = 3;
    else k = su >= sv ? 1 : 3;
    s = su - (k != 3 ? 1.0 : 0.0);
    t = sv - (k != 1 ? 1.0 : 0.0);
    set += (n - 1) * 3 + (k - 1);
    scale *= ldexp(1.0, n);
  }
}

// (face, u, v) on its patch: locate's answer and the B-spline bases (and their derivatives) at
// the sub-patch's (s, t), which a point and its tangents both weigh their 16 control points by.
struct PatchPoint {
  int set;
  float s, t, scale;
  vec4 bs, dbs, bt, dbt;
};

PatchPoint patchPoint(int face, float u, float v) {
  PatchPoint q;
  locate(face, u, v, q.set, q.s, q.t, q.scale);
  basis(q.s, q.bs, q.dbs);
  basis(q.t, q.bt, q.dbt);
  return q;
}

// Limit position and its true derivatives in the face's own (u, v): all a Newton step needs (the
// tangent points, 16 more fetches, are for the normal alone).
void evaluatePoint(int face, float u, float v, out vec3 p, out vec3 su, out vec3 sv) {
  PatchPoint q = patchPoint(face, u, v);
  p = vec3(0.0);
  vec3 ps = vec3(0.0), pt = vec3(0.0);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      vec3 c = positions[q.set * 16 + b * 4 + a].xyz;
      p += q.bs[a] * q.bt[b] * c;
      ps += q.dbs[a] * q.bt[b] * c;
      pt += q.bs[a] * q.dbt[b] * c;
    }
  // The sub-patch's derivatives scaled back to the face's parameters.
  su = ps * q.scale;
  sv = pt * q.scale;
}

// The tangent-point derivatives (for the normal) at (face, u, v).
void evaluateTangents(int face, float u, float v, out vec3 tu, out vec3 tv) {
  PatchPoint q = patchPoint(face, u, v);
  tu = vec3(0.0);
  tv = vec3(0.0);
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      vec3 r = tangents[q.set * 16 + b * 4 + a].xyz;
      tu += q.dbs[a] * q.bt[b] * r;
      tv += q.bs[a] * q.dbt[b] * r;
    }
}

void main() {
  ivec2 px = ivec2(gl_FragCoord.xy);
  vec4 c0 = texelFetch(coarse, px, 0);
  int face = int(round(c0.z));
  float u = clamp(c0.x, 0.0, 1.0), v = clamp(c0.y, 0.0, 1.0);
  vec3 p, ds, dt, su, sv;
  // Newton steps move (u, v) until the limit point lies on this pixel's ray, so the pixel shows
  // the surface where its ray meets it, whatever the coarse level.
  vec2 ndc = 2.0 * gl_FragCoord.xy / image_size - 1.0;
  vec3 o = eye, dir = ray_forward;
  if (orthographic != 0) o += ndc.x * ray_right - ndc.y * ray_up;
  else dir = normalize(ray_forward + ndc.x * ray_right - ndc.y * ray_up);
  vec3 e1 = normalize(abs(dir.x) < 0.9 ? cross(dir, vec3(1, 0, 0)) : cross(dir, vec3(0, 1, 0)));
  vec3 e2 = cross(dir, e1);
  // Each round evaluates the limit point at (u, v); the loop ends with p that of the final (u, v):
  // after newton_steps steps, or earlier once p is within 1e-6 of the size of the ray (a few
  // times float rounding there; a further step would move p by less), which saves the rest.
  for (int i = 0; i <= newton_steps; ++i) {
    evaluatePoint(face, u, v, p, su, sv);
    if (i == newton_steps) break;
    vec2 f = vec2(dot(e1, p - o), dot(e2, p - o));
    if (dot(f, f) <= 1e-12 * size * size) break;
    mat2 J = mat2(dot(e1, su), dot(e2, su), dot(e1, sv), dot(e2, sv));  // columns: d/du, d/dv
    if (abs(determinant(J)) < 1e-20) break;
    vec2 next = vec2(u, v) - inverse(J) * f;
    // Leaving the face across an edge: continue on the neighbour, in its (u, v). Edge c's frame
    // is (a along the edge from corner c, b into the face); the neighbour's edge runs the other way.
    float out_by = max(max(-next.x, next.x - 1.0), max(-next.y, next.y - 1.0));
    if (out_by > 0.0) {
      int c = -next.y >= out_by ? 0 : (next.x - 1.0 >= out_by ? 1 : (next.y - 1.0 >= out_by ? 2 : 3));
      vec2 ab = c == 0 ? next : (c == 1 ? vec2(next.y, 1.0 - next.x)
                              : (c == 2 ? vec2(1.0 - next.x, 1.0 - next.y) : vec2(1.0 - next.y, next.x)));
      int across = neighbours[face][c];
      int d = across & 3;
      vec2 g = vec2(1.0 - ab.x, -ab.y);
      // Across a boundary edge (an open mesh: -1) there is no face: stay on this one, clamped.
      if (across >= 0) next = d == 0 ? g : (d == 1 ? vec2(1.0 - g.y, g.x) : (d == 2 ? vec2(1.0 - g.x, 1.0 - g.y) : vec2(g.y, 1.0 - g.x)));
      if (across >= 0) face = across >> 2;
    }
    u = clamp(next.x, 0.0, 1.0);
    v = clamp(next.y, 0.0, 1.0);
  }
  evaluateTangents(face, u, v, ds, dt);
  // The brick owns the fragment whose exact limit point it holds (half-open box).
  if (any(lessThan(p, clip_lo)) || any(greaterThanEqual(p, clip_hi))) discard;
  if (texelFetch(nearest, px, 0).x <= length(p - o)) discard;
  vec3 n = normalize(cross(ds, dt));
  vec3 view = normalize(p - o);
  vec3 rgb;
  if (reflection_lines == 1) {
    // The reflected view ray against a striped planar light facing the surface.
    vec3 r = reflect(view, n);
    float facing = dot(r, light_dir);
    float lit = 0.0;
    if (facing > 1e-6) {
      vec3 x = p + r * (dot(centre + 2.0 * size * light_dir - p, light_dir) / facing);
      // A square light 8 sizes wide, its stripes across `stripe_axis`.
      vec3 along = x - centre;
      float a = dot(along, stripe_axis) / (8.0 * size), b = dot(along, cross(light_dir, stripe_axis)) / (8.0 * size);
      // Stripe edges ramp over 4 % of a period: a function of the limit point alone (screen-space
      // derivatives would differ with the coarse triangles), and no jump from dark to bright for a
      // rounding-sized shift.
      float c = float(stripes) * (a + 0.5), f = fract(c);
      float d = f < stripe_width ? min(f, stripe_width - f) : -min(f - stripe_width, 1.0 - f);
      if (abs(a) < 0.5 && abs(b) < 0.5) lit = clamp(d / 0.04 + 0.5, 0.0, 1.0);
    }
    rgb = colour * (0.12 + 0.88 * lit);
  } else {
    float diffuse = abs(dot(n, view));
    float specular = pow(diffuse, 40.0);  // headlight: the half vector is the view direction
    rgb = colour * (0.15 + 0.85 * diffuse) + 0.25 * vec3(specular);
  }
  out_colour = vec4(clamp(rgb, 0.0, 1.0), 1.0);
  out_surface = vec4(length(p - o), n);
  out_param = vec4(float(face), u, v, 1.0);  // after the Newton steps
}
