// Traversal of instances (kernels/instance.h, instance_trace.h, bvh.h)
// against brute force, and their surfaces against double-precision
// references.
//
// Brute force: one kernel tests every plain primitive (the loop of
// traverse.h) and every triangle of every instance, mapped into object space
// as the traversal maps it, in number order; the two-level hierarchy must
// report the same closest hit at the same t (or another primitive at the
// same t up to rounding: a shared edge), and the same any-hit answer.
//
// Surfaces: rays at known points of scaled, rotated and mirrored instances of
// one triangle with vertex normals; t, the point, the geometric normal (the
// object normal by the inverse transpose: a mirrored instance keeps its
// object normal's side, as Mitsuba's do) and the shading normal are held
// against the same quantities computed in double on the host.
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <random>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/matrix.hpp>

#include "render/device_scene.hpp"
#include "scene/transform.hpp"
#include "support/instancing.hpp"
#include "support/scene_builder.hpp"

using namespace wp;
using namespace wp::test;

namespace {

const char* kCompareSource = R"CLC(
#include "traverse.h"

/* Every primitive in number order: the plain ones, then each instance's
 * triangles mapped into its object space as the traversal maps the ray. */
static wp_uint brute_force(const WpSceneView* scene, __global const wp_uint* group_sizes,
                           float3 o, float3 d, float t_max, float* t_hit) {
    float closest;
    wp_uint hit = wp_loop_trace(scene, o, d, t_max, 0, 0, &closest);
    for (wp_uint i = 0; i < scene->instance_count; ++i) {
        __global const WpInstance* m = &scene->instances[i];
        float3 oo, od;
        wp_instance_object_ray(m, o, d, &oo, &od);
        WpShearedRay sheared = wp_shear_ray(oo, od);
        for (wp_uint k = m->first_triangle; k < m->first_triangle + group_sizes[i]; ++k) {
            __global const WpTriangle* t = &scene->group_triangles[k];
            float tk;
            if (wp_intersect_triangle(&sheared, t->v0.xyz, t->v1.xyz, t->v2.xyz, closest, &tk)) {
                closest = tk;
                hit = scene->triangle_count + scene->sphere_count + m->first_primitive +
                      (k - m->first_triangle);
            }
        }
    }
    *t_hit = closest;
    return hit;
}

__kernel void compare(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), wp_uint count,
                      __global const wp_uint* group_sizes, __global const float4* origins,
                      __global const float4* directions, __global float* t_out,
                      __global wp_uint* hits_out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    float3 o = origins[i].xyz, d = directions[i].xyz;
    float segment = directions[i].w; /* any-hit queries up to here */
    float t_bvh, t_brute, t_any;
    hits_out[4 * i + 0] = wp_closest_hit(&scene, o, d, INFINITY, &t_bvh);
    hits_out[4 * i + 1] = brute_force(&scene, group_sizes, o, d, INFINITY, &t_brute);
    hits_out[4 * i + 2] = wp_occluded(&scene, o, d, segment);
    hits_out[4 * i + 3] = brute_force(&scene, group_sizes, o, d, segment, &t_any) != WP_NO_HIT;
    t_out[2 * i + 0] = t_bvh;
    t_out[2 * i + 1] = t_brute;
}
)CLC";

const char* kSurfaceSource = R"CLC(
#include "traverse.h"

__kernel void surface(WpFrame frame WP_SCENE_BUFFERS(WP_SCENE_PARAMETER), wp_uint count,
                      __global const float4* origins, __global const float4* directions,
                      __global float4* out) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    WP_SCENE_VIEW(scene);
    float3 o = origins[i].xyz, d = directions[i].xyz;
    float t;
    wp_uint hit = wp_closest_hit(&scene, o, d, INFINITY, &t);
    out[4 * i + 0] = (float4)(t, hit == WP_NO_HIT ? 0.0f : 1.0f, 0.0f, 0.0f);
    if (hit == WP_NO_HIT)
        return;
    WpSurface s;
    wp_surface_at(&scene, hit, o, d, t, &s);
    out[4 * i + 1] = (float4)(s.position, (float)s.front_face);
    out[4 * i + 2] = (float4)(s.normal, 0.0f);
    out[4 * i + 3] = (float4)(s.shading_normal, (float)s.smooth);
}
)CLC";

cl_float4 f4(const glm::dvec3& v, double w = 0.0) {
    return float4(float(v.x), float(v.y), float(v.z), float(w));
}

glm::dvec3 d3(const cl_float4& v) {
    return {v.s[0], v.s[1], v.s[2]};
}

// The scene's buffers and a frame with its counts, bound to `kernel` from
// argument 0; returns the next argument's index.
struct Bound {
    DeviceScene flat;
    DeviceBuffers buffers;
};

