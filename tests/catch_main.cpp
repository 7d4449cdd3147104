// The one translation unit that holds Catch2's main().
#define CATCH_CONFIG_RUNNER
#include <catch2/catch.hpp>

#include <cstdlib>

int main(int argc, char* argv[]) {
    // The wavepath commands the tests run (and their own integrators, were
    // they to ask) skip the kernels' self-check: a general build and two
    // renders per new scene and options. tests/render/test_self_check.cpp
    // tests it; WAVEPATH_SELF_CHECK=1 in the environment keeps it on.
    setenv("WAVEPATH_SELF_CHECK", "0", 0);
    return Catch::Session().run(argc, argv);
}
