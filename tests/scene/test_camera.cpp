// The camera's keys in scene files: fov_axis (Mitsuba's conventions, against
// the half-extents of the image plane they define); the thin lens's and the
// filter's keys in tests/render/test_camera.cpp, with what flatten_scene makes
// of them.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/camera.hpp"
#include "scene/load.hpp"
#include "support/scene_json.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;
double radians(double degrees) {
    return degrees * kPi / 180.0;
}

wp::Scene with_camera(const std::string& extra, const std::string& resolution = "[8, 8]",
                      double fov = 90) {
    return wp::parse_scene(
        wp::test::scene_json(
            R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": )" +
            std::to_string(fov) + R"(, "resolution": )" + resolution + extra + "}"),
        "test.json");
}

} // namespace

TEST_CASE("camera: fov_axis gives the full angle along its axis", "[scene][camera]") {
    // The reference: the image plane at unit distance has half-height
    // h = tan(vertical / 2) and half-width h * aspect; the angle along an
    // axis is twice the arctangent of its half-extent (the diagonal's is
    // their hypotenuse). Not the conversion's formulas: its inverse.
    const std::vector<std::pair<int, int>> sizes{
        {640, 480}, {480, 640}, {8, 8}, {1, 16384}, {16384, 3}};
    const std::vector<double> fovs{1e-4, 1.0, 39.3076, 90.0, 150.0, 179.99};
    double worst = 0.0;
    for (const auto& [w, h] : sizes)
        for (double fov : fovs) {
            const double aspect = double(w) / double(h);
            for (wp::FovAxis axis : {wp::FovAxis::X, wp::FovAxis::Y, wp::FovAxis::Diagonal,
                                     wp::FovAxis::Smaller, wp::FovAxis::Larger}) {
                INFO(w << "x" << h << ", fov " << fov << " along " << wp::fov_axis_name(axis));
                const double vertical = wp::vertical_fov_degrees(fov, axis, w, h);
                REQUIRE(vertical > 0.0);
                REQUIRE(vertical < 180.0);
                const double half_h = std::tan(0.5 * radians(vertical));
                const double half_w = half_h * aspect;
                double half_axis = 0.0;
                switch (axis) {
                case wp::FovAxis::X:
                    half_axis = half_w;
                    break;
                case wp::FovAxis::Y:
                    half_axis = half_h;
                    CHECK(vertical == fov); // the default keeps the value exactly
                    break;
                case wp::FovAxis::Diagonal:
                    half_axis = std::hypot(half_w, half_h);
                    break;
                case wp::FovAxis::Smaller: // a square's is x (Mitsuba: aspect > 1 means y)
                    half_axis = aspect > 1.0 ? half_h : half_w;
                    break;
                case wp::FovAxis::Larger:
                    half_axis = aspect > 1.0 ? half_w : half_h;
                    break;
                }
                const double along = 2.0 * std::atan(half_axis) * 180.0 / kPi;
                const double error = std::fabs(along - fov) / fov;
                worst = std::max(worst, error);
                // The check goes through tan of the vertical angle, which
                // for a 1 x 16384 image is within 0.007 degrees of 180:
                // there tan amplifies double's rounding 10^4 times.
                CHECK(error < 1e-10);
            }
        }
    INFO("largest relative error " << worst);
    CHECK(worst < 1e-10);
}

TEST_CASE("camera: the loader reads fov_axis, the lens and the filter", "[scene][camera]") {
    CHECK(with_camera("", "[640, 480]", 60).camera.vertical_fov_degrees == 60.0);
    CHECK(with_camera(R"(, "fov_axis": "x")", "[640, 480]", 60).camera.vertical_fov_degrees ==
          Approx(wp::vertical_fov_degrees(60, wp::FovAxis::X, 640, 480)).epsilon(1e-15));
    const wp::Scene s = with_camera(
        R"(, "aperture_radius": 0.25, "focus_distance": 7.5, "filter": {"type": "tent", "radius": 2})");
    CHECK(s.camera.aperture_radius == 0.25);
    CHECK(s.camera.focus_distance == 7.5);
    CHECK(s.camera.filter == wp::FilterKind::Tent);
    CHECK(s.camera.filter_radius == 2.0);
    CHECK(with_camera(R"(, "filter": "gaussian")").camera.filter == wp::FilterKind::Gaussian);
    CHECK(with_camera("").camera.aperture_radius == 0.0);
    CHECK(with_camera("").camera.filter == wp::FilterKind::Box);
}
