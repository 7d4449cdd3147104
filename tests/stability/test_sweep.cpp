// No NaN or Inf anywhere in the stress suite: every scene of scenes/stress that
// loads renders to a finite image with no non-finite sample dropped at the
// film, with its own kernels and with the general (all-features) ones, with
// and without next-event estimation. And case 2's far end: the hexroom translated by 1e5,
// where float32's spacing (0.0078) is about the light's 1 cm gap below the
// ceiling, degrades as documented but never to NaN. There the relative ray
// offset is 0.2: floor points within sqrt(2 R 0.2) = 0.9 of the mirror
// sphere's contact start their next ray inside the sphere, which then
// bounces inside the lossless mirror until the depth cap cuts it.
#include "stability.hpp"

#include <filesystem>

using namespace wp;
using namespace wp::stability;

TEST_CASE("every stress scene renders finite, with no non-finite sample", "[stability][sweep]") {
    std::vector<std::string> names;
    for (const auto& entry :
         std::filesystem::directory_iterator(std::string(WAVEPATH_SOURCE_DIR) + "/scenes/stress"))
        if (entry.path().extension() == ".json")
            names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    REQUIRE(names.size() >= 20);
    int rendered = 0;
    for (const std::string& name : names) {
        Scene scene;
        try {
            scene = stress_scene(name, 16);
        } catch (const SceneError&) {
            CHECK(name.rfind("degenerate-", 0) == 0); // only the bad-input cases may fail
            continue;
        }
        // The scene's own kernels with next-event estimation, and the general
        // kernels with and without it: one general program serves every
        // scene, where each scene's own kernels without next-event
        // estimation would be one more program to compile per scene (the
        // general kernels render what the specialised ones do, bit for bit:
        // tests/render/test_features.cpp).
        for (int variant = 0; variant < 3; ++variant) {
            IntegratorOptions options;
            options.next_event_estimation = variant != 1;
            options.general_kernels = variant != 0;
            test::Rendered r = test::render(scene, 4, 61, 0, options);
            INFO(name << " variant " << variant << ": " << r.stats.nonfinite_samples
                      << " non-finite samples");
            CHECK(all_finite(r));
        }
        ++rendered;
    }
    WARN(rendered << " stress scenes rendered finite in 3 variants each");
    CHECK(rendered >= 17);
}

TEST_CASE("far from the origin: the hexroom translated by 1e5 degrades, never to NaN",
          "[stability][translate][statistical]") {
    // Few samples: every path trapped under the mirror sphere (see the file
    // comment) keeps its wave going for 1024 bounces.
    const int size = 24;
    const std::uint32_t spp = 32;
    test::Rendered ref = test::render(hexroom(size), spp, 11);
    auto start = std::chrono::steady_clock::now();
    test::Rendered r = test::render(stress_scene("translate-1e5", size), spp, 11);
    double seconds = seconds_since(start);
    BlockComparison b = compare_blocks(r.film, ref.film, 6);
    double worst_mean = 0.0;
    for (int c = 0; c < 3; ++c)
        worst_mean = std::max(worst_mean, image_mean_sigmas(r.film, ref.film, c));
    test::MeanWithError m = test::image_mean(r.film, 1), m0 = test::image_mean(ref.film, 1);
    WARN("translate-1e5: green mean "
         << m.mean << " vs " << m0.mean << " (" << 100.0 * (m.mean / m0.mean - 1.0) << " %), "
         << worst_mean << " sigma; blocks worst " << b.worst_sigmas << " sigma, " << b.outside
         << "/" << b.blocks << " over 5; " << r.stats.capped_paths << " capped of "
         << size * size * spp << "; " << r.stats.nonfinite_samples << " non-finite; " << seconds
         << " s");
    CHECK(all_finite(r));
}
