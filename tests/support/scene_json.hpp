// Small JSON scenes for the loader's tests: one camera, the three materials
// every test can name ("white", "mirror", "light", numbered 0, 1, 2 in file
// order), and the shapes a test gives.
#pragma once

#include <string>

namespace wp::test {

inline const std::string kSceneCamera =
    R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})";
inline const std::string kSceneMaterials = R"({
    "white": {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
    "mirror": {"type": "mirror", "reflectance": [1, 1, 1]},
    "light": {"type": "emitter", "radiance": [100, 100, 100]}})";
// One diffuse triangle: the smallest valid scene.
inline const std::string kSceneShapes =
    R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "white"}])";

inline std::string scene_json(const std::string& camera = kSceneCamera,
                              const std::string& materials = kSceneMaterials,
                              const std::string& shapes = kSceneShapes) {
    return R"({"camera": )" + camera + R"(, "materials": )" + materials + R"(, "shapes": )" +
           shapes + "}";
}

} // namespace wp::test
