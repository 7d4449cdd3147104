// The wavefront stages, in pipeline order, then the fused kernels that run
// several stages' work in one launch: the one table of their names.
// Stage X(Enum, name) is the kernel `name` of kernels/name.cl; the program
// (src/cl/program.cpp), the integrator, the profiler and `wavepath info` all
// take the stages from here.
#pragma once

#include <array>
#include <string_view>

#define WP_STAGE_KERNELS(X)                                                                        \
    X(Generate, generate)                                                                          \
    X(Intersect, intersect)                                                                        \
    X(ShadeSort, shade_sort) /* with --shade-order sorted; shade_sort_count goes with it */        \
    X(Shade, shade)                                                                                \
    X(Shadow, shadow)                                                                              \
    X(Accumulate, accumulate)                                                                      \
    /* the fused kernels of the launch plans (LaunchPlan, render/integrator_options.hpp) */        \
    X(Bounce, bounce)                                                                              \
    X(Wave, wave)                                                                                  \
    X(Tail, tail) /* a wave's last bounces, in the stages and bounce plans */

namespace wp {

#define WP_STAGE_NAME(enum_name, name) #name,
inline constexpr std::array<std::string_view, 9> kStageKernelNames = {
    WP_STAGE_KERNELS(WP_STAGE_NAME)};
#undef WP_STAGE_NAME

} // namespace wp
