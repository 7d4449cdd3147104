// The scene buffers of a prepared scene made in place (render/device_buffers.hpp):
// on a device that shares the host's memory (PoCL's CPU device) they are the
// prepared arrays themselves, not copies; they hold the bytes a copy holds;
// and the arrays live as long as the buffers, however early the caller lets
// go of them.
#include <catch2/catch.hpp>

#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "render/device_buffers.hpp"
#include "render/prepared_scene.hpp"
#include "support/render_helpers.hpp"

using namespace wp;

namespace {

// The scenes whose arrays between them fill every scene buffer but the
// environment's: the hexroom through a hierarchy (planar mirrors, mirror
// spheres, lights), a textured Mitsuba scene (texture coordinates, texels)
// and one with instances (shape groups and their hierarchies).
std::vector<std::string> scene_files() {
    const std::string root = WAVEPATH_SOURCE_DIR;
    return {root + "/scenes/hexroom.json", root + "/tests/data/mitsuba/textures-shapes.xml",
            root + "/tests/data/mitsuba/instances.xml"};
}

PreparedScene prepared(const std::string& file) {
    Scene scene = load_scene(file);
    scene.camera.width = 8;
    scene.camera.height = 6;
    IntegratorOptions options;
    options.traversal = Traversal::Hierarchy;
    return prepare_scene(scene, options);
}

// `buffer`'s bytes, read back.
std::vector<unsigned char> read_back(const cl::Buffer& buffer) {
    std::vector<unsigned char> bytes(buffer.getInfo<CL_MEM_SIZE>());
    test::device().queue.enqueueReadBuffer(buffer, CL_TRUE, 0, bytes.size(), bytes.data());
    return bytes;
}

template <typename T>
bool holds(const std::vector<unsigned char>& bytes, const DeviceArray<T>& array) {
    return bytes.size() == sizeof(T) * array.size() &&
           std::memcmp(bytes.data(), array.data(), bytes.size()) == 0;
}

} // namespace

TEST_CASE("upload in place: the scene buffers hold the arrays' bytes, as copies do, and on a "
          "device that shares the host's memory they are the arrays") {
    DeviceContext& device = test::device();
    const bool unified = device.info.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
    std::set<std::string> filled; // the buffers some scene here fills
    for (const std::string& file : scene_files()) {
        INFO(file);
        const PreparedScene scene = prepared(file);
        const DeviceScene& arrays = *scene.device_scene;
        const DeviceBuffers shared =
            allocate_device_buffers(device.context, device.info.device, scene.device_scene, 1, 1);
        const DeviceBuffers copied = allocate_device_buffers(device.context, arrays, 1, 1);
        // Every buffer, in place or not, holds the array's bytes and those of
        // the copy; an empty array gets a one-element dummy either way.
#define WP_CHECK_BUFFER(name, type)                                                                \
    {                                                                                              \
        INFO(#name << ", " << arrays.name.size() << " elements");                                  \
        const std::vector<unsigned char> bytes = read_back(shared.name);                           \
        CHECK(bytes.size() == read_back(copied.name).size());                                      \
        if (!arrays.name.empty()) {                                                                \
            CHECK(holds(bytes, arrays.name));                                                      \
            CHECK(holds(read_back(copied.name), arrays.name));                                     \
            CHECK(reinterpret_cast<std::uintptr_t>(arrays.name.data()) % kDeviceArrayAlignment ==  \
                  0);                                                                              \
            const void* host = shared.name.getInfo<CL_MEM_HOST_PTR>();                             \
            const bool uses_host =                                                                 \
                (shared.name.getInfo<CL_MEM_FLAGS>() & CL_MEM_USE_HOST_PTR) != 0;                  \
            CHECK(uses_host == unified);                                                           \
            CHECK((host == arrays.name.data()) == unified);                                        \
            CHECK(copied.name.getInfo<CL_MEM_HOST_PTR>() == nullptr);                              \
            filled.insert(#name);                                                                  \
        }                                                                                          \
    }
        WP_SCENE_BUFFERS(WP_CHECK_BUFFER)
#undef WP_CHECK_BUFFER
    }
    for (const char* name : {"triangles", "spheres", "lights", "bvh_nodes", "mirror_groups",
                             "mirror_triangles", "mirror_spheres", "triangle_uvs", "texels",
                             "instances", "group_triangles", "group_bvh_nodes"})
        CHECK(filled.count(name) == 1);
}

TEST_CASE("upload in place: the arrays live until the last buffer made over them is deleted") {
    DeviceContext& device = test::device();
    PreparedScene scene = prepared(scene_files()[0]);
    const DeviceArray<WpTriangle> triangles = scene.device_scene->triangles; // a copy
    const std::weak_ptr<const DeviceScene> arrays = scene.device_scene;
    {
        const DeviceBuffers buffers =
            allocate_device_buffers(device.context, device.info.device, scene.device_scene, 1, 1);
        scene.device_scene.reset(); // the caller lets go: the buffers still read the arrays
        const bool unified = device.info.device.getInfo<CL_DEVICE_HOST_UNIFIED_MEMORY>() == CL_TRUE;
        CHECK(arrays.expired() == !unified);
        CHECK(holds(read_back(buffers.triangles), triangles));
    }
    device.queue.finish();
    CHECK(arrays.expired()); // and are freed with the buffers
}

TEST_CASE("upload in place: an integrator renders from the arrays after the caller lets go of "
          "them, and frees them with itself") {
    const Scene scene = test::hexroom(12, 10);
    IntegratorOptions options;
    options.seed = 9;
    options.traversal = Traversal::Hierarchy;
    const test::Rendered direct = test::render(scene, 2, 9, 0, options);
    PreparedScene prepared = prepare_scene(scene, options);
    const std::weak_ptr<const DeviceScene> arrays = prepared.device_scene;
    Film film(12, 10);
    {
        WavefrontIntegrator integrator(test::device(), prepared);
        prepared.device_scene.reset();
        integrator.render(0, 2, film);
    }
    test::device().queue.finish();
    CHECK(arrays.expired());
    const Image a = film.mean(), b = direct.film.mean();
    REQUIRE(a.rgb.size() == b.rgb.size());
    CHECK(std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0);
}
