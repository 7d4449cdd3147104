// scenes/cornell-box.json against the Cornell University Program of Computer
// Graphics' published measurements (https://www.graphics.cornell.edu/online/box/data.html):
// the camera, the light's corners, the room's extent, the two blocks, and that
// every surface faces the way light must leave or meet it.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"

namespace {

const std::string kCornellBox = WAVEPATH_SOURCE_DIR "/scenes/cornell-box.json";

glm::dvec3 normal_of(const wp::Triangle& t) {
    return glm::cross(t.v[1] - t.v[0], t.v[2] - t.v[0]);
}
// True when v points along the unit vector `axis` (to rounding).
bool points_along(const glm::dvec3& v, const glm::dvec3& axis) {
    return glm::dot(glm::normalize(v), axis) > 1.0 - 1e-12;
}
double area_of(const wp::Triangle& t) {
    return 0.5 * glm::length(normal_of(t));
}
glm::dvec3 centroid_of(const wp::Triangle& t) {
    return (t.v[0] + t.v[1] + t.v[2]) / 3.0;
}
bool all_corners(const wp::Triangle& t, bool (*test)(const glm::dvec3&)) {
    return std::all_of(t.v.begin(), t.v.end(), test);
}

std::uint32_t material_index(const wp::Scene& s, const std::string& name) {
    for (std::size_t i = 0; i < s.materials.size(); ++i)
        if (s.materials[i].name == name)
            return static_cast<std::uint32_t>(i);
    FAIL("no material " << name);
    return 0;
}

// The blocks' footprints from the published corners: the short block lies in
// x 82..290, z 65..272 and is 165 high; the tall one in x 265..472,
// z 247..456 and is 330 high. Floor triangles (all corners at y = 0) are not
// part of either.
bool in_short_block(const glm::dvec3& p) {
    return p.x >= 82 && p.x <= 290 && p.z >= 65 && p.z <= 272 && p.y <= 165;
}
bool in_tall_block(const glm::dvec3& p) {
    return p.x >= 265 && p.x <= 472 && p.z >= 247 && p.z <= 456 && p.y <= 330;
}
bool on_floor(const glm::dvec3& p) {
    return p.y == 0.0;
}

} // namespace

TEST_CASE("scenes: the Cornell box camera is the published one", "[scene][scenes][cornell]") {
    const wp::Camera c = wp::load_scene(kCornellBox).camera;
    CHECK(c.eye == glm::dvec3(278, 273, -800));
    CHECK(points_along(c.look_at - c.eye, glm::dvec3(0, 0, 1)));
    CHECK(c.up == glm::dvec3(0, 1, 0));
    // A 25 mm x 25 mm film at 35 mm focal length.
    const double fov = 2.0 * std::atan(0.0125 / 0.035) * 180.0 / 3.14159265358979323846;
    CHECK(c.vertical_fov_degrees == Approx(fov).epsilon(1e-12));
    CHECK(c.width == c.height); // square film
}

TEST_CASE("scenes: the Cornell box light is the published rectangle, facing down",
          "[scene][scenes][cornell]") {
    const wp::Scene s = wp::load_scene(kCornellBox);
    CHECK(s.warnings.empty());
    std::vector<wp::Triangle> lights;
    for (const wp::Triangle& t : s.triangles)
        if (s.materials[t.material].is_emissive())
            lights.push_back(t);
    REQUIRE(lights.size() == 2);
    std::vector<glm::dvec3> corners;
    double area = 0.0;
    for (const wp::Triangle& t : lights) {
        // Emission leaves the front face only, so it must face the floor.
        CHECK(points_along(normal_of(t), glm::dvec3(0, -1, 0)));
        area += area_of(t);
        corners.insert(corners.end(), t.v.begin(), t.v.end());
    }
    CHECK(area == Approx(130.0 * 105.0));
    for (const glm::dvec3 published : {glm::dvec3(343, 548.8, 227), glm::dvec3(343, 548.8, 332),
                                       glm::dvec3(213, 548.8, 332), glm::dvec3(213, 548.8, 227)})
        CHECK(std::count(corners.begin(), corners.end(), published) >= 1);
    // The ceiling around it faces down too and, with the light, covers the
    // published ceiling (556 x 559.2) exactly once.
    double ceiling = 0.0;
    for (const wp::Triangle& t : s.triangles)
        if (all_corners(t, [](const glm::dvec3& p) { return p.y == 548.8; })) {
            CHECK(points_along(normal_of(t), glm::dvec3(0, -1, 0)));
            ceiling += area_of(t);
        }
    CHECK(ceiling == Approx(556.0 * 559.2));
}

TEST_CASE("scenes: the Cornell box walls face into the room, the blocks outwards",
          "[scene][scenes][cornell]") {
    const wp::Scene s = wp::load_scene(kCornellBox);
    REQUIRE(s.triangles.size() == 38); // 7 room surfaces (ceiling in 4) + light + 2 x 5 block faces
    CHECK(s.spheres.empty());
    const glm::dvec3 room_centre(278, 274.4, 279.6);
    // Each block's centre: the mean of its published top corners, halfway up.
    const glm::dvec3 short_centre(185.5, 82.5, 169), tall_centre(368.5, 165, 351.25);
    std::size_t short_faces = 0, tall_faces = 0, room_faces = 0;
    double short_height = 0.0, tall_height = 0.0;
    for (const wp::Triangle& t : s.triangles) {
        const glm::dvec3 n = normal_of(t), c = centroid_of(t);
        INFO("triangle at " << c.x << " " << c.y << " " << c.z);
        if (!all_corners(t, on_floor) && all_corners(t, in_short_block)) {
            ++short_faces;
            CHECK(glm::dot(n, c - short_centre) > 0.0);
            for (const glm::dvec3& p : t.v)
                short_height = std::max(short_height, p.y);
        } else if (!all_corners(t, on_floor) && all_corners(t, in_tall_block)) {
            ++tall_faces;
            CHECK(glm::dot(n, c - tall_centre) > 0.0);
            for (const glm::dvec3& p : t.v)
                tall_height = std::max(tall_height, p.y);
        } else {
            ++room_faces;
            CHECK(glm::dot(n, room_centre - c) > 0.0);
            for (const glm::dvec3& p : t.v) {
                CHECK(p.x >= 0.0);
                CHECK(p.x <= 556.0);
                CHECK(p.y >= 0.0);
                CHECK(p.y <= 548.8);
                CHECK(p.z >= 0.0);
                CHECK(p.z <= 559.2);
            }
        }
    }
    CHECK(short_faces == 10);
    CHECK(tall_faces == 10);
    CHECK(room_faces == 18);
    CHECK(short_height == 165.0);
    CHECK(tall_height == 330.0);
}

TEST_CASE("scenes: the Cornell box has the red wall on the image's left, green on its right",
          "[scene][scenes][cornell]") {
    const wp::Scene s = wp::load_scene(kCornellBox);
    const wp::Camera& c = s.camera;
    // docs/scene-format.md: the image's right is cross(view direction, up).
    const glm::dvec3 right = glm::cross(c.look_at - c.eye, c.up);
    const std::uint32_t red = material_index(s, "red"), green = material_index(s, "green");
    std::size_t seen = 0;
    for (const wp::Triangle& t : s.triangles) {
        const double side = glm::dot(right, centroid_of(t) - c.eye);
        if (t.material == red) {
            CHECK(side < 0.0);
            ++seen;
        } else if (t.material == green) {
            CHECK(side > 0.0);
            ++seen;
        }
    }
    CHECK(seen == 4);
}
