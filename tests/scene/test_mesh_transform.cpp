// wp::Transform against hand-computed results and invariants, and its effect on
// loaded meshes (positions, normals, winding).
#include <catch2/catch.hpp>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include <glm/geometric.hpp>

#include "scene/mesh.hpp"
#include "scene/transform.hpp"
#include "support/mesh_test_files.hpp"

using wp::Transform;

namespace {

void check_near(const glm::dvec3& a, const glm::dvec3& b, double eps = 1e-12) {
    INFO("got (" << a.x << ", " << a.y << ", " << a.z << "), expected (" << b.x << ", " << b.y
                 << ", " << b.z << ")");
    CHECK(glm::length(a - b) <= eps);
}

std::string error_of(const std::function<void()>& f) {
    try {
        f();
    } catch (const wp::TransformError& e) {
        return e.what();
    }
    return "<no error>";
}

glm::dvec3 random_vector(std::mt19937_64& rng) {
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    return {u(rng), u(rng), u(rng)};
}

} // namespace

TEST_CASE("transform: each step on hand-computed points", "[mesh][transform]") {
    const glm::dvec3 p(1.0, 2.0, 3.0);
    check_near(Transform().apply_to_point(p), p);
    check_near(Transform::translate({1, -1, 0.5}).apply_to_point(p), {2, 1, 3.5});
    check_near(Transform::translate({1, -1, 0.5}).apply_to_vector(p), p);
    check_near(Transform::scale(2.0).apply_to_point(p), {2, 4, 6});
    check_near(Transform::scale({1, -2, 0.5}).apply_to_point(p), {1, -4, 1.5});
    // Right-handed: +x turns towards +y about +z.
    check_near(Transform::rotate(90, {0, 0, 1}).apply_to_point({1, 0, 0}), {0, 1, 0});
    check_near(Transform::rotate(90, {0, 0, 5}).apply_to_point({0, 1, 0}), {-1, 0, 0});
    check_near(Transform::rotate(90, {1, 0, 0}).apply_to_point({0, 1, 0}), {0, 0, 1});
    // A third of a turn about the diagonal permutes the axes.
    check_near(Transform::rotate(120, {1, 1, 1}).apply_to_point({1, 0, 0}), {0, 1, 0}, 1e-12);
    check_near(Transform::rotate(-120, {1, 1, 1}).apply_to_point({1, 0, 0}), {0, 0, 1}, 1e-12);
}

TEST_CASE("transform: steps compose in list order", "[mesh][transform]") {
    const glm::dvec3 p(1.0, 0.0, 0.0);
    const std::vector<Transform> scale_then_move{Transform::scale(2.0),
                                                 Transform::translate({1, 0, 0})};
    const std::vector<Transform> move_then_scale{Transform::translate({1, 0, 0}),
                                                 Transform::scale(2.0)};
    check_near(Transform::compose(scale_then_move).apply_to_point(p), {3, 0, 0});
    check_near(Transform::compose(move_then_scale).apply_to_point(p), {4, 0, 0});
    const std::vector<Transform> rotate_then_move{Transform::rotate(90, {0, 0, 1}),
                                                  Transform::translate({0, 0, 7})};
    check_near(Transform::compose(rotate_then_move).apply_to_point(p), {0, 1, 7});
    CHECK(Transform::compose({}).is_identity());
}

TEST_CASE("transform: a raw matrix is written row by row", "[mesh][transform]") {
    // Rotate 90 degrees about z and translate by (10, 20, 30), as on paper.
    const Transform m = Transform::from_rows({0, -1, 0, 10, //
                                              1, 0, 0, 20,  //
                                              0, 0, 1, 30,  //
                                              0, 0, 0, 1});
    const std::vector<Transform> steps{Transform::rotate(90, {0, 0, 1}),
                                       Transform::translate({10, 20, 30})};
    const Transform same = Transform::compose(steps);
    for (const glm::dvec3& p : {glm::dvec3(1, 2, 3), glm::dvec3(-4, 0.5, 9)})
        check_near(m.apply_to_point(p), same.apply_to_point(p), 1e-12);
    check_near(m.apply_to_point({0, 0, 0}), {10, 20, 30});
}

