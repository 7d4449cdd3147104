// The AOVs (--aov; docs/lights-and-camera.md, "AOVs") end to end: the camera
// ray's first hit per pixel, against analytic values computed here in double
// precision from the scene's geometry and materials: the depth of a plane
// seen head-on (d / cos of each pixel's ray angle), its normal exactly, the
// albedo of each material region, 0 where the ray misses; the beauty image
// bit for bit the same with and without AOVs; the same AOVs from every launch
// plan and from two halves of the samples merged.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <initializer_list>
#include <vector>

#include "support/render_helpers.hpp"

using namespace wp;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A 32x32 camera at the origin looking along -z (image right +x, up +y), a
// field of view of 2 atan(0.5) each way, at a plane z = -kDepth that covers
// the image's lower half (film y < 0; the upper half sees nothing) in three
// regions of film x: [-1, -0.5) an emitter, [-0.5, 0) red diffuse, [0, 1]
// a conductor. Every region edge lies on a pixel edge (columns 8 and 16, row
// 16). The conductor's triangles are wound away from the camera (their front
// face is -z): the normal AOV faces the camera whatever the winding.
constexpr int kSize = 32;
constexpr double kDepth = 3.0;
constexpr double kHalf = 0.5; // tan of half the field of view
const glm::dvec3 kRed{0.8, 0.1, 0.1};
const glm::dvec3 kMetal{0.9, 0.6, 0.3};

Scene plane_scene() {
    Scene scene;
    scene.source = "aov-plane";
    Camera& c = scene.camera;
    c.eye = {0.0, 0.0, 0.0};
    c.look_at = {0.0, 0.0, -1.0};
    c.up = {0.0, 1.0, 0.0};
    c.width = kSize;
    c.height = kSize;
    c.vertical_fov_degrees = 2.0 * std::atan(kHalf) * 180.0 / kPi;
    Material light;
    light.name = "light";
    light.kind = MaterialKind::Emitter;
    light.emission = glm::dvec3(1.0);
    light.reflectance = glm::dvec3(0.5); // an emitter's albedo is 0 whatever this says
    Material red;
    red.name = "red";
    red.reflectance = kRed;
    Material metal;
    metal.name = "metal";
    metal.kind = MaterialKind::Conductor;
    metal.reflectance = kMetal;
    metal.eta = glm::dvec3(0.2);
    metal.k = glm::dvec3(3.0);
    scene.materials = {light, red, metal};
    // On the plane, film x maps to x = film_x kHalf kDepth.
    const double z = -kDepth, far = 50.0, edge = -0.5 * kHalf * kDepth;
    auto quad = [&](double x0, double x1, std::uint32_t material, bool facing) {
        const glm::dvec3 a{x0, -far, z}, b{x1, -far, z}, cc{x1, 0.0, z}, d{x0, 0.0, z};
        if (facing) { // front face +z, towards the camera
            scene.triangles.push_back({{a, b, cc}, material, false, {}});
            scene.triangles.push_back({{a, cc, d}, material, false, {}});
        } else {
            scene.triangles.push_back({{a, cc, b}, material, false, {}});
            scene.triangles.push_back({{a, d, cc}, material, false, {}});
        }
    };
    quad(-far, edge, 0, true);
    quad(edge, 0.0, 1, true);
    quad(0.0, far, 2, false);
    return scene;
}

// The film coordinates of pixel (column, row)'s centre; row 0 is the top.
double film_x(int column) {
    return 2.0 * (column + 0.5) / kSize - 1.0;
}
double film_y(int row) {
    return 1.0 - 2.0 * (row + 0.5) / kSize;
}

// The distance from the eye to the plane along pixel (column, row)'s central
// ray: kDepth / cos of the ray's angle to the axis.
double analytic_depth(int column, int row) {
    const double x = film_x(column) * kHalf, y = film_y(row) * kHalf;
    return kDepth * std::sqrt(1.0 + x * x + y * y);
}

IntegratorOptions with_aovs(LaunchPlan plan = LaunchPlan::Stages) {
    IntegratorOptions options;
    options.aovs = kAovAlbedo | kAovNormal | kAovDepth;
    options.launch_plan = plan;
    return options;
}

// Pixels next to a region's edge (their samples may round to either side)
// are left out of the checks of a region.
bool next_to_edge(int column, int row) {
    return column == 7 || column == 8 || column == 15 || column == 16 || row == 15 || row == 16;
}

} // namespace

