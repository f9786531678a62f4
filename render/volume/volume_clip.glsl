// The clip region (clip.planes, clip.box; common/clip.h) in the volume renderers' shaders: its
// half-spaces n . x <= w as (n, w), the box as its six faces. clipRay() is common/clip.h clipSpan()
// in float: every brick evaluates the same uniforms on the same ray, so each brick cuts a ray at the
// same t and a sample is taken iff its t lies in the clipped span, whichever brick owns it.
uniform vec4 u_clip[32];   // kMaxClipHalfSpaces
uniform int u_clip_count;

// The span (t0, t1) of the ray o + t d cut to the clip region (empty: t0 >= t1).
vec2 clipRay(vec3 o, vec3 d, vec2 span) {
  for (int i = 0; i < u_clip_count; ++i) {
    float nd = dot(u_clip[i].xyz, d), gap = u_clip[i].w - dot(u_clip[i].xyz, o);
    if (nd > 0.0) span.y = min(span.y, gap / nd);
    else if (nd < 0.0) span.x = max(span.x, gap / nd);
    else if (gap < 0.0) span.y = min(span.y, span.x);
  }
  return span;
}

// Whether the clip region keeps point p (slicing's fragments).
bool clipKeeps(vec3 p) {
  for (int i = 0; i < u_clip_count; ++i)
    if (dot(u_clip[i].xyz, p) > u_clip[i].w) return false;
  return true;
}
