// Several fields in one brick (the program compiled with FIELDS defined as their count; the
// `volumes` key, scene/fields_scene.h): sampleAt() of the mixture, in place of
// raycast_sample.frag.glsl's one-field sampleAt(). Everything else of the march is the same: the
// lattice, the block walk (a block is empty only if it is empty under every field's transfer
// function: render/volume/raycast_fields.cpp), compositing front to back.
//
// The model: emission-absorption of a mixture of media. At world point p each field f that holds
// p (its own box, u_field_lo/hi) has value v_f, read from its own texture (its own grid: texture
// coordinate p * scale_f + offset_f), and (c_f, tau_f) from its own table. The mixture absorbs
// with tau = sum tau_f and emits the colour sum tau_f c_f / tau (each medium emits in proportion
// to what it absorbs), so a step of length delta composites alpha = 1 - exp(-tau delta) of that
// colour (composite(), raycast_march.frag.glsl). With one field: tau_1 and tau_1 c_1 / tau_1 = c_1
// within a float rounding. A field missing there (outside its box, or NaN: a missing sample in its
// stencil) adds nothing. reference/fields_reference.h integrates the same in double.
#ifdef FIELDS
uniform sampler3D u_field_volume[FIELDS];
uniform sampler1D u_field_table[FIELDS];
uniform vec3 u_field_tex_scale[FIELDS];
uniform vec3 u_field_tex_offset[FIELDS];
uniform vec3 u_field_lo[FIELDS];         // the field's world box; lo > hi: not in this brick
uniform vec3 u_field_hi[FIELDS];
uniform vec2 u_field_value_map[FIELDS];  // as u_value_map, per field
uniform vec2 u_field_table_map[FIELDS];  // as u_table_map, per field

vec4 sampleAt(vec3 p) {
  float tau = 0.0;
  vec3 emitted = vec3(0.0);
  for (int f = 0; f < FIELDS; ++f) {
    if (any(lessThan(p, u_field_lo[f])) || any(greaterThan(p, u_field_hi[f]))) continue;
    float v = volumeAt(u_field_volume[f], p * u_field_tex_scale[f] + u_field_tex_offset[f]);
    if (isnan(v)) continue;
    float x = clamp(v * u_field_value_map[f].x + u_field_value_map[f].y, 0.0, 1.0);
    vec4 e = texture(u_field_table[f], x * u_field_table_map[f].x + u_field_table_map[f].y);
    tau += e.a;
    emitted += e.a * e.rgb;
  }
  return tau > 0.0 ? vec4(emitted / tau, tau) : vec4(0.0);
}
#endif