TEST_CASE("transform: look_at places the object's +z towards the target", "[mesh][transform]") {
    const Transform t = Transform::look_at({1, 2, 3}, {4, 2, 3}, {0, 0, 1});
    check_near(t.apply_to_point({0, 0, 0}), {1, 2, 3});
    check_near(t.apply_to_vector({0, 0, 1}), {1, 0, 0}); // towards the target
    check_near(t.apply_to_vector({0, 1, 0}), {0, 0, 1}); // up
    check_near(t.apply_to_vector({1, 0, 0}), {0, 1, 0}); // y cross z
    CHECK_FALSE(t.flips_orientation());
    // An up that is not perpendicular is straightened; the frame stays orthonormal.
    const Transform u = Transform::look_at({0, 0, 0}, {0, 0, -5}, {0, 3, 1});
    check_near(u.apply_to_vector({0, 0, 1}), {0, 0, -1});
    check_near(u.apply_to_vector({0, 1, 0}), {0, 1, 0});
    check_near(u.apply_to_vector({1, 0, 0}), {-1, 0, 0});
}

TEST_CASE("transform: rotations keep lengths and orientation", "[mesh][transform]") {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> angle(-720.0, 720.0);
    for (int i = 0; i < 200; ++i) {
        const Transform r = Transform::rotate(angle(rng), random_vector(rng));
        const glm::dvec3 v = random_vector(rng);
        CHECK(glm::length(r.apply_to_vector(v)) == Approx(glm::length(v)).epsilon(1e-12));
        CHECK_FALSE(r.flips_orientation());
        // The axis itself stays put.
    }
    const glm::dvec3 axis(0.3, -0.4, 1.2);
    check_near(Transform::rotate(33, axis).apply_to_vector(axis), axis, 1e-12);
}

TEST_CASE("transform: normals stay perpendicular under non-uniform scale", "[mesh][transform]") {
    const std::vector<Transform> steps{Transform::rotate(30, {1, 2, 3}),
                                       Transform::scale({1.0, 5.0, 0.2}),
                                       Transform::rotate(-70, {0, 1, 0})};
    const Transform t = Transform::compose(steps);
    std::mt19937_64 rng(11);
    double naive_worst = 0.0;
    for (int i = 0; i < 200; ++i) {
        const glm::dvec3 n = glm::normalize(random_vector(rng));
        // A tangent: any vector perpendicular to n.
        const glm::dvec3 tangent = glm::cross(n, random_vector(rng));
        const glm::dvec3 nt = t.apply_to_normal(n);
        const glm::dvec3 tt = glm::normalize(t.apply_to_vector(tangent));
        CHECK(glm::length(nt) == Approx(1.0));
        CHECK(std::abs(glm::dot(nt, tt)) < 1e-12);
        naive_worst =
            std::max(naive_worst, std::abs(glm::dot(glm::normalize(t.apply_to_vector(n)), tt)));
    }
    // Transforming normals like vectors would be visibly wrong here, so the test
    // above can tell the two apart.
    CHECK(naive_worst > 0.3);
}

TEST_CASE("transform: inverse and orientation", "[mesh][transform]") {
    const std::vector<Transform> steps{Transform::scale({-1, 2, 3}),
                                       Transform::rotate(40, {1, 1, 0}),
                                       Transform::translate({5, 6, 7})};
    const Transform t = Transform::compose(steps);
    CHECK(t.flips_orientation());
    const glm::dmat4 product = t.matrix() * t.inverse();
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            CHECK(product[c][r] == Approx(c == r ? 1.0 : 0.0).margin(1e-12));
    CHECK(Transform::scale(-1.0).flips_orientation());
    CHECK_FALSE(Transform::scale({-1, -1, 1}).flips_orientation());
}

