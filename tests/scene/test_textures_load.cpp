// Textures as the scene files give them: the JSON loader's and the Mitsuba
// XML reader's texture objects, texture coordinates from quads, inline
// meshes, OBJ and PLY files, and every bad input, each a one-line error that
// names the field (and the file).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "scene/load.hpp"
#include "scene/mitsuba/load_mitsuba.hpp"
#include "support/scene_json.hpp"
#include "support/temp_dir.hpp"

namespace {

const std::filesystem::path kTextures =
    std::filesystem::path(WAVEPATH_SOURCE_DIR) / "tests" / "data" / "mitsuba" / "textures";

// A scene in `folder` whose material "t" is a diffuse of `reflectance` on
// the shape `shape` (a quad by default).
std::string scene_with(const std::string& reflectance,
                       const std::string& shape =
                           R"({"type": "quad", "vertices": [[0, 0, 0], [1, 0, 0], [1, 1, 0], )"
                           R"([0, 1, 0]], "material": "t"})") {
    return wp::test::scene_json(wp::test::kSceneCamera,
                                R"({"t": {"type": "diffuse", "reflectance": )" + reflectance + "}}",
                                "[" + shape + "]");
}

wp::Scene parse_in(const std::filesystem::path& folder, const std::string& json) {
    return wp::parse_scene(json, (folder / "test.json").string());
}

std::string error_in(const std::filesystem::path& folder, const std::string& json) {
    try {
        (void)parse_in(folder, json);
    } catch (const wp::SceneError& e) {
        return e.what();
    }
    return "<no error>";
}

void write(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

} // namespace

TEST_CASE("loader: textures in a JSON scene", "[scene][load][textures]") {
    const wp::Scene s =
        parse_in(kTextures,
                 scene_with(R"({"type": "bitmap", "filename": "grid.png", "filter_type": "nearest",
                       "wrap_mode": "clamp", "to_uv": [{"translate": [0.5, 0, 0]},
                       {"scale": [2, 3, 1]}]})"));
    REQUIRE(s.textures.size() == 1);
    const wp::Texture& t = s.textures[0];
    CHECK(t.kind == wp::TextureKind::Bitmap);
    CHECK(t.filter == wp::TextureFilter::Nearest);
    CHECK(t.wrap == wp::TextureWrap::Clamp);
    REQUIRE(t.image);
    CHECK(t.image->width == 8);
    CHECK(t.image->height == 4);
    CHECK(t.image->encoding == wp::TexelEncoding::Srgb8);
    // u' = 2 (u + 0.5), v' = 3 v.
    CHECK(t.to_u == glm::dvec3(2.0, 0.0, 1.0));
    CHECK(t.to_v == glm::dvec3(0.0, 3.0, 0.0));
    CHECK(s.materials[0].reflectance_texture == 1);
    // The constant is the texture's mean (plastic's sampling weight takes it).
    CHECK(s.materials[0].reflectance == t.mean());
    // A quad's corners get the unit square's coordinates, in order.
    REQUIRE(s.triangles.size() == 2);
    CHECK(s.triangles[0].has_uvs);
    CHECK(s.triangles[0].uvs[2] == glm::dvec2(1.0, 1.0));
    CHECK(s.triangles[1].uvs[2] == glm::dvec2(0.0, 1.0));
    CHECK(s.files.back() == (kTextures / "grid.png").string());

    const wp::Scene raw = parse_in(
        kTextures, scene_with(R"({"type": "bitmap", "filename": "grid.png", "raw": true})"));
    CHECK(raw.textures[0].image->encoding == wp::TexelEncoding::Linear8);
    const wp::Scene exr =
        parse_in(kTextures, scene_with(R"({"type": "bitmap", "filename": "ramp.exr"})"));
    CHECK(exr.textures[0].image->encoding == wp::TexelEncoding::Float32);
    CHECK(exr.textures[0].image->width == 6);

    const wp::Scene checker = parse_in(
        kTextures, scene_with(R"({"type": "checkerboard", "color0": 0.9, "color1": [0, 0.5, 1]})",
                              R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], )"
                              R"([0, 1, 0]], "uvs": [[0, 0], [2, 0], [0, 3]], "material": "t"})"));
    CHECK(checker.textures[0].color0 == glm::dvec3(0.9));
    CHECK(checker.textures[0].color1 == glm::dvec3(0.0, 0.5, 1.0));
    CHECK(checker.triangles[0].uvs[2] == glm::dvec2(0.0, 3.0));
}

