// Case 4, contact: a sphere resting on the floor (touching it at one point) and
// a tetrahedron whose base lies in the floor plane. Close-ups of the sphere's
// contact and of the tetrahedron's base edge must show a dark contact shadow
// and no seam, and must not change when the whole scene is scaled by 1e-3 or
// 1e3 (same seed, within noise): a fixed ray epsilon lets light in or
// darkens too much at one end or the other (measured with the naive variant,
// docs/stability.md).
#include "stability.hpp"

using namespace wp;
using namespace wp::stability;

namespace {

constexpr int kSize = 24;
constexpr std::uint32_t kSpp = 256;

// Low and close, looking at the contact point (0, 0, 0) under the sphere.
Scene contact_view() {
    Scene s = stress_scene("contact");
    s.camera = test::make_camera({-1.6, -0.4, 0.15}, {0, 0, 0}, {0, 0, 1}, 16.0, kSize, kSize);
    return s;
}

// From outside the tetrahedron's lit base edge (x = 2), half face, half floor.
Scene edge_view() {
    Scene s = stress_scene("contact");
    s.camera = test::make_camera({1.2, -0.6, 0.35}, {2.0, 0.0, 0.0}, {0, 0, 1}, 20.0, kSize, kSize);
    return s;
}

void check_scales(const char* what, const Scene& scene) {
    test::Rendered base = test::render(scene, kSpp, 51);
    CHECK(all_finite(base));
    for (double s : {1e-3, 1e3}) {
        test::Rendered r = test::render(transformed(scene, s), kSpp, 51);
        BlockComparison b = compare_blocks(r.film, base.film, 6);
        WARN(what << " scaled by " << s << ": blocks worst " << b.worst_sigmas << " sigma, "
                  << b.outside << "/" << b.blocks << " over 5; " << r.stats.capped_paths
                  << " capped");
        CHECK(b.outside == 0);
        CHECK(all_finite(r));
    }
}

} // namespace

TEST_CASE("contact: the floor at a sphere's contact point is dark, at every scale",
          "[stability][contact][statistical]") {
    Scene view = contact_view();
    test::Rendered r = test::render(view, kSpp, 51);
    // The lit floor, for scale: the scene's own view, bottom rows.
    test::Rendered wide = test::render(stress_scene("contact", kSize), 64, 52);
    test::MeanWithError lit = region_mean(wide.film, 1, 0, kSize - 4, kSize, kSize);
    // The middle rows of the close-up: the wedge between floor and sphere.
    test::MeanWithError contact = region_mean(r.film, 1, 0, 10, kSize, 14);
    WARN("contact wedge: " << contact.mean << " +- " << contact.standard_error
                           << ", lit floor: " << lit.mean);
    CHECK(contact.mean < 0.02 * lit.mean);
    check_scales("sphere contact close-up", view);
}

TEST_CASE("contact: no seam along a tetrahedron's base in the floor plane, at every scale",
          "[stability][contact]") {
    check_scales("tetrahedron base edge close-up", edge_view());
}

TEST_CASE("contact: no path is trapped inside the hexroom's mirror sphere where it touches the "
          "floor (shade.cl absorbs paths that meet a sphere from inside, docs/stability.md case 4)",
          "[stability][contact]") {
    // The mirror sphere (centre (9, 2.5, -3), radius 2) touches the floor at
    // (9, 2.5, -5). A floor point within sqrt(2 R o) ~ 1 cm of it has its
    // offset origin (o = 2e-6 x 13) inside the sphere; a lossless mirror seen
    // from inside reflects the path forever, until the depth cap cuts it
    // after 1024 bounces. The picture is right (the contact is dark) but
    // each such path costs 1024 bounces and counts as cut.
    // Near the contact the floor hides under the sphere's paraboloid
    // (height rho^2 / 2R): a camera 1 mm above the floor, 0.5 away, sees it
    // down to rho = 2 mm. A 0.01 degree view of the floor 6 mm from the contact.
    Scene scene = hexroom(kSize);
    scene.camera =
        test::make_camera({8.5, 2.5, -4.999}, {8.994, 2.5, -5.0}, {0, 0, 1}, 0.01, kSize, kSize);
    test::Rendered r = test::render(scene, 4, 53);
    WARN("mirror sphere contact close-up: " << r.stats.capped_paths << " of " << kSize * kSize * 4
                                            << " paths cut by the depth cap");
    CHECK(all_finite(r));
    CHECK(r.stats.capped_paths == 0);
}
