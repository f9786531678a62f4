// 3D-texture slicing's fragment shader, first chunk: its inputs (render/volume/slicing.frag.glsl
// has the rest and lists the chunks).
in vec3 v_world;
uniform sampler3D u_volume;
uniform sampler1D u_table;
uniform vec3 u_tex_scale;
uniform vec3 u_tex_offset;
uniform vec3 u_eye;
uniform vec3 u_forward;
uniform int u_orthographic;   // 1: parallel rays along u_forward from the eye plane through u_eye
uniform float u_spacing;
uniform vec2 u_value_map;   // normalised value = scaledValue(v) * x + y
uniform vec2 u_table_map;   // table coordinate = normalised * x + y (texel centres at the ends)
uniform sampler2D u_surface;  // particle surface (t, normal) per pixel, t = 1e30 on a miss
uniform int u_has_surface;
uniform ivec4 u_surface_rect; // x, y, w, h where u_surface is valid (stale elsewhere)
out vec4 frag;
