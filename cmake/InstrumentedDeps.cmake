# In sanitizer and fuzz builds (cmake/Sanitizers.cmake), tinyexr and
# tinyobjloader are compiled from Debian's own headers into wavepath_image and
# wavepath_scene (fuzz/instrumented/*.cpp), with the build's sanitizer and
# coverage flags, instead of used as Debian's shared libraries, which carry
# none: so AddressSanitizer and UndefinedBehaviorSanitizer check the decoders'
# own code (where the fuzzers found a leak and an int conversion of infinity),
# and libFuzzer sees their coverage. The static libraries' definitions win over
# the shared ones at link time. Included after the modules are defined.
find_package(ZLIB REQUIRED)
set(WAVEPATH_INSTRUMENTED_TINYEXR ${CMAKE_SOURCE_DIR}/fuzz/instrumented/tinyexr.cpp)
set(WAVEPATH_INSTRUMENTED_TINYOBJ ${CMAKE_SOURCE_DIR}/fuzz/instrumented/tinyobjloader.cpp)
# Third-party code: its warnings are not ours to fix (-w), whatever WAVEPATH_WERROR says.
set_source_files_properties(${WAVEPATH_INSTRUMENTED_TINYEXR} ${WAVEPATH_INSTRUMENTED_TINYOBJ}
                            PROPERTIES COMPILE_OPTIONS -w)
target_sources(wavepath_image PRIVATE ${WAVEPATH_INSTRUMENTED_TINYEXR})
target_link_libraries(wavepath_image PRIVATE ZLIB::ZLIB)
target_sources(wavepath_scene PRIVATE ${WAVEPATH_INSTRUMENTED_TINYOBJ})
