// The camera end to end: the image of a sharp edge through a thin lens at
// and away from the plane of focus, and through each pixel filter, against
// analytic profiles computed in double precision; stiff lenses (focus
// 1e-6 and 1e6) render finite images.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include <glm/geometric.hpp>
#include <string>

#include "render/device_scene.hpp"
#include "scene/load.hpp"
#include "support/render_helpers.hpp"
#include "support/scene_json.hpp"

using namespace wp;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The edge scene: a camera at the origin looking along -z (image right +x,
// up +y) at an emitting half-plane x > 0 (radiance 1, facing the camera) at
// depth `depth`, and nothing else: a camera ray reads 1 if it hits the
// emitter, else 0, so a pixel's value is the fraction of its (filter, lens)
// samples whose ray lands at x > kEdge on that plane. The edge runs through
// column 16 of 33, 0.3 of a pixel right of its centre, so that no filter's
// profile is symmetric about a pixel's centre (which would hide the tent's
// from the box's).
constexpr int kWidth = 33, kHeight = 2;
constexpr double kDepth = 4.0;
constexpr double kHalfWidth = 0.25;  // tan of half the horizontal field of view
constexpr double kEdgePixels = 16.8; // from the image's left, in pixels
constexpr double kEdgeFilm = 2.0 * kEdgePixels / kWidth - 1.0; // in film x, [-1, 1]
constexpr double kEdge = kDepth * kHalfWidth * kEdgeFilm;      // on the plane
constexpr std::uint32_t kSpp = 16384;

Scene edge_scene() {
    Scene scene;
    scene.source = "edge";
    Camera& c = scene.camera;
    c.eye = {0.0, 0.0, 0.0};
    c.look_at = {0.0, 0.0, -1.0};
    c.up = {0.0, 1.0, 0.0};
    c.width = kWidth;
    c.height = kHeight;
    c.vertical_fov_degrees = 2.0 * std::atan(kHalfWidth * kHeight / kWidth) * 180.0 / kPi;
    Material light;
    light.name = "light";
    light.kind = MaterialKind::Emitter;
    light.emission = glm::dvec3(1.0);
    scene.materials.push_back(light);
    // The half-plane as two triangles of a large quad, front face +z.
    const double far = 100.0, z = -kDepth;
    const glm::dvec3 a{kEdge, -far, z}, b{far, -far, z}, cc{far, far, z}, d{kEdge, far, z};
    scene.triangles.push_back({{a, b, cc}, 0, false, {}});
    scene.triangles.push_back({{a, cc, d}, 0, false, {}});
    return scene;
}

// The x coordinate of a uniform point of the disk of radius r: its CDF.
double disk_marginal_cdf(double x, double r) {
    const double t = std::clamp(x / r, -1.0, 1.0);
    return 0.5 + (t * std::sqrt(1.0 - t * t) + std::asin(t)) / kPi;
}

// The expected value of column `column` through a thin lens (radius,
// focus) with the box filter: film x = s in [-1, 1] is the pinhole ray of
// direction (s kHalfWidth, ., -1); the lens ray from aperture point
// (lx, ly, 0) through that ray's point on the plane of focus meets the
// plane at kDepth in x = kDepth s kHalfWidth + lx (1 - kDepth / focus). The
// pixel averages the probability over lx of x > kEdge, over its s (midpoint
// rule, 4000 steps).
double lens_column(int column, double radius, double focus) {
    const double k = 1.0 - kDepth / focus;
    const int steps = 4000;
    const double s0 = -1.0 + 2.0 * column / kWidth, ds = 2.0 / kWidth / steps;
    double sum = 0.0;
    for (int i = 0; i < steps; ++i) {
        const double s = s0 + (i + 0.5) * ds;
        const double offset = kDepth * s * kHalfWidth - kEdge; // the pinhole ray's, from the edge
        if (radius == 0.0 || k == 0.0)
            sum += offset > 0.0 ? 1.0 : 0.0;
        else if (k > 0.0) // x > 0 when lx > -offset / k
            sum += 1.0 - disk_marginal_cdf(-offset / k, radius);
        else // when lx < -offset / k
            sum += disk_marginal_cdf(-offset / k, radius);
    }
    return sum / steps;
}

// A filter's CDF, from its definition by Simpson's rule (f: Mitsuba's).
template <typename F> double filter_cdf(F f, double radius, double x) {
    auto integral = [&](double a, double b) {
        if (b <= a)
            return 0.0;
        const int steps = 2000;
        const double h = (b - a) / steps;
        double sum = f(a) + f(b);
        for (int i = 1; i < steps; ++i)
            sum += (i % 2 ? 4.0 : 2.0) * f(a + i * h);
        return sum * h / 3.0;
    };
    return integral(-radius, std::clamp(x, -radius, radius)) / integral(-radius, radius);
}

// The expected value of column `column` through a pinhole with a filter:
// a sample at column + 1/2 + offset (pixels) sees the emitter when it lies
// right of the edge.
template <typename F> double filter_column(int column, F f, double radius) {
    return 1.0 - filter_cdf(f, radius, kEdgePixels - column - 0.5);
}

// check_columns's tolerance for a reference value p at kSpp samples.
double tolerance(double p) {
    return 5.0 * std::sqrt(p * (1.0 - p) / kSpp);
}
// Its largest, at p = 1/2.
const double kTolerance = tolerance(0.5); // sqrt(1/4 / 1024) = 1/64

// Every pixel of the render against `expected(column)`, within 5 standard
// errors of the estimator: the value is a mean of N Bernoulli samples, whose
// standard error sqrt(p (1 - p) / N) the reference p gives (so that pixels
// the reference says are all 0 or all 1 must be exactly that).
template <typename E> void check_columns(const Scene& scene, std::uint32_t spp, E expected) {
    // The independent sampler, whose samples are Bernoulli trials; the
    // stratified default would be closer still.
    IntegratorOptions options;
    options.sampler = Sampler::Independent;
    const test::Rendered r = test::render(scene, spp, 11, 0, options);
    const Image mean = r.film.mean();
    CHECK(r.stats.nonfinite_samples == 0);
    int partial = 0; // columns strictly between black and white
    for (int x = 0; x < kWidth; ++x) {
        const double p = expected(x);
        partial += p > 0.02 && p < 0.98;
        const double sigma = std::sqrt(p * (1.0 - p) / spp);
        for (int y = 0; y < kHeight; ++y)
            for (int ch = 0; ch < 3; ++ch) {
                const double got = mean.rgb[(static_cast<std::size_t>(y) * kWidth + x) * 3 + ch];
                INFO("column " << x << " row " << y << ": " << got << ", expected " << p << " +- "
                               << sigma);
                CHECK(std::fabs(got - p) <= 5.0 * sigma + 1e-6);
            }
    }
    INFO(partial << " columns between black and white");
    CHECK(partial >= 1);
}

// A scene file's camera with `extra` keys (render/test_camera.cpp's own
// copy of the scene tests' helper).
Scene with_camera(const std::string& extra, const std::string& resolution = "[8, 8]",
                  double fov = 90) {
    return parse_scene(
        test::scene_json(R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": )" +
                         std::to_string(fov) + R"(, "resolution": )" + resolution + extra + "}"),
        "test.json");
}

double radians(double degrees) {
    return degrees * kPi / 180.0;
}

} // namespace

