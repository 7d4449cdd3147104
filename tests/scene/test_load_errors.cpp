// Every validation rule of the loader: each bad input gives one SceneError whose
// message names the source and the faulty field's JSON pointer.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "scene/load.hpp"
#include "scene/validate.hpp"
#include "support/scene_json.hpp"

namespace {

const std::string kCamera = wp::test::kSceneCamera;
const std::string kMaterials = wp::test::kSceneMaterials;
const std::string kShapes = wp::test::kSceneShapes;

std::string scene(const std::string& camera = kCamera, const std::string& materials = kMaterials,
                  const std::string& shapes = kShapes) {
    return wp::test::scene_json(camera, materials, shapes);
}
std::string with_camera(const std::string& c) {
    return scene(c);
}
std::string with_materials(const std::string& m) {
    return scene(kCamera, m);
}
std::string with_shapes(const std::string& s) {
    return scene(kCamera, kMaterials, s);
}
std::string with_shape(const std::string& s) {
    return with_shapes("[" + s + "]");
}

// The base scene with an "emitters" array.
std::string with_emitters(const std::string& e) {
    std::string json = scene();
    json.pop_back(); // the closing brace
    return json + R"(, "emitters": )" + e + "}";
}

std::string error_of(const std::string& json, const std::string& source = "test.json") {
    try {
        (void)wp::parse_scene(json, source);
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

struct Case {
    const char* what;
    std::string json;
    std::string pointer; // must appear as "test.json: <pointer>: "
    std::string fragment;
};

} // namespace

TEST_CASE("loader: the base scene of the error table is valid", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(scene(), "test.json");
    CHECK(s.triangles.size() == 1);
    CHECK(s.materials.size() == 3);
}

TEST_CASE("loader: every validation error names its field", "[scene][load][errors]") {
    const std::string tri = R"("type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]])";
    const std::string sph = R"("type": "sphere", "center": [0, 0, 0])";
    const std::vector<Case> cases{
        // document structure
        {"root not an object", "[1, 2]", "(root)", "expected a scene object"},
        {"missing camera", R"({"materials": )" + kMaterials + R"(, "shapes": )" + kShapes + "}",
         "/camera", "missing required field"},
        {"missing materials", R"({"camera": )" + kCamera + R"(, "shapes": )" + kShapes + "}",
         "/materials", "missing required field"},
        {"missing shapes", R"({"camera": )" + kCamera + R"(, "materials": )" + kMaterials + "}",
         "/shapes", "missing required field"},
        {"unknown top-level key",
         R"({"camrea": {}, "camera": )" + kCamera + R"(, "materials": )" + kMaterials +
             R"(, "shapes": )" + kShapes + "}",
         "/camrea", "unknown key 'camrea'"},
        {"description not a string",
         R"({"description": 5, "camera": )" + kCamera + R"(, "materials": )" + kMaterials +
             R"(, "shapes": )" + kShapes + "}",
         "/description", "expected a string"},
        {"no shapes", with_shapes("[]"), "/shapes", "no shapes"},
        {"shapes not an array", with_shapes("{}"), "/shapes", "expected an array"},
        {"no materials", with_materials("{}"), "/materials", "at least one material"},
        {"materials not an object", with_materials("[]"), "/materials", "expected an object"},

        // camera
        {"camera not an object", with_camera("[]"), "/camera", "expected an object"},
        {"unknown camera key (typo)",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fvo": 90, "resolution": [8, 8]})"),
         "/camera/fvo", "unknown key 'fvo'"},
        {"missing eye",
         with_camera(R"({"look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye", "missing required field"},
        {"eye with 2 numbers",
         with_camera(
             R"({"eye": [-1, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye", "expected an array of 3 numbers"},
        {"eye not an array",
         with_camera(
             R"({"eye": 3, "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye", "expected an array of 3 numbers, got 3"},
        {"eye with a string",
         with_camera(
             R"({"eye": ["a", 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye/0", "expected a number"},
        {"eye beyond float32",
         with_camera(
             R"({"eye": [-1, 1e31, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye/1", "1e30"},
        {"eye overflowing to infinity",
         with_camera(
             R"({"eye": [-1, 1e999, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/eye/1", "out of range"},
        {"look_at and direction",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "direction": [1, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/direction", "not both"},
        {"neither look_at nor direction",
         with_camera(R"({"eye": [-1, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/look_at", "missing"},
        {"eye equal to look_at",
         with_camera(
             R"({"eye": [1, 2, 3], "look_at": [1, 2, 3], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/look_at", "must differ from eye"},
        {"zero direction",
         with_camera(
             R"({"eye": [1, 2, 3], "direction": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/direction", "zero vector"},
        {"up parallel to the view direction",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [-2, 0, 0], "fov": 90, "resolution": [8, 8]})"),
         "/camera/up", "parallel to the view direction"},
        {"up almost parallel",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [1, 1e-9, 0], "fov": 90, "resolution": [8, 8]})"),
         "/camera/up", "parallel"},
        {"up parallel to direction",
         with_camera(
             R"({"eye": [-1, 0, 0], "direction": [0, 0, 3], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8]})"),
         "/camera/up", "parallel"},
        {"zero up",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 0], "fov": 90, "resolution": [8, 8]})"),
         "/camera/up", "zero vector"},
        {"missing up",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "fov": 90, "resolution": [8, 8]})"),
         "/camera/up", "missing"},
        {"fov zero",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 0, "resolution": [8, 8]})"),
         "/camera/fov", "between 0 and 180"},
        {"fov 180",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 180, "resolution": [8, 8]})"),
         "/camera/fov", "got 180"},
        {"fov negative",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": -30, "resolution": [8, 8]})"),
         "/camera/fov", "got -30"},
        {"fov a string",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": "90", "resolution": [8, 8]})"),
         "/camera/fov", "expected a number, got \"90\""},
        {"missing fov",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "resolution": [8, 8]})"),
         "/camera/fov", "missing"},
        {"zero width",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [0, 8]})"),
         "/camera/resolution/0", "positive"},
        {"negative height",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, -4]})"),
         "/camera/resolution/1", "got -4"},
        {"non-integer width",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8.5, 8]})"),
         "/camera/resolution/0", "expected an integer, got 8.5"},
        {"width over the cap",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [16385, 8]})"),
         "/camera/resolution/0", "at most 16384"},
        {"huge height",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 1e300]})"),
         "/camera/resolution/1", "at most 16384"},
        {"resolution with one number",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8]})"),
         "/camera/resolution", "expected an array of 2 integers"},
        {"resolution a string",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": "8x8"})"),
         "/camera/resolution", "expected an array of 2 integers"},

        // camera: fov_axis, thin lens, filter
        {"unknown fov_axis",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "fov_axis": "z"})"),
         "/camera/fov_axis", "unknown fov_axis 'z' (expected x, y, diagonal, smaller, larger)"},
        {"fov_axis not a string",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "fov_axis": 1})"),
         "/camera/fov_axis", "expected a string"},
        {"fov along x of 180",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 180, "fov_axis": "x", "resolution": [8, 8]})"),
         "/camera/fov", "field of view along fov_axis 'x' must be between 0 and 180"},
        {"negative aperture",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": -0.1, "focus_distance": 1})"),
         "/camera/aperture_radius", "must not be negative (0 is a pinhole), got -0.1"},
        {"huge aperture",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": 1e31, "focus_distance": 1})"),
         "/camera/aperture_radius", "magnitude too large"},
        {"negative focus distance",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": 0.1, "focus_distance": -2})"),
         "/camera/focus_distance", "must be positive, got -2"},
        {"zero focus distance",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": 0.1, "focus_distance": 0})"),
         "/camera/focus_distance", "must be positive, got 0"},
        {"focus distance missing with a lens",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": 0.1})"),
         "/camera/focus_distance", "missing required field 'focus_distance'"},
        {"focus distance a string",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "aperture_radius": 0.1, "focus_distance": "far"})"),
         "/camera/focus_distance", "expected a number"},
        {"unknown filter",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": "mitchell"})"),
         "/camera/filter", "unknown filter 'mitchell' (expected box, tent, gaussian)"},
        {"unknown filter type",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"type": "lanczos"}})"),
         "/camera/filter/type", "unknown filter 'lanczos'"},
        {"filter without a type",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"radius": 2}})"),
         "/camera/filter/type", "missing required field"},
        {"a size the filter does not have",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"type": "tent", "stddev": 2}})"),
         "/camera/filter/stddev", "unknown key 'stddev'"},
        {"the box has no size",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"type": "box", "radius": 2}})"),
         "/camera/filter/radius", "unknown key 'radius'"},
        {"zero tent radius",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"type": "tent", "radius": 0}})"),
         "/camera/filter/radius", "must be positive and at most 64 pixels, got 0"},
        {"huge gaussian",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": {"type": "gaussian", "stddev": 100}})"),
         "/camera/filter/stddev", "at most 64 pixels, got 100"},
        {"filter a number",
         with_camera(
             R"({"eye": [-1, 0, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 90, "resolution": [8, 8], "filter": 3})"),
         "/camera/filter", "expected a string"},

        // materials
        {"material not an object", with_materials(R"({"white": [0.7, 0.7, 0.7]})"),
         "/materials/white", "expected a material object"},
        {"unknown material type",
         with_materials(R"({"white": {"type": "glass", "reflectance": [1, 1, 1]}})"),
         "/materials/white/type", "unknown material type 'glass'"},
        {"missing material type", with_materials(R"({"white": {"reflectance": [1, 1, 1]}})"),
         "/materials/white/type", "missing"},
        {"missing reflectance", with_materials(R"({"white": {"type": "diffuse"}})"),
         "/materials/white/reflectance", "missing"},
        {"reflectance above 1",
         with_materials(R"({"white": {"type": "diffuse", "reflectance": [1.5, 0.5, 0.5]}})"),
         "/materials/white/reflectance/0", "[0, 1], got 1.5"},
        {"negative reflectance",
         with_materials(R"({"white": {"type": "mirror", "reflectance": [1, 1, -0.1]}})"),
         "/materials/white/reflectance/2", "[0, 1], got -0.1"},
        {"negative emission",
         with_materials(
             R"({"white": {"type": "diffuse", "reflectance": [0.5, 0.5, 0.5], "emission": [1, -1, 1]}})"),
         "/materials/white/emission/1", "must not be negative"},
        {"radiance over 1e30",
         with_materials(R"({"white": {"type": "emitter", "radiance": [2e30, 1, 1]}})"),
         "/materials/white/radiance/0", "at most 1e30"},
        {"negative radiance",
         with_materials(R"({"white": {"type": "emitter", "radiance": [1, 1, -5]}})"),
         "/materials/white/radiance/2", "must not be negative"},
        {"infinite radiance",
         with_materials(R"({"white": {"type": "emitter", "radiance": [1, -1e999, 1]}})"),
         "/materials/white/radiance/1", "out of range"},
        {"missing radiance", with_materials(R"({"white": {"type": "emitter"}})"),
         "/materials/white/radiance", "missing"},
        {"emitter with a reflectance",
         with_materials(
             R"({"white": {"type": "emitter", "radiance": [1, 1, 1], "reflectance": [1, 1, 1]}})"),
         "/materials/white/reflectance", "unknown key 'reflectance'"},
        {"misspelt key",
         with_materials(R"({"white": {"type": "diffuse", "reflectence": [1, 1, 1]}})"),
         "/materials/white/reflectence", "unknown key"},
        {"duplicate material name",
         with_materials(
             R"({"white": {"type": "diffuse", "reflectance": [1, 1, 1]}, "white": {"type": "mirror", "reflectance": [1, 1, 1]}})"),
         "/materials/white", "duplicate key 'white'"},
        // conductors (Mitsuba's conductor and roughconductor parameters)
        {"unknown conductor parameter",
         with_materials(R"({"white": {"type": "roughconductor", "roughness": 0.1}})"),
         "/materials/white/roughness", "unknown key 'roughness'"},
        {"unknown metal", with_materials(R"({"white": {"type": "conductor", "material": "Xx"}})"),
         "/materials/white/material", "unknown metal 'Xx'"},
        {"named metal and eta",
         with_materials(R"({"white": {"type": "conductor", "material": "Au", "eta": [1, 1, 1]}})"),
         "/materials/white/material", "not both"},
        {"alpha zero", with_materials(R"({"white": {"type": "roughconductor", "alpha": 0}})"),
         "/materials/white/alpha", "must be in (0, 4], got 0"},
        {"alpha negative",
         with_materials(R"({"white": {"type": "roughconductor", "alpha_u": 0.1, "alpha_v": -1}})"),
         "/materials/white/alpha_v", "must be in (0, 4]"},
        {"alpha not finite",
         with_materials(R"({"white": {"type": "roughconductor", "alpha": 1e999}})"),
         "/materials/white/alpha", "out of range"},
        {"alpha_u without alpha_v",
         with_materials(R"({"white": {"type": "roughconductor", "alpha_u": 0.1}})"),
         "/materials/white/alpha_v", "go together"},
        {"alpha and alpha_u",
         with_materials(
             R"({"white": {"type": "roughconductor", "alpha": 0.1, "alpha_u": 0.1, "alpha_v": 0.2}})"),
         "/materials/white/alpha", "not both"},
        {"unknown distribution",
         with_materials(R"({"white": {"type": "roughconductor", "distribution": "phong"}})"),
         "/materials/white/distribution", "unknown distribution 'phong'"},
        {"negative eta",
         with_materials(R"({"white": {"type": "conductor", "eta": [1, -1, 1], "k": [1, 1, 1]}})"),
         "/materials/white/eta/1", "must not be negative"},
        {"k not finite",
         with_materials(
             R"({"white": {"type": "conductor", "eta": [1, 1, 1], "k": [1, 1, 1e999]}})"),
         "/materials/white/k/2", "out of range"},
        {"specular_reflectance above 1",
         with_materials(
             R"({"white": {"type": "roughconductor", "specular_reflectance": [1, 2, 1]}})"),
         "/materials/white/specular_reflectance/1", "[0, 1], got 2"},
        // dielectrics (Mitsuba's dielectric and thindielectric parameters)
        {"unknown dielectric parameter",
         with_materials(R"({"white": {"type": "dielectric", "alpha": 0.1}})"),
         "/materials/white/alpha", "unknown key 'alpha'"},
        {"unknown index of refraction",
         with_materials(R"({"white": {"type": "dielectric", "int_ior": "glass"}})"),
         "/materials/white/int_ior", "unknown index of refraction 'glass'"},
        {"index of refraction zero",
         with_materials(R"({"white": {"type": "thindielectric", "int_ior": 0}})"),
         "/materials/white/int_ior", "must be in (0, 1e4], got 0"},
        {"negative exterior index",
         with_materials(R"({"white": {"type": "dielectric", "ext_ior": -1.5}})"),
         "/materials/white/ext_ior", "must be in (0, 1e4]"},
        {"index of refraction not finite",
         with_materials(R"({"white": {"type": "dielectric", "int_ior": 1e999}})"),
         "/materials/white/int_ior", "out of range"},
        {"index of refraction not a number or name",
         with_materials(R"({"white": {"type": "dielectric", "int_ior": [1.5]}})"),
         "/materials/white/int_ior", "expected a number"},
        {"plastic nonlinear not a boolean",
         with_materials(R"({"white": {"type": "plastic", "nonlinear": 1}})"),
         "/materials/white/nonlinear", "expected true or false"},
        {"plastic with a dielectric's key",
         with_materials(R"({"white": {"type": "plastic", "specular_transmittance": [1, 1, 1]}})"),
         "/materials/white/specular_transmittance", "unknown key"},
        {"plastic diffuse_reflectance above 1",
         with_materials(R"({"white": {"type": "plastic", "diffuse_reflectance": [2, 1, 1]}})"),
         "/materials/white/diffuse_reflectance/0", "[0, 1], got 2"},
        // roughplastic (Mitsuba's roughplastic parameters)
        {"roughplastic alpha zero",
         with_materials(R"({"white": {"type": "roughplastic", "alpha": 0}})"),
         "/materials/white/alpha", "must be in (0, 4], got 0"},
        {"roughplastic alpha negative",
         with_materials(R"({"white": {"type": "roughplastic", "alpha": -0.2}})"),
         "/materials/white/alpha", "must be in (0, 4], got -0.2"},
        {"roughplastic alpha not finite",
         with_materials(R"({"white": {"type": "roughplastic", "alpha": 1e999}})"),
         "/materials/white/alpha", "out of range"},
        {"roughplastic anisotropic",
         with_materials(R"({"white": {"type": "roughplastic", "alpha_u": 0.1, "alpha_v": 0.2}})"),
         "/materials/white/alpha_u", "isotropic"},
        {"roughplastic index of refraction zero",
         with_materials(R"({"white": {"type": "roughplastic", "int_ior": 0}})"),
         "/materials/white/int_ior", "must be in (0, 1e4], got 0"},
        {"roughplastic negative exterior index",
         with_materials(R"({"white": {"type": "roughplastic", "ext_ior": -1}})"),
         "/materials/white/ext_ior", "must be in (0, 1e4]"},
        {"roughplastic index of refraction not finite",
         with_materials(R"({"white": {"type": "roughplastic", "int_ior": -1e999}})"),
         "/materials/white/int_ior", "out of range"},
        {"roughplastic unknown index of refraction",
         with_materials(R"({"white": {"type": "roughplastic", "int_ior": "glass"}})"),
         "/materials/white/int_ior", "unknown index of refraction 'glass'"},
        {"roughplastic diffuse_reflectance not finite",
         with_materials(
             R"({"white": {"type": "roughplastic", "diffuse_reflectance": [0.5, 1e999, 0.5]}})"),
         "/materials/white/diffuse_reflectance/1", "out of range"},
        {"roughplastic specular_reflectance above 1",
         with_materials(
             R"({"white": {"type": "roughplastic", "specular_reflectance": [1, 1, 1.5]}})"),
         "/materials/white/specular_reflectance/2", "[0, 1], got 1.5"},
        {"roughplastic unknown distribution",
         with_materials(R"({"white": {"type": "roughplastic", "distribution": "phong"}})"),
         "/materials/white/distribution", "unknown distribution 'phong'"},
        {"roughplastic nonlinear not a boolean",
         with_materials(R"({"white": {"type": "roughplastic", "nonlinear": "yes"}})"),
         "/materials/white/nonlinear", "expected true or false"},
        {"twosided is no material of its own", with_materials(R"({"white": {"type": "twosided"}})"),
         "/materials/white/type", "two-sided already"},
        {"specular_transmittance above 1",
         with_materials(
             R"({"white": {"type": "dielectric", "specular_transmittance": [1, 1, 1.5]}})"),
         "/materials/white/specular_transmittance/2", "[0, 1], got 1.5"},
        {"material name with a slash is escaped",
         with_materials(R"({"a/b~c": {"type": "velvet"}})"), "/materials/a~1b~0c/type",
         "unknown material type"},

        // shapes
        {"shape not an object", with_shapes("[3]"), "/shapes/0", "expected a shape object"},
        {"missing shape type", with_shape(R"({"vertices": [], "material": "white"})"),
         "/shapes/0/type", "missing"},
        {"unknown shape type", with_shape(R"({"type": "cube", "material": "white"})"),
         "/shapes/0/type", "unknown shape type 'cube'"},
        {"unknown shape key", with_shape("{" + tri + R"(, "material": "white", "colour": "red"})"),
         "/shapes/0/colour", "unknown key 'colour'"},
        {"key of another shape type",
         with_shape("{" + tri + R"(, "material": "white", "radius": 1})"), "/shapes/0/radius",
         "unknown key 'radius'"},
        {"name not a string", with_shape("{" + tri + R"(, "material": "white", "name": 7})"),
         "/shapes/0/name", "expected a string"},
        {"missing material", with_shape("{" + tri + "}"), "/shapes/0/material", "missing"},
        {"unknown material", with_shape("{" + tri + R"(, "material": "whte"})"),
         "/shapes/0/material", "unknown material 'whte'"},
        {"material not a string", with_shape("{" + tri + R"(, "material": 0})"),
         "/shapes/0/material", "expected a string"},
        {"error in a later shape",
         with_shapes("[{" + tri + R"(, "material": "white"}, {)" + tri +
                     R"(, "material": "nope"}])"),
         "/shapes/1/material", "unknown material 'nope'"},
        {"triangle with 4 vertices",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices", "exactly 3 points"},
        {"vertex with 2 numbers",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0], [0, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices/1", "expected an array of 3 numbers"},
        {"vertex coordinate null",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, null, 0]], "material": "white"})"),
         "/shapes/0/vertices/2/1", "expected a number, got null"},
        {"vertex coordinate beyond float32",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, -3e30]], "material": "white"})"),
         "/shapes/0/vertices/2/2", "1e30"},
        {"vertex coordinate infinite",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 1e400], [0, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices/1/2", "out of range"},
        {"NaN is not JSON",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, NaN, 0], [0, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices/1/1", "invalid JSON"},
        {"quad with 3 vertices",
         with_shape(
             R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices", "exactly 4 points"},
        {"quad not coplanar",
         with_shape(
             R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0.001]], "material": "white"})"),
         "/shapes/0/vertices", "not coplanar"},
        {"quad folded (bow tie)",
         with_shape(
             R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]], "material": "white"})"),
         "/shapes/0/vertices", "folded"},
        {"mesh index out of range",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 3]], "material": "white"})"),
         "/shapes/0/triangles/0/2", "out of range: the mesh has 3 vertices"},
        {"negative mesh index",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2], [-1, 1, 2]], "material": "white"})"),
         "/shapes/0/triangles/1/0", "out of range"},
        {"non-integer mesh index",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1.5, 2]], "material": "white"})"),
         "/shapes/0/triangles/0/1", "expected an integer"},
        {"mesh triangle with 4 indices",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2, 0]], "material": "white"})"),
         "/shapes/0/triangles/0", "expected an array of 3 vertex indices"},
        {"mesh without triangles",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "material": "white"})"),
         "/shapes/0/triangles", "missing"},
        {"mesh with no triangles",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [], "material": "white"})"),
         "/shapes/0/triangles", "at least one triangle"},
        {"mesh with no vertices",
         with_shape(
             R"({"type": "mesh", "vertices": [], "triangles": [[0, 0, 0]], "material": "white"})"),
         "/shapes/0/vertices", "at least one point"},
        {"mesh vertex bad",
         with_shape(
             R"({"type": "mesh", "vertices": [[0, 0, 0], [1, 0, true], [0, 1, 0]], "triangles": [[0, 1, 2]], "material": "white"})"),
         "/shapes/0/vertices/1/2", "expected a number, got true"},
        {"negative radius", with_shape("{" + sph + R"(, "radius": -1, "material": "white"})"),
         "/shapes/0/radius", "must be positive, got -1"},
        {"zero radius", with_shape("{" + sph + R"(, "radius": 0, "material": "white"})"),
         "/shapes/0/radius", "must be positive, got 0"},
        {"radius beyond float32",
         with_shape("{" + sph + R"(, "radius": 1e31, "material": "white"})"), "/shapes/0/radius",
         "1e30"},
        {"infinite radius", with_shape("{" + sph + R"(, "radius": 1e999, "material": "white"})"),
         "/shapes/0/radius", "out of range"},
        {"radius a string", with_shape("{" + sph + R"(, "radius": "2", "material": "white"})"),
         "/shapes/0/radius", "expected a number"},
        {"missing radius", with_shape("{" + sph + R"(, "material": "white"})"), "/shapes/0/radius",
         "missing"},
        {"missing center", with_shape(R"({"type": "sphere", "radius": 1, "material": "white"})"),
         "/shapes/0/center", "missing"},
        {"sphere center beyond float32",
         with_shape(
             R"({"type": "sphere", "center": [0, 0, 5e30], "radius": 1, "material": "white"})"),
         "/shapes/0/center/2", "1e30"},
        {"all shapes skipped",
         with_shape(
             R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], [2, 0, 0]], "material": "white"})"),
         "/shapes", "every shape was skipped"},
    };

    for (const Case& c : cases) {
        INFO(c.what);
        INFO(c.json);
        const std::string msg = error_of(c.json);
        INFO(msg);
        CHECK(msg.rfind("test.json", 0) == 0);
        CHECK(msg.find(c.pointer + ": ") != std::string::npos);
        CHECK(msg.find(c.fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
}

TEST_CASE("loader: every emitter error names its field", "[scene][load][errors]") {
    const std::string point = R"("type": "point", "position": [0, 0, 1])";
    const std::string spot = R"("type": "spot", "position": [0, 0, 1], "intensity": [1, 1, 1])";
    const std::string sun = R"("type": "directional", "direction": [0, 0, -1])";
    const std::vector<Case> cases{
        {"emitters not an array", with_emitters(R"({"type": "point"})"), "/emitters",
         "expected an array of emitters"},
        {"unknown emitter type", with_emitters(R"([{"type": "area"}])"), "/emitters/0/type",
         "unknown emitter type 'area' (expected point, spot, directional, constant or envmap)"},
        {"negative intensity", with_emitters("[{" + point + R"(, "intensity": [1, -2, 1]}])"),
         "/emitters/0/intensity/1", "must not be negative, got -2"},
        {"infinite intensity", with_emitters("[{" + point + R"(, "intensity": [1e999, 1, 1]}])"),
         "/emitters/0/intensity/0", "out of range"},
        {"intensity beyond float32",
         with_emitters("[{" + point + R"(, "intensity": [1e31, 1, 1]}])"),
         "/emitters/0/intensity/0", "at most 1e30"},
        {"point light without a position",
         with_emitters(R"([{"type": "point", "intensity": [1, 1, 1]}])"), "/emitters/0/position",
         "missing required field"},
        {"non-finite position",
         with_emitters(R"([{"type": "point", "position": [0, 1e999, 1], "intensity": [1, 1, 1]}])"),
         "/emitters/0/position/1", "out of range"},
        {"a key the point does not have",
         with_emitters("[{" + point + R"(, "intensity": [1, 1, 1], "cutoff_angle": 3}])"),
         "/emitters/0/cutoff_angle", "unknown key 'cutoff_angle'"},
        {"zero spot cutoff",
         with_emitters("[{" + spot + R"(, "direction": [0, 0, -1], "cutoff_angle": 0}])"),
         "/emitters/0/cutoff_angle",
         "must be in (0, 180] degrees (a zero cutoff lights nothing), got 0"},
        {"negative beam width",
         with_emitters("[{" + spot + R"(, "direction": [0, 0, -1], "beam_width": -1}])"),
         "/emitters/0/beam_width", "must be in [0, 180] degrees, got -1"},
        {"zero spot direction", with_emitters("[{" + spot + R"(, "direction": [0, 0, 0]}])"),
         "/emitters/0/direction", "must be a non-zero vector"},
        {"spot without a direction", with_emitters("[{" + spot + "}]"), "/emitters/0/direction",
         "missing required field"},
        {"negative irradiance", with_emitters("[{" + sun + R"(, "irradiance": [-1, 1, 1]}])"),
         "/emitters/0/irradiance/0", "must not be negative, got -1"},
        {"zero sun direction",
         with_emitters(
             R"([{"type": "directional", "direction": [0, 0, 0], "irradiance": [1, 1, 1]}])"),
         "/emitters/0/direction", "must be a non-zero vector"},
        {"negative sky radiance",
         with_emitters(R"([{"type": "constant", "radiance": [1, 1, -0.5]}])"),
         "/emitters/0/radiance/2", "must not be negative, got -0.5"},
        {"two skies", with_emitters(R"([{"type": "constant", "radiance": [1, 1, 1]},
                           {"type": "constant", "radiance": [1, 1, 1]}])"),
         "/emitters/1", "a second environment (constant or envmap emitter)"},
    };
    for (const Case& c : cases) {
        INFO(c.what);
        INFO(c.json);
        const std::string msg = error_of(c.json);
        INFO(msg);
        CHECK(msg.rfind("test.json", 0) == 0);
        CHECK(msg.find(c.pointer + ": ") != std::string::npos);
        CHECK(msg.find(c.fragment) != std::string::npos);
        CHECK(msg.find('\n') == std::string::npos);
    }
}

TEST_CASE("loader: emitters are read with Mitsuba's names and defaults", "[scene][load]") {
    const wp::Scene s = wp::parse_scene(
        with_emitters(R"([{"type": "spot", "position": [1, 2, 3], "direction": [0, 0, -2],
                           "intensity": [4, 5, 6], "cutoff_angle": 40},
                          {"type": "directional", "direction": [3, 0, 4], "irradiance": [1, 2, 3]},
                          {"type": "constant", "radiance": [0.5, 0.5, 0.5]}])"),
        "test.json");
    REQUIRE(s.emitters.size() == 3);
    CHECK(s.emitters[0].kind == wp::EmitterKind::Spot);
    CHECK(s.emitters[0].position == glm::dvec3(1, 2, 3));
    CHECK(s.emitters[0].direction == glm::dvec3(0, 0, -1)); // made unit
    CHECK(s.emitters[0].value == glm::dvec3(4, 5, 6));
    CHECK(s.emitters[0].cutoff_angle == 40.0);
    CHECK(s.emitters[0].beam_width == 30.0); // 3/4 of the cutoff, as in Mitsuba
    CHECK(s.emitters[1].direction == glm::dvec3(0.6, 0, 0.8));
    CHECK(s.emitters[2].kind == wp::EmitterKind::Constant);
    CHECK(s.emitters[2].value == glm::dvec3(0.5));
}

