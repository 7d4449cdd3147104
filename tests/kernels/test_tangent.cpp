// The tangent frame of anisotropic BSDFs (kernels/tangent.h, kernels/bsdf/frame.h)
// on the device, against a double-precision host reference of Mitsuba 3.9.1's
// dp/du and shading frame, and against values Mitsuba itself printed: its
// Python API (scalar_rgb), scene.ray_intersect(ray) on the same shapes,
// si.dp_du and si.sh_frame.s/t. Cases: a triangle with texture coordinates,
// one without (barycentric parameterisation), one whose coordinates are
// collinear (the fallback), a sphere, and a sphere's pole (dp/du = 0).
#include "support/kernel_test_util.hpp"

#include <cmath>
#include <string>
#include <vector>

using namespace wp::test;

namespace {

const char* const kTangentSource = R"CL(
#include "bsdf/frame.h"
#include "tangent.h"

/* Per case: the triangle (kind 0) or the sphere's unit normal (kind 1, in
 * n), the shading normal n, and out the tangent and bitangent of an
 * anisotropic material's frame. */
__kernel void frames(__global const WpTriangle* triangles, __global const WpTriangleUvs* uvs,
                     __global const uint* kind, __global const float4* n, uint count,
                     __global float4* tangent, __global float4* bitangent) {
    uint i = get_global_id(0);
    if (i >= count)
        return;
    WpSceneView scene;
    scene.triangle_uvs = uvs;
    float3 dp_du;
    if (kind[i] == 0u) {
        WpTriangle t = triangles[i];
        float3 ng = normalize(cross(t.v1.xyz - t.v0.xyz, t.v2.xyz - t.v0.xyz));
        dp_du = wp_triangle_dp_du(&scene, &t, ng);
    } else {
        dp_du = wp_sphere_dp_du(n[i].xyz);
    }
    WpShadingPoint p;
    p.n = n[i].xyz;
    p.front_face = 1;
    wp_shading_tangent(dp_du, &p);
    WpMaterial m;
    m.alpha_u = 0.05f;
    m.alpha_v = 0.3f;
    float3 t, b;
    wp_bsdf_frame(&m, &p, &t, &b);
    tangent[i] = (float4)(t, 0.0f);
    bitangent[i] = (float4)(b, 0.0f);
}
)CL";

struct Case {
    const char* what;
    bool sphere;
    D3 p[3]; // the triangle's vertices (or the sphere's unit normal in p[0])
    bool has_uvs;
    double u[3], v[3]; // its texture coordinates
    D3 mitsuba_s;      // Mitsuba's si.sh_frame.s, printed to 6 digits
};

// Mitsuba's dp/du, written from its definition (the derivative of the
// surface point along u), in double.
D3 reference_dp_du(const Case& c) {
    if (c.sphere)
        return D3(-c.p[0].y, c.p[0].x, 0.0); // d/dphi of (cos phi sin theta, sin phi sin theta, .)
    const D3 e1 = c.p[1] - c.p[0], e2 = c.p[2] - c.p[0];
    if (!c.has_uvs)
        return e1; // u = b1: moving along u alone runs from v0 to v1
    const double du1 = c.u[1] - c.u[0], dv1 = c.v[1] - c.v[0];
    const double du2 = c.u[2] - c.u[0], dv2 = c.v[2] - c.v[0];
    const double det = du1 * dv2 - dv1 * du2;
    if (det == 0.0)
        return D3(0.0);
    return (dv2 * e1 - dv1 * e2) / det;
}

// wp_make_basis's tangent (kernels/sampling.h), Mitsuba's coordinate_system.
D3 basis_tangent(const D3& n) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    return D3(1.0 + sign * n.x * n.x * a, sign * n.x * n.y * a, -sign * n.x);
}

D3 normal_of(const Case& c) {
    return c.sphere ? c.p[0] : glm::normalize(glm::cross(c.p[1] - c.p[0], c.p[2] - c.p[0]));
}

// Mitsuba's sh_frame.s: dp/du made perpendicular to n, or coordinate_system(n).
D3 reference_tangent(const Case& c) {
    const D3 n = normal_of(c);
    const D3 d = reference_dp_du(c);
    const D3 t = d - glm::dot(n, d) * n;
    if (glm::length(t) <= 1e-9 * glm::length(d) || glm::length(d) == 0.0)
        return basis_tangent(n);
    return glm::normalize(t);
}

} // namespace

