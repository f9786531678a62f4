// Text that must come through cmake/embed_shaders.cmake byte for byte (tests/unit/shader_source_test.cpp):
// raw-string ends )" )glsl" )sortlast_json" and R"( openers, "quotes", a backslash \ and \n \\ \" as text,
// a backslash at the end of a line \
// CMake syntax ${NOT_A_VARIABLE} [[bracket]] ; semicolons; $<GENEX> @AT@, a tab	here,
// trigraphs ??= ??/ and runs of marks ??? ????= and §.
// and no newline at the end