// libFuzzer target: bytes as a Mitsuba 3 XML scene, through load_scene
// (scene/load.hpp), which hands `.xml` files to the Mitsuba reader
// (src/scene/mitsuba/): pugixml's parser, the grammar (ids and refs,
// defaults and $names, includes, transforms), every plugin's parameters and
// the validator. The reader takes a file, so each input is written to
// fuzz.xml in the working directory first; fuzz/run-fuzzers.sh runs the
// targets in a folder holding the test meshes, so that mesh shapes and
// includes of fuzz.xml itself (a cycle) load real files too.
//
// A SceneError with a clean one-line message (clean_error.hpp) is the expected
// answer to bad input, and warnings must be clean too; any other exception
// escaping, a crash, a hang or a sanitizer report is a finding (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>

#include "clean_error.hpp"
#include "scene/load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    {
        std::ofstream out("fuzz.xml", std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        const wp::Scene scene = wp::load_scene("fuzz.xml");
        for (const std::string& warning : scene.warnings)
            wp::fuzz::require_clean_message(warning, "a scene warning");
    } catch (const wp::SceneError& error) {
        wp::fuzz::require_clean_message(error.what(), "a SceneError");
    }
    return 0;
}
