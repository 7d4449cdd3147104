// Case 3, shared edges and vertices: from inside a closed triangle mesh every
// ray must hit it. 10^7 rays per mesh (an icosphere of 80 triangles and a
// cube of 12), a quarter aimed exactly at vertices, half at points on edges
// (edge midpoints, and random points along edges, rounded to float), the rest
// in random directions; origins at the centre, anywhere inside, and just
// under the surface. The watertight test (kernels/triangle.h) must miss none;
// Moller-Trumbore (naive.hpp, -D ST_NAIVE=1) lets some through.
#include "stability.hpp"

#include <cstring>
#include <random>
#include <set>
#include <utility>

using namespace wp;
using namespace wp::stability;

namespace {

// Generates ray `first + i` from its index alone (a hash), traces it through
// wp_occluded or (one in 16) wp_closest_hit, and counts misses (or closest
// hits at t <= 0). Also, for the closest hits, the largest
// distance of a hit from the plane of its triangle, and for rays aimed at a
// known point the largest distance of the hit from that point, both relative
// to the coordinates' magnitude (bits of positive floats, so atomic_max
// orders them). The second is larger: a ray from just under a face to one of
// its own edges meets it at a grazing angle, where an error across the plane
// of a few ulps becomes one along the ray divided by the angle's sine.
const std::string kClosedMeshSource = std::string(kNaiveTraversalSource) + R"CLC(
#include "rng.h"

static inline float st_unit(wp_uint h) {
    return (float)(h >> 8) * (1.0f / 16777216.0f);
}

__kernel void closed_mesh(wp_uint first, wp_uint count, __global const WpTriangle* triangles,
                          wp_uint triangle_count, __global const float4* origins,
                          wp_uint origin_count, __global const float4* vertices,
                          wp_uint vertex_count, __global const uint2* edges, wp_uint edge_count,
                          __global wp_uint* counters, __global wp_uint* first_misses) {
    wp_uint i = get_global_id(0);
    if (i >= count)
        return;
    wp_uint id = first + i;
    wp_uint h1 = wp_mix32(id * 0x9e3779b9u + 0x632be5abu);
    wp_uint h2 = wp_mix32(h1 ^ 0x85ebca6bu);
    wp_uint h3 = wp_mix32(h2 + 0xc2b2ae35u);
    float3 o = origins[h1 % origin_count].xyz;
    wp_uint kind = id & 3u;
    float3 target;
    float3 d;
    if (kind == 0u) { /* exactly at a vertex */
        target = vertices[h2 % vertex_count].xyz;
    } else if (kind == 1u) { /* a random point of an edge, rounded to float */
        uint2 e = edges[h2 % edge_count];
        float3 a = vertices[e.x].xyz, b = vertices[e.y].xyz;
        target = a + st_unit(h3) * (b - a);
    } else if (kind == 2u) { /* an edge's midpoint */
        uint2 e = edges[h2 % edge_count];
        target = 0.5f * (vertices[e.x].xyz + vertices[e.y].xyz);
    }
    if (kind == 3u) { /* a uniformly random direction */
        float z = 1.0f - 2.0f * st_unit(h2);
        float r = sqrt(fmax(0.0f, 1.0f - z * z));
        float phi = 6.283185307f * st_unit(h3);
        d = (float3)(r * cos(phi), r * sin(phi), z);
    } else {
        d = target - o;
    }
    if (id & 4u)
        d = normalize(d);

    WpSceneView scene = st_scene_view(triangles, triangle_count, 0, 0u);
    /* One ray in 16 (by hash) takes the closest hit and measures its point;
     * the rest the any-hit query of shadow rays, which stops at the first
     * triangle: a miss is the same event for both (no triangle accepts). */
    if ((h3 & 0xf0u) != 0u) {
        if (!st_occluded(&scene, o, d, INFINITY)) {
            wp_uint k = atomic_inc(&counters[0]);
            if (k < 16u)
                first_misses[k] = id;
        }
        return;
    }
    float t;
    wp_uint hit = st_closest_hit(&scene, o, d, INFINITY, &t);
    if (hit == WP_NO_HIT || !(t > 0.0f)) {
        wp_uint k = atomic_inc(&counters[0]);
        if (k < 16u)
            first_misses[k] = id;
        return;
    }
    if (kind != 3u) {
        /* The hit should be the aimed-at point: its distance from it, relative
         * to the magnitude of the coordinates involved. */
        float scale = fmax(wp_max_abs_component(target), wp_max_abs_component(o));
        float error = length(t * d - (target - o)) / scale;
        atomic_max(&counters[1], as_uint(error));
    }
    /* The hit point's distance from the plane of the triangle it hit. */
    WpTriangle tri = triangles[hit];
    float3 n = normalize(wp_triangle_normal(&tri));
    float3 p = o + t * d;
    float plane = fabs(dot(p - tri.v0.xyz, n)) / fmax(wp_max_abs_component(p), wp_triangle_scale(&tri));
    atomic_max(&counters[2], as_uint(plane));
}
)CLC";

