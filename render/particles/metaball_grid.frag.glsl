// The metaball grid ray caster (render/particles/metaball_grid_renderer.h): one fragment pass per
// brick; after render/particles/metaball_common.glsl for the ray, the clip interval,
// the sample lattice and the refinement probes, so both methods sample the same points.
//
// Where the time goes on llvmpipe: walking cell lists. A ray walks the list of each cell it
// crosses (about 84 entries per particle; 2-3 cells per h), then one list per refinement pass
// and one for the gradient; every entry costs a per-lane load and the entry test (~20 vector
// operations) whether or not its particle reaches the ray. The march's walks are the bulk (one
// refinement pass is about 5% of a frame on the layers). Hence the lean entry test below (no square root: about 5% less CPU time per frame
// on the 65,536-particle layers at 512^2). What was tried and measured slower, on the same scene
// and the dam break at 512^2 (busy 2-core machine, interleaved runs):
// - Each particle once per ray, as the CPU reference does: cells of h binned by centre, a DDA
//   that brings in the 3 x 3 layer of cells beyond each step, the particles met kept in a
//   per-ray list that the sample chunks, the refinement and the gradient sum over, with interval
//   skipping (jump to the nearest listed particle's sphere entry). It loads fewer entries (127
//   a ray on the layers, against an estimated 500-700), but the list costs more than the walks:
//   a local array is indexed through a select over every element (capacity 128: 1.4x and 2.5x
//   slower than this shader; 256: about 8x on the dam break), a per-pixel storage buffer through
//   per-lane scatters and gathers (capacity 64: 1.7x and 2.5x slower). Its interval skipping
//   did not measurably pay: CPU s a frame with / without, layers 0.336 / 0.314, dam break
//   1.21 / 1.25 (the samples it skips are cheap; the list walks are not).
// - Only the refinement and gradient particles in a per-pixel storage buffer: 1.25x slower.
// - The refinement and gradient walks shared by the 8 pixels llvmpipe shades together (each lane
//   loads one entry, readInvocationARB hands it to all): 1.5x slower.
// - The gradient from the last refinement pass's walk (at its probes, interpolated) instead of a
//   walk of its own: no faster (its extra sums cost what the walk did), and it changes normals.
// - 2 refinement passes of 8 probes (secant, +-2%, +-0.08%, quartiles) instead of 3 of 4:
//   1.2x slower (each pass walks one list; 3 passes of 4 against 2 of 4 is only 5%).
// - Buffer textures instead of storage buffers for the lists: no difference.
// Measured later (CPU s a frame = (CPU of a 9-frame orbit - CPU of its first frame) / 8, min
// over 2-4 runs interleaved with this shader, on the 65,536-particle layers at 512^2; this
// shader measured 0.15-0.19 in the same runs; the code is commit 62d4268, merged into main's history):
// - A compute workgroup per 8 x 8 tile, marching its rays together segment by segment (8
//   lattice steps): it gathers the particles within reach of the segment once into shared
//   memory (from a grid binning them by centre), ranks them into particle order (images
//   identical to this shader's), and every ray sums its segment's samples over that one list.
//   0.27-0.31 (1.6x slower); without the ranking (same particles, sums in gather order) 0.22-
//   0.24; tiles of 4 x 4 0.23-0.33. Lists per group of 8 invocations (llvmpipe's SIMD width,
//   4 x 2 pixels: about 2.5x fewer entries a ray than the cell walks here) 0.20-0.21 (dam break
//   at 512^2: 0.40 against 0.41). The cause: the same compute shader walking this shader's cell
//   lists per ray (no gather) costs 0.22-0.23, i.e. llvmpipe's compute path with workgroup
//   barriers (3 a segment) is ~1.4x slower than this fragment pass for the same per-ray work,
//   and the shared lists win back only part of that. Segments of 16 steps: no clear change.
// - Centres as 3 x 16 bits relative to the cell (8 bytes an entry instead of 16): 0.168 against
//   0.156 on the layers, 0.49 against 0.47 on the dam break (min of 4 and 3 runs): the unpacking
//   costs what the smaller loads save; depth moves by up to 2.6e-3 h (rms 3e-5 h) off edges.
layout(std430, binding = 1) readonly buffer Offsets { uint offsets[]; };
// The cells' lists as the particles' centres themselves (xyz, w unused): one load per entry.
layout(std430, binding = 2) readonly buffer Items { vec4 items[]; };
uniform vec3 u_grid_lo;
uniform float u_cell;
uniform ivec4 u_dims;     // cells per axis in xyz
uniform float u_cap;       // samples allowed per pixel (those with field > 0 count)
uniform int u_refine;      // refinement passes
uniform vec3 u_colour;
layout(location = 0) out vec4 o_colour;
layout(location = 1) out vec4 o_surface;

