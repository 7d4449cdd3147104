// Kernels that check themselves (docs/gpu.md, "Self-check").
//
// A scene's specialised kernels (features switched off, counts compiled in)
// and the general ones compute the same samples: on PoCL the images agree
// bit for bit (tests/render/test_features.cpp). A driver that miscompiles
// one variant breaks that. So the first time a combination of device,
// driver and kernel build options is met, a small tile of the scene is
// rendered with both and compared: equal bit for bit passes, and so does
// near agreement (a driver may round a built-in differently in unrolled
// code: at most 10 % of values 0.1 % apart, each channel's mean within 5
// sigma). The verdict is kept in the program
// cache, keyed like a program, so it costs one general build and two tiny
// renders once per combination. On a failure the integrator builds the
// general kernels instead and warns, naming the device, the driver and the
// features the specialised build switched off or fixed.
#pragma once

#include <string>

#include "cl/context.hpp"
#include "render/integrator_options.hpp"
#include "render/prepared_scene.hpp"
#include "scene/scene.hpp"

namespace wp {

struct SelfCheckVerdict {
    bool passed = true;
    bool from_cache = false; // remembered from an earlier check
    std::string detail;      // "bit for bit", "within noise (...)", or what differed
};

// Whether renders check their kernels: IntegratorOptions::self_check, unless
// WAVEPATH_SELF_CHECK is "0" (tests set it so; the check is tested itself).
bool self_check_enabled(const IntegratorOptions& options);

// Test only: with WAVEPATH_SELF_CHECK_FAULT=1, `options` with a fault that
// stands in for a driver that miscompiles the specialised variant: the other
// sampler (WP_SAMPLER flipped), so every value differs while each still
// compiles and renders. `options` as they are when the variable is unset.
std::string with_injected_fault(std::string options);

// The check for `scene` under `options`: its specialised kernels against its
// general ones, on a tiny tile of the camera's view; the verdict is read from
// and stored in the program cache of `options` (off: checked every time).
SelfCheckVerdict check_kernels(DeviceContext& device, const Scene& scene,
                               const IntegratorOptions& options);
// The same for a prepared scene (its options), whose arrays the tile shares.
SelfCheckVerdict check_kernels(DeviceContext& device, const PreparedScene& scene);

// The check of a built-in scene that has every feature (a small room with a
// light, a planar mirror, a mirror sphere and a diffuse one), for
// `wavepath devices --check`.
Scene self_check_scene();

} // namespace wp
