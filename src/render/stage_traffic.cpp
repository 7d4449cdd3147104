#include "render/stage_traffic.hpp"

#include <array>

#include "wp_shared.h"

namespace wp {
namespace {

constexpr Access R = Access::Read, W = Access::Write, RW = Access::ReadWrite;

// kernels/generate.cl: finished_queue only when it refills finished slots.
constexpr std::array<BufferAccess, 11> kGenerate{{{"finished_queue", R},
                                                  {"path_task", RW},
                                                  {"ray_origin", W},
                                                  {"ray_direction", W},
                                                  {"throughput", W},
                                                  {"radiance", W},
                                                  {"path_pixel", W},
                                                  {"path_sample", W},
                                                  {"path_depth", W},
                                                  {"path_flags", W},
                                                  {"ray_queues", W}}};

// kernels/intersect.cl
constexpr std::array<BufferAccess, 5> kIntersect{{{"ray_queues", R},
                                                  {"ray_origin", R},
                                                  {"ray_direction", R},
                                                  {"hit_primitive", W},
                                                  {"hit_t", W}}};

// kernels/shade_sort.cl, both launches together: each reads the queue and
// what its rays hit (the material behind it, a scene buffer, is not
// counted); the second writes the sorted queue (shade_order); the counts per
// key (shade_key_counts) are a few atomics per work-group, not counted, like
// the counters.
constexpr std::array<BufferAccess, 3> kShadeSort{
    {{"ray_queues", R}, {"hit_primitive", R}, {"shade_order", W}}};

// kernels/shade.cl: ray_queues is read (its own queue) and written (the
// survivors' queue); shade_order is read instead of its own queue when
// sorted (listed, so counted: 4 bytes too many in arrival order); a path
// ends in finished_queue or goes on, never both, so the table overcounts one
// 4-byte push. The mirror_* buffers only with next-event estimation through
// planar mirrors (kernels/mirror_light.h). The aov_* buffers only with --aov
// (WP_AOV), at a path's first hit: listed, but not counted in
// stage_bytes_per_item.
constexpr std::array<BufferAccess, 26> kShade{{{"ray_queues", RW},
                                               {"shade_order", R},
                                               {"hit_primitive", R},
                                               {"hit_t", R},
                                               {"ray_origin", RW},
                                               {"ray_direction", RW},
                                               {"throughput", RW},
                                               {"radiance", RW},
                                               {"path_pixel", R},
                                               {"path_sample", R},
                                               {"path_depth", RW},
                                               {"path_flags", RW},
                                               {"shadow_queue", W},
                                               {"shadow_origin", W},
                                               {"shadow_direction", W},
                                               {"shadow_contribution", W},
                                               {"mirror_vertex", RW},
                                               {"mirror_shadow_origin", W},
                                               {"mirror_shadow_direction", W},
                                               {"mirror_shadow_origin2", W},
                                               {"mirror_shadow_direction2", W},
                                               {"mirror_shadow_contribution", W},
                                               {"finished_queue", W},
                                               {"aov_albedo", RW},
                                               {"aov_normal", RW},
                                               {"aov_depth", RW}}};

// kernels/shadow.cl: radiance is written only when the ray is unblocked; the
// mirror_shadow_* buffers only for entries through a planar mirror.
constexpr std::array<BufferAccess, 10> kShadow{{{"shadow_queue", R},
                                                {"shadow_origin", R},
                                                {"shadow_direction", R},
                                                {"shadow_contribution", R},
                                                {"mirror_shadow_origin", R},
                                                {"mirror_shadow_direction", R},
                                                {"mirror_shadow_origin2", R},
                                                {"mirror_shadow_direction2", R},
                                                {"mirror_shadow_contribution", R},
                                                {"radiance", RW}}};

// kernels/accumulate.cl: film_odd_sum only for odd samples.
constexpr std::array<BufferAccess, 7> kAccumulate{{{"finished_queue", R},
                                                   {"radiance", R},
                                                   {"path_pixel", R},
                                                   {"path_sample", R},
                                                   {"film_sum", RW},
                                                   {"film_sum_squares", RW},
                                                   {"film_odd_sum", RW}}};

// kernels/bounce.cl, per ray: shade's path state, without the hit and the
// shadow-ray buffers (those stay in registers); as in kShade, a path ends in
// finished_queue or goes on, never both; the aov_* buffers as in kShade.
constexpr std::array<BufferAccess, 13> kBounce{{{"ray_queues", RW},
                                                {"ray_origin", RW},
                                                {"ray_direction", RW},
                                                {"throughput", RW},
                                                {"radiance", RW},
                                                {"path_pixel", R},
                                                {"path_sample", R},
                                                {"path_depth", RW},
                                                {"path_flags", RW},
                                                {"finished_queue", W},
                                                {"aov_albedo", RW},
                                                {"aov_normal", RW},
                                                {"aov_depth", RW}}};

// kernels/wave.cl, per sample: a work-item's path state is its own slot's,
// touched bounce after bounce in cache; what must reach memory is the
// slot's state once and its pixel's film (and the aov_* buffers as in kShade).
constexpr std::array<BufferAccess, 14> kWave{{{"path_task", RW},
                                              {"path_pixel", RW},
                                              {"path_sample", RW},
                                              {"path_depth", RW},
                                              {"path_flags", RW},
                                              {"ray_origin", RW},
                                              {"ray_direction", RW},
                                              {"throughput", RW},
                                              {"radiance", RW},
                                              {"film_sum", RW},
                                              {"film_sum_squares", RW},
                                              {"aov_albedo", RW},
                                              {"aov_normal", RW},
                                              {"aov_depth", RW}}};

// kernels/tail.cl, per ray (an item is a bounce, as in kBounce): the same
// accesses as a bounce; the path's state stays in cache between its
// bounces, so this overcounts. tail_lengths is one atomic per path, like the
// counters.
constexpr std::array<BufferAccess, 13> kTail = kBounce;

} // namespace

std::span<const BufferAccess> stage_buffer_accesses(Stage stage) {
    switch (stage) {
    case Stage::Generate:
        return kGenerate;
    case Stage::Intersect:
        return kIntersect;
    case Stage::ShadeSort:
        return kShadeSort;
    case Stage::Shade:
        return kShade;
    case Stage::Shadow:
        return kShadow;
    case Stage::Accumulate:
        return kAccumulate;
    case Stage::Bounce:
        return kBounce;
    case Stage::Wave:
        return kWave;
    case Stage::Tail:
        return kTail;
    case Stage::Transfer:
        break;
    }
    return {};
}

std::uint64_t path_buffer_element_bytes(std::string_view buffer) {
#define WP_ELEMENT_BYTES(name, type, ...)                                                          \
    if (buffer == #name)                                                                           \
        return sizeof(type);
    WP_PATH_BUFFERS(WP_ELEMENT_BYTES)
#undef WP_ELEMENT_BYTES
    return 0;
}

std::uint64_t stage_bytes_per_item(Stage stage) {
    std::uint64_t bytes = 0;
    for (const BufferAccess& a : stage_buffer_accesses(stage)) {
        // The AOVs' sums: only with --aov, and only for camera rays (at most
        // 72 bytes a camera ray); not an item's traffic.
        if (a.buffer.starts_with("aov_"))
            continue;
        const std::uint64_t element = path_buffer_element_bytes(a.buffer);
        bytes += element * ((a.access == Access::ReadWrite) ? 2u : 1u);
    }
    return bytes;
}

} // namespace wp
