// Isosurfaces in the ray caster (render.blend: isosurface; the program compiled with ISOSURFACE
// defined, this chunk after raycast_sample.frag.glsl): the crossings of the isovalues along the
// ray's lattice, refined, shaded and composited (transfer/isosurface.h has the model).
//
// Intervals and who owns them. The ray inside the volume is cut at its lattice samples
// t_k = k delta, clipped to where it enters the volume cut by the clip region (g_span_t0) and to
// where it ends: the far side of that span (g_span_t1) or an opaque surface's t. Each interval (previous point, point] is
// owned by the brick that owns its end point: a lattice sample by its owner
// (raycast_march.frag.glsl's rule, exactly one brick), the ray's end by the brick it ends in. So
// every interval, and every crossing found in it, is counted exactly once across brick faces,
// whatever the decomposition. The interval ending at a brick's first sample starts at the sample
// before, up to one step outside the brick: it is read from the brick's one-voxel ghost layer,
// which holds it while delta <= 1 voxel (the scene refuses render.sample_spacing > 1 with
// isosurfaces), as are the refinement's samples inside it and the hit's cell. Both neighbours
// read that value from identical data at the same float position, so they agree.
//
// A crossing of isovalue v: "value >= v" differs at the interval's two ends. Found, it is
// bisected (ISO_BISECTIONS halvings of the bracket, then one secant step inside it) on the
// field the texture filters (llvmpipe: in float; a hardware GPU: FLOAT_FILTER, render/volume/
// volume_filter.glsl, so in float too): the bracket ends within delta / 2^10 <= 1e-3 voxel of
// that field's crossing. Two crossings of one value within one interval (a feature thinner than a
// step, entered and left between two samples) leave its sign unchanged and are not seen; three
// show as one. The reference finds every crossing exactly (reference/isosurface_reference.h), so
// such a miss is measured as the ray caster's error. Several values crossing in one interval are
// composited in order of their refined t.
//
// Adaptive bricks are not drawn with isosurfaces (the scene refuses adaptive.tolerance > 0): their
// atlas is filtered by the texture unit (fixed-point weights on NVIDIA: up to 1/256 of a voxel
// step off, a position error of up to 1/256 voxel where the field changes by one step per voxel,
// above the 1e-3 bound) and holds no value across a block face for the sample before a block.
#ifndef ISO_BISECTIONS
#define ISO_BISECTIONS 10
#endif
uniform int u_iso_count;
uniform float u_iso_value[8];     // transfer/isosurface.h kMaxIsovalues
uniform vec4 u_iso_colour[8];     // rgb, opacity
uniform vec3 u_iso_phong;         // ka, kd, ks
uniform float u_iso_shininess;    // p
uniform vec3 u_iso_inv_spacing;   // 1 / world spacing per axis
// (u_vol_lo, u_vol_hi: the whole volume's box, raycast_sample.frag.glsl.)

#ifdef ISO_DEBUG
// The debug output (RaycastSettings::iso_debug): the first hit's (t, unit gradient); t = 0: none.
vec4 g_iso_first = vec4(0.0);
#endif
#ifdef ISO_DEPTH
// The depth output (RaycastRenderer::renderIsoDepth, for --surface-out): the opaque hit's (t,
// outward unit normal), the normal pointing down the gradient, towards lower values (a metaball
// surface's outward normal, the field being higher inside); t = 0: no opaque hit in this brick.
vec4 g_iso_opaque = vec4(0.0);
#endif

// The search starts where the ray enters the whole volume cut to the clip region (g_span_t0,
// raycast_march.frag.glsl volumeSpan: the same float in every brick): the first interval runs
// from there to the first lattice sample after it, so a crossing is found only inside the kept
// span, and where the field at the entry is already beyond an isovalue that surface does not show
// on the cut face (ParaView's cropping gives the same).
// The start of the interval ending at lattice sample k.
float isoStart(int k) { return max(float(k - 1) * u_delta, g_span_t0); }

// The world gradient of the trilinear interpolant in the cell of the brick texture holding world
// point p: its 8 corners by texelFetch, the exact derivative of the interpolant there.
vec3 isoGradient(vec3 p) {
  ivec3 size = textureSize(u_volume, 0);
  vec3 u = (p * u_tex_scale + u_tex_offset) * vec3(size) - 0.5;
  ivec3 c = clamp(ivec3(floor(u)), ivec3(0), max(size - 2, ivec3(0)));
  vec3 f = clamp(u - vec3(c), 0.0, 1.0);
  float c000 = texelFetch(u_volume, c, 0).r, c100 = texelFetch(u_volume, c + ivec3(1, 0, 0), 0).r;
  float c010 = texelFetch(u_volume, c + ivec3(0, 1, 0), 0).r, c110 = texelFetch(u_volume, c + ivec3(1, 1, 0), 0).r;
  float c001 = texelFetch(u_volume, c + ivec3(0, 0, 1), 0).r, c101 = texelFetch(u_volume, c + ivec3(1, 0, 1), 0).r;
  float c011 = texelFetch(u_volume, c + ivec3(0, 1, 1), 0).r, c111 = texelFetch(u_volume, c + ivec3(1, 1, 1), 0).r;
  vec3 g;
  g.x = mix(mix(c100 - c000, c110 - c010, f.y), mix(c101 - c001, c111 - c011, f.y), f.z);
  g.y = mix(mix(c010 - c000, c110 - c100, f.x), mix(c011 - c001, c111 - c101, f.x), f.z);
  g.z = mix(mix(c001 - c000, c101 - c100, f.x), mix(c011 - c010, c111 - c110, f.x), f.y);
  return g * u_iso_inv_spacing;
}

