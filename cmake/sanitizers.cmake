# Two instrumented builds, each in a build directory of its own:
#  SORTLAST_SANITIZE: AddressSanitizer + UndefinedBehaviorSanitizer on everything (gcc or clang).
#    UB aborts instead of printing and carrying on, so a test that hits it fails. The tests get
#    ASAN_OPTIONS / UBSAN_OPTIONS / LSAN_OPTIONS from tests/CMakeLists.txt (sortlast_sanitizer_env).
#  SORTLAST_FUZZ: the libFuzzer targets of tests/fuzz (clang only). The whole project is compiled
#    with coverage instrumentation (-fsanitize=fuzzer-no-link) plus ASan and UBSan, so the decoders
#    the targets call are instrumented where they live; only the targets link libFuzzer's main.
#    (scripts/fuzz's build, for fuzzing campaigns.)
#  Both: the sanitizer build, with the fuzz targets in it (CI's). Coverage instrumentation only in
#    the targets' own sources (which compile the RLE codec, the brick messages and the service's
#    request and HTTP parsers in) and the scene and io libraries (tests/fuzz/CMakeLists.txt): the
#    targets replay their seeds under ASan and UBSan and mutate them, guided, without a third
#    build of the whole project (CI: ~190 s of CPU, 2026-12-07). The OBJ reader (subdivision
#    library) is not instrumented there: long runs belong to scripts/fuzz's build.
option(SORTLAST_SANITIZE "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
option(SORTLAST_FUZZ "Build the libFuzzer targets in tests/fuzz (needs clang)" OFF)

# -g1: line tables only (file:line in every report), much less to compile and link than -g; CI
# builds this on two cores within its time limit.
set(SORTLAST_SANITIZER_FLAGS -fsanitize=address,undefined -fno-sanitize-recover=undefined
  -fno-omit-frame-pointer -g1)

if(SORTLAST_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang" OR NOT CMAKE_C_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "SORTLAST_FUZZ=ON needs clang (libFuzzer ships with it), but the compilers "
      "are ${CMAKE_C_COMPILER_ID} / ${CMAKE_CXX_COMPILER_ID}. Configure a fresh build directory with "
      "-DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ (Debian: apt-get install clang "
      "libclang-rt-14-dev), or use scripts/fuzz, which does.")
  endif()
endif()
if(SORTLAST_FUZZ AND NOT SORTLAST_SANITIZE)
  add_compile_options(-fsanitize=fuzzer-no-link ${SORTLAST_SANITIZER_FLAGS})
  add_link_options(-fsanitize=address,undefined)
elseif(SORTLAST_SANITIZE)
  # -O0 (after the build type's -O2/-O3 on the command line, so it wins) for what costs compile
  # time and little run time, -O1 (sortlast_sanitizer_optimise below) for the libraries where the
  # unit tests spend theirs. Measured: session/render_session.cpp compiles in 11.2 s at -O0,
  # 17.5 s at -O1 (8.9 s at the Release build's -O3); the sanitizer unit tests ran 170 s with
  # everything at -O0, about 40 s at -O1.
  add_compile_options(${SORTLAST_SANITIZER_FLAGS} -O0)
  add_link_options(-fsanitize=address,undefined)
endif()

# Under SORTLAST_SANITIZE: -O1 for the given targets, the CPU-heavy libraries the unit tests run
# (references, subdivision, adaptive blocks, compositing). Call after they are defined.
function(sortlast_sanitizer_optimise)
  if(SORTLAST_SANITIZE)
    foreach(t ${ARGN})
      target_compile_options(${t} PRIVATE -O1)
    endforeach()
  endif()
endfunction()

# The tests' environment under SORTLAST_SANITIZE: errors end the process with a non-zero status.
# Leaks are reported at exit, except inside the libraries tests/sanitizers/lsan.supp names, in the
# tests of the current directory unless `sortlast_sanitizer_env(NO_LEAKS)`: the MPI and service
# tests run the GL driver, whose leak reports cannot be told apart from ours. llvmpipe and Open MPI
# are built without frame pointers, so ASan's fast unwinder stops one frame into them ("<unknown
# module>" for JIT code) and no suppression by library name can match; the full unwinder
# (fast_unwind_on_malloc=0) made a 96² frame on one rank take over 5 minutes. Those tests still stop at
# any memory error or undefined behaviour; the unit tests check leaks. mpirun passes the
# environment to the ranks. Call at the end of a CMakeLists.txt that adds tests.
function(sortlast_sanitizer_env)
  if(NOT SORTLAST_SANITIZE)
    return()
  endif()
  set(leaks 1)
  if("NO_LEAKS" IN_LIST ARGN)
    set(leaks 0)
  endif()
  get_property(names DIRECTORY PROPERTY TESTS)
  if(names)
    set_property(TEST ${names} APPEND PROPERTY ENVIRONMENT
      "ASAN_OPTIONS=detect_leaks=${leaks}:halt_on_error=1:detect_stack_use_after_return=0:strict_string_checks=1:check_initialization_order=1"
      "LSAN_OPTIONS=suppressions=${PROJECT_SOURCE_DIR}/tests/sanitizers/lsan.supp:print_suppressions=0"
      "UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1")
  endif()
endfunction()