TEST_CASE("loader: roughness textures and a textured conductor stays a conductor",
          "[scene][load][textures]") {
    const wp::Scene s = wp::parse_scene(
        wp::test::scene_json(wp::test::kSceneCamera, R"({
            "a": {"type": "roughconductor", "alpha": {"type": "checkerboard"}},
            "b": {"type": "conductor", "specular_reflectance": {"type": "checkerboard"}}})",
                             R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], )"
                             R"([0, 1, 0]], "material": "a"}])"),
        "test.json");
    CHECK(s.materials[0].alpha_u_texture == 1);
    CHECK(s.materials[0].alpha_v_texture == 1);
    CHECK(s.materials[1].kind == wp::MaterialKind::Conductor); // not the mirror kind
    CHECK(s.materials[1].reflectance_texture == 2);
}

TEST_CASE("loader: bad textures are one-line errors naming the field and the file",
          "[scene][load][textures][errors]") {
    wp::test::TempDir dir;
    write(dir / "broken.png", "\x89PNG\r\n\x1a\n this is not a PNG");
    // A PNG header that claims 20000 x 1 texels (stb_image reads the size
    // from IHDR without decoding anything).
    std::string huge = "\x89PNG\r\n\x1a\n";
    huge += std::string("\0\0\0\x0dIHDR", 8) +
            std::string("\0\0\x4e\x20\0\0\0\x01\x08\x02\0\0\0", 13) + std::string(4, '\0');
    write(dir / "huge.png", huge);
    const std::string m = "/materials/t/reflectance";
    struct Case {
        const char* what;
        std::string reflectance;
        std::string pointer;
        std::string fragment;
    };
    const Case cases[] = {
        {"unknown kind", R"({"type": "noise"})", m + "/type", "unknown texture type 'noise'"},
        {"missing filename", R"({"type": "bitmap"})", m + "/filename",
         "missing required field 'filename'"},
        {"missing file", R"({"type": "bitmap", "filename": "nowhere.png"})", m + "/filename",
         "nowhere.png"},
        {"corrupt file", R"({"type": "bitmap", "filename": "broken.png"})", m + "/filename",
         "broken.png"},
        {"oversized image", R"({"type": "bitmap", "filename": "huge.png"})", m + "/filename",
         "at most 16384"},
        {"unknown wrap mode", R"({"type": "bitmap", "filename": "x.png", "wrap_mode": "tile"})",
         m + "/wrap_mode", "expected repeat, mirror or clamp"},
        {"unknown filter", R"({"type": "bitmap", "filename": "x.png", "filter_type": "cubic"})",
         m + "/filter_type", "expected bilinear or nearest"},
        {"raw not a boolean", R"({"type": "bitmap", "filename": "x.png", "raw": 1})", m + "/raw",
         "expected true or false"},
        {"unknown key", R"({"type": "checkerboard", "colour0": 1})", m + "/colour0", "unknown key"},
        {"negative colour", R"({"type": "checkerboard", "color0": -1})", m + "/color0",
         "must not be negative"},
        {"singular to_uv", R"({"type": "checkerboard", "to_uv": [{"scale": [0, 1, 1]}]})",
         m + "/to_uv/0", "scale"},
    };
    for (const Case& c : cases) {
        const std::string e = error_in(dir.path(), scene_with(c.reflectance));
        INFO(c.what << ": " << e);
        CHECK(e.find("test.json: " + c.pointer + ": ") != std::string::npos);
        CHECK(e.find(c.fragment) != std::string::npos);
        CHECK(e.find('\n') == std::string::npos);
    }
    const std::string mirror = error_in(
        dir.path(), wp::test::scene_json(
                        wp::test::kSceneCamera,
                        R"({"t": {"type": "mirror", "reflectance": {"type": "checkerboard"}}})",
                        R"([{"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], )"
                        R"([0, 1, 0]], "material": "t"}])"));
    CHECK(mirror.find("/materials/t/reflectance: a mirror's reflectance cannot be a texture") !=
          std::string::npos);
    const std::string uvs = error_in(
        dir.path(), scene_with(R"({"type": "checkerboard"})",
                               R"({"type": "triangle", "vertices": [[0, 0, 0], [1, 0, 0], )"
                               R"([0, 1, 0]], "uvs": [[0, 0], [1, 0]], "material": "t"})"));
    CHECK(uvs.find("/shapes/0/uvs: expected an array of 3 texture coordinates") !=
          std::string::npos);
}

