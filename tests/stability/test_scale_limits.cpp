// The accepted range of scales and distances from the origin, tested at its
// edges both ways (docs/stability.md, "Accepted range"): just inside, the
// hexroom renders like the original (same seed, within noise); just outside,
// validate_scene refuses it with a one-line message naming the limit. And
// the renderer's rescaling (render/float_range.hpp) is exact: a power-of-two
// scale renders the very same film.
#include "render/float_range.hpp"
#include "scene/scene_box.hpp"
#include "scene/validate.hpp"
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

constexpr int kSize = 16;
constexpr int kBlock = 4;
constexpr std::uint32_t kSpp = 256;
constexpr std::uint32_t kSeed = 5;

const test::Rendered& reference() {
    static const test::Rendered r = test::render(hexroom(kSize), kSpp, kSeed);
    return r;
}

// The hexroom with its look_at point moved far along the view: the same
// image, but the camera's own check (look_at must differ from eye by 1e-9 of
// their distance from the origin) no longer limits how far it can move.
Scene hexroom_far_look_at() {
    Scene scene = hexroom(kSize);
    scene.camera.look_at = scene.camera.eye + 1e25 * (scene.camera.look_at - scene.camera.eye);
    return scene;
}

void check_renders_like_hexroom(const Scene& scene, const std::string& what) {
    REQUIRE_NOTHROW(validate_scene(scene));
    const test::Rendered& ref = reference();
    test::Rendered r = test::render(scene, kSpp, kSeed);
    BlockComparison blocks = compare_blocks(r.film, ref.film, kBlock);
    double worst_mean = 0.0;
    for (int c = 0; c < 3; ++c)
        worst_mean = std::max(worst_mean, image_mean_sigmas(r.film, ref.film, c));
    INFO(what << ": worst block " << blocks.worst_sigmas << " sigma (" << blocks.worst_where
              << "), image means worst " << worst_mean << " sigma");
    CHECK(blocks.outside == 0);
    CHECK(worst_mean < kSigmas);
    // The comparison has power: an image mean 25 % off is 5 standard errors
    // away (the hexroom scaled by 1e12 or moved by 1e6 without the rescaling
    // was 24 % and 62 % off).
    for (int c = 0; c < 3; ++c) {
        const test::MeanWithError m = test::image_mean(ref.film, c);
        CHECK(m.standard_error < 0.05 * m.mean);
    }
    CHECK(all_finite(r));
    CHECK(r.stats.capped_paths == 0);
}

void check_refused(const Scene& scene, const std::string& message) {
    try {
        validate_scene(scene);
        FAIL("accepted, but should be refused with: " << message);
    } catch (const SceneError& e) {
        const std::string text = e.what();
        INFO(text);
        CHECK(text.find(message) != std::string::npos);
        CHECK(text.find('\n') == std::string::npos);
    }
}

// The scale that makes the hexroom's largest coordinate `largest`.
double scale_to_largest(double largest) {
    return largest / scene_box(hexroom(kSize)).largest_coordinate();
}

// The translation along (1, -1, 1) that puts the far-look_at hexroom
// `ratio` times its size from the origin.
Scene hexroom_at_distance_ratio(double ratio) {
    const Scene scene = hexroom_far_look_at();
    const SceneBox box = scene_box(scene);
    const double t = ratio * box.size() - box.largest_coordinate();
    Scene moved = transformed(scene, 1.0, glm::dvec3(t, -t, t));
    moved.camera.look_at = scene.camera.look_at + glm::dvec3(t, -t, t);
    const SceneBox moved_box = scene_box(moved);
    REQUIRE(moved_box.largest_coordinate() / moved_box.size() == Approx(ratio).epsilon(1e-6));
    return moved;
}

} // namespace

TEST_CASE("scale limits: a power-of-two scale renders the hexroom's film bit for bit",
          "[stability][scale-limits]") {
    // 2^-90 and 2^90 put the hexroom's coordinates near 1e-26 and 1e28: the
    // watertight test's T (a coordinate cubed) would underflow and overflow
    // float32 without the rescaling.
    const int exponent = GENERATE(-90, -40, 40, 90);
    const Scene scene = transformed(hexroom(kSize), std::ldexp(1.0, exponent));
    REQUIRE(float_frame(scene).scale == std::ldexp(1.0, -exponent - 4)); // into [0.5, 1)
    test::Rendered r = test::render(scene, kSpp, kSeed);
    const FilmSums a = r.film.sums(), b = reference().film.sums();
    CHECK(a.sum == b.sum);
    CHECK(a.sum_squares == b.sum_squares);
    CHECK(a.count == b.count);
}

TEST_CASE("scale limits: scales 1e-30 .. 1e30 render like the original",
          "[stability][scale-limits][statistical]") {
    // Powers of ten: not exact, so compared within noise.
    const int exponent = GENERATE(-30, -20, -13, 12, 20, 28);
    check_renders_like_hexroom(transformed(hexroom(kSize), std::pow(10.0, exponent)),
                               "scale 1e" + std::to_string(exponent));
}