TEST_CASE("loader: the exact message format", "[scene][load][errors]") {
    const std::string shapes =
        R"([{"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
            {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
            {"type": "sphere", "center": [0, 0, 0], "radius": 1, "material": "white"},
            {"type": "sphere", "center": [0, 0, 0], "radius": -1, "material": "white"}])";
    CHECK(error_of(with_shapes(shapes), "hexroom.json") ==
          "hexroom.json: /shapes/3/radius: must be positive, got -1");
}

TEST_CASE("loader: syntax errors give the byte position, line and column", "[scene][load]") {
    SECTION("stray comma") {
        const std::string text = "{\n  \"camera\": {\n    \"eye\": [1, 2,, 3]\n  }\n}\n";
        const std::string msg = error_of(text);
        INFO(msg);
        CHECK(msg.rfind("test.json:3:", 0) == 0);
        CHECK(msg.find("(byte ") != std::string::npos);
        CHECK(msg.find("/camera/eye/2") != std::string::npos);
        CHECK(msg.find("invalid JSON") != std::string::npos);
    }
    SECTION("truncated") {
        const std::string msg = error_of(R"({"camera": {"eye": [1, 2)");
        INFO(msg);
        CHECK(msg.rfind("test.json:1:", 0) == 0);
        CHECK(msg.find("(byte ") != std::string::npos);
    }
    SECTION("empty text") {
        const std::string msg = error_of("");
        INFO(msg);
        CHECK(msg.find("(byte ") != std::string::npos);
    }
    SECTION("trailing garbage") {
        const std::string msg = error_of(scene() + " x");
        INFO(msg);
        CHECK(msg.find("(byte ") != std::string::npos);
    }
    SECTION("comments are not JSON") {
        const std::string msg = error_of("// hexroom\n" + scene());
        INFO(msg);
        CHECK(msg.rfind("test.json:1:", 0) == 0);
    }
}