cl_uint bind(cl::Kernel& kernel, const Bound& bound) {
    WpFrame frame{};
    frame.triangle_count = cl_uint(bound.flat.triangles.size());
    frame.sphere_count = cl_uint(bound.flat.spheres.size());
    frame.instance_count = cl_uint(bound.flat.instances.size());
    kernel.setArg(0, frame);
    return bind_scene_buffers(kernel, 1, bound.buffers);
}

std::string options_for(const Scene& scene) {
    SceneFeatures features = analyse_features(scene);
    REQUIRE(features.bvh);
    REQUIRE(features.instances);
    return features.build_options();
}

// A height field of (cells + 1)^2 vertices over [-1, 1]^2 in the xy plane,
// two triangles a cell (every inner edge shared).
void add_height_field(TriangleList& out, std::uint32_t material, int cells,
                      std::mt19937& generator) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::dvec3> grid;
    for (int j = 0; j <= cells; ++j)
        for (int i = 0; i <= cells; ++i)
            grid.emplace_back(-1.0 + 2.0 * i / cells, -1.0 + 2.0 * j / cells,
                              0.3 * std::sin(1.3 * i) * std::cos(0.9 * j) + 0.05 * unit(generator));
    auto at = [&](int i, int j) { return grid[static_cast<std::size_t>(j * (cells + 1) + i)]; };
    for (int j = 0; j < cells; ++j)
        for (int i = 0; i < cells; ++i) {
            out.push_back({{at(i, j), at(i + 1, j), at(i + 1, j + 1)}, material});
            out.push_back({{at(i, j), at(i + 1, j + 1), at(i, j + 1)}, material});
        }
}

