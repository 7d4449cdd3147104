#include "render/self_check.hpp"

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string_view>
#include <utility>

#include "cl/program.hpp"
#include "cl/program_cache.hpp"
#include "render/film.hpp"
#include "render/wavefront.hpp"
#include "scene/load.hpp"

namespace wp {
namespace {

// The tile: every pixel of the scene's view at this size, a few samples
// each. Small enough to cost milliseconds on a CPU; large enough that a
// fault shows (a sample differs in a few pixels at least).
constexpr int kTileSize = 16;
constexpr std::uint32_t kTileSamples = 4;
constexpr double kSigmas = 5.0;
// Values closer than this, relatively, agree; at most this share may not.
constexpr double kCloseRelative = 1e-3;
constexpr double kMostApart = 0.1;

// A render of the tile with one variant, self-check off (no recursion).
Film render_tile(DeviceContext& device, PreparedScene tile, bool general) {
    tile.options.general_kernels = general;
    tile.options.self_check = false;
    tile.options.pool_size = 0;
    tile.options.launch_plan =
        LaunchPlan::Stages; // the same for both: the kernels are the question
    WavefrontIntegrator integrator(device, tile);
    Film film(tile.width, tile.height);
    integrator.render(0, kTileSamples, film);
    return film;
}

// Bit for bit; else the two renders, which trace the same samples with the
// same random numbers, must agree value by value almost everywhere (a
// rounding difference only moves the few paths whose decisions it tips) and
// each channel's mean within kSigmas standard errors. A noise test alone is
// too weak on so small a tile: a kernel that drops every bounce's light was
// measured within 2.3 sigma on the hexroom's.
bool agree(const Film& specialised, const Film& general, std::string& detail) {
    const Image a = specialised.mean(), b = general.mean();
    const Image va = specialised.variance_of_mean(), vb = general.variance_of_mean();
    if (std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0) {
        detail = "bit for bit";
        return true;
    }
    std::array<double, 3> difference{}, variance{};
    std::size_t nonfinite = 0, apart = 0;
    for (std::size_t i = 0; i < a.rgb.size(); ++i) {
        const double x = a.rgb[i], y = b.rgb[i];
        nonfinite += !std::isfinite(x) || !std::isfinite(y);
        apart += !(std::abs(x - y) <= kCloseRelative * std::max(std::abs(x), std::abs(y)) + 1e-6);
        difference[i % 3] += x - y;
        variance[i % 3] += double(va.rgb[i]) + double(vb.rgb[i]);
    }
    double largest = 0.0;
    for (std::size_t c = 0; c < 3; ++c) {
        const double z = variance[c] > 0.0      ? std::abs(difference[c]) / std::sqrt(variance[c])
                         : difference[c] == 0.0 ? 0.0
                                                : INFINITY;
        largest = std::max(largest, z);
    }
    const double share = double(apart) / double(a.rgb.size());
    char text[200];
    std::snprintf(text, sizeof text, "%.1f%% of values differ, the means by %.2f sigma%s",
                  100.0 * share, largest, nonfinite ? "; NaN or Inf in one variant" : "");
    detail = text;
    return nonfinite == 0 && share <= kMostApart && largest <= kSigmas;
}

// The verdict's cache key: the program's, with both variants' options.
// The verdict's cache entry: its key, and the key's text the entry holds and
// is checked against (program_cache.hpp).
struct VerdictKey {
    std::uint64_t key = 0;
    std::string text;
};

VerdictKey verdict_key(const DeviceContext& device, const std::string& specialised,
                       const std::string& general) {
    static const std::string source = expand_includes(wavefront_program_source(), "wavefront.cl");
    const std::string options = "self-check\n" + specialised + "\n" + general;
    const std::string identity = device_cache_identity(device.info.device);
    return {program_cache_key(source, options, identity),
            program_cache_key_text(source, options, identity)};
}

std::optional<ProgramCache> verdict_store(const CachePolicy& policy) {
    if (!policy.enabled)
        return std::nullopt;
    std::filesystem::path dir =
        policy.directory.empty() ? default_program_cache_directory() : policy.directory;
    if (dir.empty())
        return std::nullopt;
    return ProgramCache(dir);
}

} // namespace

bool self_check_enabled(const IntegratorOptions& options) {
    const char* value = std::getenv("WAVEPATH_SELF_CHECK");
    return options.self_check && !(value && std::string_view(value) == "0");
}

std::string with_injected_fault(std::string options) {
    const char* value = std::getenv("WAVEPATH_SELF_CHECK_FAULT");
    if (!value || std::string_view(value) != "1")
        return options;
    for (const auto& [from, to] :
         {std::pair<const char*, const char*>{"WP_SAMPLER=1", "WP_SAMPLER=0"},
          {"WP_SAMPLER=0", "WP_SAMPLER=1"}})
        if (const std::size_t at = options.find(from); at != std::string::npos)
            return options.replace(at, std::string_view(from).size(), to);
    return options;
}

SelfCheckVerdict check_kernels(DeviceContext& device, const Scene& scene,
                               const IntegratorOptions& options) {
    return check_kernels(device, prepare_scene(scene, options));
}

SelfCheckVerdict check_kernels(DeviceContext& device, const PreparedScene& scene) {
    const IntegratorOptions& options = scene.options;
    const SceneFeatures& features = scene.features;
    const std::string specialised = with_injected_fault(kernel_build_options(features, options));
    const std::string general = kernel_build_options(SceneFeatures::general_for(features), options);
    SelfCheckVerdict verdict;
    const std::optional<ProgramCache> store = verdict_store(options.program_cache);
    const VerdictKey key = verdict_key(device, specialised, general);
    if (store) {
        if (CacheLookup found = store->load(key.key, key.text); found.binary) {
            const std::string text(found.binary->begin(), found.binary->end());
            verdict.from_cache = true;
            verdict.passed = text.rfind("pass:", 0) == 0;
            verdict.detail = text.substr(text.find(':') + 2);
            return verdict;
        }
    }
    // The whole view at the tile's size: the scene's arrays, not a copy.
    PreparedScene tile = scene;
    tile.width = tile.height = kTileSize;
    const Film a = render_tile(device, tile, false);
    const Film b = render_tile(device, tile, true);
    verdict.passed = agree(a, b, verdict.detail);
    if (store) {
        const std::string text = (verdict.passed ? "pass: " : "fail: ") + verdict.detail;
        store->store(key.key, key.text, std::vector<unsigned char>(text.begin(), text.end()));
    }
    return verdict;
}

Scene self_check_scene() {
    // A closed box (so shadow culling applies) seen from inside: a light in
    // the ceiling, a mirror wall, a mirror sphere and a diffuse one.
    static constexpr std::string_view kScene = R"({
  "camera": {"eye": [0, -3.5, 0], "look_at": [0, 0, 0], "up": [0, 0, 1], "fov": 70,
             "resolution": [16, 16]},
  "materials": {
    "white":  {"type": "diffuse", "reflectance": [0.7, 0.7, 0.7]},
    "red":    {"type": "diffuse", "reflectance": [0.7, 0.2, 0.2]},
    "mirror": {"type": "mirror", "reflectance": [0.9, 0.9, 0.9]},
    "light":  {"type": "emitter", "radiance": [20, 20, 20]}
  },
  "shapes": [
    {"type": "quad", "material": "white", "vertices": [[-4,-4,-2],[4,-4,-2],[4,4,-2],[-4,4,-2]]},
    {"type": "quad", "material": "white", "vertices": [[-4,-4,2],[-4,4,2],[4,4,2],[4,-4,2]]},
    {"type": "quad", "material": "red", "vertices": [[-4,-4,-2],[-4,4,-2],[-4,4,2],[-4,-4,2]]},
    {"type": "quad", "material": "mirror", "vertices": [[4,-4,-2],[4,-4,2],[4,4,2],[4,4,-2]]},
    {"type": "quad", "material": "white", "vertices": [[-4,4,-2],[4,4,-2],[4,4,2],[-4,4,2]]},
    {"type": "quad", "material": "white", "vertices": [[-4,-4,-2],[-4,-4,2],[4,-4,2],[4,-4,-2]]},
    {"type": "quad", "material": "light", "vertices": [[-1,-1,1.99],[-1,1,1.99],[1,1,1.99],[1,-1,1.99]]},
    {"type": "sphere", "material": "mirror", "center": [1, 1, -1.2], "radius": 0.8},
    {"type": "sphere", "material": "red", "center": [-1.2, 0.5, -1.3], "radius": 0.7}
  ]
})";
    return parse_scene(kScene, "self-check scene");
}

} // namespace wp