// Samples taken per walk of a cell's list: a ray crosses a cell of edge h/2 in at most
// sqrt(3) (h/2) / w + 1 = 7.9 samples at the default step h/8, so one walk covers a cell.
const int CHUNK = 8;
float g_s[CHUNK];   // sample distances
float g_f[CHUNK];   // field at them

ivec3 cellOf(vec3 x) { return clamp(ivec3(floor((x - u_grid_lo) / u_cell)), ivec3(0), u_dims.xyz - 1); }
uvec2 cellRange(ivec3 c) {
  int i = (c.z * u_dims.y + c.y) * u_dims.x + c.x;
  return uvec2(offsets[i], offsets[i + 1]);
}
// Where the ray leaves cell c (slab exits).
float cellExit(ivec3 c, vec3 d) {
  vec3 lo = u_grid_lo + vec3(c) * u_cell;
  vec3 a = (lo - u_eye) / d, b = (lo + u_cell - u_eye) / d;
  vec3 m = max(a, b);
  return min(min(m.x, m.y), m.z);
}
vec2 gridInterval(vec3 d) {
  vec3 a = (u_grid_lo - u_eye) / d, b = (u_grid_lo + vec3(u_dims.xyz) * u_cell - u_eye) / d;
  vec3 lo = min(a, b), hi = max(a, b);
  return vec2(max(max(lo.x, lo.y), lo.z), min(min(hi.x, hi.y), hi.z));
}
#ifdef ANISOTROPIC
// Smoothed anisotropic metaballs (io/anisotropic_kernels.h). How one particle adds to the
// field, all in this block. A list entry is (centre, reach): the longest semi-axis, for the
// cheap sphere test against the ray's stretch, which loads nothing more. Only a particle that
// passes it loads its index (the parallel buffer Indices, entry for entry) and then its kernel:
// per particle 3 vec4, (A row 0, C), (A row 1, reach), (A row 2, unused); A is symmetric. On the
// ray x = eye + s d, with tb the centre's distance along it and perp its offset across, the
// ellipsoid frame's offset is u(s) = A ((s - tb) d - perp) = (s - tb) A d - A perp: two
// matrix products per particle and stretch, not one per sample, and an exact test of whether
// the ellipsoid meets the stretch (the closest u to 0 over it) before any sample.
layout(std430, binding = 3) readonly buffer Kernels { vec4 kernels[]; };
layout(std430, binding = 4) readonly buffer Indices { uint indices[]; };
struct Kernel { vec3 a0, a1, a2; float c, reach; };
Kernel kernelOf(uint entry) {
  uint i = 3u * indices[entry];
  vec4 k0 = kernels[i], k1 = kernels[i + 1u], k2 = kernels[i + 2u];
  return Kernel(k0.xyz, k1.xyz, k2.xyz, k0.w, k1.w);
}
vec3 ellipsoidFrame(Kernel k, vec3 r) { return vec3(dot(k.a0, r), dot(k.a1, r), dot(k.a2, r)); }
// Its gradient: -2 C (1 - |u|/h) / (h |u|) A u with u = A r (A = A^T); 0 at the centre.
vec3 kernelGradient(Kernel k, vec3 r) {
  vec3 u = ellipsoidFrame(k, r);
  float len = length(u);
  float q = max(1.0 - len / u_h, 0.0);
  return len > 0.0 ? (-2.0 * k.c * q / (u_h * len)) * ellipsoidFrame(k, u) : vec3(0.0);
}
#endif
float field(float s, float tb, float perp2) {
  float ds = s - tb;
  float q = max(1.0 - sqrt(perp2 + ds * ds) / u_h, 0.0);
  return q * q;
}
// F at g_s[0..m-1] (ascending, all in the cell whose list is r), summed in list order, which is
// global particle order. Particles whose reach along the ray misses [g_s[0], g_s[m-1]] (with a
// margin) are skipped: they would add zeros. The test compares the squared distance from the
// particle to that stretch of the ray with h^2: no square root, and the same particles pass
// but for ones at distance h + O(ulp) beyond the 1e-3 h margin, which add exactly 0 anyway.
void sumSamples(uvec2 r, vec3 d, int m) {
  for (int k = 0; k < CHUNK; ++k) g_f[k] = 0.0;
  float hh = u_h * u_h, first = g_s[0] - 1e-3 * u_h, last = g_s[m - 1] + 1e-3 * u_h;
  for (uint j = r.x; j < r.y; ++j) {
#ifdef ANISOTROPIC
    vec4 entry = items[j];
    vec3 oc = entry.xyz - u_eye;
    float tb = dot(d, oc);
    vec3 perp = oc - tb * d;
    float perp2 = dot(perp, perp);
    float e = tb - clamp(tb, first, last);
    if (perp2 + e * e >= entry.w * entry.w) continue;
    Kernel kern = kernelOf(j);
    vec3 ad = ellipsoidFrame(kern, d), ap = ellipsoidFrame(kern, perp);
    // The stretch's closest point to the centre in the ellipsoid's frame: outside, it adds 0.
    float aa = dot(ad, ad);
    float ds = aa > 0.0 ? clamp(dot(ad, ap) / aa, first - tb, last - tb) : 0.0;
    vec3 u0 = ds * ad - ap;
    if (dot(u0, u0) >= hh) continue;
    for (int k = 0; k < m; ++k) {
      float q = max(1.0 - length((g_s[k] - tb) * ad - ap) / u_h, 0.0);
      g_f[k] += kern.c * q * q;
    }
#else
    vec3 oc = items[j].xyz - u_eye;
    float tb = dot(d, oc);
    vec3 perp = oc - tb * d;
    float perp2 = dot(perp, perp);
    float e = tb - clamp(tb, first, last);
    if (perp2 + e * e >= hh) continue;
    for (int k = 0; k < m; ++k) g_f[k] += field(g_s[k], tb, perp2);
#endif
  }
}
// F at the 4 refinement probes q (ascending) into g_f[0..3].
void sumProbes(float q[4], vec3 d) {
  ivec3 c0 = cellOf(u_eye + q[0] * d), c3 = cellOf(u_eye + q[3] * d);
  if (c0 == c3) {
    for (int k = 0; k < 4; ++k) g_s[k] = q[k];
    sumSamples(cellRange(c0), d, 4);
    return;
  }
  float f[4];
  for (int k = 0; k < 4; ++k) {
    g_s[0] = q[k];
    sumSamples(cellRange(cellOf(u_eye + q[k] * d)), d, 1);
    f[k] = g_f[0];
  }
  for (int k = 0; k < 4; ++k) g_f[k] = f[k];
}

