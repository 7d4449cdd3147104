// wavepath against Mitsuba 3, end to end: each scene tests/data/mitsuba/NAME.json
// has a reference NAME.exr that Mitsuba 3 rendered from wavepath's own export
// of the scene, with NAME-error.exr the standard error of each of its pixels
// (tools/mitsuba-references.sh made both; tests/data/mitsuba/README.md has the
// command and the figures). The two renderers share no code: an image mean or
// block mean more than 5 combined standard errors apart is a disagreement in
// what a material, a light or the camera computes. Mitsuba is never needed
// here.
//
// The Mitsuba reader (scene/mitsuba/load_mitsuba.hpp) is held to the same
// references twice: each JSON scene exported at test time and rendered from
// its XML, and boxes.xml, written by hand in Mitsuba's idioms (rectangles and
// cubes with to_world, twosided, ref, default), whose reference Mitsuba
// rendered from the file itself.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "image/exr.hpp"
#include "scene/load.hpp"
#include "scene/mitsuba_export.hpp"
#include "support/render_helpers.hpp"
#include "support/temp_dir.hpp"

using namespace wp;
using namespace wp::test;

namespace {

const std::string kDir = std::string(WAVEPATH_SOURCE_DIR) + "/tests/data/mitsuba/";

// The mean of a region of an image of means, and its standard error from the
// per-pixel variances of the mean (pixels are independent in both renderers).
MeanWithError region_mean(const Image& mean, const Image& variance, int x0, int y0, int x1, int y1,
                          int c) {
    double sum = 0.0, var = 0.0;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            sum += mean.pixel(x, y)[c];
            var += variance.pixel(x, y)[c];
        }
    const double n = static_cast<double>(x1 - x0) * (y1 - y0);
    return {sum / n, std::sqrt(var) / n};
}

Image squared(Image image) {
    for (float& v : image.rgb)
        v *= v;
    return image;
}

// How a render of wavepath's lies from Mitsuba's NAME.exr: the image mean
// and every kBlock x kBlock block mean, per channel, in combined standard
// errors.
struct Agreement {
    double image_sigmas[3] = {0.0, 0.0, 0.0};
    int regions = 0, far = 0; // block means, and those more than 5 sigma apart
    double worst = 0.0;       // the farthest block mean
    std::string means;        // both image means, for the message
};

// Renders `scene` at `spp` with `options` and compares it with NAME.exr.
Agreement compare_with_mitsuba(const std::string& name, const Scene& scene, std::uint32_t spp,
                               const IntegratorOptions& options) {
    const Image reference = read_exr(kDir + name + ".exr");
    const Image reference_variance = squared(read_exr(kDir + name + "-error.exr"));
    REQUIRE(reference.width == scene.camera.width);
    REQUIRE(reference.height == scene.camera.height);

    const Rendered ours = render(scene, spp, 11, 0, options);
    CHECK(ours.stats.nonfinite_samples == 0);
    const Image mean = ours.film.mean(), variance = ours.film.variance_of_mean();

    constexpr int kBlock = 8;
    const int width = scene.camera.width, height = scene.camera.height;
    Agreement out;
    for (int c = 0; c < 3; ++c) {
        const MeanWithError a = region_mean(mean, variance, 0, 0, width, height, c);
        const MeanWithError b = region_mean(reference, reference_variance, 0, 0, width, height, c);
        out.means += name + " channel " + std::to_string(c) + ": wavepath " +
                     std::to_string(a.mean) + " +- " + std::to_string(a.standard_error) +
                     ", Mitsuba 3 " + std::to_string(b.mean) + " +- " +
                     std::to_string(b.standard_error) + "\n";
        out.image_sigmas[c] = sigmas_apart(a, b);
        for (int y = 0; y + kBlock <= height; y += kBlock)
            for (int x = 0; x + kBlock <= width; x += kBlock) {
                const MeanWithError ours_block =
                    region_mean(mean, variance, x, y, x + kBlock, y + kBlock, c);
                const MeanWithError reference_block =
                    region_mean(reference, reference_variance, x, y, x + kBlock, y + kBlock, c);
                // A block of background seen straight against a constant
                // emitter has no noise in either renderer (every sample is
                // the radiance): there the two differ by rounding alone, so
                // the error is at least 1e-4 of the mean. (Mitsuba 3.9.1's
                // scalar_rgb reads the sky's 0.7 as 0.699992, 1.1e-5 less:
                // measured in sky.exr, whose error is 0 there.)
                const double z =
                    std::abs(ours_block.mean - reference_block.mean) /
                    std::max(std::hypot(ours_block.standard_error, reference_block.standard_error),
                             1e-4 * std::abs(reference_block.mean));
                ++out.regions;
                out.far += z > 5.0 ? 1 : 0;
                out.worst = std::max(out.worst, z);
            }
    }
    return out;
}