struct MeshRays {
    std::vector<WpTriangle> triangles;
    std::vector<cl_float4> origins;
    std::vector<cl_float4> vertices;
    std::vector<cl_uint2> edges;
};

// The scene's triangles in float, with their distinct vertices and edges.
MeshRays mesh_of(const Scene& scene) {
    MeshRays m;
    std::vector<D3> verts;
    auto index_of = [&](const D3& v) {
        for (std::size_t i = 0; i < verts.size(); ++i)
            if (verts[i].x == v.x && verts[i].y == v.y && verts[i].z == v.z)
                return static_cast<cl_uint>(i);
        verts.push_back(v);
        return static_cast<cl_uint>(verts.size() - 1);
    };
    std::set<std::pair<cl_uint, cl_uint>> edges;
    for (const Triangle& t : scene.triangles) {
        WpTriangle w = make_triangle(t.v[0], t.v[1], t.v[2]);
        m.triangles.push_back(w);
        cl_uint i[3] = {index_of(from_float4(w.v0)), index_of(from_float4(w.v1)),
                        index_of(from_float4(w.v2))};
        for (int k = 0; k < 3; ++k) {
            cl_uint a = i[k], b = i[(k + 1) % 3];
            edges.insert({std::min(a, b), std::max(a, b)});
        }
    }
    for (const D3& v : verts)
        m.vertices.push_back(to_float4(v));
    for (const auto& [a, b] : edges) {
        cl_uint2 e;
        e.s[0] = a;
        e.s[1] = b;
        m.edges.push_back(e);
    }
    return m;
}

// Origins: the centroid of the vertices, points anywhere inside (scaled
// towards the centroid by up to 0.9 of the inradius), and points just under
// the surface (0.999 of the way to a face's plane from the centroid).
void add_origins(MeshRays& m) {
    D3 centre(0.0);
    for (const cl_float4& v : m.vertices)
        centre = centre + from_float4(v);
    centre = centre / static_cast<double>(m.vertices.size());
    double inradius = INFINITY;
    for (const WpTriangle& t : m.triangles) {
        D3 n = normalize(
            cross(from_float4(t.v1) - from_float4(t.v0), from_float4(t.v2) - from_float4(t.v0)));
        inradius = std::min(inradius, std::abs(dot(from_float4(t.v0) - centre, n)));
    }
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    m.origins.push_back(to_float4(centre));
    while (m.origins.size() < 48) {
        D3 p(u(rng), u(rng), u(rng));
        if (length(p) > 1.0)
            continue;
        m.origins.push_back(to_float4(centre + p * (0.9 * inradius)));
    }
    for (std::size_t i = 0; i < 16; ++i) {
        const WpTriangle& t = m.triangles[(i * 7) % m.triangles.size()];
        D3 c = (from_float4(t.v0) + from_float4(t.v1) + from_float4(t.v2)) / 3.0;
        m.origins.push_back(
            to_float4(centre + (c - centre) * 0.999 * (inradius / length(c - centre))));
    }
}

struct MeshResult {
    std::uint64_t rays = 0;
    std::uint64_t misses = 0;
    double max_aim_error = 0.0;   // distance from the aimed point, relative to |coordinates|
    double max_plane_error = 0.0; // distance from the hit triangle's plane, relative
    std::vector<cl_uint> first_misses;
    double seconds = 0.0;
};

