// Subdivision surfaces, pass 1: the fragment shader only passes on (u, v, face, surface), so the
// depth test runs before it (no discard, no written depth).
in vec3 v_param;
layout(location = 0) out vec4 out_coarse;
void main() { out_coarse = vec4(v_param, 1.0); }