TEST_CASE("loader: texture coordinates from OBJ (v flipped, as Mitsuba) and PLY files",
          "[scene][load][textures][mesh]") {
    wp::test::TempDir dir;
    write(dir / "t.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.25 0.125\nvt 1 0\nvt 0 1\n"
                         "f 1/1 2/2 3/3\n");
    write(dir / "t.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                         "property float y\nproperty float z\nproperty float s\nproperty float t\n"
                         "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                         "0 0 0 0.25 0.125\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n");
    for (const char* file : {"t.obj", "t.ply"}) {
        const std::string shape =
            std::string(R"({"type": "mesh", "file": ")") + file + R"(", "material": "t"})";
        const wp::Scene textured =
            parse_in(dir.path(), scene_with(R"({"type": "checkerboard"})", shape));
        INFO(file);
        REQUIRE(textured.triangles.size() == 1);
        REQUIRE(textured.triangles[0].has_uvs);
        const bool obj = std::string(file) == "t.obj";
        CHECK(textured.triangles[0].uvs[0] == glm::dvec2(0.25, obj ? 0.875 : 0.125));
        CHECK(textured.triangles[0].uvs[2] == glm::dvec2(0.0, obj ? 0.0 : 1.0));
        // Without textures in the scene the coordinates are not kept.
        const wp::Scene plain = parse_in(dir.path(), scene_with("[0.5, 0.5, 0.5]", shape));
        CHECK_FALSE(plain.triangles[0].has_uvs);
    }
    write(dir / "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt nan 0\nf 1/1 2/1 3/1\n");
    const std::string e =
        error_in(dir.path(), scene_with(R"({"type": "checkerboard"})",
                                        R"({"type": "mesh", "file": "bad.obj", "material": "t"})"));
    CHECK(e.find("bad.obj:4: texture coordinate is not finite") != std::string::npos);
}

TEST_CASE("Mitsuba reader: textures, by nesting and by reference, and bad ones",
          "[scene][mitsuba][textures]") {
    wp::test::TempDir dir;
    std::filesystem::copy_file(kTextures / "grid.png", dir / "grid.png");
    const std::string head = R"(<scene version="3.0.0">
        <sensor type="perspective"><film type="hdrfilm"><integer name="width" value="8"/>
        <integer name="height" value="8"/></film></sensor>
        <texture type="bitmap" id="g"><string name="filename" value="grid.png"/></texture>)";
    auto load = [&](const std::string& bsdf) {
        write(dir / "s.xml", head + R"(<shape type="rectangle">)" + bsdf + "</shape></scene>");
        return wp::load_mitsuba_scene(dir / "s.xml");
    };
    const wp::Scene s = load(R"(<bsdf type="twosided"><bsdf type="roughconductor">
        <ref id="g" name="specular_reflectance"/>
        <texture type="checkerboard" name="alpha"><float name="color0" value="0.3"/></texture>
        </bsdf></bsdf>)");
    REQUIRE(s.textures.size() == 2);
    CHECK(s.materials[0].reflectance_texture == 1);
    CHECK(s.materials[0].alpha_u_texture == 2);
    CHECK(s.textures[1].color0 == glm::dvec3(0.3));
    CHECK(s.triangles[0].has_uvs);

    auto error = [&](const std::string& bsdf) {
        try {
            (void)load(bsdf);
        } catch (const wp::SceneError& e) {
            return std::string(e.what());
        }
        return std::string("<no error>");
    };
    CHECK(error(R"(<bsdf type="conductor"><texture type="checkerboard" name="eta"/></bsdf>)")
              .find("parameter 'eta' of <bsdf type=\"conductor\"> cannot be a texture") !=
          std::string::npos);
    CHECK(error(R"(<bsdf type="diffuse"><texture type="bitmap" name="reflectance">
        <string name="filename" value="gone.png"/></texture></bsdf>)")
              .find("gone.png") != std::string::npos);
    CHECK(error(R"(<bsdf type="diffuse"><texture type="perlin" name="reflectance"/></bsdf>)")
              .find("unsupported texture type 'perlin'") != std::string::npos);
    CHECK(error(R"(<bsdf type="diffuse"><rgb name="reflectance" value="0.5"/>
        <ref id="g" name="reflectance"/></bsdf>)")
              .find("given twice") != std::string::npos);
}