TEST_CASE("camera: an edge on the plane of focus is as sharp as through a pinhole",
          "[render][camera][statistical]") {
    Scene scene = edge_scene();
    scene.camera.aperture_radius = 0.2;
    scene.camera.focus_distance = kDepth;
    // Every column but the edge's is exactly black or white, and that one is
    // grey by the part of it right of the edge, as through a pinhole.
    check_columns(scene, kSpp, [](int x) { return lens_column(x, 0.2, kDepth); });
    CHECK(lens_column(16, 0.2, kDepth) == Approx(0.2).margin(1e-9));
    CHECK(lens_column(16, 0.0, 1.0) == Approx(0.2).margin(1e-9));
}

TEST_CASE("camera: an edge behind and in front of the plane of focus blurs by the circle of "
          "confusion",
          "[render][camera][statistical]") {
    // Focused at half the edge's depth: a point of the edge spreads over a
    // disk of radius 0.2 |1/4 - 1/2| = 0.05 at unit distance, 0.2 of the
    // film's half-width, 3.3 columns; focused at twice its depth, half that.
    for (double focus : {0.5 * kDepth, 2.0 * kDepth}) {
        INFO("focus " << focus);
        Scene scene = edge_scene();
        scene.camera.aperture_radius = 0.2;
        scene.camera.focus_distance = focus;
        check_columns(scene, kSpp, [&](int x) { return lens_column(x, 0.2, focus); });
    }
    // The blur the test expects is wide: columns 2 away from the edge's are
    // still grey (a check of the reference, not the render), so a sharp
    // image would fail.
    CHECK(lens_column(18, 0.2, 0.5 * kDepth) < 1.0 - kTolerance);
    CHECK(lens_column(14, 0.2, 0.5 * kDepth) > kTolerance);
    CHECK(lens_column(17, 0.2, 2.0 * kDepth) < 1.0 - kTolerance);
    CHECK(lens_column(15, 0.2, 2.0 * kDepth) > kTolerance);
}