// Renders `scene` at `spp` and checks that the image mean and every block
// mean, per channel, are within 5 sigma of Mitsuba's NAME.exr.
void check_agreement(const std::string& name, const Scene& scene, std::uint32_t spp,
                     const IntegratorOptions& options = {}) {
    const Agreement a = compare_with_mitsuba(name, scene, spp, options);
    INFO(a.means);
    for (int c = 0; c < 3; ++c)
        CHECK(a.image_sigmas[c] < 5.0);
    INFO(name << ": " << a.far << " of " << a.regions << " block means more than 5 sigma apart "
              << "(the farthest " << a.worst << " sigma)");
    CHECK(a.far == 0);
}

void check_agreement(const std::string& name, std::uint32_t spp) {
    check_agreement(name, load_scene(kDir + name + ".json"), spp);
}

// NAME.json through wavepath's export and back in through the XML reader.
void check_agreement_through_xml(const std::string& name, std::uint32_t spp) {
    TempDir dir;
    write_mitsuba(export_mitsuba(load_scene(kDir + name + ".json"), name), dir / (name + ".xml"));
    check_agreement(name, load_scene(dir / (name + ".xml")), spp);
}

} // namespace

TEST_CASE("Mitsuba 3 agreement: rough and smooth conductors", "[render][materials][statistical]") {
    check_agreement("metals", 1024);
}

TEST_CASE("Mitsuba 3 agreement: smooth and thin dielectrics", "[render][materials][statistical]") {
    check_agreement("glass", 1024);
}

TEST_CASE("Mitsuba 3 agreement: plastic, linear and nonlinear",
          "[render][materials][statistical]") {
    check_agreement("plastic", 1024);
}

TEST_CASE("Mitsuba 3 agreement: rough dielectrics", "[render][materials][statistical]") {
    check_agreement("roughglass", 2048);
}