TEST_CASE("AOVs: depth, normal and albedo of a plane against their analytic values; 0 where the "
          "camera ray misses",
          "[render][aov]") {
    const Scene scene = plane_scene();
    const test::Rendered r = test::render(scene, 16, 3, 0, with_aovs());
    REQUIRE(r.film.has_aovs());
    const std::vector<float> albedo = r.film.aov_mean(0), normal = r.film.aov_mean(1),
                             depth = r.film.aov_mean(2);
    REQUIRE(albedo.size() == kSize * kSize * 3);
    REQUIRE(depth.size() == kSize * kSize);

    double worst_depth = 0.0;  // the largest relative error of the depth
    double most_oblique = 1.0; // the largest depth / kDepth seen (a z-depth would be 1)
    int exact_normals = 0, checked = 0;
    for (int row = 0; row < kSize; ++row)
        for (int column = 0; column < kSize; ++column) {
            const std::size_t p = static_cast<std::size_t>(row) * kSize + column;
            INFO("pixel " << column << ", " << row);
            if (row < 15) { // the upper half: every ray misses
                CHECK(depth[p] == 0.0f);
                for (int c = 0; c < 3; ++c) {
                    CHECK(albedo[p * 3 + c] == 0.0f);
                    CHECK(normal[p * 3 + c] == 0.0f);
                }
                continue;
            }
            if (next_to_edge(column, row))
                continue;
            ++checked;
            const double expected = analytic_depth(column, row);
            worst_depth = std::max(worst_depth, std::abs(depth[p] - expected) / expected);
            most_oblique = std::max(most_oblique, expected / kDepth);
            // The plane's normal, facing the camera: +z for either winding.
            exact_normals +=
                normal[p * 3 + 0] == 0.0f && normal[p * 3 + 1] == 0.0f && normal[p * 3 + 2] == 1.0f;
            const glm::dvec3 expected_albedo = column < 8    ? glm::dvec3(0.0)
                                               : column < 16 ? kRed
                                                             : kMetal;
            for (int c = 0; c < 3; ++c)
                CHECK(albedo[p * 3 + c] ==
                      Approx(static_cast<float>(expected_albedo[c])).epsilon(1e-6));
        }
    CHECK(checked == 15 * 28);
    CHECK(exact_normals == checked);
    // The depth is a distance along the ray, not a z-depth: the corner
    // pixels are 1.2 times as far, and every pixel is within 1e-3 of d / cos.
    CHECK(most_oblique > 1.2);
    CHECK(worst_depth < 1e-3);
    UNSCOPED_INFO("worst relative depth error " << worst_depth);
}

TEST_CASE("AOVs: the beauty image is the same bit for bit with and without them", "[render][aov]") {
    const Scene scene = test::hexroom(16, 16);
    IntegratorOptions plain;
    plain.launch_plan = LaunchPlan::Stages;
    const test::Rendered without = test::render(scene, 4, 7, 0, plain);
    const test::Rendered with = test::render(scene, 4, 7, 0, with_aovs());
    CHECK_FALSE(without.film.has_aovs());
    REQUIRE(with.film.has_aovs());
    const Image a = without.film.mean(), b = with.film.mean();
    REQUIRE(a.rgb.size() == b.rgb.size());
    CHECK(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
    // And the AOVs are there: the hexroom's camera sees a wall in every pixel.
    const std::vector<float> depth = with.film.aov_mean(2);
    CHECK(*std::min_element(depth.begin(), depth.end()) > 0.0f);
}

TEST_CASE("AOVs: every launch plan, and two halves of the samples merged, give the same AOVs",
          "[render][aov]") {
    const Scene scene = plane_scene();
    const test::Rendered stages = test::render(scene, 8, 3, 0, with_aovs());
    Film halves(kSize, kSize);
    {
        const test::Rendered first = test::render(scene, 4, 3, 0, with_aovs());
        const test::Rendered second = test::render(scene, 4, 3, 4, with_aovs(LaunchPlan::Wave));
        halves.merge(first.film);
        halves.merge(second.film);
    }
    const test::Rendered bounce = test::render(scene, 8, 3, 0, with_aovs(LaunchPlan::Bounce));
    const test::Rendered wave = test::render(scene, 8, 3, 0, with_aovs(LaunchPlan::Wave));
    for (std::uint32_t aov = 0; aov < kAovCount; ++aov) {
        INFO("AOV " << aov_name(aov));
        const std::vector<float> expected = stages.film.aov_mean(aov);
        for (const Film* film :
             std::initializer_list<const Film*>{&halves, &bounce.film, &wave.film}) {
            const std::vector<float> got = film->aov_mean(aov);
            REQUIRE(got.size() == expected.size());
            double worst = 0.0;
            for (std::size_t i = 0; i < got.size(); ++i)
                worst = std::max(worst, static_cast<double>(std::abs(got[i] - expected[i])));
            CHECK(worst < 1e-5); // float32 batch sums grouped differently
        }
    }
    // The merged film's AOVs survive its sums (a checkpoint or an MPI rank's film).
    const Film copy(kSize, kSize, halves.sums());
    CHECK(copy.aov_mean(2) == halves.aov_mean(2));
}

TEST_CASE("AOVs: their code is compiled only for a render that asks for them", "[render][aov]") {
    const Scene scene = plane_scene();
    IntegratorOptions plain;
    const SceneFeatures features = integrator_features(scene, plain);
    CHECK(kernel_build_options(features, plain).find("WP_AOV") == std::string::npos);
    for (std::uint32_t aovs : {kAovAlbedo, kAovNormal, kAovDepth, kAovAlbedo | kAovDepth}) {
        IntegratorOptions options;
        options.aovs = aovs;
        CHECK(kernel_build_options(features, options).find(" -D WP_AOV=1") != std::string::npos);
    }
    WavefrontIntegrator without(test::device(), scene, plain);
    CHECK(without.program().options.find("WP_AOV") == std::string::npos);
    WavefrontIntegrator with(test::device(), scene, with_aovs());
    CHECK(with.program().options.find(" -D WP_AOV=1") != std::string::npos);
}
