// A chunk that compiles (tests/unit/gl_program_test.cpp), put before the broken one so that the
// error lies in the second source string: the message must name the file of the right chunk.
float testValue() { return float(TEST_VALUE); }
