// Premultiplied float pixels to RGBA8 on the GPU, bit for bit as toRGBA8 (io/image.cpp) rounds
// them on the CPU: each channel clamped to [0, 1], times 255, rounded half away from zero
// (lround), colour then clamped to alpha. t - floor(t) is exact in float for t in [0, 255]
// (Sterbenz), so the comparison with 0.5 decides exactly as lround does; the output is an integer
// target (RGBA8UI), so no fixed-point conversion of the driver's rounds again.
uniform sampler2D u_source;  // RGBA32F, the brick's float target
layout(location = 0) out uvec4 o_rgba8;

uint rounded(float v) {
  float t = clamp(v, 0.0, 1.0) * 255.0;
  float r = floor(t);
  return uint(r) + ((t - r >= 0.5) ? 1u : 0u);
}

void main() {
  vec4 p = texelFetch(u_source, ivec2(gl_FragCoord.xy), 0);
  uint a = rounded(p.a);
  o_rgba8 = uvec4(min(rounded(p.r), a), min(rounded(p.g), a), min(rounded(p.b), a), a);
}