TEST_CASE("camera: the tent and Gaussian filters give the edge their profiles",
          "[render][camera][statistical]") {
    auto tent = [](double r) {
        return [r](double x) { return std::max(0.0, 1.0 - std::fabs(x) / r); };
    };
    auto gaussian = [](double stddev) {
        const double alpha = -1.0 / (2.0 * stddev * stddev), r = 4.0 * stddev;
        return [alpha, r](double x) {
            return std::max(0.0, std::exp(alpha * x * x) - std::exp(alpha * r * r));
        };
    };
    // Each filter's reference differs from the box's by more than both
    // tolerances in some column (a check of the test: the box would fail it).
    auto distinct = [](auto reference) {
        double most = 0.0; // the difference beyond both tolerances
        for (int x = 0; x < kWidth; ++x) {
            const double a = reference(x), b = lens_column(x, 0.0, 1.0);
            most = std::max(most, std::fabs(a - b) - tolerance(a) - tolerance(b));
        }
        INFO("largest difference from the box's profile beyond both tolerances " << most);
        CHECK(most > 0.0);
    };
    SECTION("tent, radius 1 (Mitsuba's default)") {
        Scene scene = edge_scene();
        scene.camera.filter = FilterKind::Tent;
        auto reference = [&](int x) { return filter_column(x, tent(1.0), 1.0); };
        distinct(reference);
        check_columns(scene, kSpp, reference);
    }
    SECTION("tent, radius 2.5") {
        Scene scene = edge_scene();
        scene.camera.filter = FilterKind::Tent;
        scene.camera.filter_radius = 2.5;
        auto reference = [&](int x) { return filter_column(x, tent(2.5), 2.5); };
        distinct(reference);
        check_columns(scene, kSpp, reference);
    }
    SECTION("gaussian, stddev 0.5 (Mitsuba's default)") {
        Scene scene = edge_scene();
        scene.camera.filter = FilterKind::Gaussian;
        auto reference = [&](int x) { return filter_column(x, gaussian(0.5), 2.0); };
        distinct(reference);
        check_columns(scene, kSpp, reference);
    }
    SECTION("the box, as before: only the edge's column is grey") {
        check_columns(edge_scene(), kSpp, [](int x) { return lens_column(x, 0.0, 1.0); });
    }
}

TEST_CASE("camera: focus distances of 1e-6 and 1e6 render finite images", "[render][camera]") {
    for (double focus : {1e-6, 1e6}) {
        INFO("focus " << focus);
        Scene scene = test::hexroom(16, 16);
        scene.camera.aperture_radius = 0.05;
        scene.camera.focus_distance = focus;
        const test::Rendered r = test::render(scene, 2, 3);
        CHECK(r.stats.nonfinite_samples == 0);
        const Image mean = r.film.mean();
        double sum = 0.0;
        bool finite = true;
        for (float v : mean.rgb) {
            finite = finite && std::isfinite(v);
            sum += v;
        }
        CHECK(finite);
        CHECK(sum > 0.0);
    }
}

