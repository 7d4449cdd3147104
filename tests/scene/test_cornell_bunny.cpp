// scenes/cornell-bunny.json: the Cornell box with the Stanford bunny instead
// of the blocks. Loaded only, never rendered here: without a BVH its 69,451
// triangles take minutes per image on the CPU device.
#include <catch2/catch.hpp>

#include <algorithm>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/load.hpp"
#include "scene/mesh.hpp"

namespace {

const std::string kScenes = WAVEPATH_SOURCE_DIR "/scenes/";

bool same_triangle(const wp::Triangle& a, const wp::Triangle& b) {
    return a.v == b.v && a.material == b.material;
}

} // namespace

TEST_CASE("scenes: the bunny box is the Cornell box with the bunny for the blocks",
          "[scene][scenes][cornell]") {
    const wp::Scene box = wp::load_scene(kScenes + "cornell-box.json");
    const wp::Scene bunny = wp::load_scene(kScenes + "cornell-bunny.json");
    CHECK(bunny.warnings.empty()); // no degenerate triangle dropped, no usemtl
    // The room: the box's first 18 triangles (walls, ceiling, light), unchanged.
    const std::size_t room = 18;
    REQUIRE(box.triangles.size() == room + 20);
    // The bunny's face count, as ../shared/models/README.md gives it.
    REQUIRE(bunny.triangles.size() == room + 69451);
    for (std::size_t t = 0; t < room; ++t)
        CHECK(same_triangle(box.triangles[t], bunny.triangles[t]));
    CHECK(box.camera.eye == bunny.camera.eye);
    CHECK(box.materials.size() == bunny.materials.size());
}

TEST_CASE("scenes: the bunny stands on the floor inside the box, clear of the walls and light",
          "[scene][scenes][cornell]") {
    const wp::Scene s = wp::load_scene(kScenes + "cornell-bunny.json");
    REQUIRE(s.triangles.size() > 18);
    glm::dvec3 low(1e300), high(-1e300);
    for (std::size_t t = 18; t < s.triangles.size(); ++t)
        for (const glm::dvec3& p : s.triangles[t].v) {
            low = glm::min(low, p);
            high = glm::max(high, p);
        }
    INFO("bunny bounds " << low.x << " " << low.y << " " << low.z << " to " << high.x << " "
                         << high.y << " " << high.z);
    // Its lowest point on the floor (y = 0) to well under a millimetre.
    CHECK(std::abs(low.y) < 1e-3);
    // Inside the walls (the red wall's innermost x is 549.6) with room to spare,
    // and below the ceiling.
    CHECK(low.x > 20.0);
    CHECK(high.x < 549.6 - 20.0);
    CHECK(low.z > 20.0);
    CHECK(high.z < 559.2 - 20.0);
    CHECK(high.y < 548.8 - 100.0);
    // The scan's own height (in metres, read without the scene) times the
    // scene's scale 2000: the rotation about +y keeps heights.
    const wp::TriangleMesh scan = wp::load_mesh(kScenes + "models/stanford-bunny.obj");
    double scan_low = 1e300, scan_high = -1e300;
    for (const glm::dvec3& p : scan.positions) {
        scan_low = std::min(scan_low, p.y);
        scan_high = std::max(scan_high, p.y);
    }
    CHECK(high.y - low.y == Approx(2000.0 * (scan_high - scan_low)).epsilon(1e-9));
}