void main() {
  o_colour = vec4(0.0);
  o_surface = vec4(INF, 0.0, 0.0, 0.0);
  vec3 d = safeDir(pixelRay(gl_FragCoord.xy));
  // Beyond the grid's box the field is 0: nothing to find outside [g0, g1].
  vec4 iv;
  if (!rayStretch(d, gridInterval(d), iv)) return;
  float t_in = iv.x, t_out = iv.y, g0 = iv.z, g1 = iv.w;

  // The samples are t_in, then every lattice point up to t_out, then t_out: the billboard
  // method's points, except that it also skips the rear halves of spheres (its eq. 3). Empty
  // cells are jumped; the lattice point before the next sample then lies in the empty stretch,
  // so the bracket starts there with I = -T.
  float s = t_in, t_last = t_in, i_last = -u_T, n = 0.0;
  bool hit = false;
  vec4 b = vec4(0.0);
  bool jump = g0 > t_in;
  float jump_to = g0;
  for (int iter = 0; iter < 65536; ++iter) {
    if (jump) {
      float c = latticeCeil(jump_to);
      if (c <= s) c = latticeNext(s);
      float prev = (round(c / u_w) - 1.0) * u_w;
      s = min(c, t_out);
      if (prev > t_last && prev < s) { t_last = prev; i_last = -u_T; }
      jump = false;
    }
    if (s > g1) break;
    ivec3 c = cellOf(u_eye + s * d);
    float t_exit = cellExit(c, d);
    uvec2 r = cellRange(c);
    if (r.x == r.y) {
      if (t_exit >= g1 || s >= t_out) break;
      jump = true;
      jump_to = t_exit;
      continue;
    }
    g_s[0] = s;
    int m = 1;
    while (m < CHUNK && g_s[m - 1] < t_out) {
      float nx = min(latticeNext(g_s[m - 1]), t_out);
      if (nx >= t_exit) break;
      g_s[m++] = nx;
    }
    sumSamples(r, d, m);
    bool done = false;
    for (int k = 0; k < m; ++k) {
      if (n >= u_cap) { done = true; break; }  // out of samples: a hole, the paper's Fig. 12
      float value = sqrt(g_f[k]) - u_T;
      if (g_f[k] > 0.0) n += 1.0;
      if (value >= 0.0) {
        // Already inside at the box entry: the surface lies in front of this brick (its owner
        // draws it), so this brick shows nothing here.
        if (g_s[k] > t_in) { hit = true; b = vec4(t_last, i_last, g_s[k], value); }
        done = true;
        break;
      }
      t_last = g_s[k];
      i_last = value;
      if (g_s[k] >= t_out) { done = true; break; }
    }
    if (done) break;
    s = min(latticeNext(g_s[m - 1]), t_out);
  }
  if (!hit) return;

  // Refinement (eqs. 5-6): the first sign change among t_neg, the 4 probes and t_pos. (Gathering
  // the particles that reach the bracket once, instead of walking the cell's list per pass, was
  // measured no faster on llvmpipe: 0.131 against 0.128 s on the 65,536-particle layers.)
  for (int i = 0; i < u_refine; ++i) {
    float q[4];
    refineProbes(b, q);
    sumProbes(q, d);
    b = refineBracket(b, q, vec4(g_f[0], g_f[1], g_f[2], g_f[3]));
  }
  float t = secantEstimate(b);

  // Gradient of F at t (r = x - c; dP/dx = -2 (1 - |r|/h) / h * r / |r|), in list order.
  uvec2 r = cellRange(cellOf(u_eye + t * d));
  vec3 grad = vec3(0.0);
  for (uint j = r.x; j < r.y; ++j) {
#ifdef ANISOTROPIC
    vec4 entry = items[j];
    vec3 oc = entry.xyz - u_eye;
    float tb = dot(d, oc);
    vec3 perp = oc - tb * d;
    if (dot(perp, perp) >= entry.w * entry.w) continue;
    grad += kernelGradient(kernelOf(j), (t - tb) * d - perp);
#else
    vec3 oc = items[j].xyz - u_eye;
    float tb = dot(d, oc);
    vec3 perp = oc - tb * d;
    if (dot(perp, perp) >= u_h * u_h) continue;
    vec3 rr = (t - tb) * d - perp;
    float len = length(rr);
    float q = max(1.0 - len / u_h, 0.0);
    grad += len > 0.0 ? (-2.0 * q / (u_h * len)) * rr : vec3(0.0);
#endif
  }
  vec3 nrm;
  o_colour = shade(u_colour, grad, d, nrm);
  o_surface = vec4(t, nrm);
}