TEST_CASE("camera: the scene file's fov_axis reaches the image plane", "[render][camera]") {
    // 640x480 at 60 degrees along x: the flattened camera's right vector is
    // the half-width at unit distance, tan(30 degrees).
    const Scene s = with_camera(R"(, "fov_axis": "x")", "[640, 480]", 60);
    const DeviceScene flat = flatten_scene(s);
    const glm::dvec3 right(flat.camera.right.s[0], flat.camera.right.s[1], flat.camera.right.s[2]);
    const glm::dvec3 up(flat.camera.up.s[0], flat.camera.up.s[1], flat.camera.up.s[2]);
    CHECK(glm::length(right) == Approx(std::tan(radians(30.0))).epsilon(1e-6));
    CHECK(glm::length(up) == Approx(std::tan(radians(30.0)) * 480.0 / 640.0).epsilon(1e-6));
    // Without the key, fov is vertical, as it always was.
    CHECK(with_camera("", "[640, 480]", 60).camera.vertical_fov_degrees == 60.0);
    CHECK(with_camera(R"(, "fov_axis": "y")", "[640, 480]", 60).camera.vertical_fov_degrees ==
          60.0);
    CHECK(
        with_camera(R"(, "fov_axis": "diagonal")", "[300, 400]", 60).camera.vertical_fov_degrees ==
        Approx(2.0 * std::atan(std::tan(radians(30.0)) * 0.8) * 180.0 / kPi).epsilon(1e-12));
}

TEST_CASE("camera: the thin lens and the filter keys", "[render][camera]") {
    SECTION("absent: a pinhole with the box filter") {
        const Scene s = with_camera("");
        CHECK(s.camera.aperture_radius == 0.0);
        CHECK(s.camera.filter == FilterKind::Box);
        CHECK_FALSE(analyse_features(s).lens);
        const DeviceScene flat = flatten_scene(s);
        CHECK(flat.camera.lens_up.s[3] == 0.0f);
        CHECK(flat.camera.filter == WP_FILTER_BOX);
    }
    SECTION("aperture 0 is the pinhole: the same device camera, bit for bit") {
        const Scene s = with_camera(R"(, "aperture_radius": 0, "focus_distance": 3)");
        CHECK_FALSE(analyse_features(s).lens);
        const WpCamera a = flatten_scene(s).camera;
        const WpCamera b = flatten_scene(with_camera("")).camera;
        // Every field but the focus distance, which a pinhole never reads.
        CHECK(std::memcmp(&a.eye, &b.eye, 4 * sizeof(cl_float4)) == 0);
        CHECK(std::memcmp(&a.lens_up, &b.lens_up, sizeof(cl_float4)) == 0);
        CHECK(analyse_features(s).build_options() ==
              analyse_features(with_camera("")).build_options());
    }
    SECTION("a lens: the aperture along the image's right and up, the focus distance") {
        const Scene s = with_camera(R"(, "aperture_radius": 0.25, "focus_distance": 7.5)");
        CHECK(s.camera.aperture_radius == 0.25);
        CHECK(s.camera.focus_distance == 7.5);
        const SceneFeatures f = analyse_features(s);
        CHECK(f.lens);
        CHECK(f.build_options().find("-D WP_HAS_LENS=1") != std::string::npos);
        const WpCamera c = flatten_scene(s).camera;
        // The hexroom-like camera looks along +x with up +z: right is -y.
        CHECK(c.lens_right.s[0] == 0.0f);
        CHECK(c.lens_right.s[1] == -0.25f);
        CHECK(c.lens_right.s[3] == 7.5f);
        CHECK(c.lens_up.s[2] == 0.25f);
        CHECK(c.lens_up.s[3] == 0.25f);
    }
    SECTION("filters: by name or with their size") {
        CHECK(with_camera(R"(, "filter": "box")").camera.filter == FilterKind::Box);
        const Scene tent = with_camera(R"(, "filter": "tent")");
        CHECK(tent.camera.filter == FilterKind::Tent);
        CHECK(tent.camera.filter_radius == 1.0);
        CHECK(analyse_features(tent).tent_filter);
        CHECK_FALSE(analyse_features(tent).gaussian_filter);
        CHECK(with_camera(R"(, "filter": {"type": "tent", "radius": 2})").camera.filter_radius ==
              2.0);
        const Scene g = with_camera(R"(, "filter": {"type": "gaussian"})");
        CHECK(g.camera.filter == FilterKind::Gaussian);
        CHECK(g.camera.filter_stddev == 0.5);
        CHECK(analyse_features(g).gaussian_filter);
        const WpCamera c = flatten_scene(g).camera;
        CHECK(c.filter == WP_FILTER_GAUSSIAN);
        CHECK(c.filter_radius == 2.0f); // 4 standard deviations
        CHECK(c.filter_bias == Approx(std::exp(-8.0)).epsilon(1e-6));
        CHECK(with_camera(R"(, "filter": {"type": "gaussian", "stddev": 0.3})")
                  .camera.filter_stddev == 0.3);
    }
}
