# Sanitizer and fuzzing builds of the software (docs/stability.md, "Sanitizers"
# and "Fuzzing"). Both are for clang; scripts/test builds them in build-asan:
#   cmake -S . -B build-asan -G Ninja -DCMAKE_CXX_COMPILER=clang++-14 -DCMAKE_C_COMPILER=clang-14 \
#         -DLANCER_HW_MODELS=OFF -DLANCER_SANITIZE=address,undefined -DLANCER_FUZZ=ON
#
#   LANCER_SANITIZE  comma-separated -fsanitize= list (e.g. address,undefined) for
#                    every target of the tree. Findings are fatal
#                    (-fno-sanitize-recover=all): a report fails the test that ran it.
#   LANCER_FUZZ      also compile everything with libFuzzer's coverage
#                    instrumentation (-fsanitize=fuzzer-no-link) and build the
#                    fuzz targets of tests/fuzz (label `fuzz`). Needs clang.
# Both are meant for a tree without the hardware models (LANCER_HW_MODELS=OFF):
# the Verilated RTL and the SystemC kernel are slow to build and not ours to
# sanitize.
set(LANCER_SANITIZE "" CACHE STRING "Sanitizers for every target, e.g. address,undefined (clang or gcc)")
option(LANCER_FUZZ "Build the libFuzzer targets of tests/fuzz (clang)" OFF)

if(LANCER_SANITIZE)
  # Keep frame pointers and line tables so reports name the line; -O1 (after
  # the build type's -O3, so it wins) keeps the tests quick without the
  # optimizer hiding the bug, and assert() is on whatever the build type.
  set(lancer_sanitize_flags -fsanitize=${LANCER_SANITIZE} -fno-sanitize-recover=all
      -fno-omit-frame-pointer -g -O1 -UNDEBUG)
  add_compile_options(${lancer_sanitize_flags})
  add_link_options(-fsanitize=${LANCER_SANITIZE} -fno-sanitize-recover=all)
  message(STATUS "Sanitizers: ${LANCER_SANITIZE}")
endif()

if(LANCER_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "LANCER_FUZZ needs clang (libFuzzer); configure with -DCMAKE_CXX_COMPILER=clang++-14")
  endif()
  # Coverage for libFuzzer in every library the targets reach; the fuzz
  # targets themselves link with -fsanitize=fuzzer (tests/fuzz/CMakeLists.txt).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