// Plain triangles and spheres, two shape groups (a height field and a
// triangle soup), and 40 instances, every third mirrored.
Scene random_instanced_scene(unsigned seed) {
    std::mt19937 generator(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Scene scene;
    scene.camera = make_camera({0, 5, -20}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    const auto white = add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    for (int k = 0; k < 60; ++k) { // loose plain triangles
        const glm::dvec3 c(20 * unit(generator) - 10, 6 * unit(generator) - 1,
                           20 * unit(generator) - 10);
        auto corner = [&] {
            return c + 1.5 * glm::dvec3(unit(generator) - 0.5, unit(generator) - 0.5,
                                        unit(generator) - 0.5);
        };
        scene.triangles.push_back({{corner(), corner(), corner()}, white});
    }
    for (int k = 0; k < 12; ++k)
        scene.spheres.push_back(
            {glm::dvec3(20 * unit(generator) - 10, 5 * unit(generator), 20 * unit(generator) - 10),
             0.2 + 0.6 * unit(generator), white});
    ShapeGroup field{"field", {}};
    add_height_field(field.triangles, white, 12, generator);
    ShapeGroup soup{"soup", {}};
    for (int k = 0; k < 150; ++k) {
        const glm::dvec3 c(2 * unit(generator) - 1, 2 * unit(generator) - 1,
                           2 * unit(generator) - 1);
        auto corner = [&] {
            return c + 0.5 * glm::dvec3(unit(generator) - 0.5, unit(generator) - 0.5,
                                        unit(generator) - 0.5);
        };
        soup.triangles.push_back({{corner(), corner(), corner()}, white});
    }
    scene.shape_groups = {field, soup};
    for (int k = 0; k < 40; ++k)
        scene.instances.push_back(
            {static_cast<std::uint32_t>(k % 2),
             random_placement(generator, k % 3 == 0, {-10, -1, -10}, {10, 5, 10})});
    return scene;
}

} // namespace

TEST_CASE("instances: the two-level hierarchy finds the closest and any hit of brute force, for "
          "10000 rays on a random scene of 40 scaled, rotated and mirrored instances",
          "[cl][bvh][instances]") {
    const Scene scene = random_instanced_scene(3);
    const Scene flat_scene = flattened_copy(scene);
    std::mt19937 generator(29);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    auto direction = [&] {
        const double z = 2 * unit(generator) - 1, phi = 2 * M_PI * unit(generator);
        const double r = std::sqrt(std::max(0.0, 1 - z * z));
        return glm::dvec3(r * std::cos(phi), z, r * std::sin(phi));
    };
    std::vector<cl_float4> origins, directions;
    const int rays = 10000;
    const std::size_t plain = scene.triangles.size();
    for (int k = 0; k < rays; ++k) {
        glm::dvec3 o, d = direction();
        if (k % 2 == 0) { // anywhere in the scene's box
            o = glm::dvec3(24 * unit(generator) - 12, 10 * unit(generator) - 3,
                           24 * unit(generator) - 12);
        } else { // aimed at a vertex or an edge of an instanced triangle
            const Triangle& t =
                flat_scene.triangles[plain + generator() % (flat_scene.triangles.size() - plain)];
            const glm::dvec3 target =
                k % 4 == 1 ? t.v[0] : t.v[0] + unit(generator) * (t.v[2] - t.v[0]);
            o = target + 4.0 * direction();
            d = glm::normalize(target - o);
        }
        origins.push_back(f4(o));
        directions.push_back(f4(d, 0.5 + 20 * unit(generator)));
    }

    Bound bound{flatten_scene(scene, true), {}};
    bound.buffers = allocate_device_buffers(device().context, bound.flat, 1, 1);
    REQUIRE(bound.flat.instances.size() == 40);
    std::vector<cl_uint> group_sizes;
    for (const WpInstance& m : bound.flat.instances) {
        // Each instance's group, by where its triangles start.
        group_sizes.push_back(m.first_triangle == 0
                                  ? cl_uint(scene.shape_groups[0].triangles.size())
                                  : cl_uint(scene.shape_groups[1].triangles.size()));
    }
    cl::Kernel kernel(program(kCompareSource, "instances_compare.cl", options_for(scene)),
                      "compare");
    const std::size_t n = origins.size();
    cl::Buffer sizes = upload(group_sizes), o = upload(origins), d = upload(directions);
    cl::Buffer t = upload(std::vector<float>(2 * n)), h = upload(std::vector<cl_uint>(4 * n));
    cl_uint next = bind(kernel, bound);
    kernel.setArg(next++, cl_uint(n));
    kernel.setArg(next++, sizes);
    kernel.setArg(next++, o);
    kernel.setArg(next++, d);
    kernel.setArg(next++, t);
    kernel.setArg(next++, h);
    launch(kernel, n);
    const std::vector<float> ts = download<float>(t, 2 * n);
    const std::vector<cl_uint> hits = download<cl_uint>(h, 4 * n);

    const cl_uint first_instanced =
        cl_uint(bound.flat.triangles.size() + bound.flat.spheres.size());
    int hit_count = 0, instanced = 0, ties = 0, occluded = 0;
    for (int k = 0; k < rays; ++k) {
        const cl_uint bvh = hits[4 * k], brute = hits[4 * k + 1];
        INFO("ray " << k);
        REQUIRE((bvh == WP_NO_HIT) == (brute == WP_NO_HIT));
        if (bvh == brute) {
            REQUIRE(float_bits(ts[2 * k]) == float_bits(ts[2 * k + 1]));
        } else {
            REQUIRE(std::fabs(ts[2 * k] - ts[2 * k + 1]) <= 4.0f * 1.2e-7f * ts[2 * k + 1]);
            ++ties;
        }
        hit_count += bvh != WP_NO_HIT;
        instanced += bvh != WP_NO_HIT && bvh >= first_instanced;
        REQUIRE(hits[4 * k + 2] == hits[4 * k + 3]);
        occluded += hits[4 * k + 2] != 0;
    }
    WARN("instances: " << hit_count << " hits (" << instanced << " on instances), " << ties
                       << " ties on another primitive, " << occluded << " occluded segments");
    CHECK(instanced > rays / 4);
    CHECK(occluded > rays / 10);
    CHECK(ties < rays / 100);
}

TEST_CASE("instances: hit t, point, geometric and shading normal of scaled, rotated and mirrored "
          "instances equal double-precision references",
          "[cl][instances]") {
    Scene scene;
    scene.camera = make_camera({0, 0, -10}, {0, 0, 0}, {0, 1, 0}, 40.0, 8, 8);
    const auto white = add_material(scene, MaterialKind::Diffuse, glm::dvec3(0.5));
    // One triangle with tilted vertex normals.
    Triangle object{{glm::dvec3(0, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0)}, white};
    object.has_normals = true;
    object.normals = {glm::normalize(glm::dvec3(0.2, 0.1, 1)),
                      glm::normalize(glm::dvec3(-0.3, 0, 1)),
                      glm::normalize(glm::dvec3(0, 0.4, 1))};
    scene.shape_groups = {{"one", {object}}};
    const std::vector<std::vector<Transform>> placements = {
        {Transform::scale(glm::dvec3(2.0, 0.5, 3.0)), Transform::translate({-6, 0, 0})},
        {Transform::rotate(30.0, {1, 1, 0}), Transform::translate({-3, 0, 0})},
        {Transform::scale(glm::dvec3(-1.5, 1.0, 1.0)), Transform::rotate(-20.0, {0, 1, 0}),
         Transform::translate({0.5, 0, 0})},
        {Transform::scale(glm::dvec3(0.7, -2.0, 1.3)), Transform::rotate(75.0, {0.2, 1, 0.5}),
         Transform::translate({3, 0, 0})},
        {Transform::rotate(170.0, {0, 1, 0}), Transform::scale(glm::dvec3(1.0, 1.0, -1.0)),
         Transform::translate({6, 0.5, 0})}};
    for (const auto& steps : placements)
        scene.instances.push_back({0, Transform::compose(steps).matrix()});

    // Per instance, a ray from each side at barycentrics (0.25, 0.3).
    std::vector<cl_float4> origins, directions;
    for (const Instance& instance : scene.instances) {
        const Triangle world = placed_triangle(object, instance.to_world);
        const glm::dvec3 target =
            world.v[0] + 0.25 * (world.v[1] - world.v[0]) + 0.3 * (world.v[2] - world.v[0]);
        const glm::dvec3 n =
            glm::normalize(glm::cross(world.v[1] - world.v[0], world.v[2] - world.v[0]));
        for (double side : {1.0, -1.0}) {
            const glm::dvec3 o = target + side * 2.0 * n + glm::dvec3(0.1, -0.2, 0.05);
            origins.push_back(f4(o));
            directions.push_back(f4(target - o));
        }
    }
    Bound bound{flatten_scene(scene, true), {}};
    bound.buffers = allocate_device_buffers(device().context, bound.flat, 1, 1);
    cl::Kernel kernel(program(kSurfaceSource, "instances_surface.cl", options_for(scene)),
                      "surface");
    const std::size_t n = origins.size();
    cl::Buffer o = upload(origins), d = upload(directions),
               out = upload(std::vector<cl_float4>(4 * n));
    cl_uint next = bind(kernel, bound);
    kernel.setArg(next++, cl_uint(n));
    kernel.setArg(next++, o);
    kernel.setArg(next++, d);
    kernel.setArg(next++, out);
    launch(kernel, n);
    const std::vector<cl_float4> got = download<cl_float4>(out, 4 * n);

    for (std::size_t i = 0; i < n; ++i) {
        const Instance& instance = scene.instances[i / 2];
        INFO("instance " << i / 2 << ", ray " << i);
        // The reference, in double from the float ray as uploaded.
        const glm::dmat3 linear(instance.to_world);
        const glm::dmat3 normal_map = glm::transpose(glm::inverse(linear));
        glm::dvec3 w[3];
        for (int k = 0; k < 3; ++k)
            w[k] = glm::dvec3(instance.to_world * glm::dvec4(object.v[k], 1.0));
        const glm::dvec3 ro = d3(origins[i]), rd = d3(directions[i]);
        const glm::dvec3 plane = glm::cross(w[1] - w[0], w[2] - w[0]);
        const double t = glm::dot(w[0] - ro, plane) / glm::dot(rd, plane);
        const glm::dvec3 p = ro + t * rd;
        const glm::dvec3 normal = glm::normalize(
            normal_map * glm::cross(object.v[1] - object.v[0], object.v[2] - object.v[0]));
        const double area = glm::dot(plane, plane);
        const double b1 = glm::dot(glm::cross(p - w[0], w[2] - w[0]), plane) / area;
        const double b2 = glm::dot(glm::cross(w[1] - w[0], p - w[0]), plane) / area;
        glm::dvec3 shading =
            glm::normalize((1 - b1 - b2) * glm::normalize(normal_map * object.normals[0]) +
                           b1 * glm::normalize(normal_map * object.normals[1]) +
                           b2 * glm::normalize(normal_map * object.normals[2]));
        if (glm::dot(shading, normal) < 0.0)
            shading = -shading;
        const bool front = glm::dot(rd, normal) < 0.0;

        REQUIRE(got[4 * i].s[1] == 1.0f); // hit
        CHECK(std::fabs(got[4 * i].s[0] - t) <= 1e-5 * t);
        CHECK(glm::length(d3(got[4 * i + 1]) - p) <= 1e-5 * (1.0 + glm::length(p)));
        CHECK((got[4 * i + 1].s[3] != 0.0f) == front);
        CHECK(glm::length(d3(got[4 * i + 2]) - normal) <= 1e-5);
        CHECK(glm::length(d3(got[4 * i + 3]) - shading) <= 1e-5);
        CHECK(got[4 * i + 3].s[3] == 1.0f); // smooth
    }
    // Both sides were tried on every instance: half the rays met a front face.
    int fronts = 0;
    for (std::size_t i = 0; i < n; ++i)
        fronts += got[4 * i + 1].s[3] != 0.0f;
    CHECK(fronts == int(n / 2));
}
