#pragma once
// GLSL for the tile march of the metaball grid ray caster (an experiment, issue 12): a compute
// workgroup per TILE x TILE pixels walks the tile's rays together, depth segment by depth segment
// (8 lattice steps each, t in [8 j w, 8 (j + 1) w)). For each segment the workgroup gathers once,
// into shared memory, the particles within reach of the segment of any of its rays (from a grid
// of cells binning the particles by centre), puts them in global particle order (each entry's
// rank), and then every ray sums its samples in the segment over that one list. On llvmpipe a
// workgroup runs on one thread, so the gather is paid once per tile rather than once per pixel.
// The samples are the fragment march's (t_in, the lattice points, t_out) and a sample's sum has
// the same non-zero terms in the same order, so the images are the same. Refinement and shading:
// kGridFinish, over the cell lists as in the fragment march. A segment whose list outgrows the
// shared array falls back to the cell lists for its samples.
// Appended to kMetaballCommon, kGridChunkTile and kGridLists.
namespace sortlast::shaders {

inline constexpr const char* kGridTileCompute = R"(
layout(local_size_x = TILE * TILE) in;
layout(rgba32f, binding = 0) writeonly uniform image2D u_colour_img;
layout(rgba32f, binding = 1) writeonly uniform image2D u_surface_img;
// The particles binned by centre: cell i holds bins[bin_offsets[i] .. bin_offsets[i + 1]),
// xyz the centre, w the particle's number (as a float: exact below 2^24).
layout(std430, binding = 3) readonly buffer BinOffsets { uint bin_offsets[]; };
layout(std430, binding = 4) readonly buffer Bins { vec4 bins[]; };
uniform vec3 u_bin_lo;
uniform float u_bin_cell;
uniform ivec4 u_bin_dims;
uniform ivec4 u_rect;     // the brick's screen rectangle: x, y, w, h

#ifndef SEG
#define SEG 8
#endif
const int CAP = 512;
const int NT = TILE * TILE;
shared vec4 s_raw[CAP];   // gathered, unordered: centre, number
#ifdef GROUPS
// Lists per group of 8 invocations (llvmpipe's SIMD width: a 4 x 2 pixel block each).
const int NG = TILE * TILE / 8, GCAP = 160;
shared vec4 s_list[NG * GCAP];
shared vec4 s_gdir[NG];   // the block's centre direction, its chord
shared uint s_gn[2][NG];
#else
shared vec4 s_list[CAP];  // in particle order: centre less the eye
#endif
shared uint s_count[2];   // entries gathered, by segment parity
shared uint s_next[2];   // the earliest next sample of the tile's rays (float bits), by parity
shared uint s_active;     // rays of the tile still marching
shared uint s_tmin, s_tmax;  // the tile's first sample and last grid exit (float bits, >= 0)

// F at g_s[0..m-1] over the shared list's n entries.
void sumShared(vec3 d, int m, uint base, uint n) {
  for (int k = 0; k < CHUNK; ++k) g_f[k] = 0.0;
  float first = g_s[0] - 1e-3 * u_h, last = g_s[m - 1] + 1e-3 * u_h;
  for (uint j = base; j < base + n; ++j) addParticle(s_list[j].xyz, d, first, last, m);
}

void main() {
  uint lid = gl_LocalInvocationIndex;
#ifdef GROUPS
  uint grp = lid / 8u, lane = lid % 8u;
  ivec2 off = ivec2(4u * (grp % uint(TILE / 4)) + lane % 4u, 2u * (grp / uint(TILE / 4)) + lane / 4u);
#else
  ivec2 off = ivec2(lid % uint(TILE), lid / uint(TILE));
#endif
  ivec2 loc = ivec2(gl_WorkGroupID.xy) * TILE + off;
  ivec2 px = u_rect.xy + loc;
  bool mine = all(lessThan(loc, u_rect.zw));
#ifdef EARLYOUT
  if (mine) { imageStore(u_colour_img, px, vec4(0.0)); imageStore(u_surface_img, px, vec4(INF, 0.0, 0.0, 0.0)); }
  return;
#endif
  if (lid == 0u) { s_count[0] = 0u; s_count[1] = 0u; s_next[0] = floatBitsToUint(INF); s_active = 0u; s_tmin = floatBitsToUint(INF); s_tmax = 0u; }
  barrier();

  vec3 d = safeDir(rayDir(vec2(px) + 0.5));
  vec2 iv = clipInterval(d);
  float t_in = iv.x, t_out = iv.y;
  vec2 g = gridInterval(d);
  float g0 = max(g.x, t_in), g1 = min(g.y, t_out);
  bool marching = mine && t_in < t_out && g0 < g1;
  // Samples before the grid are 0: start at the first lattice point in it, the bracket at the
  // lattice point before (the fragment march's jump).
  float s = t_in, t_last = t_in, i_last = -u_T, n_pos = 0.0;
  if (marching && g0 > t_in) {
    float c = latticeCeil(g0);
    if (c <= s) c = latticeNext(s);
    float prev = (round(c / u_w) - 1.0) * u_w;
    s = min(c, t_out);
    if (prev > t_last && prev < s) { t_last = prev; i_last = -u_T; }
  }
  bool hit = false;
  vec4 b = vec4(0.0);
  if (marching) {
    atomicAdd(s_active, 1u);
    atomicMin(s_tmin, floatBitsToUint(s));
    atomicMax(s_tmax, floatBitsToUint(g1));
  }

  // The tile's centre ray, and how far its rays stray from it per unit of t (the largest chord
  // to a corner pixel's direction: the angle from dc is largest at a corner).
  vec2 t0 = vec2(u_rect.xy + ivec2(gl_WorkGroupID.xy) * TILE);
  vec3 dc = safeDir(rayDir(t0 + 0.5 * float(TILE)));
  float chord = 0.0;
  for (int k = 0; k < 4; ++k) {
    vec2 corner = t0 + 0.5 + vec2(float(k & 1), float(k >> 1)) * float(TILE - 1);
    chord = max(chord, length(rayDir(corner) - dc));
  }
  chord = chord * 1.001 + 1e-6;
#ifdef GROUPS
  if (lid < uint(NG)) {
    vec2 b0 = t0 + vec2(4.0 * float(lid % uint(TILE / 4)), 2.0 * float(lid / uint(TILE / 4)));
    vec3 gd = safeDir(rayDir(b0 + vec2(2.0, 1.0)));
    float gc = 0.0;
    for (int k = 0; k < 4; ++k) gc = max(gc, length(rayDir(b0 + 0.5 + vec2(float(k & 1) * 3.0, float(k >> 1))) - gd));
    s_gdir[lid] = vec4(gd, gc * 1.001 + 1e-6);
    s_gn[0][lid] = 0u;
  }
#endif
  barrier();

  float seg = float(SEG) * u_w;
  int j0 = max(int(floor(uintBitsToFloat(s_tmin) / seg)) - 1, 0);
  int j1 = int(floor(uintBitsToFloat(s_tmax) / seg)) + 1;
  int j_next = j0;
  for (int iter = 0; iter < 65536; ++iter) {
    int j = j_next;
    if (s_active == 0u || j > j1) break;
    uint par = uint(iter) & 1u;
    float ta = float(SEG * j) * u_w, te = float(SEG * j + SEG) * u_w;
    // Gather: particles within reach of the central ray's stretch [ta, te], widened by the
    // tile's spread there and a margin (as the cell lists' kGridPad).
    float reach = u_h * 1.01 + te * chord + 1e-3 * u_h;
    vec3 pa = u_eye + (ta - 1e-3 * u_h) * dc, pb = u_eye + te * dc;
    ivec3 clo = max(ivec3(floor((min(pa, pb) - reach - u_bin_lo) / u_bin_cell)), ivec3(0));
    ivec3 chi = min(ivec3(floor((max(pa, pb) + reach - u_bin_lo) / u_bin_cell)), u_bin_dims.xyz - 1);
    ivec3 cn = max(chi - clo + 1, ivec3(0));
    int cells = cn.x * cn.y * cn.z;
    vec3 ab = pb - pa;
    float ab2 = max(dot(ab, ab), 1e-30);
    float cell_reach = reach + 0.8660254 * u_bin_cell;
#ifdef NOGATHER
    cells = 0;
#endif
    for (int ci = int(lid); ci < cells; ci += NT) {
      ivec3 c = clo + ivec3(ci % cn.x, (ci / cn.x) % cn.y, ci / (cn.x * cn.y));
      vec3 cc = u_bin_lo + (vec3(c) + 0.5) * u_bin_cell;
      vec3 q = cc - pa - clamp(dot(cc - pa, ab) / ab2, 0.0, 1.0) * ab;
      if (dot(q, q) > cell_reach * cell_reach) continue;
      int i = (c.z * u_bin_dims.y + c.y) * u_bin_dims.x + c.x;
      for (uint k = bin_offsets[i]; k < bin_offsets[i + 1]; ++k) {
        vec4 p = bins[k];
        vec3 r = p.xyz - pa - clamp(dot(p.xyz - pa, ab) / ab2, 0.0, 1.0) * ab;
        if (dot(r, r) > reach * reach) continue;
        uint at = atomicAdd(s_count[par], 1u);
        if (at < uint(CAP)) s_raw[at] = p;
      }
    }
    barrier();
    uint n = s_count[par];
    if (lid == 0u) { s_count[par ^ 1u] = 0u; s_next[par ^ 1u] = floatBitsToUint(INF); }
#ifdef GROUPS
    if (lid < uint(NG)) s_gn[par ^ 1u][lid] = 0u;
    if (n <= uint(CAP))
      for (uint i = lid; i < n; i += uint(NT)) {
        vec4 p = s_raw[i];
        for (int gi = 0; gi < NG; ++gi) {
          vec4 gd = s_gdir[gi];
          float rg = u_h * 1.01 + te * gd.w + 1e-3 * u_h;
          vec3 ga = u_eye + (ta - 1e-3 * u_h) * gd.xyz, gab = (te - ta + 1e-3 * u_h) * gd.xyz;
          vec3 rr = p.xyz - ga - clamp(dot(p.xyz - ga, gab) / max(dot(gab, gab), 1e-30), 0.0, 1.0) * gab;
          if (dot(rr, rr) > rg * rg) continue;
          uint at = atomicAdd(s_gn[par][gi], 1u);
          if (at < uint(GCAP)) s_list[uint(gi * GCAP) + at] = vec4(p.xyz - u_eye, p.w);
        }
      }
#else
    // Order: each entry's rank among the gathered numbers.
    if (n <= uint(CAP))
      for (uint i = lid; i < n; i += uint(NT)) {
        float key = s_raw[i].w;
        uint rank = 0u;
#ifdef NOSORT
        rank = i;
#else
        for (uint k = 0u; k < n; ++k) rank += s_raw[k].w < key ? 1u : 0u;
#endif
        s_list[rank] = vec4(s_raw[i].xyz - u_eye, 0.0);
      }
#endif
    barrier();
#ifdef GROUPS
    uint base = grp * uint(GCAP), nl = s_gn[par][grp];
    bool over = n > uint(CAP) || nl > uint(GCAP);
#ifdef FORCEOVER
    over = true;
#endif
#else
    uint base = 0u, nl = n;
    bool over = n > uint(CAP);
#endif

    // March this ray's samples in [.., te).
    bool was = marching;
    while (marching && s < te) {
      if (s > g1) { marching = false; break; }
      float limit = te;
      ivec3 c = ivec3(0);
      if (over) {  // overflow: this cell's list, as the fragment march
        c = cellOf(u_eye + s * d);
        limit = min(te, cellExit(c, d));
      }
      g_s[0] = s;
      int m = 1;
      while (m < CHUNK && g_s[m - 1] < t_out) {
        float nx = min(latticeNext(g_s[m - 1]), t_out);
        if (nx >= limit) break;
        g_s[m++] = nx;
      }
      if (over) sumSamples(c, d, m);
      else {
#ifdef NOWALK
        for (int k = 0; k < CHUNK; ++k) g_f[k] = 0.0;
#else
        sumShared(d, m, base, nl);
#endif
      }
      for (int k = 0; k < m; ++k) {
        if (n_pos >= u_cap) { marching = false; break; }  // out of samples: a hole
        float value = sqrt(g_f[k]) - u_T;
        if (g_f[k] > 0.0) n_pos += 1.0;
        if (value >= 0.0) {
          if (g_s[k] > t_in) { hit = true; b = vec4(t_last, i_last, g_s[k], value); }
          marching = false;
          break;
        }
        t_last = g_s[k];
        i_last = value;
        if (g_s[k] >= t_out) { marching = false; break; }
      }
      if (!marching) break;
      s = min(latticeNext(g_s[m - 1]), t_out);
    }
    // Jump the empty cells ahead (their samples are 0), as the fragment march does, and tell
    // the tile where this ray's next sample is: the next segment is the first one any ray needs.
    while (marching) {
      if (s > g1) { marching = false; break; }
      ivec3 c = cellOf(u_eye + s * d);
      uvec2 r = cellRange(c);
      if (r.x != r.y) break;
      float t_exit = cellExit(c, d);
      if (t_exit >= g1 || s >= t_out) { marching = false; break; }
      float cl = latticeCeil(t_exit);
      if (cl <= s) cl = latticeNext(s);
      float prev = (round(cl / u_w) - 1.0) * u_w;
      float s_new = min(cl, t_out);
      if (prev > t_last && prev < s_new) { t_last = prev; i_last = -u_T; }
      s = s_new;
    }
    if (was && !marching) atomicAdd(s_active, uint(-1));
    if (marching) atomicMin(s_next[par], floatBitsToUint(s));
    barrier();
    // The segment holding the earliest next sample: [8 k w, 8 (k + 1) w) contains it.
    float tn = uintBitsToFloat(s_next[par]);
    int k = int(floor(tn / seg));
    if (tn < float(SEG * k) * u_w) --k;
    if (tn >= float(SEG * k + SEG) * u_w) ++k;
    j_next = max(j + 1, k);
  }

  if (!mine) return;
  vec4 colour = vec4(0.0), surface = vec4(INF, 0.0, 0.0, 0.0);
  if (hit) finishHit(d, b, colour, surface);
  imageStore(u_colour_img, px, colour);
  imageStore(u_surface_img, px, surface);
}
)";

}  // namespace sortlast::shaders