MeshResult shoot(const MeshRays& m, std::uint64_t rays, bool naive) {
    const cl::Program& program =
        test_program(kClosedMeshSource, "stability_closed_mesh.cl",
                     std::string("-D WP_HAS_SPHERES=0") + (naive ? " -D ST_NAIVE=1" : ""));
    cl::Kernel kernel(program, "closed_mesh");
    cl::Buffer tri = upload(m.triangles), org = upload(m.origins), ver = upload(m.vertices),
               edg = upload(m.edges);
    cl::Buffer counters = upload(std::vector<cl_uint>(3, 0u));
    cl::Buffer misses = upload(std::vector<cl_uint>(16, 0u));
    auto start = std::chrono::steady_clock::now();
    const std::uint64_t batch = 1u << 21;
    for (std::uint64_t first = 0; first < rays; first += batch) {
        cl_uint count = static_cast<cl_uint>(std::min(batch, rays - first));
        set_args(kernel, static_cast<cl_uint>(first), count, tri,
                 static_cast<cl_uint>(m.triangles.size()), org,
                 static_cast<cl_uint>(m.origins.size()), ver,
                 static_cast<cl_uint>(m.vertices.size()), edg, static_cast<cl_uint>(m.edges.size()),
                 counters, misses);
        launch(kernel, count);
    }
    MeshResult r;
    r.seconds = seconds_since(start);
    r.rays = rays;
    std::vector<cl_uint> c = download<cl_uint>(counters, 3);
    r.misses = c[0];
    float errors[2];
    std::memcpy(errors, &c[1], sizeof errors);
    r.max_aim_error = errors[0];
    r.max_plane_error = errors[1];
    r.first_misses = download<cl_uint>(misses, std::min<std::size_t>(16, c[0]));
    return r;
}

void check_closed_mesh(const std::string& name, std::size_t expected_triangles) {
    Scene scene = stress_scene(name);
    MeshRays m = mesh_of(scene);
    REQUIRE(m.triangles.size() == expected_triangles);
    // Closed: every edge is shared by exactly two triangles (V - E + F = 2).
    CHECK(m.vertices.size() + m.triangles.size() == m.edges.size() + 2);
    add_origins(m);

    const std::uint64_t rays = 10'000'000;
    MeshResult ours = shoot(m, rays, false);
    MeshResult naive = shoot(m, rays / 10, true);
    WARN(name << ": watertight: " << ours.misses << " misses in " << ours.rays << " rays ("
              << ours.seconds << " s); largest distance of a hit from its triangle's plane "
              << ours.max_plane_error << ", from the aimed point " << ours.max_aim_error
              << " (x |coordinates|); Moller-Trumbore: " << naive.misses << " misses in "
              << naive.rays << " rays (" << naive.max_plane_error << ", " << naive.max_aim_error
              << ")");
    CHECK(ours.misses == 0);
    CHECK(ours.max_plane_error < 2e-6); // within one ray offset (WP_RAY_OFFSET_RELATIVE)
    CHECK(ours.max_aim_error < 1e-4);   // grazing hits of origins just under a face
    // The naive variant shows what the watertight test prevents.
    CHECK(naive.misses > 0);
}

} // namespace

TEST_CASE("closed meshes: no ray from inside an icosphere slips through an edge or vertex",
          "[stability][watertight]") {
    check_closed_mesh("closed-icosphere", 80);
}

TEST_CASE("closed meshes: no ray from inside a cube slips through an edge or vertex",
          "[stability][watertight]") {
    check_closed_mesh("closed-cube", 12);
}

TEST_CASE("closed meshes: a camera inside an emitting closed mesh sees exactly its radiance",
          "[stability][watertight]") {
    // Every camera ray must hit the inward-facing emitter: a ray slipping out
    // would leave a pixel below 1.
    for (const char* name : {"closed-icosphere", "closed-cube"}) {
        INFO(name);
        test::Rendered r = test::render(stress_scene(name, 64), 4);
        Image mean = r.film.mean();
        float lo = *std::min_element(mean.rgb.begin(), mean.rgb.end());
        float hi = *std::max_element(mean.rgb.begin(), mean.rgb.end());
        CHECK(lo == 1.0f);
        CHECK(hi == 1.0f);
        CHECK(r.stats.nonfinite_samples == 0);
    }
}
