// 3D-texture slicing: the slice polygons (render/volume/slice_geometry.h) in world coordinates.
layout(location = 0) in vec3 a_world;
uniform mat4 u_view_proj;
out vec3 v_world;
void main() {
  v_world = a_world;
  gl_Position = u_view_proj * vec4(a_world, 1.0);
}