TEST_CASE("Mitsuba 3 agreement: rough plastic, GGX and Beckmann, linear and nonlinear",
          "[render][materials][statistical]") {
    check_agreement("roughplastic", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: conductors", "[render][mitsuba][statistical]") {
    check_agreement_through_xml("metals", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: dielectrics", "[render][mitsuba][statistical]") {
    check_agreement_through_xml("glass", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: plastic", "[render][mitsuba][statistical]") {
    check_agreement_through_xml("plastic", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: rough dielectrics", "[render][mitsuba][statistical]") {
    check_agreement_through_xml("roughglass", 2048);
}

TEST_CASE("Mitsuba 3 agreement through XML: rough plastic", "[render][mitsuba][statistical]") {
    check_agreement_through_xml("roughplastic", 1024);
}

TEST_CASE("Mitsuba 3 agreement: a hand-written XML scene (rectangles, cubes, twosided, ref)",
          "[render][mitsuba][statistical]") {
    check_agreement("boxes", load_scene(kDir + "boxes.xml"), 1024);
}

TEST_CASE("Mitsuba 3 agreement: textures (bitmap, checkerboard, to_uv, wrap modes, roughness)",
          "[render][materials][textures][statistical]") {
    check_agreement("textures", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: textures", "[render][mitsuba][textures][statistical]") {
    check_agreement_through_xml("textures", 1024);
}

TEST_CASE("Mitsuba 3 agreement: textures on a cube, rectangles, a disk and an OBJ mesh",
          "[render][mitsuba][textures][statistical]") {
    check_agreement("textures-shapes", load_scene(kDir + "textures-shapes.xml"), 1024);
}

TEST_CASE("Mitsuba 3 agreement: anisotropic roughness along dp/du (sphere, rectangle, OBJ)",
          "[render][mitsuba][anisotropy][statistical]") {
    check_agreement("anisotropic", load_scene(kDir + "anisotropic.xml"), 1024);
}

TEST_CASE("Mitsuba 3 agreement: shapegroups placed by scaled, turned and mirrored instances",
          "[render][mitsuba][instances][statistical]") {
    check_agreement("instances", load_scene(kDir + "instances.xml"), 1024);
}

TEST_CASE("Mitsuba 3 agreement: a point light", "[render][emitters][statistical]") {
    check_agreement("point", 1024);
}

TEST_CASE("Mitsuba 3 agreement: a spot light's cone and falloff",
          "[render][emitters][statistical]") {
    check_agreement("spot", 1024);
}

TEST_CASE("Mitsuba 3 agreement: a directional light (a sun)", "[render][emitters][statistical]") {
    check_agreement("sun", 1024);
}

TEST_CASE("Mitsuba 3 agreement: a constant environment, with MIS",
          "[render][emitters][statistical]") {
    check_agreement("sky", 1024);
}

TEST_CASE("Mitsuba 3 agreement: an environment map, turned and scaled, with MIS",
          "[render][emitters][envmap][statistical]") {
    check_agreement("envmap", 1024);
}

TEST_CASE("Mitsuba 3 agreement: sphere lights on glossy plates (Veach's MIS scene)",
          "[render][emitters][sphere-light][statistical]") {
    check_agreement("veach-mis", 1024);
}

TEST_CASE("Mitsuba 3 agreement through XML: the five emitters", "[render][mitsuba][statistical]") {
    for (const char* name : {"point", "spot", "sun", "sky", "envmap"})
        check_agreement_through_xml(name, 256);
}

TEST_CASE("Mitsuba 3 agreement: mitsuba-data's Cornell box, unchanged (spectra, OBJ meshes)",
          "[render][mitsuba][third-party][statistical]") {
    // The file as mitsuba-data has it, at 64x64 and without its max_depth
    // of 6 (wavepath ends paths by roulette alone): both renderers read it
    // with -D res=64 -D max_depth=-1 (cbox-mitsuba-data.exr, README.md).
    SceneReadOptions options;
    options.defines = {{"res", "64"}, {"max_depth", "-1"}};
    check_agreement("cbox-mitsuba-data",
                    load_scene(std::string(WAVEPATH_SOURCE_DIR) +
                                   "/tests/data/third-party/mitsuba-data/scenes/cbox/cbox.xml",
                               options),
                    1024);
}

TEST_CASE("Mitsuba 3 agreement: max_depth 2 and 3, by a mirror and a rough conductor, with and "
          "without next-event estimation through the mirror",
          "[render][mitsuba][max-depth][statistical]") {
    // max-depth.xml read with -D max_depth=M, as Mitsuba rendered it
    // (max-depth-M.exr, README.md): paths of at most M edges, the camera ray
    // included. At M = 2 a light sample through the mirror would be a path
    // of three edges; at M = 3 it is made, at the first vertex only.
    for (int max_depth : {2, 3})
        for (bool mirror_next_event : {true, false}) {
            INFO("max_depth " << max_depth << ", mirror next-event estimation "
                              << (mirror_next_event ? "on" : "off"));
            SceneReadOptions read;
            read.defines = {{"max_depth", std::to_string(max_depth)}};
            IntegratorOptions options;
            options.mirror_next_event = mirror_next_event;
            check_agreement("max-depth-" + std::to_string(max_depth),
                            load_scene(kDir + "max-depth.xml", read), 1024, options);
        }
    // Neither of wavepath's bounce caps around it is Mitsuba's max_depth 2:
    // 0 (light samples at the first vertex, through the mirror too, but no
    // light found by its BSDF sample: none seen in the mirror, no BSDF half
    // of the sphere's weighed light) nor 1 (light samples at the second
    // vertex as well). The test tells them apart (both come out brighter,
    // 14 and 46 sigma).
    SceneReadOptions unlimited;
    unlimited.defines = {{"max_depth", "-1"}};
    for (std::uint32_t bounces : {0u, 1u}) {
        IntegratorOptions cap;
        cap.max_depth = bounces;
        const Agreement a = compare_with_mitsuba(
            "max-depth-2", load_scene(kDir + "max-depth.xml", unlimited), 1024, cap);
        INFO("wavepath's cap of " << bounces << " bounces\n" << a.means);
        CHECK(std::min({a.image_sigmas[0], a.image_sigmas[1], a.image_sigmas[2]}) > 5.0);
    }
}

TEST_CASE("Mitsuba 3 agreement: mitsuba-data's Cornell box at max_depth 3",
          "[render][mitsuba][max-depth][third-party][statistical]") {
    // The file as mitsuba-data has it, read by both with -D res=64 -D
    // max_depth=3 (cbox-max-depth-3.exr, README.md): direct light and one
    // bounce of indirect light. (The film's edge is the next test's.)
    SceneReadOptions options;
    options.defines = {{"res", "64"}, {"max_depth", "3"}};
    check_agreement("cbox-max-depth-3",
                    load_scene(std::string(WAVEPATH_SOURCE_DIR) +
                                   "/tests/data/third-party/mitsuba-data/scenes/cbox/cbox.xml",
                               options),
                    1024);
}

TEST_CASE("Mitsuba 3 agreement: the film's edge: the Cornell box's outermost pixels at 32x32",
          "[render][mitsuba][camera][third-party][statistical]") {
    // Mitsuba's film samples only inside the image and splats each sample
    // with the Gaussian filter's weight, so a pixel near the edge averages the
    // part of its footprint inside the image; wavepath draws such a pixel's
    // offsets from the filter restricted to the image (kernels/camera.h).
    // Drawn from the whole filter, the outermost ring of this box, whose
    // walls end at the image's edge, came out 18 % darker than Mitsuba's
    // (z = -31). The reference is Mitsuba's llvm_ad_rgb, which evaluates the
    // filter exactly: scalar_rgb looks it up in a 31-step table, which
    // widens it and puts its own ring 0 1.9 % above llvm_ad_rgb's (and
    // wavepath's; docs/lights-and-camera.md, "The film's edge"). The rings
    // are compared here, where block means would mix them with the inside
    // (cbox-edge-32.exr: -D res=32 -D max_depth=3, 16 x 4096 spp; README.md).
    SceneReadOptions read;
    read.defines = {{"res", "32"}, {"max_depth", "3"}};
    const Scene scene = load_scene(std::string(WAVEPATH_SOURCE_DIR) +
                                       "/tests/data/third-party/mitsuba-data/scenes/cbox/cbox.xml",
                                   read);
    const Image reference = read_exr(kDir + "cbox-edge-32.exr");
    const Image reference_variance = squared(read_exr(kDir + "cbox-edge-32-error.exr"));
    REQUIRE(reference.width == 32);
    REQUIRE(reference.height == 32);
    const Rendered ours = render(scene, 1024, 11);
    const Image mean = ours.film.mean(), variance = ours.film.variance_of_mean();
    // The mean of ring r (the pixels r steps in from the nearest edge) and
    // its standard error.
    auto ring_mean = [](const Image& image, const Image& var, int ring, int c) {
        double sum = 0.0, sum_var = 0.0;
        int n = 0;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                if (std::min({x, y, image.width - 1 - x, image.height - 1 - y}) == ring) {
                    sum += image.pixel(x, y)[c];
                    sum_var += var.pixel(x, y)[c];
                    ++n;
                }
        return MeanWithError{sum / n, std::sqrt(sum_var) / n};
    };
    for (int ring : {0, 1, 2})
        for (int c = 0; c < 3; ++c) {
            const MeanWithError a = ring_mean(mean, variance, ring, c);
            const MeanWithError b = ring_mean(reference, reference_variance, ring, c);
            INFO("ring " << ring << " channel " << c << ": wavepath " << a.mean << " +- "
                         << a.standard_error << ", Mitsuba 3 " << b.mean << " +- "
                         << b.standard_error);
            CHECK(sigmas_apart(a, b) < 5.0);
            // The test's power: 5 sigma is under a third of the 18 % the
            // whole filter lost in ring 0.
            if (ring == 0)
                CHECK(5.0 * std::hypot(a.standard_error, b.standard_error) < 0.06 * b.mean);
        }
}
