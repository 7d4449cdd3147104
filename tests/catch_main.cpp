// The one translation unit that holds Catch2's main(), and the environment
// every test process of a build shares.
//
// Each ctest test is a process of its own, and most of a cold run's time is
// spent compiling kernels; so every test executable keeps wavepath's program
// cache and PoCL's kernel cache in the build tree (WAVEPATH_TEST_CACHE_DIR),
// one pair for the whole run, whichever way the test is started (ctest, or
// the executable by hand). PoCL's cache is where the CLI puts it for the same
// program cache (app/caches.cpp), so the CLI tests' `wavepath` processes and
// the in-process renders share compiled kernels too. A variable already set
// in the environment wins.
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <string>

int main(int argc, char* argv[]) {
    const std::filesystem::path cache = WAVEPATH_TEST_CACHE_DIR;
    ::setenv("WAVEPATH_CACHE_DIR", cache.c_str(), 0);
    // PoCL reads it when the platform is first queried, after this.
    ::setenv("POCL_CACHE_DIR", (cache / "pocl").c_str(), 0);
    // The wavepath commands the tests run (and their own integrators, were
    // they to ask) skip the kernels' self-check: a general build and two
    // renders per new scene and options. tests/render/test_self_check.cpp
    // tests it; WAVEPATH_SELF_CHECK=1 in the environment keeps it on.
    ::setenv("WAVEPATH_SELF_CHECK", "0", 0);
    return Catch::Session().run(argc, argv);
}