// The crossing of `iso` in (ta, tb], where the values va and vb lie on its two sides.
float isoRefine(float ta, float va, float tb, float vb, float iso, vec3 dir) {
  bool side = va >= iso;
  float lo = ta, hi = tb, vlo = va, vhi = vb;
  for (int i = 0; i < ISO_BISECTIONS; ++i) {
    float tm = 0.5 * (lo + hi);
    float vm = sampleVolume(u_eye + tm * dir);
    if ((vm >= iso) == side) {
      lo = tm;
      vlo = vm;
    } else {
      hi = tm;
      vhi = vm;
    }
  }
  // One secant step inside the last bracket (vlo and vhi on the two sides: vhi != vlo).
  return mix(lo, hi, clamp((iso - vlo) / (vhi - vlo), 0.0, 1.0));
}

// Isovalue i's hit at t, shaded, front to back into acc; an opaque one makes acc opaque exactly.
void isoHit(inout vec4 acc, int i, float t, vec3 dir) {
  vec3 g = isoGradient(u_eye + t * dir);
  float len = length(g);
  float cosine = len > 0.0 ? min(abs(dot(g, dir)) / len, 1.0) : 1.0;
  vec3 c = u_iso_colour[i].rgb;
  vec3 shaded = clamp(c * (u_iso_phong.x + u_iso_phong.y * cosine) + u_iso_phong.z * pow(cosine, u_iso_shininess),
                      0.0, 1.0);
  float a = u_iso_colour[i].a;
  acc += (1.0 - acc.a) * vec4(shaded * a, a);
  if (a >= 1.0) acc.a = 1.0;
#ifdef ISO_DEBUG
  if (g_iso_first.x == 0.0) g_iso_first = vec4(t, len > 0.0 ? g / len : vec3(0.0));
#endif
#ifdef ISO_DEPTH
  if (a >= 1.0) g_iso_opaque = vec4(t, len > 0.0 ? -g / len : vec3(0.0));  // the ray ends here
#endif
}

// The interval (ta, tb] with end values va, vb: its crossings, nearest first.
void isoInterval(inout vec4 acc, float ta, float va, float tb, float vb, vec3 dir) {
  if (isnan(va) || isnan(vb)) return;  // a missing sample's stencil: no surface there
  float th[8];
  int found = 0;
  for (int i = 0; i < u_iso_count; ++i) {
    float iso = u_iso_value[i];
    th[i] = 1e30;
    if ((va >= iso) != (vb >= iso)) {
      th[i] = isoRefine(ta, va, tb, vb, iso, dir);
      ++found;
    }
  }
  for (; found > 0 && acc.a < 1.0; --found) {
    int best = 0;
    for (int i = 1; i < u_iso_count; ++i)
      if (th[i] < th[best]) best = i;
    isoHit(acc, best, th[best], dir);
    th[best] = 1e30;
  }
}

// The intervals ending at lattice samples k .. k_end - 1, which this block owns. v_back holds the
// value at the start of the interval ending at sample k when k_back == k (the last one taken);
// else it is read. Stops after an opaque hit.
void isoSamples(inout vec4 acc, inout int k, inout int k_back, inout float v_back, int k_end, vec3 dir) {
  float ta = isoStart(k);
  float va = k == k_back ? v_back : sampleVolume(u_eye + ta * dir);
  for (; k < k_end && acc.a < 1.0; ++k) {
    float tb = float(k) * u_delta;
    float vb = sampleVolume(u_eye + tb * dir);
    isoInterval(acc, ta, va, tb, vb, dir);
    ta = tb;
    va = vb;
  }
  k_back = k;
  v_back = va;
}

// The last interval, from lattice sample k_last (clipped to the volume) to the ray's end t_end,
// when the ray ends in this brick.
void isoTail(inout vec4 acc, int k_last, float t_end, vec3 dir) {
  float ta = max(float(k_last) * u_delta, g_span_t0);
  if (!(ta < t_end) || acc.a >= 1.0) return;
  isoInterval(acc, ta, sampleVolume(u_eye + ta * dir), t_end, sampleVolume(u_eye + t_end * dir), dir);
}