TEST_CASE("scale limits: the largest coordinate 1e30, just inside and just outside",
          "[stability][scale-limits]") {
    check_renders_like_hexroom(transformed(hexroom(kSize), scale_to_largest(0.999e30)),
                               "largest coordinate 0.999e30");
    check_refused(transformed(hexroom(kSize), scale_to_largest(1.001e30)),
                  "must be in [-1e+30, 1e+30], got");
}

TEST_CASE("scale limits: the smallest scene size 1e-60, just inside and just outside",
          "[stability][scale-limits]") {
    const double size = scene_box(hexroom(kSize)).size();
    check_renders_like_hexroom(transformed(hexroom(kSize), 1.001e-60 / size), "size 1.001e-60");
    check_refused(transformed(hexroom(kSize), 0.999e-60 / size),
                  "shapes: the scene's size 9.99e-61 (its box's longest side) is below 1e-60, "
                  "the smallest whose areas squared double holds");
}

TEST_CASE("scale limits: distance from the origin 2^29 times the size, just inside and outside",
          "[stability][scale-limits]") {
    // Inside, the hexroom is moved to 1.4e10 from the origin, where float32's
    // spacing (1024) is 40 times the room's size: it renders only because
    // flatten_scene moves it back to the origin in double first.
    check_renders_like_hexroom(hexroom_far_look_at(), "the far look_at alone");
    check_renders_like_hexroom(hexroom_at_distance_ratio(0.999 * 536870912.0),
                               "0.999 x 2^29 times its size away");
    check_refused(hexroom_at_distance_ratio(1.001 * 536870912.0),
                  "times its size 16; at most 2^29 = 5.4e8 times its size can be rendered (its "
                  "coordinates would need more than double's 16 digits)");
}

TEST_CASE("scale limits: the loader refuses a scene too far from its origin in one line",
          "[stability][scale-limits]") {
    const std::string json = R"({
      "camera": {"eye": [1e12, 0, 0], "look_at": [2e12, 0, 0], "up": [0, 0, 1], "fov": 40,
                 "resolution": [8, 8]},
      "materials": {"light": {"type": "emitter", "radiance": [1, 1, 1]}},
      "shapes": [{"type": "triangle", "material": "light",
                  "vertices": [[1e12, 1, 0], [1e12, 0, 1], [1e12, 1, 1]]}]
    })";
    try {
        parse_scene(json, "far.json");
        FAIL("accepted");
    } catch (const SceneError& e) {
        CHECK(std::string(e.what()) ==
              "far.json: shapes: the scene lies 1e+12 from the origin, 1e+12 times its size 1; at "
              "most 2^29 = 5.4e8 times its size can be rendered (its coordinates would need more "
              "than double's 16 digits)");
    }
}

TEST_CASE("scale limits: the camera's eye and look_at closer than 1e-9 of their distance",
          "[stability][scale-limits]") {
    // The hexroom's look_at is 1 from its eye: moved by (t, -t, t), the
    // camera's check refuses it once |eye| exceeds 1e9, i.e. t above 5.77e8.
    const Scene inside = transformed(hexroom(kSize), 1.0, glm::dvec3(5.7e8, -5.7e8, 5.7e8));
    check_renders_like_hexroom(inside, "hexroom moved by 5.7e8");
    check_refused(transformed(hexroom(kSize), 1.0, glm::dvec3(5.8e8, -5.8e8, 5.8e8)),
                  "camera.look_at: must differ from camera.eye by more than 1e-9 of their "
                  "distance from the origin");
}

TEST_CASE("scale limits: the float frame leaves comfortable scenes exactly where they are",
          "[stability][scale-limits]") {
    const Scene room = hexroom(kSize);
    // In the band, not far from the origin: untouched, so images stay bit for bit.
    const FloatFrame identity = float_frame(room);
    CHECK(identity.origin == glm::dvec3(0.0));
    CHECK(identity.scale == 1.0);
    CHECK(float_frame(transformed(room, 1.0, glm::dvec3(1e5, -1e5, 1e5))).scale == 1.0);
    CHECK(float_frame(transformed(room, 1.0, glm::dvec3(1e5, -1e5, 1e5))).origin ==
          glm::dvec3(0.0));
    // 2^14 times its size away: moved to the box's centre, not rescaled.
    const Scene far = transformed(room, 1.0, glm::dvec3(1e6, -1e6, 1e6));
    const FloatFrame moved = float_frame(far);
    CHECK(moved.origin == scene_box(far).centre());
    CHECK(moved.scale == 1.0);
    CHECK(std::abs(moved.point(far.camera.eye).x) <= 0.5 * scene_box(far).size());
    // A camera without shapes (a box of size 0) stays where it is.
    Scene camera_only;
    camera_only.camera.eye = {1.0, 2.0, 3.0};
    CHECK(float_frame(camera_only).origin == glm::dvec3(0.0));
    CHECK(float_frame(camera_only).scale == 1.0);
}
