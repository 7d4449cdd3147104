// Sweeps of the hexroom over scales 1e-30 .. 1e30 and translations to 1e30
// (docs/stability.md, "Accepted range"), rendered whether validate_scene
// accepts them or not, so that the table shows what the limits guard
// against. Each row: the green image mean over the unscaled one's, the worst
// of the three channel means and the 48 blocks (4 x 4 pixels x 3 channels)
// in combined standard errors, and the validation's verdict. A tool, not a
// test (it prints tables and asserts nothing; tests/stability/test_scale_limits.cpp
// holds the accepted range to its images), built beside the tests and run by
// its tags:
//   build/wavepath_scale_sweep "[scale-sweep]"
#include <cstdio>

#include "scene/validate.hpp"
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

constexpr int kSize = 16;
constexpr int kBlock = 4;
constexpr std::uint32_t kSpp = 32;
constexpr std::uint32_t kSeed = 7;

const test::Rendered& reference() {
    static const test::Rendered r = test::render(hexroom(kSize), kSpp, kSeed);
    return r;
}

std::string verdict(const Scene& scene) {
    try {
        validate_scene(scene);
        return "accepted";
    } catch (const SceneError& e) {
        const std::string text = e.what();
        return "refused: " + text.substr(text.find(": ") + 2); // without the file name
    }
}

void row(double s, double t, bool far_look_at = false) {
    Scene scene = hexroom(kSize);
    // The same view with look_at far along it: the camera's own check (1e-9)
    // then no longer refuses translations first.
    if (far_look_at)
        scene.camera.look_at = scene.camera.eye + 1e25 * (scene.camera.look_at - scene.camera.eye);
    const glm::dvec3 look_at = scene.camera.look_at + glm::dvec3(t, -t, t);
    scene = transformed(scene, s, glm::dvec3(t, -t, t));
    if (far_look_at)
        scene.camera.look_at = look_at;
    const test::Rendered& ref = reference();
    test::Rendered r = test::render(scene, kSpp, kSeed);
    BlockComparison blocks = compare_blocks(r.film, ref.film, kBlock);
    double worst_mean = 0.0;
    for (int c = 0; c < 3; ++c)
        worst_mean = std::max(worst_mean, image_mean_sigmas(r.film, ref.film, c));
    const double m = test::image_mean(r.film, 1).mean / test::image_mean(ref.film, 1).mean;
    std::printf("| %.0e | %.0e | %.4f | %.2f | %d/%d | %.3g | %llu | %llu | %s |\n", s, t, m,
                worst_mean, blocks.outside, blocks.blocks, blocks.worst_sigmas,
                static_cast<unsigned long long>(r.stats.nonfinite_samples),
                static_cast<unsigned long long>(r.stats.capped_paths), verdict(scene).c_str());
    std::fflush(stdout);
}

} // namespace

TEST_CASE("scale sweep: the hexroom scaled by 1e-30 .. 1e30", "[scale-sweep]") {
    std::printf("| scale | translation | mean / unscaled (G) | mean sigma | blocks over 5 | worst "
                "block sigma | non-finite | capped | validation |\n");
    for (int k = -30; k <= 30; ++k)
        row(std::pow(10.0, k), 0.0);
}

TEST_CASE("scale sweep: the hexroom translated by 1 .. 1e30", "[translate-sweep]") {
    for (int k = 0; k <= 30; ++k)
        row(1.0, std::pow(10.0, k));
}

TEST_CASE("scale sweep: the hexroom, look_at far along the view, translated by 1 .. 1e30",
          "[translate-far-sweep]") {
    for (int k = 0; k <= 30; ++k)
        row(1.0, std::pow(10.0, k), true);
    // Either side of the limit 2^29 x the size (16): 8.59e9.
    for (double t : {8.5e9, 8.6e9})
        row(1.0, t, true);
}
