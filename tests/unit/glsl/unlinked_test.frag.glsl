// A chunk that compiles but cannot link (tests/unit/gl_program_test.cpp): it calls a function
// that no chunk defines.
float neverDefined();
out vec4 frag;
void main() { frag = vec4(neverDefined()); }
