// Building small scenes in code for tests, without going through JSON.
#pragma once

#include <string>

#include "scene/scene.hpp"

namespace wp::test {

inline std::uint32_t add_material(Scene& scene, MaterialKind kind, glm::dvec3 reflectance,
                                  glm::dvec3 emission = glm::dvec3(0.0)) {
    Material m;
    m.name = "material" + std::to_string(scene.materials.size());
    m.kind = kind;
    m.reflectance = reflectance;
    m.emission = emission;
    scene.materials.push_back(m);
    return static_cast<std::uint32_t>(scene.materials.size() - 1);
}

// Two triangles (a, b, c) and (a, c, d); the front face follows the winding.
inline void add_quad(Scene& scene, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 d,
                     std::uint32_t material) {
    scene.triangles.push_back({{a, b, c}, material});
    scene.triangles.push_back({{a, c, d}, material});
}

// The six faces of the axis-aligned box [lo, hi], front faces inward.
inline void add_box_inward(Scene& scene, glm::dvec3 lo, glm::dvec3 hi, std::uint32_t material) {
    auto p = [&](int x, int y, int z) {
        return glm::dvec3(x ? hi.x : lo.x, y ? hi.y : lo.y, z ? hi.z : lo.z);
    };
    add_quad(scene, p(0, 0, 0), p(1, 0, 0), p(1, 1, 0), p(0, 1, 0), material); // floor, +z
    add_quad(scene, p(0, 0, 1), p(0, 1, 1), p(1, 1, 1), p(1, 0, 1), material); // ceiling, -z
    add_quad(scene, p(0, 0, 0), p(0, 1, 0), p(0, 1, 1), p(0, 0, 1), material); // x = lo, +x
    add_quad(scene, p(1, 0, 0), p(1, 0, 1), p(1, 1, 1), p(1, 1, 0), material); // x = hi, -x
    add_quad(scene, p(0, 0, 0), p(0, 0, 1), p(1, 0, 1), p(1, 0, 0), material); // y = lo, +y
    add_quad(scene, p(0, 1, 0), p(1, 1, 0), p(1, 1, 1), p(0, 1, 1), material); // y = hi, -y
}

inline Camera make_camera(glm::dvec3 eye, glm::dvec3 look_at, glm::dvec3 up, double fov, int width,
                          int height) {
    Camera c;
    c.eye = eye;
    c.look_at = look_at;
    c.up = up;
    c.vertical_fov_degrees = fov;
    c.width = width;
    c.height = height;
    return c;
}

} // namespace wp::test
