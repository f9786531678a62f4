// CRLF line ends (tests/unit/shader_source_test.cpp): cmake/embed_shaders.cmake keeps the
// carriage returns, "quotes" and \ too.
