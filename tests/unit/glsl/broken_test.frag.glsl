// A deliberately broken chunk (tests/unit/gl_program_test.cpp): the line marked below uses a name
// nothing declares, so the driver's compile error must come back naming this file and that line.
out vec4 frag;
void main() {
  frag = vec4(testValue(), undeclared_on_purpose);  // the compile error
}
