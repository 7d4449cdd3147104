// Stage 4, shadow: an unblocked segment adds its contribution to its slot's
// radiance, a blocked one adds nothing, and slots not queued are untouched.
#include "support/kernel_test_util.hpp"

#include <vector>

using namespace wp;
using namespace wp::test;

TEST_CASE("shadow: contributions arrive exactly when nothing blocks the segment", "[cl][shadow]") {
    std::vector<WpTriangle> triangles(2);
    triangles[0].v0 = float4(2, -1, -1); // a small wall at x = 2 ...
    triangles[0].v1 = float4(2, 1, -1);
    triangles[0].v2 = float4(2, 0, 1);
    triangles[1].v0 = float4(-10, -3, -10); // ... and a floor at y = -3
    triangles[1].v1 = float4(10, -3, -10);
    triangles[1].v2 = float4(0, -3, 20);
    std::vector<WpSphere> spheres(2);
    spheres[0].center_radius = float4(50, 50, 50, 1); // off every segment
    spheres[1].center_radius = float4(0, 5, 2, 0.5f);

    struct Segment {
        const char* what;
        D3 origin, direction;
        double length;
        bool blocked;
    };
    const Segment segments[] = {
        // Slot 0 unblocked: work-items past the queue's end that trace its
        // segment must still add nothing.
        {"ends before the wall", {0, 0, 0}, {1, 0, 0}, 1.9, false},
        {"through the wall", {0, 0, 0}, {1, 0, 0}, 4.0, true},
        {"through the sphere", {0, 5, 0}, {0, 0, 1}, 5.0, true},
        {"ends before the sphere", {0, 5, 0}, {0, 0, 1}, 1.4, false},
        {"wall behind the origin", {0, 0, 0}, {-1, 0, 0}, 10.0, false},
        {"from inside the sphere", {0, 5, 2}, {1, 0, 0}, 3.0, true},
        {"ends before the floor", {0, 0, 5}, {0, -1, 0}, 2.0, false},
        {"ends just past the wall", {0, 0, 0}, {1, 0, 0}, 2.01, true},
        {"oblique through the wall", {0, 0, 0}, normalize(D3(2, 0.2, 0.2)), 3.0, true},
        {"not queued", {0, 0, 0}, {0, 0, 1}, 1.0, false},
        {"queued past shadow_count", {0, 0, 0}, {0, 0, 1}, 1.0, false},
        {"starts on the wall", {2, 0, 0}, {1, 0, 0}, 3.0, false},
        {"through the floor (second triangle)", {0, 0, 5}, {0, -1, 0}, 4.0, true},
    };
    const std::size_t slots = std::size(segments);
    const std::vector<cl_uint> queue = {8, 3, 0, 5, 1, 7, 12, 2, 6, 11, 4, 10};
    const cl_uint shadow_count = 11; // slot 10 is in the buffer but not counted; 9 is absent

    std::vector<cl_float4> origins, directions, contributions, radiance;
    for (std::size_t i = 0; i < slots; ++i) {
        const Segment& s = segments[i];
        origins.push_back(to_float4(s.origin));
        directions.push_back(to_float4(s.direction, s.length));
        float f = float(i);
        contributions.push_back(float4(0.1f * (f + 1.0f), 0.3f, 1.0f / (f + 3.0f), 0.0f));
        radiance.push_back(float4(f + 0.25f, 2.0f * f + 0.5f, -f - 0.125f, 0.0f));
    }

    WpFrame frame{};
    frame.triangle_count = 2;
    frame.sphere_count = 2;
    DeviceBuffers buffers = stage_buffers(slots, 1);
    buffers.shadow_queue = upload(queue);
    buffers.shadow_origin = upload(origins);
    buffers.shadow_direction = upload(directions);
    buffers.shadow_contribution = upload(contributions);
    buffers.triangles = upload(triangles);
    buffers.spheres = upload(spheres);
    buffers.radiance = upload(radiance);
    // With the runtime counts and with the counts compiled in, whose kernel
    // PoCL vectorises and whose surplus work-items trace slot 0's segment
    // without adding anything (kernels/traverse.h, WP_TRACE_SURPLUS_ITEMS).
    for (const char* options : {"", "-D WP_TRIANGLE_COUNT=2 -D WP_SPHERE_COUNT=2"}) {
        INFO("build options: '" << options << "'");
        buffers.radiance = upload(radiance);
        run_stage("shadow", frame, make_launch(shadow_count, 0), buffers, shadow_count, options);
        std::vector<cl_float4> got = download<cl_float4>(buffers.radiance, slots);

        for (std::size_t i = 0; i < slots; ++i) {
            const Segment& s = segments[i];
            bool queued = i != 9 && i != 10;
            INFO(s.what);
            for (int k = 0; k < 4; ++k) {
                float expected = radiance[i].s[k];
                if (queued && !s.blocked)
                    expected += contributions[i].s[k];
                CHECK(got[i].s[k] == expected);
            }
            if (queued && !s.blocked)
                CHECK(got[i].s[0] != radiance[i].s[0]); // the contribution is not lost in rounding
        }
    }
}