TEST_CASE("tangent frame: dp/du made perpendicular to n, as Mitsuba 3 orients alpha_u",
          "[kernels][bsdf][anisotropy]") {
    const D3 sphere_n = glm::normalize(D3(1.65831, 1.0, 0.5));
    // Mitsuba's printed frames for these shapes (tools: mi.Mesh with these
    // vertices and texcoords, mi sphere of radius 2 hit at (1.65831, 1, 0.5)).
    const std::vector<Case> cases = {
        {"triangle with texture coordinates",
         false,
         {D3(0, 0, 0), D3(2, 0, 0.5), D3(0, 1, 0)},
         true,
         {0, 0.3, 1},
         {0, 0.8, 0.1},
         D3(-0.242091, 0.968364, -0.0605228)},
        {"triangle without texture coordinates",
         false,
         {D3(0, 0, 0), D3(2, 0, 0.5), D3(0, 1, 0)},
         false,
         {},
         {},
         D3(0.970143, 0, 0.242536)},
        {"triangle with collinear texture coordinates",
         false,
         {D3(0, 0, 0), D3(2, 0, 0.5), D3(0, 1, 0)},
         true,
         {0, 0.5, 1},
         {0, 0.5, 1},
         D3(0.970143, 0, 0.242536)},
        {"sphere", true, {sphere_n, D3(0), D3(0)}, false, {}, {}, D3(-0.516398, 0.856349, 0)},
        {"sphere's pole", true, {D3(0, 0, 1), D3(0), D3(0)}, false, {}, {}, D3(1, 0, 0)},
    };
    std::vector<WpTriangle> triangles;
    std::vector<WpTriangleUvs> uvs;
    std::vector<wp_uint> kinds;
    std::vector<wp_float4> normals;
    for (const Case& c : cases) {
        WpTriangle t{};
        t.v0 = to_float4(c.p[0]);
        t.v1 = to_float4(c.p[1]);
        t.v2 = to_float4(c.p[2]);
        if (!c.sphere && c.has_uvs) {
            WpTriangleUvs w{};
            for (int k = 0; k < 3; ++k) {
                w.u.s[k] = static_cast<float>(c.u[k]);
                w.v.s[k] = static_cast<float>(c.v[k]);
            }
            uvs.push_back(w);
            wp_set_triangle_uvs(&t, static_cast<wp_uint>(uvs.size()));
        }
        triangles.push_back(t);
        kinds.push_back(c.sphere ? 1u : 0u);
        normals.push_back(to_float4(normal_of(c)));
    }
    cl::Kernel kernel(program(kTangentSource, "tangent_test.cl"), "frames");
    cl::Buffer tangent = upload(std::vector<wp_float4>(cases.size()));
    cl::Buffer bitangent = upload(std::vector<wp_float4>(cases.size()));
    // Named: the buffers must outlive the launch, not just set_args.
    cl::Buffer triangle_buffer = upload(triangles), uv_buffer = upload(uvs);
    cl::Buffer kind_buffer = upload(kinds), normal_buffer = upload(normals);
    set_args(kernel, triangle_buffer, uv_buffer, kind_buffer, normal_buffer,
             static_cast<cl_uint>(cases.size()), tangent, bitangent);
    launch(kernel, cases.size());
    const std::vector<wp_float4> t = download<wp_float4>(tangent, cases.size());
    const std::vector<wp_float4> b = download<wp_float4>(bitangent, cases.size());
    for (std::size_t i = 0; i < cases.size(); ++i) {
        const Case& c = cases[i];
        const D3 n = normal_of(c), got_t = from_float4(t[i]), got_b = from_float4(b[i]);
        const D3 want = reference_tangent(c);
        INFO(c.what << ": device tangent " << got_t.x << " " << got_t.y << " " << got_t.z
                    << ", reference " << want.x << " " << want.y << " " << want.z);
        // Orthonormal, right-handed about n.
        CHECK(std::abs(glm::length(got_t) - 1.0) < 1e-6);
        CHECK(std::abs(glm::length(got_b) - 1.0) < 1e-6);
        CHECK(std::abs(glm::dot(got_t, n)) < 1e-6);
        CHECK(std::abs(glm::dot(got_b, n)) < 1e-6);
        CHECK(std::abs(glm::dot(got_t, got_b)) < 1e-6);
        CHECK(glm::length(glm::cross(n, got_t) - got_b) < 1e-6);
        // The double reference, and Mitsuba's own frame (6 printed digits).
        CHECK(glm::length(got_t - want) < 1e-6);
        CHECK(glm::length(want - c.mitsuba_s) < 2e-6);
        // Along dp/du: the tangent is its component in the tangent plane,
        // pointing the same way (dp/du has one, except at the pole).
        const D3 d = reference_dp_du(c);
        if (glm::length(d) > 0.0) {
            CHECK(glm::dot(got_t, d) > 0.0);
            CHECK(glm::length(glm::cross(got_t, d - glm::dot(d, n) * n)) < 1e-6 * glm::length(d));
        }
    }
}
