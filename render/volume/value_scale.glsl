// transfer.scale on the GPU: s(v), the value in the domain the transfer table is laid out in
// (transfer/value_scale.h has the definition and the CPU copy). Applied to the trilinearly
// interpolated sample, before the table's affine map u_value_map.
uniform int u_scale;            // 0 linear, 1 log (log10), 2 symlog (matplotlib's SymLogNorm)
uniform float u_linear_width;   // symlog's linear half-width w

float scaledValue(float v) {
  if (u_scale == 0) return v;
  if (u_scale == 1) return v > 0.0 ? log2(v) * 0.30102999566398120 : -1e30;  // <= 0: below the range
  const float c = 1.0 / 0.9;  // linscale / (1 - 1 / base), linscale 1, base 10
  float a = abs(v);
  if (a <= u_linear_width) return v * c;
  return sign(v) * u_linear_width * (c + log2(a / u_linear_width) * 0.30102999566398120);
}
