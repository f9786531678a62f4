// Subdivision surfaces, pass 1 (render/surfaces/subdiv_renderer.h): the coarse mesh with an
// ordinary depth test, each vertex carrying its (u, v, face).
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 param;  // u, v, face
uniform mat4 view_projection;
out vec3 v_param;
void main() {
  v_param = param;
  gl_Position = view_projection * vec4(position, 1.0);
}