TEST_CASE("loader: missing file", "[scene][load]") {
    const std::string path = std::string(WAVEPATH_SOURCE_DIR) + "/scenes/no-such-scene.json";
    try {
        (void)wp::load_scene(path);
        FAIL("no error");
    } catch (const wp::SceneError& e) {
        const std::string msg = e.what();
        INFO(msg);
        CHECK(msg.rfind("cannot open scene '" + path + "': ", 0) == 0);
        CHECK(msg.find("No such file or directory") != std::string::npos);
    }
}

TEST_CASE("loader: a directory is not a scene", "[scene][load]") {
    const std::string path = std::string(WAVEPATH_SOURCE_DIR) + "/scenes";
    CHECK_THROWS_AS(wp::load_scene(path), wp::SceneError);
}

TEST_CASE("validate_scene: rejects bad hand-built scenes", "[scene][validate]") {
    wp::Scene s = wp::parse_scene(scene(), "built");
    REQUIRE_NOTHROW(wp::validate_scene(s));
    const auto message = [](const wp::Scene& bad) {
        try {
            wp::validate_scene(bad);
        } catch (const wp::SceneError& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    {
        wp::Scene bad = s;
        wp::Triangle t = bad.triangles[0];
        t.v[1].y = std::nan("");
        bad.triangles.set(0, t);
        CHECK(message(bad).find("built: triangles[0].v[1][1]: must be finite") == 0);
    }
    {
        wp::Scene bad = s;
        wp::Triangle t = bad.triangles[0];
        t.material = 7;
        bad.triangles.set(0, t);
        CHECK(message(bad).find("triangles[0].material") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.camera.width = 0;
        CHECK(message(bad).find("camera.width") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.camera.up = glm::dvec3(1, 0, 0);
        CHECK(message(bad).find("camera.up") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        wp::Triangle t = bad.triangles[0];
        t.v[2] = t.v[1];
        bad.triangles.set(0, t);
        CHECK(message(bad).find("triangles[0]: zero-area") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.materials[0].reflectance.x = 2.0;
        CHECK(message(bad).find("materials[0] ('white').reflectance[0]") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.materials[0].kind = static_cast<wp::MaterialKind>(99);
        CHECK(message(bad).find("materials[0] ('white').kind: unknown material kind") !=
              std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.materials[0].kind = wp::MaterialKind::RoughPlastic;
        bad.materials[0].alpha_u = bad.materials[0].alpha_v = 0.3;
        REQUIRE_NOTHROW(wp::validate_scene(bad));
        bad.materials[0].alpha_v = 0.2;
        CHECK(message(bad).find("materials[0] ('white').alpha_v: must equal alpha_u") !=
              std::string::npos);
        bad.materials[0].alpha_u = bad.materials[0].alpha_v = std::nan("");
        CHECK(message(bad).find("materials[0] ('white').alpha_u") != std::string::npos);
        bad.materials[0].alpha_u = bad.materials[0].alpha_v = 0.3;
        bad.materials[0].int_ior = -1.0;
        CHECK(message(bad).find("materials[0] ('white').int_ior") != std::string::npos);
    }
    {
        wp::Scene bad = s;
        bad.materials[0].kind = wp::MaterialKind::RoughConductor;
        bad.materials[0].alpha_v = 0.0;
        CHECK(message(bad).find("materials[0] ('white').alpha_v: must be in (0, 4]") !=
              std::string::npos);
        bad.materials[0].alpha_v = 0.1;
        bad.materials[0].k.y = std::nan("");
        CHECK(message(bad).find("materials[0] ('white').k[1]: must be finite") !=
              std::string::npos);
    }
}
