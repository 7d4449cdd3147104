# Sanitizer and fuzzing builds (docs/fuzzing.md). Included before any target is
# defined, so that the flags reach every library, executable and test; kernels
# run inside PoCL and are not instrumented. Both are off by default.
#
#   -DWAVEPATH_SANITIZE=address,undefined   host code and tests under ASan + UBSan
#                                           (any -fsanitize= list; gcc or clang)
#   -DWAVEPATH_FUZZ=ON                      the libFuzzer targets in fuzz/ (clang
#                                           only), with ASan + UBSan unless
#                                           WAVEPATH_SANITIZE says otherwise

set(WAVEPATH_SANITIZE "" CACHE STRING
    "Comma-separated -fsanitize= list for every target, e.g. address,undefined (empty: none)")
option(WAVEPATH_FUZZ "Build the libFuzzer targets in fuzz/ (needs clang)" OFF)
option(WAVEPATH_SANITIZE_TEST_CODE
       "In a WAVEPATH_SANITIZE build, instrument the test programs' own code too" OFF)

if(WAVEPATH_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "WAVEPATH_FUZZ needs clang for libFuzzer (configure with "
                        "CC=clang CXX=clang++); this is ${CMAKE_CXX_COMPILER_ID}")
  endif()
  if(NOT WAVEPATH_SANITIZE)
    set(WAVEPATH_SANITIZE address,undefined)
  endif()
  # Coverage instrumentation for libFuzzer in all code; only the fuzz targets
  # link libFuzzer itself (-fsanitize=fuzzer, fuzz/CMakeLists.txt).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

if(WAVEPATH_SANITIZE)
  # Frame pointers give whole stacks in reports. A UBSan finding stops the
  # program (like an ASan one) instead of printing and going on, so that a
  # test or fuzzer cannot pass over it.
  add_compile_options(-fsanitize=${WAVEPATH_SANITIZE} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${WAVEPATH_SANITIZE})
  if(WAVEPATH_SANITIZE MATCHES "undefined")
    # gcc leaves float-to-int conversions out of range (e.g. infinity to int)
    # out of "undefined"; clang has them in it. Both get them.
    add_compile_options(-fsanitize=float-cast-overflow -fno-sanitize-recover=all)
    add_link_options(-fsanitize=float-cast-overflow)
  endif()
  if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
    # gcc 12 warns "may be used uninitialized" inside <regex>'s std::function
    # moves when the sanitizers instrument them (a false positive; the Release
    # build, which CI also runs with -Werror, compiles the same files clean).
    # Off in this build for the files that use <regex>, found by their include.
    file(GLOB_RECURSE candidates CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/*.cpp
         ${CMAKE_SOURCE_DIR}/tests/*.cpp)
    foreach(source ${candidates})
      file(STRINGS ${source} uses_regex REGEX "^#include <regex>")
      if(uses_regex)
        set_source_files_properties(${source} PROPERTIES COMPILE_OPTIONS -Wno-maybe-uninitialized)
      endif()
    endforeach()
  endif()
  message(STATUS "wavepath: sanitizers ${WAVEPATH_SANITIZE}")
endif()

# wavepath_plain_test_code(TARGET): a test program's own code in a sanitizer
# build. What the sanitizers are there for is wavepath's host code, which every
# library and the executable carry instrumented; the test files around it are
# compiled plain at -O0 (unless WAVEPATH_SANITIZE_TEST_CODE), which takes a
# third of the time ASan + UBSan at -O1 take (docs/fuzzing.md has the
# figures), and linked with the sanitizer runtime all the same, so the
# tests' heap calls are still checked by its interceptors, and any report in
# wavepath's code still fails the test. WAVEPATH_SANITIZED tells the test code
# that it runs in such a process (tests/support/sanitizer.hpp), as the
# compiler's own __SANITIZE_ADDRESS__ no longer does there.
function(wavepath_plain_test_code target)
  if(NOT WAVEPATH_SANITIZE)
    return()
  endif()
  target_compile_definitions(${target} PRIVATE WAVEPATH_SANITIZED="${WAVEPATH_SANITIZE}")
  if(WAVEPATH_SANITIZE_TEST_CODE OR WAVEPATH_FUZZ)
    return()
  endif()
  get_target_property(options ${target} COMPILE_OPTIONS)
  list(FILTER options EXCLUDE REGEX "^-f(no-)?sanitize|^-fno-omit-frame-pointer$")
  set_property(TARGET ${target} PROPERTY COMPILE_OPTIONS ${options})
  target_compile_options(${target} PRIVATE -O0)
endfunction()
