// libFuzzer target: bytes as scene JSON, through parse_scene (scene/load.hpp),
// the loader's in-memory entry point: the JSON parser with its diagnostics,
// every field's checks, inline meshes, transforms and the validator. The scene
// is named "fuzz.json", so mesh files it names are looked up in the working
// directory; fuzz/run-fuzzers.sh runs this target in a folder holding the test
// meshes, so that mesh shapes load real files too.
//
// A SceneError with a clean one-line message (clean_error.hpp) is the expected
// answer to bad input, and warnings must be clean too; any other exception
// escaping, a crash, a hang or a sanitizer report is a finding (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "clean_error.hpp"
#include "scene/load.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    try {
        const wp::Scene scene = wp::parse_scene(text, "fuzz.json");
        for (const std::string& warning : scene.warnings)
            wp::fuzz::require_clean_message(warning, "a scene warning");
    } catch (const wp::SceneError& error) {
        wp::fuzz::require_clean_message(error.what(), "a SceneError");
    }
    return 0;
}