TEST_CASE("transform: invalid steps are one-line errors", "[mesh][transform]") {
    CHECK(error_of([] { Transform::rotate(10, {0, 0, 0}); }) == "rotate: axis has zero length");
    CHECK(error_of([] {
              Transform::rotate(NAN, {0, 0, 1});
          }) == "rotate: angle or axis is not finite");
    CHECK(error_of([] { Transform::scale(0.0); }) == "scale: factor must be non-zero");
    CHECK(error_of([] { Transform::scale({1, 0, 1}); }) == "scale: factor must be non-zero");
    CHECK(error_of([] {
              Transform::translate({INFINITY, 0, 0});
          }) == "translate: offset is not finite");
    CHECK(error_of([] {
              Transform::look_at({1, 1, 1}, {1, 1, 1}, {0, 1, 0});
          }) == "look_at: 'to' equals 'from'");
    CHECK(error_of([] {
              Transform::look_at({0, 0, 0}, {0, 2, 0}, {0, 1, 0});
          }) == "look_at: 'up' is zero or parallel to the direction 'to' - 'from'");
    CHECK(error_of([] {
              Transform::from_rows({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 1, 1});
          }) == "matrix: last row must be 0 0 0 1 (only affine transforms)");
    CHECK(error_of([] {
              Transform::from_rows({1, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1});
          }) == "matrix: transform is singular (it flattens the object, so normals cannot be "
                "transformed)");
    // Small but honest scales are not "singular".
    CHECK(error_of([] { Transform::scale(1e-6); }) == "<no error>");
}

TEST_CASE("transform: applied to a loaded mesh", "[mesh][transform]") {
    const auto cube = mesh_test::data_dir() / "cube.obj";
    SECTION("non-uniform scale and translation scale area and volume as by hand") {
        wp::MeshLoadOptions o;
        const std::vector<Transform> steps{Transform::scale({2, 3, 4}),
                                           Transform::translate({-10, 0, 10})};
        o.transform = Transform::compose(steps);
        const wp::TriangleMesh m = wp::load_mesh(cube, o);
        CHECK(mesh_test::surface_area(m) == Approx(2 * (2 * 3 + 3 * 4 + 2 * 4)));
        CHECK(mesh_test::signed_volume(m) == Approx(24.0));
        check_near(m.positions[6], {-8, 3, 14});
    }
    SECTION("a mirror reverses the winding so the cube still faces outwards") {
        wp::MeshLoadOptions o;
        o.transform = Transform::scale({-1, 1, 1});
        const wp::TriangleMesh m = wp::load_mesh(cube, o);
        CHECK(mesh_test::signed_volume(m) == Approx(1.0));
        check_near(m.positions[1], {-1, 0, 0});
    }
    SECTION("file normals follow the inverse transpose and agree with the winding") {
        // The crease file: the normal (0, 0.6, 0.8) on the triangle (0,0,0) (1,1,0) (0,1,0).
        for (const Transform& t : {Transform::scale({1, 4, 0.5}), Transform::scale({1, 1, -1}),
                                   Transform::rotate(50, {1, 0, 0})}) {
            wp::MeshLoadOptions o;
            o.transform = t;
            const wp::TriangleMesh m = wp::load_mesh(mesh_test::data_dir() / "crease.obj", o);
            REQUIRE(m.normals.size() == 6);
            const glm::dvec3 n = m.normals[m.triangles[1][0]];
            check_near(n, t.apply_to_normal({0, 0.6, 0.8}));
            CHECK(glm::length(n) == Approx(1.0));
            // A flat file normal (0, 0, 1) stays the front side of its triangle.
            const glm::dvec3 flat = m.normals[m.triangles[0][0]];
            CHECK(glm::dot(flat, mesh_test::face_normal(m, 0)) == Approx(1.0));
        }
    }
    SECTION("a transform that overflows or leaves the scene limits is reported per vertex") {
        wp::MeshLoadOptions o;
        o.transform = Transform::scale(1e308);
        const auto path = mesh_test::write_file("far.obj", "v 0 0 0\nv 10 0 0\nv 0 1 0\nf 1 2 3\n");
        CHECK(mesh_test::error_of(path, o) ==
              path.string() + ": vertex 1: coordinate is not finite after the transform");
        o.transform = Transform::scale(1e30);
        CHECK(mesh_test::error_of(path, o) ==
              path.string() + ": vertex 1: coordinate 1e+31 exceeds the scene limit 1e30");
    }
}
